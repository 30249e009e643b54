// Stage 2: partitions. Each face of a body typed (plane, cylinder, cone,
// sphere, torus, other), faces stored as free-form surfaces that are really
// analytic recognised as such, and adjacent faces with the same parameters
// merged into maximal partitions (the paper's list of merged partitions).
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Bnd_Box.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Dir.hxx>
#include <gp_Pnt.hxx>
#include <gp_Trsf.hxx>

#include "contactcore/common/errors.h"

namespace contactcore {

enum class SurfaceKind { Plane, Cylinder, Cone, Sphere, Torus, Other };
const char* to_string(SurfaceKind kind);

// Which side of the surface the material is on.
//  - Plane: always Outward (the outward normal is in `axis`).
//  - Revolution surfaces: Convex when the material is inside the surface
//    (shaft, ball, outer side of a torus tube), Concave when it is outside
//    (bore, spherical cup, groove).
enum class MaterialSide { Outward, Convex, Concave };
const char* to_string(MaterialSide side);

// Two faces of the same revolution surface can only touch with one convex
// (material inside) and the other concave.
inline bool convex_against_concave(MaterialSide a, MaterialSide b) {
  return (a == MaterialSide::Convex && b == MaterialSide::Concave) ||
         (a == MaterialSide::Concave && b == MaterialSide::Convex);
}

// Parameters of an analytic surface, in global coordinates (mm, radians).
struct SurfaceParams {
  SurfaceKind kind = SurfaceKind::Other;
  gp_Pnt location;   // plane: a point; cylinder: a point on the axis; cone: apex;
                     // sphere, torus: centre
  gp_Dir axis;       // plane: outward normal (face orientation honoured);
                     // cone: axis direction from the apex into the opening;
                     // cylinder, torus: axis direction, its sign carries no meaning
                     // (compare as lines); sphere: the Z axis of its frame
  double radius = 0;        // cylinder, sphere; torus: major radius
  double minor_radius = 0;  // torus
  double half_angle = 0;    // cone, in (0, pi/2)
};

// Where a face (or partition) lies on its surface.
//  - Revolution surfaces: an axial range [axial_min, axial_max] measured along
//    `axis` from `location` (sphere: along Z from the centre), and the angular
//    intervals it covers around the axis, in [0, 2 pi), measured from a
//    reference direction `ref_dir` perpendicular to the axis.
//  - Planes: the 2D outline in the plane frame (origin `location`, x = ref_dir,
//    y = axis ^ ref_dir): closed polygons, outer loops counter-clockwise,
//    holes clockwise, each chord with the bulge of its curve (Point2).
struct AngularInterval {
  double start = 0;  // radians in [0, 2 pi)
  double span = 0;   // radians in (0, 2 pi]
};
struct Point2 {
  double x = 0, y = 0;
  // Twice the signed area between the boundary curve and the chord from this
  // point to the next (positive where the curve swings counter-clockwise of
  // the chord): Green's theorem on chords plus bulges gives exact areas.
  double bulge = 0;
};
using Polygon2 = std::vector<Point2>;

// The loops of a plane outline, stored once: copies of an extent share them
// (a face and its one-face partition, an instance's faces and its source's,
// which are in the same plane frame). Immutable once made; read it as a
// const std::vector<Polygon2>.
class Outline {
 public:
  Outline() = default;
  Outline(std::vector<Polygon2> loops)  // NOLINT: implicit, as the vector it replaces
      : loops_(loops.empty() ? nullptr : std::make_shared<const std::vector<Polygon2>>(std::move(loops))) {}
  const std::vector<Polygon2>& loops() const { return loops_ ? *loops_ : empty_loops(); }
  operator const std::vector<Polygon2>&() const { return loops(); }  // NOLINT
  bool empty() const { return loops().empty(); }
  std::size_t size() const { return loops().size(); }
  const Polygon2& operator[](std::size_t i) const { return loops()[i]; }
  std::vector<Polygon2>::const_iterator begin() const { return loops().begin(); }
  std::vector<Polygon2>::const_iterator end() const { return loops().end(); }

 private:
  static const std::vector<Polygon2>& empty_loops() {
    static const std::vector<Polygon2> none;
    return none;
  }
  std::shared_ptr<const std::vector<Polygon2>> loops_;
};

struct Extent {
  gp_Dir ref_dir;
  double axial_min = 0, axial_max = 0;
  std::vector<AngularInterval> angular;  // revolution surfaces
  Outline outline;                       // planes
  double angular_span() const;           // sum of the spans, <= 2 pi
};

struct FaceInfo {
  int index = 0;            // 1-based, in TopExp_Explorer order: FreeCAD's "FaceN"
  TopoDS_Face face;
  SurfaceParams params;
  MaterialSide side = MaterialSide::Outward;
  bool recognised = false;  // stored as a free-form surface, typed by fitting
  double max_deviation = 0; // of the fitted surface on samples (recognised faces)
  double area = 0;
  Extent extent;
  Bnd_Box box;
};

struct Partition {
  int id = 0;                 // 0-based within its body
  std::vector<int> faces;     // 1-based face indices, ascending
  SurfaceParams params;
  MaterialSide side = MaterialSide::Outward;
  double area = 0;
  Extent extent;              // axial range and angular union; plane outlines of all faces
  Bnd_Box box;
};

struct Tolerances {
  double linear = 1e-3;   // mm
  double angular = 1e-4;  // radians
};

// Defaults that scale with what is compared: linear = 1e-5 of the box
// diagonal (no floor or ceiling, so a model scaled by 1e-6 or 1e6 behaves the
// same); angular 1e-4 rad. Shapes are in mm, so the same assembly in inch and
// in mm gets the same tolerances. The contact stage gives each body the
// defaults of its own box (body_tolerances) and a body pair the coarser of its
// two (pair_tolerances): a part far away or a huge one changes nothing about
// the others (issue 25).
constexpr double kDefaultRelativeLinear = 1e-5;
Tolerances default_tolerances(const Bnd_Box& model_box);

// Those defaults, with whichever value the caller gives instead.
Tolerances resolve_tolerances(const Bnd_Box& model_box, std::optional<double> linear,
                              std::optional<double> angular);

// Largest tolerances accepted, relative to the model: linear below 1 % of the
// box diagonal (beyond it every face "touches" every other and the search
// blows up), angular below 0.1 rad (about 6 degrees).
constexpr double kMaxRelativeLinear = 1e-2;
constexpr double kMaxAngular = 0.1;

// InvalidArgument naming the bad value unless both tolerances are finite,
// positive and below those bounds.
Status check_tolerances(const Bnd_Box& model_box, const Tolerances& tolerances);

// A body's tolerances: the caller's values where given, else the defaults of
// the body's own box. InvalidArgument when the box is not finite.
Status body_tolerances(const Bnd_Box& body_box, std::optional<double> linear, std::optional<double> angular,
                       Tolerances& out);
// The same from the shape's box (BRepBndLib, as the contact stage measures it).
Status body_tolerances(const TopoDS_Shape& shape, std::optional<double> linear, std::optional<double> angular,
                       Tolerances& out);

struct BodyPartitions {
  Status status;
  std::vector<FaceInfo> faces;        // every face, in FaceN order
  std::vector<Partition> partitions;  // every face in exactly one partition
  Bnd_Box box;
  Tolerances tolerances;              // those the body was partitioned with
};

// The tolerances of a comparison between two bodies: the coarser linear and
// angular of the two (each body's surfaces are known to its own tolerance).
inline Tolerances pair_tolerances(const BodyPartitions& a, const BodyPartitions& b) {
  return {a.tolerances.linear > b.tolerances.linear ? a.tolerances.linear : b.tolerances.linear,
          a.tolerances.angular > b.tolerances.angular ? a.tolerances.angular : b.tolerances.angular};
}

// Types one face. Never throws: a face OCCT cannot evaluate comes back as
// Other with status failing (the caller names body and face).
Status type_face(const TopoDS_Face& face, const Tolerances& tol, FaceInfo& out);

// Types every face of `shape` and merges adjacent faces (shared edge, seams
// included) of the same kind, parameters and material side into maximal
// partitions.
BodyPartitions partition_shape(const TopoDS_Shape& shape, const Tolerances& tol);

// The partitions of `shape`, which is `source_partitions`' shape moved by
// `motion`: faces are `shape`'s own (FaceN order), surfaces, reference
// directions and boxes moved; outlines and angular ranges, which are
// measured in the surfaces' own frames, unchanged (the outlines shared with
// the source, not copied). Status InvalidInput when the face counts differ
// (not the same shape).
BodyPartitions moved_partitions(const BodyPartitions& source_partitions, const gp_Trsf& motion,
                                const TopoDS_Shape& shape);

// The extent of a revolution face seen from another frame on the same axis
// line (origin on the axis, axis of either sign, ref_dir perpendicular to it):
// axial range measured along `axis` from `origin`, angles from `ref_dir`
// counter-clockwise about `axis`. `linear` is the model's linear tolerance
// (a sphere face re-measured about another axis classifies its poles with it).
Extent revolution_extent_in(const FaceInfo& face, const gp_Pnt& origin, const gp_Dir& axis,
                            const gp_Dir& ref_dir, double linear);

// The outline of a planar face in another plane frame (origin, x_dir, y_dir),
// loops re-oriented so outer loops are counter-clockwise in that frame.
std::vector<Polygon2> outline_in(const FaceInfo& face, const gp_Pnt& origin, const gp_Dir& x_dir,
                                 const gp_Dir& y_dir);

// Angular interval sets (each interval start in [0, 2 pi), span in (0, 2 pi]).
std::vector<AngularInterval> unite(std::vector<AngularInterval> intervals);
double overlap(const std::vector<AngularInterval>& a, const std::vector<AngularInterval>& b,
               std::vector<AngularInterval>* common = nullptr);

// True when the two surfaces are the same within tolerance (same kind and
// parameters; plane normals and cone axes must point the same way, cylinder
// and torus axes are compared as lines, sphere axes are ignored). Other never
// matches.
bool same_surface(const SurfaceParams& a, const SurfaceParams& b, const Tolerances& tol);

}  // namespace contactcore
