// Stage 1: bodies. Every solid of an assembly with its global placement,
// whether it comes from FreeCAD (one BRep compound, one child per body) or
// from a STEP file read through OCCT's XDE reader (product names, instances,
// units, MAPPED_ITEM placements).
#pragma once

#include <string>
#include <vector>

#include <TopoDS_Shape.hxx>
#include <gp_Pnt.hxx>

#include "contactcore/errors.h"

namespace contactcore {

struct Body {
  std::string name;    // unique within the assembly
  std::string path;    // assembly tree path, "Root/Sub/Part" (STEP) or the caller's
  TopoDS_Shape shape;  // a solid (or compsolid/compound of solids), located globally
};

struct Assembly {
  std::vector<Body> bodies;
  std::string units = "mm";            // unit of the source file; shapes are always in mm
  double source_unit_in_mm = 1.0;      // 25.4 for an inch file
  std::vector<std::string> messages;   // what was skipped and why (open shells, ...)
};

struct AssemblyResult {
  Status status;
  Assembly assembly;
};

// Reads a STEP file with names, instances and units (shapes converted to mm).
// Open shells and surface models are skipped with a message.
AssemblyResult read_step(const std::string& path, Progress* progress = nullptr);

// Splits a BRep string holding one compound into bodies: each direct child of
// the compound is one body, named by `names` (same order; missing names get
// "Body<N>"). A child without any solid is skipped with a message.
AssemblyResult bodies_from_brep(const std::string& brep, const std::vector<std::string>& names);

// Shapes <-> BRep text (the format of FreeCAD's exportBrepToString).
Status shape_from_brep(const std::string& brep, TopoDS_Shape& shape);
std::string shape_to_brep(const TopoDS_Shape& shape);

// One compound of all bodies' shapes (in order), e.g. to hand back to FreeCAD.
TopoDS_Shape assembly_compound(const Assembly& assembly);

// Volume (mm^3) and centre of mass of a body's solid(s).
struct MassProperties {
  double volume = 0;
  gp_Pnt centre;
};
MassProperties mass_properties(const TopoDS_Shape& shape);

// Makes names unique by appending ".2", ".3", ... to repeats, keeping order.
void make_names_unique(std::vector<Body>& bodies);

}  // namespace contactcore
