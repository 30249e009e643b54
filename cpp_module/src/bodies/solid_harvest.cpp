#include "bodies/solid_harvest.h"

#include <cmath>
#include <sstream>

#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>

namespace contactcore {

SolidHarvest harvest_solids(const TopoDS_Shape& shape) {
  SolidHarvest out;
  for (TopExp_Explorer it(shape, TopAbs_SOLID); it.More(); it.Next()) out.solids.push_back(it.Current());
  for (TopExp_Explorer it(shape, TopAbs_SHELL, TopAbs_SOLID); it.More(); it.Next()) {
    const TopoDS_Shell& shell = TopoDS::Shell(it.Current());
    if (BRep_Tool::IsClosed(shell)) {
      BRepBuilderAPI_MakeSolid make(shell);
      if (make.IsDone()) {
        out.solids.push_back(make.Solid());
        continue;
      }
    }
    ++out.open_shells;
  }
  for (TopExp_Explorer it(shape, TopAbs_FACE, TopAbs_SHELL); it.More(); it.Next()) ++out.loose_faces;
  return out;
}

std::string skipped_message(const std::string& name, const SolidHarvest& h) {
  std::ostringstream msg;
  msg << "skipped in '" << name << "':";
  if (h.open_shells) msg << ' ' << h.open_shells << " open shell(s)";
  if (h.loose_faces) msg << ' ' << h.loose_faces << " face(s) outside any shell";
  msg << " (surface model, not a solid)";
  return msg.str();
}

bool has_finite_box(const TopoDS_Shape& shape) {
  Bnd_Box box;
  BRepBndLib::Add(shape, box, false);
  if (box.IsVoid()) return true;
  double x0, y0, z0, x1, y1, z1;
  box.Get(x0, y0, z0, x1, y1, z1);
  for (double v : {x0, y0, z0, x1, y1, z1})
    if (!std::isfinite(v) || std::abs(v) >= 1e100) return false;
  return true;
}

}  // namespace contactcore
