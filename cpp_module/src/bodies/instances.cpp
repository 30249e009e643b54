#include "contactcore/bodies/instances.h"

#include <cmath>
#include <unordered_map>

namespace contactcore {

namespace {

bool is_rigid(const gp_Trsf& motion) {
  return std::abs(motion.ScaleFactor() - 1.0) < 1e-12 && !motion.IsNegative();
}

}  // namespace

gp_Trsf relative_motion(const Body& from, const Body& to) {
  return to.shape.Location().Transformation().Multiplied(from.shape.Location().Transformation().Inverted());
}

std::vector<int> instance_sources(const std::vector<Body>& bodies) {
  std::vector<int> sources(bodies.size());
  std::unordered_map<const void*, std::vector<int>> seen;  // TShape -> bodies partitioned on their own
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    sources[i] = static_cast<int>(i);
    const TopoDS_Shape& shape = bodies[i].shape;
    if (shape.IsNull()) continue;
    std::vector<int>& firsts = seen[shape.TShape().get()];
    for (int first : firsts) {
      if (bodies[first].shape.Orientation() == shape.Orientation() &&
          is_rigid(relative_motion(bodies[first], bodies[i]))) {
        sources[i] = first;
        break;
      }
    }
    if (sources[i] == static_cast<int>(i)) firsts.push_back(static_cast<int>(i));
  }
  return sources;
}

}  // namespace contactcore
