#include "contactcore/instances.h"

#include <cmath>
#include <unordered_map>

#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>

namespace contactcore {

// moved_partitions moves every field of these structs that lives in global
// coordinates. A new field must be moved there too: these sizes make the
// build say so when the structs change.
static_assert(sizeof(SurfaceParams) == 80 && sizeof(Extent) == 88 && sizeof(FaceInfo) == 288 &&
                  sizeof(Partition) == 280 && sizeof(BodyPartitions) == 224,
              "partition structs changed: update moved_partitions (instances.cpp) for the new fields");

namespace {

bool is_rigid(const gp_Trsf& motion) {
  return std::abs(motion.ScaleFactor() - 1.0) < 1e-12 && !motion.IsNegative();
}

void move(SurfaceParams& params, const gp_Trsf& motion) {
  params.location.Transform(motion);
  params.axis.Transform(motion);
}

}  // namespace

gp_Trsf relative_motion(const Body& from, const Body& to) {
  return to.shape.Location().Transformation().Multiplied(from.shape.Location().Transformation().Inverted());
}

std::vector<int> instance_sources(const std::vector<Body>& bodies) {
  std::vector<int> sources(bodies.size());
  std::unordered_map<const void*, std::vector<int>> seen;  // TShape -> bodies partitioned on their own
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    sources[i] = static_cast<int>(i);
    const TopoDS_Shape& shape = bodies[i].shape;
    if (shape.IsNull()) continue;
    std::vector<int>& firsts = seen[shape.TShape().get()];
    for (int first : firsts) {
      if (bodies[first].shape.Orientation() == shape.Orientation() &&
          is_rigid(relative_motion(bodies[first], bodies[i]))) {
        sources[i] = first;
        break;
      }
    }
    if (sources[i] == static_cast<int>(i)) firsts.push_back(static_cast<int>(i));
  }
  return sources;
}

namespace {

// The extent without its outline (which stays in the source).
Extent without_outline(const Extent& extent) {
  Extent out;
  out.ref_dir = extent.ref_dir;
  out.axial_min = extent.axial_min;
  out.axial_max = extent.axial_max;
  out.angular = extent.angular;
  return out;
}

}  // namespace

BodyPartitions moved_partitions(const BodyPartitions& source_partitions, const gp_Trsf& motion,
                                const TopoDS_Shape& shape, bool with_outlines) {
  TopTools_IndexedMapOfShape face_map;
  TopExp::MapShapes(shape, TopAbs_FACE, face_map);
  BodyPartitions out;
  if (face_map.Extent() != static_cast<int>(source_partitions.faces.size())) {
    out.status = Status::failure(StatusCode::InvalidInput, "not an instance of the same shape");
    return out;
  }
  if (with_outlines) {
    out = source_partitions;
  } else {
    out.status = source_partitions.status;
    out.faces.reserve(source_partitions.faces.size());
    for (const FaceInfo& face : source_partitions.faces) {
      FaceInfo copy;
      copy.index = face.index;
      copy.params = face.params;
      copy.side = face.side;
      copy.recognised = face.recognised;
      copy.max_deviation = face.max_deviation;
      copy.area = face.area;
      copy.extent = without_outline(face.extent);
      copy.box = face.box;
      out.faces.push_back(std::move(copy));
    }
    out.partitions.reserve(source_partitions.partitions.size());
    for (const Partition& partition : source_partitions.partitions) {
      Partition copy;
      copy.id = partition.id;
      copy.faces = partition.faces;
      copy.params = partition.params;
      copy.side = partition.side;
      copy.area = partition.area;
      copy.extent = without_outline(partition.extent);
      out.partitions.push_back(std::move(copy));
    }
  }
  out.box.SetVoid();
  for (std::size_t i = 0; i < out.faces.size(); ++i) {
    FaceInfo& face = out.faces[i];
    face.face = TopoDS::Face(face_map(static_cast<int>(i) + 1));
    move(face.params, motion);
    face.extent.ref_dir.Transform(motion);
    if (!face.box.IsVoid()) face.box = face.box.Transformed(motion);
    out.box.Add(face.box);
  }
  for (Partition& partition : out.partitions) {
    move(partition.params, motion);
    partition.extent.ref_dir.Transform(motion);
    partition.box.SetVoid();
    for (int index : partition.faces) partition.box.Add(out.faces[index - 1].box);
  }
  return out;
}

void copy_outlines(const BodyPartitions& from, BodyPartitions& to) {
  for (std::size_t i = 0; i < from.faces.size() && i < to.faces.size(); ++i)
    to.faces[i].extent.outline = from.faces[i].extent.outline;
  for (std::size_t k = 0; k < from.partitions.size() && k < to.partitions.size(); ++k)
    to.partitions[k].extent.outline = from.partitions[k].extent.outline;
}

void drop_outlines(BodyPartitions& body) {
  for (FaceInfo& face : body.faces) std::vector<Polygon2>().swap(face.extent.outline);
  for (Partition& partition : body.partitions) std::vector<Polygon2>().swap(partition.extent.outline);
}

}  // namespace contactcore
