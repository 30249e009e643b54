// Stage 2 (partitions), instances: the partitions of one shape placed again, moved rigidly
// instead of computed anew (the driver finds the instances: bodies/instances.h).
#include "contactcore/partitions/partitions.h"

#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>

namespace contactcore {

// moved_partitions moves every field of these structs that lives in global
// coordinates. A new field must be moved there too: these sizes make the
// build say so when the structs change.
static_assert(sizeof(SurfaceParams) == 80 && sizeof(Extent) == 80 && sizeof(FaceInfo) == 280 &&
                  sizeof(Partition) == 272 && sizeof(BodyPartitions) == 240,  // tolerances: not moved (copied)
              "partition structs changed: update moved_partitions (moved_partitions.cpp) for the new fields");

namespace {

void move(SurfaceParams& params, const gp_Trsf& motion) {
  params.location.Transform(motion);
  params.axis.Transform(motion);
}

}  // namespace

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
