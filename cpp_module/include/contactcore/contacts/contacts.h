// Stage 3: contacts. Broad phase on body boxes (the paper's LBiB), candidate
// partition pairs with the same surface parameters and opposite material
// sides (LpC) found by sorting, then a real common-area test per candidate.
#pragma once

#include <cmath>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <TopoDS_Compound.hxx>
#include <TopoDS_Shape.hxx>

#include "contactcore/bodies/bodies.h"
#include "contactcore/partitions/partitions.h"

namespace contactcore {

enum class ContactType {
  PLF,  // planar fit: coplanar planes, opposite normals
  CLJ,  // cylindrical joint: shaft in a bore of the same radius and axis
  CJU,  // cylindrical joint unidirectional: cone in a cone (same apex, axis, angle)
  SPF,  // spherical fit: ball in a spherical cup
  LAF,  // linear annular fit: ball in a bore of its radius, centre on the axis
  SPT,  // sphere in a torus groove of its radius (a ball in its raceway)
  TRF,  // torus on torus: same axis, centre and radii, opposite sides
};
const char* to_string(ContactType type);

struct Contact {
  ContactType type = ContactType::PLF;
  int body_a = 0, body_b = 0;            // indices into Assembly::bodies, body_a < body_b
  int partition_a = 0, partition_b = 0;  // partition ids within each body
  std::vector<int> faces_a, faces_b;     // 1-based FaceN indices of the faces in contact
  gp_Pnt point;     // PLF: a point of the common area; revolution: on the axis; sphere: centre
  gp_Dir direction; // PLF: outward normal of body_a; revolution: axis
  double radius = 0;        // CLJ, SPF, LAF, SPT (ball radius), TRF (minor radius)
  double half_angle = 0;    // CJU
  double area = 0;          // common area, mm^2 (LAF, SPT: 0, they touch along a circle)
  bool partial = false;     // revolution contact spanning less than 180 degrees
  double span = 0;          // common angular span, radians (revolution contacts)
  Tolerances tolerances;    // tolerances used
  // SPF, LAF, SPT: where the common region lies as seen from the ball's
  // centre: every direction from the centre to it is within `region_angle`
  // of `region_axis` (SPF: a cap of the sphere covering the common region,
  // exact for a cup bounded by a circle; LAF, SPT: the arc of the contact
  // circle, in the plane across `direction`). pi: all around (a ball held
  // on every side). What makes a ball in a cup or an open groove one-sided.
  gp_Dir region_axis;
  double region_angle = M_PI;
  // The common region itself, as faces (for drawing it): the part of the
  // contact's faces both sides share, oriented as side a's faces (their
  // normals out of body_a), placed as the bodies are. Null unless asked for
  // (ContactOptions::regions, find_common_regions); stays null for the
  // circle contacts (LAF, SPT), whose region is a circle. Its area is the
  // contact's area (the same Boolean common the area test uses, or a face
  // of one side where it lies wholly on the other's).
  TopoDS_Compound region;
};

// Point and line contacts (higher pairs), reported apart from the surface
// contacts above (whose counts they never change): a ball on a plane or
// against a cylinder of another radius touches at a point; a cylinder lying
// on a plane, or along a parallel cylinder of another radius (outside it, or
// inside a larger bore), along a line; a cone lying on a plane along a
// generator; a torus (a ring, an O-ring, a rounded wheel) on a plane or
// against a cylinder with a parallel axis at a point, or along a circle when
// it lies flat or sits coaxially; a cone seated on a bore's rim along a
// circle. Each is one-sided.
enum class HigherPairType {
  SphereOnPlane,       // point
  SphereOnCylinder,    // point: a ball against a shaft, or inside a larger bore
  CylinderOnPlane,     // line
  CylinderOnCylinder,  // line: parallel axes, different radii
  ConeOnPlane,         // line: a generator of a cone lying on a plane, from its apex
  TorusOnPlane,        // point (tilted or standing), circle (lying flat)
  TorusOnCylinder,     // point (parallel axes apart), circle (coaxial): its outer
                       // equator in a bore or against a shaft, its inner one on a shaft
  ConeOnCylinder,      // circle: a cone seated on the rim of a coaxial bore's mouth
};
// "sphere_on_plane", "sphere_on_cylinder", "cylinder_on_plane",
// "cylinder_on_cylinder", "cone_on_plane", "torus_on_plane",
// "torus_on_cylinder", "cone_on_cylinder".
const char* to_string(HigherPairType type);

enum class HigherPairKind { Point, Line, Circle };
// "point", "line", "circle".
const char* to_string(HigherPairKind kind);

struct HigherPair {
  HigherPairType type = HigherPairType::SphereOnPlane;
  HigherPairKind kind = HigherPairKind::Point;
  int body_a = 0, body_b = 0;            // body_a < body_b
  int partition_a = 0, partition_b = 0;
  std::vector<int> faces_a, faces_b;     // 1-based FaceN of the faces touching
  gp_Pnt point;   // the point of contact; a line's middle; a circle's centre
  gp_Dir normal;  // the common normal there, out of body_a's material (a circle: at `start`)
  gp_Pnt start, end;  // a line's ends (a point: the point twice; a circle: one of its points twice)
  double length = 0;  // a line's length, a circle's circumference, mm (a point: 0)
  // A circle: its axis and radius; the normal at a point of the circle is
  // `normal` turned about `axis` with the point (a surface of revolution).
  gp_Dir axis;
  double radius = 0;
  bool is_line() const { return kind == HigherPairKind::Line; }
  bool is_circle() const { return kind == HigherPairKind::Circle; }
};

// Which solid checks run (validity.h): Quick, the default, or also OCCT's
// whole BRepCheck_Analyzer and faces crossing each other (Full: seconds on
// a large model, against tens of milliseconds).
enum class SolidChecks { Quick, Full };

struct ContactOptions {
  std::optional<double> linear;   // mm; unset: each body's scaled to its own size (body_tolerances)
  std::optional<double> angular;  // radians; unset: the default
  double min_area_ratio = 1e-6;   // common area below ratio * smaller partition area: no contact
  double clearance_gap = 0;       // mm; > 0: also report clearance fits with radii this close
  int threads = 0;                // worker threads; 0: all cores, 1: serial in the calling thread
  bool reuse_instances = true;    // partition each shared shape once, moved to its other placements
  // Beyond this many body pairs with meeting boxes the broad phase stops with
  // a Status (heavily overlapping input: duplicates placed in place) instead
  // of enumerating them all. Raise it to go on.
  std::size_t max_body_pairs = 2'000'000;
  SolidChecks solid_checks = SolidChecks::Quick;
  // For tests: called before each candidate pair's test (bodies, partitions);
  // what it throws skips that pair as a failing test would.
  std::function<void(int, int, int, int)> candidate_hook;
  // Also compute each contact's common region (Contact::region) and each
  // interference's overlapping solid (Interference::solid): for the contacts
  // and interferences touching `region_bodies` only, or every one when it is
  // empty (find_common_regions).
  bool regions = false;
  std::vector<int> region_bodies;
};

// Found beside contacts, never counted as contacts.
// Bodies whose material overlaps (a press fit, a duplicate placed in place).
struct Interference {
  int body_a = 0, body_b = 0;  // body_a < body_b
  double volume = 0;           // mm^3 of the common solid
  TopoDS_Shape solid;          // the common solid; null unless asked for (ContactOptions::regions)
};
// A body whose solid is not valid (validity.h: a self-intersecting boundary,
// open, inside out, zero volume, ...): its contacts and areas may be wrong.
struct InvalidBody {
  int body = 0;
  std::vector<int> faces;  // 1-based FaceN where the fault lies; empty: the whole solid
  std::string reason;      // one of the k* strings of validity.h
};
// Same surface type and axis, radii differing by less than the clearance gap
// (a nut on its bolt): a fit with play, not a contact.
struct Clearance {
  int body_a = 0, body_b = 0;
  int partition_a = 0, partition_b = 0;
  SurfaceKind kind = SurfaceKind::Cylinder;
  double gap = 0;  // mm, radial (cylinders, spheres) or normal (planes)
};
// A candidate pair whose test raised an exception (OCCT or C++): skipped, the rest kept.
struct SkippedPair {
  int body_a = 0, body_b = 0;
  int partition_a = 0, partition_b = 0;
  std::vector<int> faces_a, faces_b;  // 1-based FaceN of the two partitions
  std::string message;
};

// Timings of each stage in seconds, for benchmarks and the CLI.
struct StageTimes {
  double partitions = 0, broad_phase = 0, candidates = 0, area = 0;
  double validity = 0, interferences = 0;  // the solid checks, the interference pass
  double regions = 0;                      // the common regions (ContactOptions::regions)
};

struct ContactsResult {
  Status status;
  // The caller's, or the coarsest body's; each body's own are in
  // partitions[i].tolerances, a pair's are pair_tolerances() of its two.
  Tolerances tolerances;
  std::vector<BodyPartitions> partitions;  // one per body
  // Per body, the body whose shape it instances (itself when none). An
  // instance's partitions are its source's moved; their plane outlines are
  // its source's (same plane frame), shared, not copied.
  std::vector<int> instance_of;
  std::vector<std::pair<int, int>> body_pairs;  // broad phase output, i < j
  std::size_t candidates = 0;  // candidate partition pairs (those of body pairs placed alike each counted)
  std::vector<Contact> contacts;
  std::vector<HigherPair> higher_pairs;  // point and line contacts, apart from `contacts`
  std::vector<Interference> interferences;
  std::vector<InvalidBody> invalid_bodies;  // in body order
  std::vector<Clearance> clearances;
  std::vector<SkippedPair> skipped;
  std::vector<std::string> messages;  // what was skipped or doubtful, for the user
  StageTimes times;
  // Common regions and interference solids computed by the last
  // find_common_regions (ContactOptions::regions) on this result.
  std::size_t regions_computed = 0;
};

// The solid checks of find_contacts (validity.h) on bodies partitioned
// elsewhere (partitions[i] of assembly.bodies[i], each with its tolerances):
// the invalid ones, in body order. For the mesh tools, which name them.
Status find_invalid_solids(const Assembly& assembly, const std::vector<BodyPartitions>& partitions,
                           std::vector<InvalidBody>& invalid, SolidChecks checks = SolidChecks::Quick);

// Body pairs (i < j, sorted) whose boxes meet within `gap`, by sort and sweep
// on the axis along which the fewest boxes overlap (so an assembly stacked
// along any axis does not degrade). Stops once more than `max_pairs` pairs
// are found: `pairs` then holds max_pairs + 1 of them and the Status says how
// many there may be and how to raise the limit.
struct BroadPhase {
  Status status;
  std::vector<std::pair<int, int>> pairs;
};
// Reports "broad phase" progress and stops when asked (Status Cancelled).
BroadPhase broad_phase(const std::vector<Bnd_Box>& boxes, double gap,
                       std::size_t max_pairs = static_cast<std::size_t>(-1), Progress* progress = nullptr);
// The same with a gap per box (each body's own linear tolerance): boxes i and
// j meet within the larger of gaps[i] and gaps[j].
BroadPhase broad_phase(const std::vector<Bnd_Box>& boxes, const std::vector<double>& gaps,
                       std::size_t max_pairs = static_cast<std::size_t>(-1), Progress* progress = nullptr);

// Area of the intersection of two polygon sets (outer loops counter-clockwise,
// holes clockwise) in the same 2D frame.
double common_area(const std::vector<Polygon2>& a, const std::vector<Polygon2>& b, double tol);

// Fills Contact::region of the contacts and Interference::solid of the
// interferences touching `bodies` (every one when empty) of a result of
// find_contacts on `assembly`, on `threads` threads (progress "regions");
// counts them in result.regions_computed. A region whose Boolean fails is
// left null and named in result.messages (drawing only: the rest go on).
// Status Cancelled when the progress asks to stop.
Status find_common_regions(const Assembly& assembly, ContactsResult& result, const std::vector<int>& bodies,
                           int threads = 0, Progress* progress = nullptr);

// Triangles of a region (Contact::region) for drawing: xyz of each point,
// three 0-based point indices per triangle wound counter-clockwise seen
// from the side its face's normal points to (out of body_a). Meshes the
// region (BRepMesh, `deflection` mm, `angular` radians) where it has no
// triangulation that fine yet.
struct RegionMesh {
  std::vector<double> points;
  std::vector<int> triangles;
};
Status mesh_region(const TopoDS_Shape& region, double deflection, double angular, RegionMesh& mesh);

// The whole stage on an assembly. Partitions each body (progress "partitions"),
// then broad phase, candidates ("candidates") and area ("contacts"), the
// partitions and the candidate tests on `options.threads` threads; the result
// is the same whatever the number of threads (bodies, pairs and contacts in
// the serial order). Progress is reported, and cancellation honoured within
// one body's or one candidate's work, from the calling thread.
ContactsResult find_contacts(const Assembly& assembly, const ContactOptions& options,
                             Progress* progress = nullptr);

}  // namespace contactcore
