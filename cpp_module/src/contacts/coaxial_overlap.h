// Stage 3 (contacts), part of the interference pass: the exact material two
// bodies share about one axis, from their typed faces alone (no Boolean),
// when one of them is a solid of revolution about that axis (a shaft or pin
// with its chamfers and shoulders) and the other is one too wherever the first
// can reach (a bore with its chamfered or counterbored mouths in a block whose
// other faces stay away). Press fits with chamfers, which the rings between
// the two cylinders undercount by up to 5 % (R08), are measured exactly.
#pragma once

#include <optional>

#include <TopoDS_Shape.hxx>
#include <gp_Ax1.hxx>

#include "contactcore/partitions/partitions.h"

namespace contactcore {

// The common volume (mm^3) of bodies `a` and `b` (their partitions and
// shapes) when, about `axis`, one of them has only planes across the axis and
// coaxial cylinders, cones, spheres centred on it and halves of coaxial torus
// tubes (tori stored as tori), and every face of the other within the first
// one's reach (each of its faces' axial range and largest radius, grown by a
// margin) is one of those too: then, at each axial position, both bodies are
// sets of radial intervals bounded by those faces, their common area a sum of
// rings, quadratic in z between the faces' ends and the crossings of their
// radii over cylinders, cones and spheres (two-point Gauss exact), smooth over
// torus halves (32 sub-slices). Which side of a radius is material comes from
// the face's material side; a section where the second body has no face within
// reach is classified once (BRepClass3d). std::nullopt when neither body
// qualifies (another face in reach, a B-spline not recognised): the caller
// falls back to a Boolean.
std::optional<double> coaxial_common_volume(const BodyPartitions& a, const TopoDS_Shape& shape_a,
                                            const BodyPartitions& b, const TopoDS_Shape& shape_b,
                                            const gp_Ax1& axis, const Tolerances& tol);

}  // namespace contactcore
