// Shared by the collision test files: rigid placements as OCCT transforms,
// random ones for seeded pose sweeps, and a shape moved by one.
#pragma once

#include <random>

#include <BRepBuilderAPI_Transform.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Mat.hxx>
#include <gp_Quaternion.hxx>
#include <gp_Trsf.hxx>

#include "contactcore/simulation/collision.h"
#include "draw_order.h"

namespace contactcore::testing {

inline gp_Trsf to_gp(const RigidTransform& t) {
  gp_Trsf trsf;
  const auto& r = t.rotation;
  trsf.SetValues(r[0], r[1], r[2], t.translation[0], r[3], r[4], r[5], t.translation[1], r[6], r[7], r[8],
                 t.translation[2]);
  return trsf;
}

// A uniformly random rotation (normalised Gaussian quaternion) and a
// translation in [-spread, spread]^3.
inline RigidTransform random_placement(std::mt19937& rng, double spread) {
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(-spread, spread);
  const auto n = drawn_last_first<4>([&] { return normal(rng); });
  gp_Quaternion q(n[0], n[1], n[2], n[3]);
  q.Normalize();
  const gp_Mat m = q.GetMatrix();
  RigidTransform t;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) t.rotation[i * 3 + j] = m.Value(i + 1, j + 1);
  t.translation = {uniform(rng), uniform(rng), uniform(rng)};
  return t;
}

inline TopoDS_Shape placed(const TopoDS_Shape& shape, const RigidTransform& t) {
  return BRepBuilderAPI_Transform(shape, to_gp(t), true).Shape();
}

}  // namespace contactcore::testing
