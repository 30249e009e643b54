// Common to the stages: Gauss quadrature on curve pieces, shared by the exact
// face areas (partitions/face_typing.cpp), the plane outlines
// (partitions/outlines.cpp) and the signed volumes (contacts/signed_volume.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <GeomAbs_CurveType.hxx>
#include <GeomAbs_Shape.hxx>
#include <TColStd_Array1OfReal.hxx>

namespace contactcore::detail {

// 8-point Gauss-Legendre on [a, b].
template <class Integrand>
double gauss(double a, double b, Integrand f) {
  static constexpr double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
  static constexpr double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
  const double mid = (a + b) / 2, half = (b - a) / 2;
  double sum = 0;
  for (int i = 0; i < 4; ++i) sum += w[i] * (f(mid - half * x[i]) + f(mid + half * x[i]));
  return sum * half;
}

// Break points of [first, last] such that 8-point Gauss is exact to round-off
// on each piece: lines whole, conics by eighths of a turn, B-splines span by
// span (every knot: a C2 spline is still piecewise), rational spans halved,
// anything else in 16 pieces.
template <class Curve>
void integration_pieces(const Curve& curve, double first, double last, std::vector<double>& breaks) {
  constexpr double kEighthTurn = 3.14159265358979323846 / 4;
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

}  // namespace contactcore::detail
