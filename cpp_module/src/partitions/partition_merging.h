// Internal to the partitions stage: adjacent faces of the same kind,
// parameters and material side merged into maximal partitions
// (partition_merging.cpp).
#pragma once

#include <vector>

#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Shape.hxx>

#include "contactcore/partitions/partitions.h"

namespace contactcore::detail {

// The partitions of `shape` whose typed faces are `faces` (FaceN order, as
// in `face_map`): faces sharing an edge (seams included) on the same surface
// with the same side joined, partitions in the order of their first face,
// faces ascending; each with its area, box and extent (axial range and
// angular union for revolution surfaces, the faces' outlines for planes).
std::vector<Partition> merge_faces(const TopoDS_Shape& shape, const TopTools_IndexedMapOfShape& face_map,
                                   const std::vector<FaceInfo>& faces, const Tolerances& tol);

}  // namespace contactcore::detail
