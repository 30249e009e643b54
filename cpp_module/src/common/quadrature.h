// Common to the stages: Gauss quadrature on curve pieces and the boundary
// integral along a curve, shared by the exact face areas
// (partitions/face_typing.cpp), the plane outlines (partitions/outlines.cpp)
// and the signed volumes (contacts/signed_volume.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <GeomAbs_CurveType.hxx>
#include <GeomAbs_Shape.hxx>
#include "contactcore/common/angles.h"
#include <TColStd_Array1OfReal.hxx>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>

namespace contactcore::detail {

// The 8-point Gauss-Legendre rule on [-1, 1]: nodes +-kGaussNodes[i] with
// weight kGaussWeights[i] (the project's only copy of the table).
inline constexpr double kGaussNodes[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                          0.9602898564975363};
inline constexpr double kGaussWeights[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                            0.1012285362903763};

// 8-point Gauss-Legendre on [a, b].
template <class Integrand>
double gauss(double a, double b, Integrand f) {
  const double mid = (a + b) / 2, half = (b - a) / 2;
  double sum = 0;
  for (int i = 0; i < 4; ++i) sum += kGaussWeights[i] * (f(mid - half * kGaussNodes[i]) + f(mid + half * kGaussNodes[i]));
  return sum * half;
}

// The same rule's nodes on [a, b], ascending, each with its weight scaled to
// [a, b]: visit(t, weight). For integrands that are not a double (vectors),
// whose caller sums weight * f(t) itself.
template <class Visit>
void gauss_nodes(double a, double b, Visit visit) {
  const double mid = (a + b) / 2, half = (b - a) / 2;
  for (int i = 3; i >= 0; --i) visit(mid - half * kGaussNodes[i], kGaussWeights[i] * half);
  for (int i = 0; i < 4; ++i) visit(mid + half * kGaussNodes[i], kGaussWeights[i] * half);
}

// Break points of [first, last] such that 8-point Gauss is exact to round-off
// on each piece: lines whole, conics by eighths of a turn, B-splines span by
// span (every knot: a C2 spline is still piecewise), rational spans halved,
// anything else in 16 pieces.
template <class Curve>
void integration_pieces(const Curve& curve, double first, double last, std::vector<double>& breaks) {
  constexpr double kEighthTurn = kPi / 4;
  breaks.clear();
  auto uniform = [&](double a, double b, int pieces) {
    for (int i = 0; i < pieces; ++i) breaks.push_back(a + (b - a) * i / pieces);
  };
  switch (curve.GetType()) {
    case GeomAbs_Line: breaks.push_back(first); break;
    case GeomAbs_Circle:
    case GeomAbs_Ellipse: {
      // A damaged edge can span 4e11 rad: at most 1,024 pieces (a turn is 8),
      // counted as a double (an int overflows).
      const double eighths = std::ceil((last - first) / kEighthTurn);
      uniform(first, last, eighths >= 1 && eighths <= 1024 ? static_cast<int>(eighths) : eighths > 1024 ? 1024 : 1);
      break;
    }
    case GeomAbs_BSplineCurve:
    case GeomAbs_BezierCurve: {
      const int spans = curve.NbIntervals(GeomAbs_CN);
      TColStd_Array1OfReal knots(1, spans + 1);
      curve.Intervals(knots, GeomAbs_CN);
      const int pieces_per_span = curve.IsRational() ? 2 : 1;
      double previous = first;
      for (int i = 2; i <= spans + 1; ++i) {
        const double knot = std::min(knots(i), last);
        if (knot <= previous) continue;
        uniform(previous, knot, pieces_per_span);
        previous = knot;
      }
      if (previous < last) uniform(previous, last, pieces_per_span);
      break;
    }
    default: uniform(first, last, 16); break;
  }
  breaks.push_back(last);
}

// A boundary integral (Green, Stokes) along a whole 3D curve: the integral of
// f(p, dp/dt) over the curve's parameter range, 8-point Gauss on each of its
// integration_pieces (`breaks` is scratch space, kept to save allocations).
template <class Curve, class Integrand>
double curve_integral(const Curve& curve, std::vector<double>& breaks, Integrand f) {
  integration_pieces(curve, curve.FirstParameter(), curve.LastParameter(), breaks);
  double sum = 0;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    sum += gauss(breaks[i], breaks[i + 1], [&](double t) {
      gp_Pnt p;
      gp_Vec d;
      curve.D1(t, p, d);
      return f(p.XYZ(), d.XYZ());
    });
  }
  return sum;
}

}  // namespace contactcore::detail
