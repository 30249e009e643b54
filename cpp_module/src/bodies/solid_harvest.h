// Stage 1 (bodies): the solids a shape holds, as both STEP reads and the
// BRep read take them (closed shells made solids, open ones counted).
#pragma once

#include <string>
#include <vector>

#include <TopoDS_Shape.hxx>

namespace contactcore {

// Solids of a shape, in explorer order. Closed shells that no solid holds are
// turned into solids (some exporters write solids as shell-based models);
// open shells and faces are counted so the caller can report them.
struct SolidHarvest {
  std::vector<TopoDS_Shape> solids;
  int open_shells = 0;
  int loose_faces = 0;
};

SolidHarvest harvest_solids(const TopoDS_Shape& shape);

// "skipped in 'NAME': 2 open shell(s) (surface model, not a solid)".
std::string skipped_message(const std::string& name, const SolidHarvest& harvest);

// False for a shape with NaN or infinite coordinates (a broken placement).
bool has_finite_box(const TopoDS_Shape& shape);

}  // namespace contactcore
