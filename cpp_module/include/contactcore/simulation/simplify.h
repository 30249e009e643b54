// Stage 5 (simulation), simplified models: simplified models. Small features (holes narrower than a size,
// blends of a smaller radius, chamfers) removed from the B-rep with OCCT's
// BRepAlgoAPI_Defeaturing, then tessellated with the partitions of the
// original faces carried to the faces that survive; the two-sided Hausdorff
// distance to the original is measured on the meshes' vertices against the
// exact other B-rep, and the model refused when it exceeds the envelope.
#pragma once

#include <string>
#include <vector>

#include <TopoDS_Shape.hxx>

#include "contactcore/common/errors.h"
#include "contactcore/simulation/meshes.h"
#include "contactcore/partitions/partitions.h"

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
  std::vector<int> removed_faces;  // 1-based FaceN of the original, ascending
  int features_kept = 0;      // small features OCCT could not remove
  double hausdorff = 0;       // mm, two-sided, on mesh vertices
};

// The small features of a body: concave cylinders of diameter below `size`
// (holes), cylinder or torus faces of radius below size / 2 that span less
// than a half turn (blends), plane strips narrower than `size` beveling
// between two faces that both lean towards them (chamfers); 1-based FaceN of
// `shape`, whose partitions (or at least typed faces) `partitions` holds.
std::vector<int> small_features(const TopoDS_Shape& shape, const BodyPartitions& partitions, double size);

// Largest distance from a mesh (its vertices, edge midpoints and triangle
// centroids) to the exact surface of `shape`: one side of a Hausdorff
// distance. Samples are screened against a tessellation of `shape` of the
// given deflection (FCL), the farthest measured exactly (BRepExtrema).
// Leaves that tessellation on `shape`.
double hausdorff_to_shape(const TaggedMesh& mesh, const TopoDS_Shape& shape, double reference_deflection);

// Faces on one surface split by the modelling history are unified first
// (ShapeUpgrade_UnifySameDomain), so a hole cut in halves or layers goes whole.
SimplifiedModel simplify_body(const TopoDS_Shape& shape, const BodyPartitions& partitions,
                              const SimplifyOptions& options);

// A body's two simulation models: the view model (the original B-rep, every
// feature, tessellated finely) and the collision model (the B-rep without the
// features below `feature_size`, tessellated coarser). Each one's distance to
// the original is measured; a simplification beyond the envelope is refused
// and the collision model made from the original B-rep instead (`message`
// says why). With feature_size 0 nothing is simplified.
struct SimulationModelOptions {
  MeshOptions view;
  MeshOptions collision;
  double feature_size = 0;  // mm; 0: no simplification
  double envelope = 0;      // mm; needed with a feature size
};

struct SimulationModels {
  Status status;                   // fails only when a model cannot be made at all
  MeshResult view;
  double view_deviation = 0;       // mm: farthest point of the view mesh from the original B-rep
  MeshResult collision;
  bool simplified = false;         // the collision model comes from the defeatured B-rep
  double collision_hausdorff = 0;  // mm: two-sided when simplified, else its mesh's deviation
  std::vector<int> removed_faces;  // 1-based FaceN of the original (when simplified)
  int features_kept = 0;
  std::string message;             // why the simplification was refused, if it was
};

SimulationModels simulation_models(const TopoDS_Shape& shape, const BodyPartitions& partitions,
                                   const SimulationModelOptions& options);

}  // namespace contactcore
