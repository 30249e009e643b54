// The contacts stage driver: broad phase against brute force, parallel runs
// against serial ones (body for body, contact for contact), instances moved
// against instances partitioned on their own, failing pairs skipped, the
// pair limit, cancellation from every stage.
#include <gtest/gtest.h>

#include <csignal>

#include <random>
#include <stdexcept>
#include <string>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <Standard_Failure.hxx>
#include <TopLoc_Location.hxx>
#include <gp_Ax2.hxx>
#include <gp_Trsf.hxx>

#include "contacts/common_area.h"
#include "contactcore/contacts/contacts.h"
#include "contactcore/bodies/instances.h"
#include "contactcore/common/occt_guard.h"
#include "test_helpers.h"
#include "draw_order.h"

using namespace contactcore;
using contactcore::testing::drawn_last_first;
using contactcore::testing::sample;
using contactcore::testing::shared_step;

namespace {

// ------------------------------------------------------------- broad phase

std::vector<std::pair<int, int>> brute_force_pairs(const std::vector<Bnd_Box>& boxes, double gap) {
  std::vector<std::pair<int, int>> pairs;
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i)
    for (int j = i + 1; j < static_cast<int>(boxes.size()); ++j)
      if (boxes_meet(boxes[i], boxes[j], gap)) pairs.emplace_back(i, j);
  return pairs;
}

// `count` random boxes spread `spread` along each axis, each `size` long.
std::vector<Bnd_Box> random_boxes(std::mt19937& random, int count, const gp_XYZ& spread, const gp_XYZ& size) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Bnd_Box> boxes(count);
  for (Bnd_Box& box : boxes) {
    const auto l = drawn_last_first<3>([&] { return unit(random); });
    const gp_XYZ lo(spread.X() * l[0], spread.Y() * l[1], spread.Z() * l[2]);
    const auto h = drawn_last_first<3>([&] { return unit(random); });
    const gp_XYZ hi = lo + gp_XYZ(size.X() * h[0], size.Y() * h[1], size.Z() * h[2]);
    box.Update(lo.X(), lo.Y(), lo.Z(), hi.X(), hi.Y(), hi.Z());
    if (unit(random) < 0.1) box.SetGap(0.05 * unit(random));  // boxes with their own gap, as BRepBndLib makes
  }
  return boxes;
}

TEST(BroadPhase, ExactAgainstBruteForceWhateverTheOrientation) {
  std::mt19937 random(20261123);
  // A cloud, then assemblies stacked along x, y and z (long in one axis,
  // thin in the others), and flat layers.
  const std::vector<std::pair<gp_XYZ, gp_XYZ>> layouts = {
      {{100, 100, 100}, {10, 10, 10}}, {{1000, 5, 5}, {20, 5, 5}},   {{5, 1000, 5}, {5, 20, 5}},
      {{5, 5, 1000}, {5, 5, 20}},      {{300, 300, 1}, {15, 15, 2}}, {{1, 300, 300}, {2, 15, 15}}};
  for (const auto& [spread, size] : layouts) {
    for (const double gap : {0.0, 0.5}) {
      std::vector<Bnd_Box> boxes = random_boxes(random, 400, spread, size);
      boxes[17].SetVoid();  // void boxes meet nothing
      const BroadPhase found = broad_phase(boxes, gap);
      ASSERT_TRUE(found.status.ok()) << found.status.describe();
      EXPECT_EQ(found.pairs, brute_force_pairs(boxes, gap))
          << "spread " << spread.X() << "," << spread.Y() << "," << spread.Z() << " gap " << gap;
    }
  }
}

TEST(BroadPhase, StopsBeyondTheLimitSayingHowToRaiseIt) {
  std::vector<Bnd_Box> boxes(200);
  for (Bnd_Box& box : boxes) box.Update(0, 0, 0, 1, 1, 1);  // 200 copies in one place: 19,900 pairs
  const BroadPhase limited = broad_phase(boxes, 0, 1000);
  EXPECT_EQ(limited.status.code, StatusCode::InvalidInput);
  EXPECT_NE(limited.status.message.find("more than 1000 body pairs"), std::string::npos) << limited.status.message;
  EXPECT_NE(limited.status.message.find("up to 19900"), std::string::npos) << limited.status.message;
  EXPECT_NE(limited.status.message.find("--max-pairs"), std::string::npos) << limited.status.message;
  EXPECT_EQ(limited.pairs.size(), 1001u);  // enumeration stopped, memory bounded
  const BroadPhase raised = broad_phase(boxes, 0, 19900);
  ASSERT_TRUE(raised.status.ok());
  EXPECT_EQ(raised.pairs.size(), 19900u);
}

// ------------------------------------------------------------- assemblies

TopoDS_Shape plate_with_hole() {
  const TopoDS_Shape plate = BRepPrimAPI_MakeBox(40, 20, 5).Shape();
  const TopoDS_Shape hole = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(10, 10, -1), gp_Dir(0, 0, 1)), 3, 7).Shape();
  return BRepAlgoAPI_Cut(plate, hole).Shape();
}

TopoDS_Shape placed(const TopoDS_Shape& shape, const gp_Trsf& motion) { return shape.Moved(TopLoc_Location(motion)); }

// A tower of one plate instanced under rotations about z and its pins: one
// TShape each, placed by rigid motions that are not translations.
Assembly rotated_instances() {
  const TopoDS_Shape plate = plate_with_hole();
  // Pins shorter than the plates are thick: their ends touch nothing.
  const TopoDS_Shape pin = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(10, 10, 0.5), gp_Dir(0, 0, 1)), 3, 4).Shape();
  Assembly assembly;
  for (int level = 0; level < 6; ++level) {
    gp_Trsf turn, lift, motion;
    turn.SetRotation(gp_Ax1(gp_Pnt(10, 10, 0), gp_Dir(0, 0, 1)), 0.7 * level);
    lift.SetTranslation(gp_Vec(0, 0, 5.0 * level));
    motion = lift * turn;
    const std::string n = std::to_string(level);
    assembly.bodies.push_back({"plate" + n, "plate" + n, placed(plate, motion)});
    assembly.bodies.push_back({"pin" + n, "pin" + n, placed(pin, lift)});
  }
  return assembly;
}

ContactsResult run(const Assembly& assembly, int threads, bool reuse = true) {
  ContactOptions options;
  options.threads = threads;
  options.reuse_instances = reuse;
  ContactsResult result = find_contacts(assembly, options);
  EXPECT_TRUE(result.status.ok()) << result.status.describe();
  return result;
}

bool same_box(const Bnd_Box& a, const Bnd_Box& b) {
  if (a.IsVoid() || b.IsVoid()) return a.IsVoid() == b.IsVoid();
  double a0, a1, a2, a3, a4, a5, b0, b1, b2, b3, b4, b5;
  a.Get(a0, a1, a2, a3, a4, a5);
  b.Get(b0, b1, b2, b3, b4, b5);
  return a0 == b0 && a1 == b1 && a2 == b2 && a3 == b3 && a4 == b4 && a5 == b5;
}

// Parallel and serial runs do the same arithmetic: everything equal exactly.
void expect_identical(const ContactsResult& serial, const ContactsResult& parallel, const std::string& what) {
  ASSERT_EQ(serial.partitions.size(), parallel.partitions.size()) << what;
  for (std::size_t i = 0; i < serial.partitions.size(); ++i) {
    const BodyPartitions& s = serial.partitions[i];
    const BodyPartitions& p = parallel.partitions[i];
    ASSERT_EQ(s.faces.size(), p.faces.size()) << what << " body " << i;
    ASSERT_EQ(s.partitions.size(), p.partitions.size()) << what << " body " << i;
    EXPECT_TRUE(same_box(s.box, p.box)) << what << " body " << i;
    for (std::size_t k = 0; k < s.partitions.size(); ++k) {
      const Partition& a = s.partitions[k];
      const Partition& b = p.partitions[k];
      EXPECT_EQ(a.faces, b.faces) << what << " body " << i << " partition " << k;
      EXPECT_EQ(a.params.kind, b.params.kind);
      EXPECT_EQ(a.side, b.side);
      EXPECT_EQ(a.area, b.area);
      EXPECT_TRUE(a.params.location.IsEqual(b.params.location, 0)) << what << " body " << i << " partition " << k;
      EXPECT_TRUE(a.params.axis.IsEqual(b.params.axis, 0));
      EXPECT_EQ(a.params.radius, b.params.radius);
      EXPECT_TRUE(same_box(a.box, b.box)) << what << " body " << i << " partition " << k;
    }
  }
  EXPECT_EQ(serial.body_pairs, parallel.body_pairs) << what;
  EXPECT_EQ(serial.candidates, parallel.candidates) << what;
  ASSERT_EQ(serial.contacts.size(), parallel.contacts.size()) << what;
  for (std::size_t k = 0; k < serial.contacts.size(); ++k) {
    const Contact& a = serial.contacts[k];
    const Contact& b = parallel.contacts[k];
    EXPECT_EQ(a.type, b.type) << what << " contact " << k;
    EXPECT_EQ(a.body_a, b.body_a) << what << " contact " << k;
    EXPECT_EQ(a.body_b, b.body_b);
    EXPECT_EQ(a.partition_a, b.partition_a);
    EXPECT_EQ(a.partition_b, b.partition_b);
    EXPECT_EQ(a.faces_a, b.faces_a);
    EXPECT_EQ(a.faces_b, b.faces_b);
    EXPECT_EQ(a.area, b.area) << what << " contact " << k;
    EXPECT_EQ(a.radius, b.radius);
    EXPECT_EQ(a.span, b.span);
    EXPECT_EQ(a.partial, b.partial);
    EXPECT_TRUE(a.point.IsEqual(b.point, 0));
    EXPECT_TRUE(a.direction.IsEqual(b.direction, 0));
  }
  EXPECT_EQ(serial.skipped.size(), parallel.skipped.size()) << what;
}

// Many parallel runs (more threads than cores, to vary the interleavings),
// each equal to the serial run; with instances reused, and without (then
// bodies sharing TShapes are partitioned concurrently).
void expect_parallel_equals_serial(const Assembly& assembly, const std::string& what, int runs) {
  for (const bool reuse : {true, false}) {
    const ContactsResult serial = run(assembly, 1, reuse);
    for (int r = 0; r < runs; ++r)
      expect_identical(serial, run(assembly, 2 + r % 7, reuse),
                       what + (reuse ? "" : " (no reuse)") + " run " + std::to_string(r));
  }
}

TEST(Driver, ParallelEqualsSerialOnTheMotor) {
  const AssemblyResult read = read_step(sample("motor.step"));
  ASSERT_TRUE(read.status.ok()) << read.status.describe();
  expect_parallel_equals_serial(read.assembly, "motor", 30);
}

TEST(Driver, ParallelEqualsSerialOnRotatedInstances) {
  expect_parallel_equals_serial(rotated_instances(), "rotated instances", 30);
}

// 100 bodies of two shapes: many concurrent readers of each TShape.
TEST(Driver, ParallelEqualsSerialOnABoltedGrid) {
  const AssemblyResult read = read_step(sample("families/bolted_grid_100.step"));
  ASSERT_TRUE(read.status.ok()) << read.status.describe();
  expect_parallel_equals_serial(read.assembly, "bolted grid 100", 10);
}

TEST(Driver, ParallelEqualsSerialOnTheSharedFiles) {
  for (const char* name : {"R01_as1-oc-214.stp", "R05_SKF_6004.stp", "R06_bearing_20x37x9_freecad.stp",
                           "R08_presse_asm.step", "R09_chrono_assembly.stp", "R10_wrenchnut.stp",
                           "D03_asm4_tuto2_disk_arm.step"}) {
    const std::string path = shared_step(name);
    CONTACTS_REQUIRE_FILE(path);
    const AssemblyResult read = read_step(path);
    ASSERT_TRUE(read.status.ok()) << read.status.describe();
    expect_parallel_equals_serial(read.assembly, name, 5);
  }
}

// Instances moved from the first placement of their shape give the contacts
// that partitioning every body on its own gives (to rounding).
void expect_same_contacts(const ContactsResult& direct, const ContactsResult& reused, const std::string& what) {
  ASSERT_EQ(direct.contacts.size(), reused.contacts.size()) << what;
  for (std::size_t k = 0; k < direct.contacts.size(); ++k) {
    const Contact& a = direct.contacts[k];
    const Contact& b = reused.contacts[k];
    EXPECT_EQ(a.partition_a, b.partition_a) << what << " contact " << k;
    EXPECT_EQ(a.partition_b, b.partition_b) << what << " contact " << k;
    EXPECT_EQ(a.type, b.type) << what << " contact " << k;
    EXPECT_EQ(a.body_a, b.body_a) << what << " contact " << k;
    EXPECT_EQ(a.body_b, b.body_b);
    EXPECT_EQ(a.faces_a, b.faces_a);
    EXPECT_EQ(a.faces_b, b.faces_b);
    // Curved plane outlines are cut by a chordal tolerance on a grid of the
    // plane's own frame: a rotated copy agrees to that error, not to rounding.
    EXPECT_NEAR(a.area, b.area, 1e-5 * std::max(1.0, a.area)) << what << " contact " << k;
    EXPECT_NEAR(a.radius, b.radius, 1e-9);
    EXPECT_EQ(a.partial, b.partial);
    if (a.type == ContactType::PLF) {
      // "A point of the common area": the box centre of the smaller face,
      // which of two equal faces hangs on rounding. Both on the plane.
      EXPECT_LT(std::abs(gp_Vec(a.point, b.point).Dot(gp_Vec(a.direction))), 1e-6) << what << " contact " << k;
    } else {
      EXPECT_LT(a.point.Distance(b.point), 1e-6) << what << " contact " << k;
    }
    EXPECT_LT(a.direction.Angle(b.direction), 1e-9);
  }
}

TEST(Driver, InstancesMovedEqualInstancesPartitioned) {
  const Assembly rotated = rotated_instances();
  const std::vector<int> sources = instance_sources(rotated.bodies);
  EXPECT_EQ(sources, (std::vector<int>{0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1}));
  const ContactsResult direct = run(rotated, 1, false);
  // Each plate sits on the one below (5 PLF), each pin fills its plate's hole (6 CLJ).
  EXPECT_EQ(direct.contacts.size(), 5u + 6u);
  expect_same_contacts(direct, run(rotated, 0, true), "rotated instances");
  for (const char* name : {"motor.step", "families/bolted_grid_100.step"}) {
    const AssemblyResult read = read_step(sample(name));
    ASSERT_TRUE(read.status.ok()) << read.status.describe();
    expect_same_contacts(run(read.assembly, 1, false), run(read.assembly, 0, true), name);
  }
}

// Area of an outline loop: Green on the chords plus the bulges.
double loop_area(const Polygon2& loop) {
  double twice = 0;
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const Point2 &p = loop[k], &q = loop[(k + 1) % loop.size()];
    twice += p.x * q.y - q.x * p.y + p.bulge;
  }
  return twice / 2;
}

// Plane outlines are stored once: a one-face partition holds its face's
// loops, an instance its source's (the same storage), and they are the
// outlines the instance gets when partitioned on its own.
TEST(Driver, OutlinesAreStoredOnce) {
  const Assembly rotated = rotated_instances();
  const ContactsResult shared = run(rotated, 0, true), own = run(rotated, 1, false);
  int planes = 0;
  for (std::size_t i = 0; i < rotated.bodies.size(); ++i) {
    const BodyPartitions& body = shared.partitions[i];
    const BodyPartitions& source = shared.partitions[shared.instance_of[i]];
    for (std::size_t f = 0; f < body.faces.size(); ++f) {
      const Outline& outline = body.faces[f].extent.outline;
      if (body.faces[f].params.kind != SurfaceKind::Plane) {
        EXPECT_TRUE(outline.empty());
        continue;
      }
      ++planes;
      ASSERT_FALSE(outline.empty()) << rotated.bodies[i].name << " Face" << f + 1;
      EXPECT_EQ(&outline.loops(), &source.faces[f].extent.outline.loops()) << rotated.bodies[i].name;
      // A turned instance partitioned on its own cuts its arcs elsewhere:
      // the same loops and area, not the same points.
      const std::vector<Polygon2>& alone = own.partitions[i].faces[f].extent.outline;
      ASSERT_EQ(outline.size(), alone.size());
      for (std::size_t l = 0; l < alone.size(); ++l)
        EXPECT_NEAR(loop_area(outline[l]), loop_area(alone[l]), 1e-9 * std::abs(loop_area(alone[l])));
    }
    for (const Partition& partition : body.partitions) {
      if (partition.faces.size() == 1 && partition.params.kind == SurfaceKind::Plane)
        EXPECT_EQ(&partition.extent.outline.loops(), &body.faces[partition.faces[0] - 1].extent.outline.loops());
    }
  }
  EXPECT_EQ(planes, 6 * 6 + 6 * 2);  // a plate (box with a hole): six planar faces; a pin: two
}

// (OCCT 7.6 forbids scaled and mirrored locations on shapes: Moved raises,
// so only orientation can tell two placements of one TShape apart.)
TEST(Driver, ReversedPlacementsArePartitionedOnTheirOwn) {
  const TopoDS_Shape plate = plate_with_hole();
  gp_Trsf shift;
  shift.SetTranslation(gp_Vec(100, 0, 0));
  Assembly assembly;
  assembly.bodies.push_back({"a", "a", plate});

  assembly.bodies.push_back({"moved", "moved", placed(plate, shift)});
  assembly.bodies.push_back({"reversed", "reversed", plate.Reversed()});
  EXPECT_EQ(instance_sources(assembly.bodies), (std::vector<int>{0, 0, 2}));
}

// ------------------------------------------------------------- failures

Assembly three_stacked_boxes() {
  Assembly assembly;
  for (int i = 0; i < 3; ++i) {
    const std::string name = "box" + std::to_string(i);
    assembly.bodies.push_back({name, name, BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 10.0 * i), 10, 10, 10).Shape()});
  }
  return assembly;
}

TEST(Driver, AFailingPairIsSkippedAndTheRestKept) {
  const Assembly assembly = three_stacked_boxes();
  for (const int threads : {1, 3}) {
    for (const bool occt : {true, false}) {
      ContactOptions options;
      options.threads = threads;
      // MakeBox's faces: Face5 bottom, Face6 top; one partition each (ids 4, 5).
      options.candidate_hook = [occt](int body_a, int partition_a, int body_b, int partition_b) {
        if (body_a == 1 && partition_a == 5 && body_b == 2 && partition_b == 4) {
          if (occt) throw Standard_Failure("deliberate failure");
          throw std::runtime_error("deliberate failure");
        }
      };
      const ContactsResult result = find_contacts(assembly, options);
      ASSERT_TRUE(result.status.ok()) << result.status.describe();
      ASSERT_EQ(result.contacts.size(), 1u);  // box0-box1 kept
      EXPECT_EQ(result.contacts[0].body_a, 0);
      EXPECT_EQ(result.contacts[0].body_b, 1);
      ASSERT_EQ(result.skipped.size(), 1u);  // top of 1 on bottom of 2; its coplanar sides tested and kept
      const SkippedPair& skipped = result.skipped[0];
      EXPECT_EQ(skipped.body_a, 1);
      EXPECT_EQ(skipped.body_b, 2);
      EXPECT_EQ(skipped.partition_a, 5);
      EXPECT_EQ(skipped.partition_b, 4);
      EXPECT_EQ(skipped.faces_a, std::vector<int>{6});
      EXPECT_EQ(skipped.faces_b, std::vector<int>{5});
      EXPECT_EQ(skipped.message, occt ? "OCCT: deliberate failure" : "deliberate failure");
      ASSERT_EQ(result.messages.size(), 1u);
      const std::string expected = "skipped the candidate pair 'box1' Face" + std::to_string(skipped.faces_a[0]) +
                                   " / 'box2' Face" + std::to_string(skipped.faces_b[0]) + ": " + skipped.message;
      EXPECT_EQ(result.messages[0], expected);
    }
  }
}

// The same pair's test faulting inside OCCT (a null dereference, SIGSEGV):
// skipped with the signal's message under OCCT's handler, the other pairs
// kept, on one thread and on worker threads; the process's handlers are
// given back.
TEST(Driver, ASignalInsideOcctSkipsThePairAndTheRestKept) {
  const Assembly assembly = three_stacked_boxes();
  { const OcctGuard first; }  // glibc reports flags as set once any handler was (SA_RESTORER)
  struct sigaction before;
  sigaction(SIGSEGV, nullptr, &before);
  for (const int threads : {1, 3}) {
    ContactOptions options;
    options.threads = threads;
    options.candidate_hook = [](int body_a, int partition_a, int body_b, int partition_b) {
      if (body_a == 1 && partition_a == 5 && body_b == 2 && partition_b == 4)
        contactcore::testing::dereference_null_inside_occt();
    };
    const ContactsResult result = find_contacts(assembly, options);
    ASSERT_TRUE(result.status.ok()) << result.status.describe();
    ASSERT_EQ(result.contacts.size(), 1u);  // box0-box1 kept
    EXPECT_EQ(result.contacts[0].body_a, 0);
    EXPECT_EQ(result.contacts[0].body_b, 1);
    ASSERT_EQ(result.skipped.size(), 1u);
    EXPECT_EQ(result.skipped[0].body_a, 1);
    EXPECT_EQ(result.skipped[0].partition_a, 5);
    EXPECT_EQ(result.skipped[0].body_b, 2);
    EXPECT_EQ(result.skipped[0].partition_b, 4);
    EXPECT_EQ(result.skipped[0].message.rfind("OCCT: SIGSEGV", 0), 0u) << result.skipped[0].message;
    struct sigaction after;
    sigaction(SIGSEGV, nullptr, &after);
    EXPECT_EQ(reinterpret_cast<void*>(after.sa_sigaction), reinterpret_cast<void*>(before.sa_sigaction));
    EXPECT_EQ(after.sa_flags, before.sa_flags);
  }
}

TEST(Driver, TooManyOverlappingBodiesStopWithAClearStatus) {
  Assembly assembly;
  const TopoDS_Shape part = BRepPrimAPI_MakeBox(10, 10, 10).Shape();
  for (int i = 0; i < 300; ++i) assembly.bodies.push_back({"copy", "copy", part});  // 44,850 pairs
  ContactOptions options;
  options.max_body_pairs = 1000;
  const ContactsResult result = find_contacts(assembly, options);
  EXPECT_EQ(result.status.code, StatusCode::InvalidInput);
  EXPECT_NE(result.status.message.find("more than 1000 body pairs"), std::string::npos) << result.status.message;
  EXPECT_TRUE(result.contacts.empty());
}

// Cancels the first time `stage` is reported; counts the reports after that.
struct CancelAt : Progress {
  explicit CancelAt(std::string s) : stage(std::move(s)) {}
  bool report(const char* reported, double) override {
    if (cancelled) ++after;
    if (stage == reported) cancelled = true;
    return !cancelled;
  }
  std::string stage;
  bool cancelled = false;
  int after = 0;
};

TEST(Driver, EveryStageReportsAndCancels) {
  const AssemblyResult read = read_step(sample("motor.step"));
  ASSERT_TRUE(read.status.ok());
  for (const int threads : {1, 2}) {
    for (const char* stage : {"partitions", "broad phase", "candidates", "contacts"}) {
      CancelAt progress(stage);
      ContactOptions options;
      options.threads = threads;
      const ContactsResult result = find_contacts(read.assembly, options, &progress);
      EXPECT_TRUE(progress.cancelled) << stage << " was never reported";
      EXPECT_EQ(result.status.code, StatusCode::Cancelled) << stage;
      EXPECT_EQ(progress.after, 0) << stage << ": work went on after the cancel";
    }
  }
}

}  // namespace
