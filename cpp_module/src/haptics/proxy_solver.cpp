#include "contactcore/haptics/proxy_solver.h"

#include <algorithm>

#include <Eigen/Cholesky>

namespace contactcore::haptics {

namespace {
constexpr int kMaxRows = 40;
}

ProxyStep solve_proxy_step(const Vec6& desired, const Mat6& metric, const Mat6& basis, int free,
                           const ProxyConstraint* constraints, int count, int sweeps) {
  ProxyStep out;
  if (free <= 0) return out;
  using Cols = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>;
  using Square = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
  using Column = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;
  const Cols s = basis.leftCols(free);
  const Square h = s.transpose() * metric * s;
  const Eigen::LDLT<Square> ldlt(h);
  Column q = ldlt.solve(s.transpose() * (metric * desired));  // unconstrained: the hand's twist, projected
  count = std::min(count, kMaxRows);
  // Dual: multipliers >= 0; q = q0 + H^-1 A^T lambda.
  Column a[kMaxRows], h_inv_a[kMaxRows];
  double w[kMaxRows], lambda[kMaxRows];
  for (int k = 0; k < count; ++k) {
    a[k] = s.transpose() * constraints[k].row;
    h_inv_a[k] = ldlt.solve(a[k]);
    w[k] = a[k].dot(h_inv_a[k]);
    lambda[k] = 0;
  }
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    double change = 0;
    for (int k = 0; k < count; ++k) {
      if (w[k] <= 1e-14) continue;  // a constraint the free twists cannot act on
      const double residual = constraints[k].bound - a[k].dot(q);
      const double next = std::max(0.0, lambda[k] + residual / w[k]);
      const double delta = next - lambda[k];
      if (delta != 0) {
        q += delta * h_inv_a[k];
        lambda[k] = next;
        change = std::max(change, std::abs(delta) * w[k]);
      }
    }
    if (change < 1e-12) break;
  }
  out.twist = s * q;
  for (int k = 0; k < count; ++k) {
    if (lambda[k] > 0) ++out.active;
    out.load += lambda[k];
    if (w[k] > 1e-14) out.violation = std::max(out.violation, constraints[k].bound - constraints[k].row.dot(out.twist));
  }
  return out;
}

}  // namespace contactcore::haptics
