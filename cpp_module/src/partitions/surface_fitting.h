// Internal to the partitions stage: recognition of faces stored as free-form
// surfaces (B-spline, Bezier, offset, revolved or extruded) that are really a
// plane, cylinder, cone, sphere or torus, by fitting sampled points and
// normals (surface_fitting.cpp), and the sampling helpers face typing shares.
#pragma once

#include <utility>
#include <vector>

#include <BRepAdaptor_Surface.hxx>
#include <TopoDS_Face.hxx>
#include <gp_Dir.hxx>
#include <gp_XYZ.hxx>

#include "contactcore/partitions/partitions.h"

namespace contactcore::detail {

// Samples per parameter direction for fitting a free-form face; the fit is
// then checked on a grid twice as fine (the fitted points and the cell middles).
constexpr int kFitGrid = 7;
constexpr int kCheckGrid = 2 * kFitGrid - 1;

// Parameter range of a face on its surface, from its pcurves.
struct UVBounds {
  double u1 = 0, u2 = 0, v1 = 0, v2 = 0;
};
UVBounds uv_bounds(const TopoDS_Face& face);

// Two unit vectors completing `axis` to a right-handed frame.
std::pair<gp_XYZ, gp_XYZ> perpendicular_basis(const gp_Dir& axis);

// Distance of p from the line through `origin` along the unit vector `axis`.
double distance_to_axis(const gp_XYZ& p, const gp_XYZ& origin, const gp_XYZ& axis);

// Oriented unit normal and point of the face at (u, v); false at singular points.
bool oriented_normal(const BRepAdaptor_Surface& surface, bool reversed, double u, double v, gp_XYZ& point,
                     gp_XYZ& normal);

// The direction away from the "core" of a revolution surface at p: from the
// axis (cylinder, cone), the centre (sphere) or the tube centre (torus).
gp_XYZ away_from_core(const SurfaceParams& s, const gp_XYZ& p);

// Types a free-form face (params, side, recognised, max_deviation of `out`):
// surfaces swept from a line or a circle from their curve, others by trying
// plane, sphere, cylinder, cone and torus fits in that order; the first whose
// deviation on the check grid is within tolerance wins. False (nothing
// typed) when none fits.
bool recognise(const BRepAdaptor_Surface& surface, bool reversed, const UVBounds& uv, const Tolerances& tol,
               FaceInfo& out);

}  // namespace contactcore::detail
