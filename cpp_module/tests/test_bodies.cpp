#include <gtest/gtest.h>

#include <BRepGProp.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <GProp_GProps.hxx>
#include <STEPControl_Writer.hxx>
#include <fstream>
#include <sstream>
#include <TopExp_Explorer.hxx>
#include <algorithm>
#include <set>
#include <vector>
#include <gp_Ax1.hxx>
#include <gp_Trsf.hxx>

#include "contactcore/bodies/assembly_of_bodies.h"
#include "contactcore/bodies/bodies.h"
#include "test_helpers.h"

using namespace contactcore;
using contactcore::testing::shared_step;

namespace {
int count_faces(const TopoDS_Shape& shape) {
  int n = 0;
  for (TopExp_Explorer it(shape, TopAbs_FACE); it.More(); it.Next()) ++n;
  return n;
}
}  // namespace

TEST(Bodies, BrepRoundTripKeepsVolumeAndPlacement) {
  gp_Trsf move;
  move.SetTranslation(gp_Vec(10, 20, 30));
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(1, 2, 3).Shape().Moved(TopLoc_Location(move));
  TopoDS_Shape back;
  ASSERT_TRUE(shape_from_brep(shape_to_brep(box), back).ok());
  const MassProperties props = mass_properties(back);
  EXPECT_NEAR(props.volume, 6.0, 1e-9);
  EXPECT_NEAR(props.centre.X(), 10.5, 1e-9);
  EXPECT_NEAR(props.centre.Z(), 31.5, 1e-9);
}

TEST(Bodies, BadBrepIsAnErrorNotACrash) {
  TopoDS_Shape shape;
  const Status status = shape_from_brep("this is not a BRep", shape);
  EXPECT_EQ(status.code, StatusCode::InvalidInput);
}

TEST(Bodies, MeshedShapeBrepIsReadable) {
  // A shape meshed once (meshes, simulation models) carries its triangulation
  // into its BRep text, with "p" marks the damaged-number check must accept.
  const TopoDS_Shape cylinder = BRepPrimAPI_MakeCylinder(2.0, 5.0).Shape();
  BRepMesh_IncrementalMesh(cylinder, 0.05);
  const std::string text = shape_to_brep(cylinder);
  ASSERT_NE(text.find("\np "), std::string::npos);
  TopoDS_Shape back;
  ASSERT_TRUE(shape_from_brep(text, back).ok());
  EXPECT_NEAR(mass_properties(back).volume, M_PI * 4.0 * 5.0, 1e-6);
}

TEST(Bodies, CompoundChildrenBecomeNamedBodies) {
  Assembly source;
  source.bodies.push_back({"a", "a", BRepPrimAPI_MakeBox(1, 1, 1).Shape()});
  source.bodies.push_back({"b", "b", BRepPrimAPI_MakeBox(2, 2, 2).Shape()});
  const AssemblyResult result = bodies_from_brep(shape_to_brep(assembly_compound(source)), {"first", "first"});
  ASSERT_TRUE(result.status.ok());
  ASSERT_EQ(result.assembly.bodies.size(), 2u);
  EXPECT_EQ(result.assembly.bodies[0].name, "first");
  EXPECT_EQ(result.assembly.bodies[1].name, "first.2");
  EXPECT_NEAR(mass_properties(result.assembly.bodies[1].shape).volume, 8.0, 1e-9);
}

// Bodies read before, gathered (a recompute's unchanged bodies): the shapes
// and their mass caches kept as they are, named as bodies_from_brep names the
// children of a compound; a count that differs or a body without a shape is
// an error value naming it.
TEST(Bodies, AssemblyOfBodiesKeepsShapesAndNamesThemAsACompoundRead) {
  Assembly source;
  source.bodies.push_back({"a", "a", BRepPrimAPI_MakeBox(1, 1, 1).Shape()});
  source.bodies.push_back({"b", "b", BRepPrimAPI_MakeBox(2, 2, 2).Shape()});
  const AssemblyResult read = bodies_from_brep(shape_to_brep(assembly_compound(source)), {"x", "y"});
  ASSERT_TRUE(read.status.ok());
  EXPECT_NEAR(read.assembly.bodies[1].mass().volume, 8.0, 1e-9);  // filled once, shared by the copies below
  const AssemblyResult gathered =
      assembly_of_bodies({read.assembly.bodies[1], read.assembly.bodies[0], read.assembly.bodies[1]}, {"first", "first", "first"});
  ASSERT_TRUE(gathered.status.ok());
  ASSERT_EQ(gathered.assembly.bodies.size(), 3u);
  const AssemblyResult compound = bodies_from_brep(
      shape_to_brep(assembly_compound(gathered.assembly)), {"first", "first", "first"});
  ASSERT_TRUE(compound.status.ok());
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(gathered.assembly.bodies[i].name, compound.assembly.bodies[i].name);
    EXPECT_EQ(gathered.assembly.bodies[i].path, "first");
  }
  EXPECT_EQ(gathered.assembly.bodies[2].name, "first.3");
  EXPECT_TRUE(gathered.assembly.bodies[0].shape.IsEqual(read.assembly.bodies[1].shape));
  EXPECT_TRUE(gathered.assembly.bodies[1].shape.IsEqual(read.assembly.bodies[0].shape));
  EXPECT_EQ(gathered.assembly.bodies[0].mass_cache.get(), read.assembly.bodies[1].mass_cache.get());
  EXPECT_EQ(gathered.assembly.units, "mm");
  EXPECT_TRUE(gathered.assembly.messages.empty());

  const AssemblyResult miscounted = assembly_of_bodies(read.assembly.bodies, {"only"});
  EXPECT_EQ(miscounted.status.code, StatusCode::InvalidArgument);
  EXPECT_EQ(miscounted.status.message, "2 bodies but 1 names");
  const AssemblyResult empty = assembly_of_bodies({read.assembly.bodies[0], Body{}}, {"a", "hollow"});
  EXPECT_EQ(empty.status.code, StatusCode::InvalidArgument);
  EXPECT_EQ(empty.status.body, "hollow");
}

TEST(Bodies, NamesMadeUniqueWithoutClashes) {
  std::vector<Body> bodies{{"A", "", {}}, {"A", "", {}}, {"A.2", "", {}}};
  make_names_unique(bodies);
  EXPECT_EQ(bodies[0].name, "A");
  EXPECT_EQ(bodies[1].name, "A.2");
  EXPECT_EQ(bodies[2].name, "A.2.2");
}

// Thousands of identical screws are normal: 8,000 same-named instances get
// the suffixes in order, every one distinct, and a name already taken by
// hand keeps its place.
TEST(Bodies, ManySameNamedInstancesGetUniqueNamesInOrder) {
  std::vector<std::string> names(8000, "Screw");
  names.insert(names.begin() + 1, "Screw.3");
  const std::vector<std::string> unique = unique_names(names);
  ASSERT_EQ(unique.size(), names.size());
  EXPECT_EQ(unique[0], "Screw");
  EXPECT_EQ(unique[1], "Screw.3");
  EXPECT_EQ(unique[2], "Screw.2");
  EXPECT_EQ(unique[3], "Screw.4");  // .3 was taken
  EXPECT_EQ(unique.back(), "Screw.8001");
  EXPECT_EQ(std::set<std::string>(unique.begin(), unique.end()).size(), unique.size());
}

// Volumes and centres computed once for all bodies (each shared shape once,
// moved to its other placements) equal each body's own computation.
TEST(Bodies, MassPropertiesOfInstancesEqualTheirOwn) {
  const TopoDS_Shape part = BRepPrimAPI_MakeBox(gp_Pnt(1, 2, 3), 4, 5, 6).Shape();
  Assembly assembly;
  for (int i = 0; i < 20; ++i) {
    gp_Trsf turn, shift;
    turn.SetRotation(gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(1, 1, 0)), 0.3 * i);
    shift.SetTranslation(gp_Vec(10.0 * i, -3.0 * i, 7));
    assembly.bodies.push_back({"part", "part", part.Moved(TopLoc_Location(shift * turn))});
  }
  assembly.bodies.push_back({"other", "other", BRepPrimAPI_MakeBox(2, 2, 2).Shape()});
  ASSERT_TRUE(compute_mass_properties(assembly, 3).ok());
  for (const Body& body : assembly.bodies) {
    const MassProperties own = mass_properties(body.shape);
    EXPECT_NEAR(body.mass().volume, own.volume, 1e-9 * own.volume) << body.name;
    EXPECT_LT(body.mass().centre.Distance(own.centre), 1e-9) << body.name;
  }
  EXPECT_NEAR(assembly.bodies[0].mass().volume, 120.0, 1e-9);
  const Body copy = assembly.bodies[5];  // copies share the cache
  EXPECT_EQ(&copy.mass(), &assembly.bodies[5].mass());
}

TEST(Bodies, MissingStepFileIsAReadError) {
  const AssemblyResult result = read_step("/nonexistent/file.step");
  EXPECT_EQ(result.status.code, StatusCode::ReadError);
  EXPECT_NE(result.status.describe().find("/nonexistent/file.step"), std::string::npos);
}

namespace {

// Records the read's fractions; cancels at the first one OCCT's transfer
// reports (strictly between 0.3 and 0.9: the read's own reports are 0, 0.3,
// the tree walk's after 0.9, and 1) when asked to.
struct TransferWatch : Progress {
  explicit TransferWatch(bool cancel_in_transfer) : cancel_in_transfer(cancel_in_transfer) {}
  bool report(const char* stage, double fraction) override {
    if (cancelled) ++after;
    if (std::string(stage) == "read") {
      fractions.push_back(fraction);
      if (cancel_in_transfer && fraction > 0.3 && fraction < 0.9) cancelled = true;
    }
    return !cancelled;
  }
  bool cancel_in_transfer;
  bool cancelled = false;
  int after = 0;
  std::vector<double> fractions;
};

}  // namespace

TEST(Bodies, StepTransferReportsProgressAndStopsOnCancel) {
  // The motor's transfer takes long enough for OCCT to be asked (every
  // 50 ms): its fractions climb from 0.3 to 0.9, and a cancel there stops
  // the read with no bodies.
  TransferWatch watch(false);
  const AssemblyResult read = read_step(contactcore::testing::sample("motor.step"), &watch);
  ASSERT_TRUE(read.status.ok()) << read.status.describe();
  EXPECT_EQ(read.assembly.bodies.size(), 18u);
  std::vector<double> inside;
  for (double f : watch.fractions)
    if (f > 0.3 && f < 0.9) inside.push_back(f);
  ASSERT_FALSE(inside.empty());
  EXPECT_TRUE(std::is_sorted(inside.begin(), inside.end()));
  EXPECT_EQ(watch.fractions.back(), 1.0);

  TransferWatch cancelling(true);
  const AssemblyResult cancelled = read_step(contactcore::testing::sample("motor.step"), &cancelling);
  EXPECT_TRUE(cancelling.cancelled);
  EXPECT_EQ(cancelled.status.code, StatusCode::Cancelled) << cancelled.status.describe();
  EXPECT_TRUE(cancelled.assembly.bodies.empty());
  EXPECT_EQ(cancelling.after, 0);
}

// A NaN in one vertex's point made OCCT 7.6's shape healing loop forever in
// the transfer, an infinite one dropped the body silently: points and
// directions that are not finite are refused before it, naming the entity.
TEST(Bodies, NonFiniteStepPointIsRefusedNamingTheEntity) {
  const std::string good = ::testing::TempDir() + "contacts_box.step";
  STEPControl_Writer writer;
  writer.Transfer(BRepPrimAPI_MakeBox(10, 10, 10).Shape(), STEPControl_AsIs);
  ASSERT_EQ(writer.Write(good.c_str()), IFSelect_RetDone);
  ASSERT_TRUE(read_step(good).status.ok());
  std::stringstream text;
  text << std::ifstream(good).rdbuf();
  const std::string box = text.str();
  const std::string prefix = "CARTESIAN_POINT('',(";
  const size_t at = box.rfind(prefix);
  const size_t first = at + prefix.size();
  const size_t hash = box.rfind('#', at);
  const std::string entity = box.substr(hash, box.find(' ', hash) - hash);
  for (const char* value : {"NAN", "1.E+400", "-1.E+400"}) {
    std::string damaged = box;
    damaged.replace(first, box.find(',', first) - first, value);
    const std::string bad = ::testing::TempDir() + "contacts_box_non_finite.step";
    std::ofstream(bad) << damaged;
    const AssemblyResult result = read_step(bad);
    EXPECT_EQ(result.status.code, StatusCode::InvalidInput) << value;
    EXPECT_NE(result.status.describe().find(entity + " (CARTESIAN_POINT)"), std::string::npos)
        << value << ": " << result.status.describe();
  }
}

// R09 places its second body through a legacy MAPPED_ITEM; a plain reader
// returns both roots twice. The XDE walk must give the 2 real bodies, in mm.
TEST(Bodies, ChronoAssemblyHasTwoBodiesWithoutDuplicates) {
  const std::string path = shared_step("R09_chrono_assembly.stp");
  CONTACTS_REQUIRE_FILE(path);
  const AssemblyResult result = read_step(path);
  ASSERT_TRUE(result.status.ok()) << result.status.describe();
  EXPECT_EQ(result.assembly.bodies.size(), 2u);
  EXPECT_EQ(result.assembly.units, "m");
  EXPECT_DOUBLE_EQ(result.assembly.source_unit_in_mm, 1000.0);
  for (const Body& body : result.assembly.bodies) EXPECT_GT(mass_properties(body.shape).volume, 0);
}

TEST(Bodies, As1HasItsEighteenSolids) {
  const std::string path = shared_step("R01_as1-oc-214.stp");
  CONTACTS_REQUIRE_FILE(path);
  const AssemblyResult result = read_step(path);
  ASSERT_TRUE(result.status.ok()) << result.status.describe();
  EXPECT_EQ(result.assembly.bodies.size(), 18u);
  std::set<std::string> names;
  for (const Body& body : result.assembly.bodies) names.insert(body.name);
  EXPECT_EQ(names.size(), result.assembly.bodies.size()) << "names must be unique";
}

// R08's thread cosmetics are open shells: skipped, with a message.
TEST(Bodies, PressSkipsOpenShellsWithAMessage) {
  const std::string path = shared_step("R08_presse_asm.step");
  CONTACTS_REQUIRE_FILE(path);
  const AssemblyResult result = read_step(path);
  ASSERT_TRUE(result.status.ok()) << result.status.describe();
  EXPECT_FALSE(result.assembly.messages.empty());
  for (const Body& body : result.assembly.bodies) {
    EXPECT_GT(count_faces(body.shape), 0);
    EXPECT_GT(mass_properties(body.shape).volume, 0) << body.name;
  }
}
