// Stage 5a': simplified models. Small features (holes narrower than a size,
// blends of a smaller radius) removed from the B-rep with OCCT's
// BRepAlgoAPI_Defeaturing, then tessellated with the partitions of the
// original faces carried to the faces that survive; the two-sided Hausdorff
// distance to the original is measured on the meshes' vertices against the
// exact other B-rep, and the model refused when it exceeds the envelope.
#pragma once

#include <vector>

#include <TopoDS_Shape.hxx>

#include "contactcore/errors.h"
#include "contactcore/meshes.h"
#include "contactcore/partitions.h"

namespace contactcore {

struct SimplifyOptions {
  double feature_size = 0;  // mm: holes of a smaller diameter, blends of a smaller radius go
  double envelope = 0;      // mm: largest Hausdorff distance allowed to the original
  MeshOptions mesh;
};

struct SimplifiedModel {
  Status status;              // fails when the envelope is exceeded (the model is still filled in)
  TopoDS_Shape shape;         // the defeatured solid
  TaggedMesh mesh;            // partitions: the original body's ids
  MeshQuality quality;
  std::vector<int> removed_faces;  // 1-based FaceN of the original
  int features_kept = 0;      // small features OCCT could not remove
  double hausdorff = 0;       // mm, two-sided, on mesh vertices
};

// The small features of a body: concave cylinders of diameter below `size`
// (holes) and cylinder or torus faces of radius below size / 2 that span less
// than a half turn (blends); 1-based FaceN.
std::vector<int> small_features(const BodyPartitions& partitions, double size);

SimplifiedModel simplify_body(const TopoDS_Shape& shape, const BodyPartitions& partitions,
                              const SimplifyOptions& options);

}  // namespace contactcore
