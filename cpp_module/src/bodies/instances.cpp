#include "contactcore/bodies/instances.h"

#include <cmath>
#include <unordered_map>

#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>

namespace contactcore {

// moved_partitions moves every field of these structs that lives in global
// coordinates. A new field must be moved there too: these sizes make the
// build say so when the structs change.
static_assert(sizeof(SurfaceParams) == 80 && sizeof(Extent) == 80 && sizeof(FaceInfo) == 280 &&
                  sizeof(Partition) == 272 && sizeof(BodyPartitions) == 240,  // tolerances: not moved (copied)
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

BodyPartitions moved_partitions(const BodyPartitions& source_partitions, const gp_Trsf& motion,
                                const TopoDS_Shape& shape) {
  TopTools_IndexedMapOfShape face_map;
  TopExp::MapShapes(shape, TopAbs_FACE, face_map);
  BodyPartitions out;
  if (face_map.Extent() != static_cast<int>(source_partitions.faces.size())) {
    out.status = Status::failure(StatusCode::InvalidInput, "not an instance of the same shape");
    return out;
  }
  out = source_partitions;  // outlines shared with the source, not copied
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

}  // namespace contactcore
