// Stage 1: bodies. Every solid of an assembly with its global placement,
// whether it comes from FreeCAD (one BRep compound, one child per body) or
// from a STEP file read through OCCT's XDE reader (product names, instances,
// units, MAPPED_ITEM placements).
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <TopoDS_Shape.hxx>
#include <gp_Pnt.hxx>

#include "contactcore/common/errors.h"

namespace contactcore {

// Volume (mm^3) and centre of mass of a body's solid(s).
struct MassProperties {
  double volume = 0;
  gp_Pnt centre;
};

// Filled once, on first use (copies of a body share it).
struct MassCache {
  std::once_flag once;
  MassProperties value;
};

struct Body {
  std::string name;    // unique within the assembly
  std::string path;    // assembly tree path, "Root/Sub/Part" (STEP) or the caller's
  TopoDS_Shape shape;  // a solid (or compsolid/compound of solids), located globally
  std::shared_ptr<MassCache> mass_cache = std::make_shared<MassCache>();

  // Volume and centre of mass, computed on the first call only (thread-safe).
  const MassProperties& mass() const;
};

struct Assembly {
  std::vector<Body> bodies;
  std::string units = "mm";            // unit of the source file; shapes are always in mm
  double source_unit_in_mm = 1.0;      // 25.4 for an inch file
  std::vector<std::string> messages;   // what was skipped and why (open shells, ...)
  std::string reader;                  // STEP: "products" (the fast read) or "xde" (its fallback); else ""
};

struct AssemblyResult {
  Status status;
  Assembly assembly;
};

// How read_step brings a file's products in. Products: each product
// transferred once and its instances placed (time N log N at most in the
// parts), falling back to the XDE read, with a message and a progress stage
// "read (XDE fallback)", for a product structure it does not know. Xde:
// OCCT's XDE reader alone (time quadratic in the instances), as a reference.
// ProductsAsWritten: Products on the file's text as written, without the
// assemblies' lists of placements shortened for OCCT's parser (what the
// shortening changes is measured and tested against it).
enum class StepReadMode { Products, Xde, ProductsAsWritten };

// Reads a STEP file with names, instances and units (shapes converted to mm).
// Open shells and surface models are skipped with a message. Both modes give
// the same bodies (names, paths, placements) in the same order. An assembly
// that expands to more than `max_bodies` instances (or a set or mapped item to
// more items) is refused (InvalidInput) before OCCT's transfer expands it.
AssemblyResult read_step(const std::string& path, Progress* progress = nullptr,
                         StepReadMode mode = StepReadMode::Products, std::size_t max_bodies = 1'000'000);

// Splits a BRep string holding one compound into bodies: each direct child of
// the compound is one body, named by `names` (same order; missing names get
// "Body<N>"). A child without any solid is skipped with a message.
AssemblyResult bodies_from_brep(const std::string& brep, const std::vector<std::string>& names);

// Shapes <-> BRep text (the format of FreeCAD's exportBrepToString).
Status shape_from_brep(const std::string& brep, TopoDS_Shape& shape);
std::string shape_to_brep(const TopoDS_Shape& shape);

// One compound of all bodies' shapes (in order), e.g. to hand back to FreeCAD.
TopoDS_Shape assembly_compound(const Assembly& assembly);

// Volume and centre of mass of a shape, computed each call (Body::mass keeps them).
MassProperties mass_properties(const TopoDS_Shape& shape);

// Fills every body's mass cache on `threads` threads (0: all cores), each
// shared shape computed once and moved to its other placements. Reports
// "mass properties"; Cancelled when cancelled; a body whose computation
// fails inside OCCT (an exception or a signal) fails the call, named.
Status compute_mass_properties(const Assembly& assembly, int threads = 0, Progress* progress = nullptr);

// Names made unique by appending ".2", ".3", ... to repeats (the smallest
// suffix not yet taken), keeping order; linear time however many repeat.
std::vector<std::string> unique_names(const std::vector<std::string>& names);
void make_names_unique(std::vector<Body>& bodies);

}  // namespace contactcore
