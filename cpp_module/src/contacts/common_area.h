// Stage 3 (contacts), the per-candidate part: for one pair of partitions of two bodies
// with the same surface parameters, the test of the contact it makes and its
// real common area (planes, cylinders and cones, spheres and tori, balls in
// bores and grooves). The driver in contacts.cpp calls test_candidate.
#pragma once

#include <vector>

#include <memory>

#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <Geom_Surface.hxx>
#include <Precision.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <gp_Vec.hxx>
#include <cmath>

#include "contactcore/contacts/contacts.h"

namespace contactcore {

// What every candidate test reads: all bodies' partitions and the tolerances.
struct PairContext {
  const std::vector<BodyPartitions>& parts;
  const Tolerances& tol;
  double min_area_ratio;
};

// Boxes that meet once one is grown by `gap` (void boxes never meet).
inline bool boxes_meet(const Bnd_Box& a, const Bnd_Box& b, double gap) {
  if (a.IsVoid() || b.IsVoid()) return false;
  Bnd_Box grown = a;
  grown.Enlarge(gap);
  return !grown.IsOut(b);
}

// Distance from p to the line through `origin` along `axis`.
inline double distance_to_line(const gp_Pnt& p, const gp_Pnt& origin, const gp_Dir& axis) {
  const gp_Vec v(origin, p);
  return v.Crossed(gp_Vec(axis)).Magnitude();
}

// A point on a face (within tolerance of its surface and inside its
// boundaries)? For samples of circle contacts. The projection gives
// parameters in the surface's natural period; the face's own range may be
// shifted by whole turns (u in [pi, 3 pi] is common in exported bearings), so
// periodic parameters are brought into the face's range before classifying.
class FaceProbe {
 public:
  explicit FaceProbe(const FaceInfo& info)
      : face_(info.face), surface_(BRep_Tool::Surface(info.face)), analysis_(surface_) {
    BRepTools::UVBounds(face_, u_min_, u_max_, v_min_, v_max_);
  }
  // Probes come in runs of nearby points (samples along a line, bisections):
  // the projection starts from the previous one's parameters (Newton; the
  // global search over the surface only when that misses: on a B-spline face
  // it costs a grid of distances per point), and the face's 2D classifier is
  // built once (BRepClass_FaceClassifier rebuilt it per point).
  bool contains(const gp_Pnt& p, double tol) {
    const gp_Pnt2d uv = has_last_ ? analysis_.NextValueOfUV(last_uv_, p, tol, tol) : analysis_.ValueOfUV(p, tol);
    if (analysis_.Gap() > tol) return false;
    last_uv_ = uv, has_last_ = true;
    const double u = into_range(uv.X(), u_min_, u_max_, surface_->IsUPeriodic() ? surface_->UPeriod() : 0);
    const double v = into_range(uv.Y(), v_min_, v_max_, surface_->IsVPeriodic() ? surface_->VPeriod() : 0);
    if (!classifier_) classifier_ = std::make_unique<BRepTopAdaptor_FClass2d>(face_, Precision::PConfusion());
    const TopAbs_State state = classifier_->Perform(gp_Pnt2d(u, v));
    return state == TopAbs_IN || state == TopAbs_ON;
  }

  // The value shifted by whole periods to lie in [low, high] when some shift
  // does (else the one closest to the middle of the range).
  static double into_range(double value, double low, double high, double period) {
    if (period <= 0) return value;
    const double middle = (low + high) / 2;
    return value + period * std::round((middle - value) / period);
  }

 private:
  TopoDS_Face face_;
  Handle(Geom_Surface) surface_;
  ShapeAnalysis_Surface analysis_;
  std::unique_ptr<BRepTopAdaptor_FClass2d> classifier_;
  gp_Pnt2d last_uv_;
  bool has_last_ = false;
  double u_min_ = 0, u_max_ = 0, v_min_ = 0, v_max_ = 0;
};

// The region two plane outlines (in one frame) have in common: its area
// (exact on arcs, by the chords' bulges) and the length of its boundary.
struct CommonRegion {
  double area = 0;
  double perimeter = 0;
};
CommonRegion common_region(const std::vector<Polygon2>& a, const std::vector<Polygon2>& b, double tol);

// The region two faces on the same surface have in common (OCCT's Boolean
// common of the two faces, fuzzy by the linear tolerance, arguments left
// untouched), each piece typed; a failed Boolean is a failed Status.
Status boolean_common(const TopoDS_Face& a, const TopoDS_Face& b, const Tolerances& tol,
                      std::vector<FaceInfo>& pieces);

// Whether a revolution face is bounded by parallels (constant axial
// coordinate) and meridians (constant angle) about the axis only.
bool is_angle_axial_rectangle(const TopoDS_Face& face, const gp_Pnt& origin, const gp_Dir& axis, double tol);

// Tests one candidate pair (a from body ia, b from body ib, ia < ib) and
// appends the contact it makes, if any, to `out` (side a = body ia).
// A failed test (OCCT's Boolean common of two faces, or typing a piece of it)
// is a failed Status and appends nothing: the caller decides what to skip.
// OCCT may still throw from inside (or raise a signal): the caller runs it
// under run_guarded.
Status test_candidate(int ia, const Partition& a, int ib, const Partition& b, const PairContext& ctx,
                      std::vector<Contact>& out);

}  // namespace contactcore
