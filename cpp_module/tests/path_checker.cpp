#include "path_checker.h"

#include <algorithm>

#include <BRepAlgoAPI_Common.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepGProp.hxx>
#include <Bnd_Box.hxx>
#include <Bnd_OBB.hxx>
#include <GProp_GProps.hxx>
#include <TopTools_ListOfShape.hxx>
#include <gp_Trsf.hxx>

namespace contactcore::testing {

namespace {

gp_Trsf to_trsf(const haptics::Pose& pose) {
  gp_Trsf t;
  const auto& r = pose.linear();
  const auto& x = pose.translation();
  t.SetValues(r(0, 0), r(0, 1), r(0, 2), x.x(), r(1, 0), r(1, 1), r(1, 2), x.y(), r(2, 0), r(2, 1), r(2, 2), x.z());
  return t;
}

void overlap_at(const Assembly& assembly, int moving, const haptics::Pose& pose, double t, double volume_floor,
                PathOverlap& out) {
  const TopoDS_Shape placed = BRepBuilderAPI_Transform(assembly.bodies[moving].shape, to_trsf(pose), true).Shape();
  Bnd_Box part_box;
  BRepBndLib::Add(placed, part_box, false);
  for (std::size_t b = 0; b < assembly.bodies.size(); ++b) {
    if (static_cast<int>(b) == moving) continue;
    Bnd_Box other_box;
    BRepBndLib::Add(assembly.bodies[b].shape, other_box, false);
    if (part_box.IsOut(other_box)) continue;
    BRepAlgoAPI_Common common(placed, assembly.bodies[b].shape);
    if (!common.IsDone()) continue;
    const TopoDS_Shape& shape = common.Shape();
    GProp_GProps props;
    BRepGProp::VolumeProperties(shape, props);
    const double volume = std::abs(props.Mass());
    if (volume < volume_floor) continue;
    Bnd_OBB obb;
    BRepBndLib::AddOBB(shape, obb, false, true, false);
    const double depth = 2 * std::min({obb.XHSize(), obb.YHSize(), obb.ZHSize()});
    out.max_volume = std::max(out.max_volume, volume);
    if (depth > out.max_depth) {
      out.max_depth = depth;
      out.worst_t = t;
      out.worst_body = assembly.bodies[b].name;
    }
  }
  ++out.samples_checked;
}

int index_of(const Assembly& assembly, const std::string& part) {
  for (std::size_t i = 0; i < assembly.bodies.size(); ++i)
    if (assembly.bodies[i].name == part) return static_cast<int>(i);
  return -1;
}

haptics::Pose pose_of(const haptics::Vec3& translate, const haptics::Vec3& rotate_deg, const haptics::Vec3& centre) {
  using haptics::rad;
  return haptics::offset_pose(translate, haptics::Vec3(rad(rotate_deg.x()), rad(rotate_deg.y()), rad(rotate_deg.z())),
                              centre);
}

}  // namespace

PathOverlap check_path(const Assembly& assembly, const std::string& part, const haptics::Vec3& centre,
                       const std::vector<haptics::TrialSample>& path, int stride, double volume_floor) {
  PathOverlap out;
  const int moving = index_of(assembly, part);
  if (moving < 0) return out;
  stride = std::max(1, stride);
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (i % stride != 0 && i + 1 != path.size()) continue;
    overlap_at(assembly, moving, pose_of(path[i].translate, path[i].rotate_deg, centre), path[i].t, volume_floor, out);
  }
  return out;
}

PathOverlap check_pose(const Assembly& assembly, const std::string& part, const haptics::Vec3& centre,
                       const haptics::Vec3& translate, const haptics::Vec3& rotate_deg, double volume_floor) {
  PathOverlap out;
  const int moving = index_of(assembly, part);
  if (moving >= 0) overlap_at(assembly, moving, pose_of(translate, rotate_deg, centre), 0, volume_floor, out);
  return out;
}

}  // namespace contactcore::testing
