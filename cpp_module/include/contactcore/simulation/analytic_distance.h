// Stage 5 (simulation): closed-form distance, contact points and normals
// between two analytic partitions (plane, cylinder, cone, sphere), bounded by
// the partitions' outlines, axial ranges and angular intervals. The closest
// pair is found from the surface parameters; it is the answer only when it
// lies inside both partitions (then no edge or rim can be closer): otherwise,
// and for tori and free-form surfaces, the caller falls back to the meshes.
// Plain numbers, no OCCT after set-up, no allocation per query: fit for the
// haptic loop.
#pragma once

#include <limits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "contactcore/partitions/partitions.h"

namespace contactcore {

// A partition's surface and bounds as numbers (the frame of its body's
// placement; move it with placed()).
struct AnalyticPatch {
  SurfaceKind kind = SurfaceKind::Other;
  MaterialSide side = MaterialSide::Outward;
  // As SurfaceParams: plane a point and its outward normal; cylinder a point
  // on the axis; cone its apex, axis into the opening; sphere its centre.
  Eigen::Vector3d location{0, 0, 0}, axis{0, 0, 1};
  Eigen::Vector3d ref_dir{1, 0, 0};  // angles (revolution) and the outline's x (plane)
  double radius = 0, half_angle = 0;
  double axial_min = 0, axial_max = 0;  // revolution: along axis from location
  struct Arc {
    double start = 0, span = 0;
  };
  std::vector<Arc> angular;  // revolution: intervals from ref_dir about axis (empty: none known)
  // Plane: outline loops in the plane frame (x = ref_dir, y = axis ^ ref_dir),
  // with each chord's bulge (Point2): a point is judged inside only when it is
  // farther from every chord than that chord's arc can swing.
  std::vector<std::vector<Point2>> loops;
  // Plane: the outline made ready for the point-in-outline test (prepare_outline,
  // called by analytic_patch; in the plane frame, so placed() keeps it): every
  // chord with its squared length and squared reach (the arc's swing), flat (an
  // even-odd count needs no loop structure); horizontal slabs over the outline,
  // each listing the chords whose y-range grown by their reach meets it (every
  // chord a horizontal ray from q can cross, or q can lie within the swing of,
  // is in q's slab: a point costs the chords near its height, not the whole
  // outline); and the box of all the outline's vertices (outside it no point is
  // inside).
  struct Chord {
    double x = 0, y = 0, ex = 0, ey = 0, length2 = 0, reach2 = 0;
    // Its end exactly as the next chord's start (x + ex may round off it: the
    // even-odd count must see a shared vertex on one side of q's ray for both chords).
    double x_end = 0, y_end = 0;
    double x0 = 0, x1 = 0, y0 = 0, y1 = 0;  // its box grown by the reach (no swing test beyond)
  };
  std::vector<Chord> chords;
  double slab_y0 = 0, slab_height = 1;
  int slab_count = 0;
  std::vector<int> slab_first;   // slab_count + 1 offsets into slab_chords
  std::vector<int> slab_chords;  // chord indices, slab by slab
  double outline_x0 = 0, outline_y0 = 0, outline_x1 = -1, outline_y1 = -1;  // empty when x0 > x1
  // A circle holding the whole outline, arcs' swing included (about its box's centre).
  double outline_cx = 0, outline_cy = 0, outline_radius = -1;
  // Plane: the outline as exact annuli (inner 0: a disk), in the plane frame,
  // when every loop is one circle (its vertices on the circle within
  // kCircleTolerance, each chord's bulge that circle's arc) and every hole is
  // concentric with the smallest outer circle around it, one hole at most per
  // outer circle (prepare_outline; empty otherwise: the outline test decides).
  // A shaft's shoulder, a bearing's or a seal's face: two such faces are
  // judged by their radii, not vertex by vertex, so coincident circles (a
  // shoulder's rim on a bore's edge, a line-to-line shaft's inner circles)
  // are decided too.
  struct Annulus {
    double cx = 0, cy = 0, inner = 0, outer = 0;
  };
  std::vector<Annulus> annuli;
  // Plane: the outline's holes that are whole circles (a hole loop as
  // AnalyticPatch::annuli reads one) with no other loop reaching inside them
  // (prepare_outline): the face's material lies outside such a circle, so a
  // shaft whose axis crosses the plane inside it is nearest to its rim, however
  // the rest of the outline runs (a screw through a cover's plate, which has
  // other holes and a square outline).
  struct Circle {
    double cx = 0, cy = 0, r = 0;
  };
  std::vector<Circle> round_holes;
};

// mm: a loop's vertices this close to one circle (and holes' centres this
// close to their outer circle's) make it that circle (AnalyticPatch::annuli);
// coordinates carry rounding of about 1e-13 mm.
constexpr double kCircleTolerance = 1e-9;
// mm: two annuli share area when the band of radii they have in common is
// wider than this; narrower (circles coincident up to rounding), they only
// touch along a rim.
constexpr double kAnnulusOverlap = 1e-6;

// Fills the patch's chords and boxes from its loops (set-up: allocates).
void prepare_outline(AnalyticPatch& patch);

// The patch of a partition (kind Other when it has no closed form here).
AnalyticPatch analytic_patch(const Partition& partition);

// The patch moved by a rigid motion (outlines and angles move with their frame).
AnalyticPatch placed(const AnalyticPatch& patch, const Eigen::Isometry3d& motion);

struct AnalyticContact {
  double gap = 0;  // signed: > 0 apart, < 0 overlapping by that much along `normal`
  Eigen::Vector3d point_a{0, 0, 0}, point_b{0, 0, 0};  // on each surface
  Eigen::Vector3d normal{0, 0, 1};  // unit, from b towards a: the way out for a
};

// Tolerances of the closed forms: axes (and plane normals) this close in
// angle count as parallel; cones this close in half-angle as one angle.
struct AnalyticTolerances {
  double parallel = 0.05;  // rad
  double angle = 1e-3;     // rad
  // mm: a signed overlap deeper than this is no contact being pushed into
  // (faces back to back, a shaft beside a bore rather than in it): the
  // meshes decide. A haptic proxy never lets parts sink this deep.
  double max_depth = 0.5;
  // mm: nothing farther is wanted (a haptic query's reach). A pair whose gap
  // is known early to be at least this (a lower bound: two parallel planes'
  // separation, a cylinder's end height over a plane) is answered with that
  // bound, its points not checked against the partitions' bounds: the caller
  // only needs to know it is out of reach, and the outline tests are the cost.
  // With a reach, any two planes, cylinders, cones or spheres are first tried
  // for such a bound, whether or not their kinds have a closed form: one patch
  // in front of the other's plane by more than the reach (behind it, by more
  // than max_depth), apart along a cylinder's or cone's axis, or two
  // revolution patches' cores farther apart than their radii.
  double reach = std::numeric_limits<double>::infinity();
};

// True and `out` filled when the closest pair of a and b (both placed in one
// frame) has a closed form here and lies inside both partitions; false when
// the meshes must answer. Pairs: plane-plane (parallel, facing; two outlines
// made of annuli (AnalyticPatch::annuli) also when they do not share area:
// the closest pair of their rims, sqrt(gap^2 + in-plane distance^2)), plane with
// a shaft (convex cylinder) or a ball (convex sphere), a shaft through a plane's
// round hole (AnalyticPatch::round_holes) or through a chamfer at a bore's
// mouth (a concave cone: its small rim), a shaft's chamfered end (a convex
// cone: its large rim) in a bore, cylinder-cylinder
// (shaft in bore with near-parallel axes, two shafts side by side), sphere-
// sphere (two balls, a ball in a cup), a ball in a bore, cone in cone (a
// plug on its seat: one half-angle, near-parallel axes). Overlaps are signed
// gaps along the normal of the contact (a shaft pushed into its bore's wall).
bool analytic_contact(const AnalyticPatch& a, const AnalyticPatch& b, AnalyticContact& out,
                      const AnalyticTolerances& tolerances = {}) noexcept;

// Whether point p (on or near the patch's surface) lies within its bounds:
// axial range and angular intervals, or inside its outline (with a margin
// for the arcs). `slack` mm of tolerance on the axial range.
bool within_patch(const AnalyticPatch& patch, const Eigen::Vector3d& p, double slack = 1e-6) noexcept;

}  // namespace contactcore
