// Internal to the partitions stage: edge discretisation and plane outlines
// (outlines.cpp). The public part (outline_in) is in partitions.h.
#pragma once

#include <vector>

#include <BRepAdaptor_Curve.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <gp_Dir.hxx>
#include <gp_Pnt.hxx>
#include <gp_XYZ.hxx>

#include "contactcore/partitions/partitions.h"

namespace contactcore::detail {

// Largest angle between two points of a discretised free-form curve (tangent
// turning); circles follow the chordal rule of plane_outline instead.
constexpr double kArcStep = 0.0236;

// Points along an edge's curve, both ends included, in the edge's direction
// when `reversed` is false, no two consecutive ones more than `arc_step` apart
// in tangent direction.
void discretise_curve(const BRepAdaptor_Curve& curve, bool reversed, std::vector<gp_Pnt>& points,
                      double arc_step = kArcStep);
void discretise_edge(const TopoDS_Edge& edge, std::vector<gp_Pnt>& points, double arc_step = kArcStep);

// FORWARD or REVERSED (INTERNAL and EXTERNAL edges bound nothing).
bool bounds_the_face(const TopoDS_Edge& edge);

// The direction from which the arcs of every face on a plane are cut: it
// depends on the plane's normal line only (either sign), so coincident
// circles of two faces facing each other get the same points.
gp_Dir canonical_plane_ref(const gp_Dir& normal);

// The outline of a planar face in the plane frame (origin, x_dir, y_dir):
// one loop per wire, outer loops counter-clockwise, holes clockwise. Arcs of
// circles are cut at angles k 2 pi / n from canonical_plane_ref (n a power of
// two, the chord at most `sag` from the arc, and at least 64 a turn) plus
// their ends; other curves by tangent turning. Every point carries the bulge
// of its boundary curve beyond the chord to the next point, so the outline's
// area (Green on the chords plus the bulges) is the face's exact area. With
// `area`, also that exact area, integrated on the curves themselves.
std::vector<Polygon2> plane_outline(const TopoDS_Face& face, const gp_XYZ& origin, const gp_XYZ& x_dir,
                                    const gp_XYZ& y_dir, double sag, double* area = nullptr);

// Signed area of a loop: chords and bulges.
double signed_area(const Polygon2& loop);

// The same loop run the other way (bulges follow their chords).
void reverse_loop(Polygon2& loop);

}  // namespace contactcore::detail
