// Closed-form contacts between analytic partitions: the closest pair of the
// unbounded surfaces (or, for a shaft in a bore and a plug on its seat, the
// signed gap across the common band), accepted only when both points lie in
// the partitions' bounds; everything else goes back to the meshes.
#include "contactcore/simulation/analytic_distance.h"
#include "contactcore/common/angles.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fcl/narrowphase/detail/primitive_shape_algorithm/triangle_distance.h>

namespace contactcore {

namespace {

using Vector3 = Eigen::Vector3d;
constexpr double kAngularSlack = 1e-9;  // rad, on the angular intervals

Vector3 to_vec(const gp_XYZ& p) { return Vector3(p.X(), p.Y(), p.Z()); }

// Any unit vector perpendicular to `axis`, preferring `ref` when it is.
Vector3 perpendicular(const Vector3& axis, const Vector3& ref) {
  Vector3 v = ref - ref.dot(axis) * axis;
  if (v.norm() < 1e-9) v = axis.unitOrthogonal();
  return v.normalized();
}

bool revolution(SurfaceKind k) { return k == SurfaceKind::Cylinder || k == SurfaceKind::Cone || k == SurfaceKind::Sphere; }

// The slab of the patch's outline (prepare_outline) holding height y in its
// plane frame; heights beyond the outline go to the nearest slab.
int slab_of(const AnalyticPatch& patch, double y) {
  return std::clamp(static_cast<int>(std::floor((y - patch.slab_y0) / patch.slab_height)), 0, patch.slab_count - 1);
}

// Even-odd test of the plane-frame point q against the patch's outline; false
// when q is within a chord's possible arc swing of it (the arcs are not known
// exactly here). Outside the outline's box no point is inside; inside it only
// the chords of q's slab can cross q's horizontal ray or lie within their swing
// of q (prepare_outline), so the others are not looked at.
bool inside_outline(const AnalyticPatch& patch, double qx, double qy) {
  if (qx < patch.outline_x0 || qx > patch.outline_x1 || qy < patch.outline_y0 || qy > patch.outline_y1) return false;
  if (patch.slab_count <= 0) return false;
  const int slab = slab_of(patch, qy);
  bool in = false;
  const int* index = patch.slab_chords.data();
  for (int k = patch.slab_first[slab], end = patch.slab_first[slab + 1]; k < end; ++k) {
    const AnalyticPatch::Chord& c = patch.chords[index[k]];
    if (qx >= c.x0 && qx <= c.x1) {  // (its slab already bounds the y-range)
      double t = c.length2 > 0 ? ((qx - c.x) * c.ex + (qy - c.y) * c.ey) / c.length2 : 0.0;
      t = std::clamp(t, 0.0, 1.0);
      const double dx = qx - (c.x + t * c.ex), dy = qy - (c.y + t * c.ey);
      if (dx * dx + dy * dy <= c.reach2) return false;
    }
    // The exact end, not c.y + c.ey: rounded, a vertex at q's height would lie
    // above the ray for one of its chords and below it for the other.
    if ((c.y > qy) != (c.y_end > qy)) {
      const double x = c.x + (qy - c.y) / (c.y_end - c.y) * (c.x_end - c.x);
      if (qx < x) in = !in;
    }
  }
  return in;
}

// Whether a chord of the patch's outline (its box grown by its reach) meets the
// plane-frame box [x0, x1] x [y0, y1]. None: the box lies in one region of the
// outline (inside or outside, away from every edge), so every point in it has
// the status of any one of them.
bool chord_meets_box(const AnalyticPatch& patch, double x0, double y0, double x1, double y1) {
  if (patch.slab_count <= 0) return false;
  const int* index = patch.slab_chords.data();
  for (int s = slab_of(patch, y0), last = slab_of(patch, y1); s <= last; ++s)
    for (int k = patch.slab_first[s], end = patch.slab_first[s + 1]; k < end; ++k) {
      const AnalyticPatch::Chord& c = patch.chords[index[k]];
      if (c.x0 <= x1 && c.x1 >= x0 && c.y0 <= y1 && c.y1 >= y0) return true;
    }
  return false;
}

// One loop as a circle: centre, radius and turn (+1 counter-clockwise: an outer
// loop; -1: a hole). True only when every vertex lies on the circle within
// kCircleTolerance and every chord's bulge is that circle's arc over it, turning
// the loop's way (so a polygon inscribed in a circle is no circle).
struct LoopCircle {
  double cx = 0, cy = 0, r = 0;
  int turn = 0;
};

// The centre of the circle through p, q and r; false when they are collinear.
bool circumcentre(const Point2& p, const Point2& q, const Point2& r, double& x, double& y) {
  const double bx = q.x - p.x, by = q.y - p.y, cx = r.x - p.x, cy = r.y - p.y;
  const double d = 2 * (bx * cy - by * cx);
  if (std::abs(d) < 1e-300) return false;
  const double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
  x = p.x + (cy * b2 - by * c2) / d;
  y = p.y + (bx * c2 - cx * b2) / d;
  return true;
}

// The angle a chord a -> b of a circle of radius r subtends when a's bulge is
// that circle's arc over it, turning `turn` (+1 counter-clockwise); -1 when not.
double arc_angle(const Point2& a, const Point2& b, double r, int turn) {
  const double delta = 2 * std::asin(std::min(1.0, 0.5 * std::hypot(b.x - a.x, b.y - a.y) / r));
  const double arc = turn * r * r * (delta - std::sin(delta));
  return std::abs(a.bulge - arc) > 1e-6 * std::abs(arc) + 1e-15 * r * r ? -1.0 : delta;
}

bool loop_circle(const Polygon2& loop, LoopCircle& out) {
  const std::size_t n = loop.size();
  if (n < 3) return false;
  // The circle through three vertices a third of the loop apart.
  if (!circumcentre(loop[0], loop[n / 3], loop[(2 * n) / 3], out.cx, out.cy)) return false;
  const Point2& p = loop[0];
  out.r = std::hypot(p.x - out.cx, p.y - out.cy);
  if (!(out.r > 0) || !std::isfinite(out.r)) return false;
  double twice_area = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Point2 &a = loop[i], &b = loop[(i + 1) % n];
    if (std::abs(std::hypot(a.x - out.cx, a.y - out.cy) - out.r) > kCircleTolerance) return false;
    twice_area += a.x * b.y - b.x * a.y + a.bulge;
  }
  out.turn = twice_area > 0 ? 1 : -1;
  for (std::size_t i = 0; i < n; ++i)
    if (arc_angle(loop[i], loop[(i + 1) % n], out.r, out.turn) < 0) return false;
  return true;
}

// One counter-clockwise loop as an annular sector about a centre (a face of an
// annulus split in halves along its seams, a quarter of a washer): every vertex
// on one of two concentric circles (inner 0: the centre itself), each chord
// between two vertices of one circle that circle's arc (counter-clockwise on
// the outer circle, clockwise on the inner), each straight chord radial. The
// centre is the circle through three vertices joined by two arcs.
struct LoopSector {
  double cx = 0, cy = 0, inner = 0, outer = 0, span = 0;
};
bool loop_sector(const Polygon2& loop, LoopSector& out) {
  const std::size_t n = loop.size();
  if (n < 4) return false;
  std::size_t first = n;
  for (std::size_t i = 0; i < n && first == n; ++i)
    if (loop[i].bulge != 0 && loop[(i + 1) % n].bulge != 0) first = i;
  if (first == n) return false;
  if (!circumcentre(loop[first], loop[(first + 1) % n], loop[(first + 2) % n], out.cx, out.cy)) return false;
  if (!std::isfinite(out.cx) || !std::isfinite(out.cy)) return false;
  // The two radii.
  double radii[2] = {-1, -1};
  std::vector<int> on(n);
  double twice_area = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double rho = std::hypot(loop[i].x - out.cx, loop[i].y - out.cy);
    int k = 0;
    while (k < 2 && radii[k] >= 0 && std::abs(rho - radii[k]) > kCircleTolerance) ++k;
    if (k == 2) return false;  // a third radius
    if (radii[k] < 0) radii[k] = rho;
    on[i] = k;
    const Point2& next = loop[(i + 1) % n];
    twice_area += loop[i].x * next.y - next.x * loop[i].y + loop[i].bulge;
  }
  if (radii[1] < 0 || twice_area <= 0) return false;  // one circle (loop_circle's), or a hole
  const int outer = radii[0] > radii[1] ? 0 : 1;
  double span[2] = {0, 0};
  for (std::size_t i = 0; i < n; ++i) {
    const Point2 &a = loop[i], &b = loop[(i + 1) % n];
    if (on[i] == on[(i + 1) % n]) {  // an arc of that circle
      const double rho = radii[on[i]];
      if (rho <= kCircleTolerance) return false;
      const double delta = arc_angle(a, b, rho, on[i] == outer ? 1 : -1);
      if (delta < 0) return false;
      span[on[i]] += delta;
    } else {  // a straight chord along a radius
      const double ax = a.x - out.cx, ay = a.y - out.cy, ex = b.x - out.cx, ey = b.y - out.cy;
      if (a.bulge != 0 || std::abs(ax * ey - ay * ex) > kCircleTolerance * (radii[0] + radii[1]) ||
          ax * ex + ay * ey < 0)
        return false;
    }
  }
  out.outer = radii[outer];
  out.inner = radii[1 - outer] <= kCircleTolerance ? 0.0 : radii[1 - outer];
  out.span = span[outer];
  if (out.inner > 0 && std::abs(span[outer] - span[1 - outer]) > 1e-9) return false;
  return out.span > 0 && out.span <= kTwoPi + 1e-9;
}

// The outline as annuli (AnalyticPatch::annuli), or none: loops that are whole
// circles (outer circles and their concentric holes), and sectors of one
// centre and two radii whose spans add up to a whole turn (the faces of one
// partition do not overlap, so they cover it).
std::vector<AnalyticPatch::Annulus> outline_annuli(const std::vector<Polygon2>& loops) {
  std::vector<LoopCircle> outer, holes;
  std::vector<LoopSector> sectors;
  for (const Polygon2& loop : loops) {
    LoopCircle c;
    LoopSector sector;
    if (loop_circle(loop, c)) (c.turn > 0 ? outer : holes).push_back(c);
    else if (loop_sector(loop, sector)) sectors.push_back(sector);
    else return {};
  }
  std::vector<AnalyticPatch::Annulus> annuli;
  for (const LoopCircle& o : outer) annuli.push_back({o.cx, o.cy, 0.0, o.r});
  for (const LoopCircle& h : holes) {
    // The smallest outer circle around the hole: its annulus, concentric with it.
    int around = -1;
    for (std::size_t k = 0; k < outer.size(); ++k)
      if (std::hypot(h.cx - outer[k].cx, h.cy - outer[k].cy) + h.r <= outer[k].r + kCircleTolerance &&
          (around < 0 || outer[k].r < outer[around].r))
        around = static_cast<int>(k);
    if (around < 0 || annuli[around].inner > 0 || h.r >= outer[around].r ||
        std::hypot(h.cx - outer[around].cx, h.cy - outer[around].cy) > kCircleTolerance)
      return {};
    annuli[around].inner = h.r;
  }
  // Sectors of one annulus, added up.
  std::vector<char> used(sectors.size(), 0);
  for (std::size_t i = 0; i < sectors.size(); ++i) {
    if (used[i]) continue;
    const LoopSector& s = sectors[i];
    double span = 0;
    for (std::size_t j = i; j < sectors.size(); ++j) {
      const LoopSector& t = sectors[j];
      if (used[j] || std::hypot(s.cx - t.cx, s.cy - t.cy) > kCircleTolerance ||
          std::abs(s.inner - t.inner) > kCircleTolerance || std::abs(s.outer - t.outer) > kCircleTolerance)
        continue;
      used[j] = 1;
      span += t.span;
    }
    if (std::abs(span - kTwoPi) > 1e-9) return {};  // part of an annulus: the outline test decides
    annuli.push_back({s.cx, s.cy, s.inner, s.outer});
  }
  return annuli;
}

// The outline's round holes (AnalyticPatch::round_holes): circles whose whole
// turn is covered by chords that are clockwise arcs of them (a hole's loop, or
// a hole split between the faces of a partition, each face's loop holding part
// of it), with every other chord outside the circle, its arc's swing included.
// Runs of arcs are found on the circle through three consecutive vertices (a
// loose fit: close vertices place its centre to about 1e-9 mm), then each
// circle is fitted again through three vertices spread over all its runs and
// every vertex and arc checked against it as loop_circle does. `loop_first`:
// each loop's first chord in patch.chords, then the chords' count.
std::vector<AnalyticPatch::Circle> round_holes(const AnalyticPatch& patch, const std::vector<std::size_t>& loop_first) {
  constexpr double kLoose = 1e-6;  // mm: the first fit's tolerance
  struct Run {
    double cx, cy, r;
    std::size_t loop, first, count;  // chords first .. first + count - 1 of the loop
  };
  std::vector<Run> runs;
  for (std::size_t l = 0; l < patch.loops.size(); ++l) {
    const Polygon2& loop = patch.loops[l];
    const std::size_t n = loop.size();
    if (n < 3) continue;
    std::size_t i = 0;
    while (i < n) {
      Run run{0, 0, 0, l, i, 0};
      const Point2 &p0 = loop[i], &p1 = loop[(i + 1) % n], &p2 = loop[(i + 2) % n];
      bool arcs = false;
      if (circumcentre(p0, p1, p2, run.cx, run.cy)) {
        run.r = std::hypot(p0.x - run.cx, p0.y - run.cy);
        arcs = run.r > kLoose && std::isfinite(run.r) && arc_angle(p0, p1, run.r, -1) >= 0 &&
               arc_angle(p1, p2, run.r, -1) >= 0;
      }
      if (!arcs) {
        ++i;
        continue;
      }
      // Chords i and i + 1 are arcs of one circle, clockwise: extend while the next chord is too.
      std::size_t k = i + 2;
      while (k < n) {
        const Point2 &a = loop[k], &b = loop[(k + 1) % n];
        if (std::abs(std::hypot(b.x - run.cx, b.y - run.cy) - run.r) > kLoose || arc_angle(a, b, run.r, -1) < 0) break;
        ++k;
      }
      run.count = k - i;
      runs.push_back(run);
      i = k;
    }
  }
  std::vector<AnalyticPatch::Circle> holes;
  std::vector<char> used(runs.size(), 0), of_circle(patch.chords.size(), 0);
  std::vector<const Point2*> starts;  // each chord's first vertex, over the circle's runs
  std::vector<const Point2*> ends;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    if (used[r]) continue;
    std::fill(of_circle.begin(), of_circle.end(), 0);
    starts.clear();
    ends.clear();
    for (std::size_t q = r; q < runs.size(); ++q) {
      const Run& other = runs[q];
      if (used[q] || std::hypot(other.cx - runs[r].cx, other.cy - runs[r].cy) > kLoose ||
          std::abs(other.r - runs[r].r) > kLoose)
        continue;
      used[q] = 1;
      const Polygon2& loop = patch.loops[other.loop];
      for (std::size_t k = other.first; k < other.first + other.count; ++k) {
        of_circle[loop_first[other.loop] + k] = 1;
        starts.push_back(&loop[k]);
        ends.push_back(&loop[(k + 1) % loop.size()]);
      }
    }
    // The circle again, through vertices a third of its chords apart, checked exactly.
    const std::size_t m = starts.size();
    AnalyticPatch::Circle c;
    if (m < 3 || !circumcentre(*starts[0], *starts[m / 3], *starts[(2 * m) / 3], c.cx, c.cy)) continue;
    c.r = std::hypot(starts[0]->x - c.cx, starts[0]->y - c.cy);
    double span = 0;
    bool on_circle = true;
    for (std::size_t k = 0; k < m && on_circle; ++k) {
      const double delta = arc_angle(*starts[k], *ends[k], c.r, -1);
      on_circle = std::abs(std::hypot(starts[k]->x - c.cx, starts[k]->y - c.cy) - c.r) <= kCircleTolerance &&
                  std::abs(std::hypot(ends[k]->x - c.cx, ends[k]->y - c.cy) - c.r) <= kCircleTolerance && delta >= 0;
      span += delta;
    }
    if (!on_circle || std::abs(span - kTwoPi) > 1e-9) continue;  // part of a circle: the outline test decides
    // Every other chord outside the circle (to a micrometre: chords ending on it touch it).
    constexpr double kClear = 1e-6;
    bool clear = true;
    for (std::size_t k = 0; k < patch.chords.size() && clear; ++k) {
      if (of_circle[k]) continue;
      const AnalyticPatch::Chord& chord = patch.chords[k];
      const double px = c.cx - chord.x, py = c.cy - chord.y;
      const double t = chord.length2 > 0 ? std::clamp((px * chord.ex + py * chord.ey) / chord.length2, 0.0, 1.0) : 0.0;
      clear = std::hypot(px - t * chord.ex, py - t * chord.ey) - std::sqrt(chord.reach2) >= c.r - kClear;
    }
    if (clear) holes.push_back(c);
  }
  return holes;
}

// Two outlines made of annuli (b's plane frame; a's centres mapped by
// q = (ox, oy) + M v), planes parallel and facing, `gap` apart along b's
// normal n. Two annuli share area where some circle about b's centre, of a
// radius d in (b.inner, b.outer), reaches distances [|d - e|, d + e] from a's
// centre (e apart) that meet (a.inner, a.outer): d in (max(b.inner, e - a.outer,
// a.inner - e), min(b.outer, e + a.outer)). Sharing area: the contact is the
// planes' gap at a point in the middle of that band. Else their rims' closest
// pair lies on the line of the centres, delta apart in the plane (a's disk in
// b's hole, the disks apart, or b's in a's hole): the faces are sqrt(gap^2 +
// delta^2) apart; rims that touch (delta 0) on one plane (gap 0) leave the
// meshes to decide (no direction).
bool annuli_pair(const AnalyticPatch& a, const AnalyticPatch& b, double gap, const Vector3& n, double ox, double oy,
                 double m00, double m01, double m10, double m11, AnalyticContact& out) {
  const Vector3 bx = b.ref_dir, by = b.axis.cross(b.ref_dir);
  double best_delta = std::numeric_limits<double>::infinity();
  double best_ax = 0, best_ay = 0, best_bx = 0, best_by = 0;
  for (const AnalyticPatch::Annulus& p : a.annuli) {
    const double ax = ox + m00 * p.cx + m01 * p.cy, ay = oy + m10 * p.cx + m11 * p.cy;
    for (const AnalyticPatch::Annulus& q : b.annuli) {
      const double ex = ax - q.cx, ey = ay - q.cy, e = std::hypot(ex, ey);
      // u: from b's centre towards a's (any direction when concentric), v: u turned a quarter.
      const double ux = e > 1e-12 ? ex / e : 1.0, uy = e > 1e-12 ? ey / e : 0.0;
      const double lo = std::max({q.inner, e - p.outer, p.inner - e}), hi = std::min(q.outer, e + p.outer);
      if (hi - lo > kAnnulusOverlap) {
        // The band's middle radius d about b's centre, and on that circle the point whose distance t
        // from a's centre is the middle of the radii a has there (law of cosines).
        const double d = 0.5 * (lo + hi);
        const double t = 0.5 * (std::max(std::abs(d - e), p.inner) + std::min(d + e, p.outer));
        double cos_t = 1, sin_t = 0;
        if (e > 1e-12) {
          cos_t = std::clamp((d * d + e * e - t * t) / (2 * d * e), -1.0, 1.0);
          sin_t = std::sqrt(std::max(0.0, 1 - cos_t * cos_t));
        }
        const double px = q.cx + d * (cos_t * ux - sin_t * uy), py = q.cy + d * (cos_t * uy + sin_t * ux);
        out.gap = gap;
        out.normal = n;
        out.point_b = b.location + px * bx + py * by;
        out.point_a = out.point_b + gap * n;
        return true;
      }
      // Apart in the plane: the three ways two annuli miss each other, the largest is their distance.
      const double in_hole = q.inner - e - p.outer, apart = e - p.outer - q.outer, around = p.inner - e - q.outer;
      const double delta = std::max({in_hole, apart, around});
      if (std::max(delta, 0.0) >= best_delta) continue;
      best_delta = std::max(delta, 0.0);
      double ra, rb;  // the rims' points: centre + r u
      if (delta == in_hole) ra = p.outer, rb = q.inner;
      else if (delta == apart) ra = -p.outer, rb = q.outer;
      else ra = -p.inner, rb = -q.outer;
      best_bx = q.cx + rb * ux, best_by = q.cy + rb * uy;
      best_ax = ax + ra * ux, best_ay = ay + ra * uy;
      if (delta <= 0) best_ax = best_bx, best_ay = best_by;  // touching (or a sliver): no in-plane offset
    }
  }
  if (!std::isfinite(best_delta)) return false;
  out.point_b = b.location + best_bx * bx + best_by * by;
  out.point_a = b.location + best_ax * bx + best_ay * by + gap * n;
  const Vector3 d = out.point_a - out.point_b;
  const double distance = d.norm();
  if (distance < 1e-12) return false;  // rims touching on one plane: no direction, the meshes decide
  out.gap = distance;
  out.normal = d / distance;
  return true;
}

// Cylinder axis points: a point on b's axis line at coordinate s.
Vector3 on_axis(const AnalyticPatch& p, double s) { return p.location + s * p.axis; }

// Radii of a revolution patch about its axis over its extent: a cylinder's
// one, a cone's at its ends (a sphere: 0 to its radius about any line through
// its centre).
double least_radius(const AnalyticPatch& p) {
  return p.kind == SurfaceKind::Cone ? p.axial_min * std::tan(p.half_angle)
                                     : p.kind == SurfaceKind::Sphere ? 0.0 : p.radius;
}
double widest_radius(const AnalyticPatch& p) {
  return p.kind == SurfaceKind::Cone ? p.axial_max * std::tan(p.half_angle) : p.radius;
}

bool swap_result(bool ok, AnalyticContact& out) {
  if (ok) {
    std::swap(out.point_a, out.point_b);
    out.normal = -out.normal;
  }
  return ok;
}

// ---- the pairs (a's role first)

// A pair known to be at least `gap` apart along `normal`, beyond the reach: answered with that bound
// (AnalyticTolerances::reach), its points placed at `at` without checking the bounds.
bool out_of_reach(double gap, const Vector3& normal, const Vector3& at, AnalyticContact& out) {
  out.gap = gap;
  out.normal = normal;
  out.point_a = at;
  out.point_b = at - gap * normal;
  return true;
}

// cos and sin of the eight multiples of 45 degrees.
constexpr double kHalfRoot2 = 0.70710678118654752440;
constexpr double kEighthTurns[8][2] = {{1, 0},           {kHalfRoot2, kHalfRoot2},   {0, 1},  {-kHalfRoot2, kHalfRoot2},
                                       {-1, 0},          {-kHalfRoot2, -kHalfRoot2}, {0, -1}, {kHalfRoot2, -kHalfRoot2}};

bool plane_plane(const AnalyticPatch& a, const AnalyticPatch& b, AnalyticContact& out, const AnalyticTolerances& tol) {
  if (a.axis.dot(b.axis) > -std::cos(tol.angle)) return false;  // not facing, or tilted: an edge is closest
  if (a.loops.empty() || b.loops.empty()) return false;
  const Vector3& n = b.axis;
  const double gap = (a.location - b.location).dot(n);
  // Back to back deeper than any contact (analytic_contact refuses it): no outline test.
  if (gap < -tol.max_depth) return false;
  if (gap > tol.reach) return out_of_reach(gap, n, a.location, out);
  const Vector3 ax = a.ref_dir, ay = a.axis.cross(a.ref_dir);
  const Vector3 bx = b.ref_dir, by = b.axis.cross(b.ref_dir);
  // a's plane frame into b's (q = o + M v) and back (planes parallel within
  // the angle tolerance: both maps are the exact dot products, linear in v).
  const Vector3 o_ab = a.location - b.location;
  const double ox = o_ab.dot(bx), oy = o_ab.dot(by);
  const double m00 = ax.dot(bx), m01 = ay.dot(bx), m10 = ax.dot(by), m11 = ay.dot(by);
  // Two outlines of annuli (shoulders, bearings' and seals' faces): decided by their radii.
  if (!a.annuli.empty() && !b.annuli.empty()) return annuli_pair(a, b, gap, n, ox, oy, m00, m01, m10, m11, out);
  const Vector3 o_ba = b.location - a.location;
  const double px = o_ba.dot(ax), py = o_ba.dot(ay);
  const double n00 = bx.dot(ax), n01 = by.dot(ax), n10 = bx.dot(ay), n11 = by.dot(ay);
  // The outlines' boxes first: a's box mapped into b's plane frame (the
  // parallelogram's corners, bounded by their box) against b's box. Apart, no
  // vertex of either outline lies inside the other.
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (double u : {a.outline_x0, a.outline_x1})
    for (double v : {a.outline_y0, a.outline_y1}) {
      const double x = ox + m00 * u + m01 * v, y = oy + m10 * u + m11 * v;
      x0 = std::min(x0, x);
      x1 = std::max(x1, x);
      y0 = std::min(y0, y);
      y1 = std::max(y1, y);
    }
  constexpr double kSlack = 1e-9;  // the mapped vertices round differently from the box's corners
  x0 -= kSlack, y0 -= kSlack, x1 += kSlack, y1 += kSlack;
  if (x1 < b.outline_x0 || x0 > b.outline_x1 || y1 < b.outline_y0 || y0 > b.outline_y1) return false;
  out.gap = gap;
  out.normal = n;
  // No edge of b near a's box: all of a's vertices lie in one region of b's
  // outline (the first one says which), and no vertex of b lies in a's box, so
  // none inside a. The scan below would give the same answer, vertex by vertex.
  if (!chord_meets_box(b, x0, y0, x1, y1)) {
    const Point2* first = nullptr;
    for (const auto& loop : a.loops)
      if (!loop.empty() && !first) first = &loop.front();
    if (!first || !inside_outline(b, ox + m00 * first->x + m01 * first->y, oy + m10 * first->x + m11 * first->y))
      return false;
    out.point_a = a.location + first->x * ax + first->y * ay;
    out.point_b = out.point_a - out.gap * n;
    return true;
  }
  // An annulus' outer rim first (a screw head's underside around the cover's hole: its inner rim,
  // scanned first below, lies along the hole's edge, no vertex of it inside), at eight points.
  for (const AnalyticPatch::Annulus& k : a.annuli)
    for (int i = 0; i < 8; ++i) {
      const double u = k.cx + k.outer * kEighthTurns[i][0], v = k.cy + k.outer * kEighthTurns[i][1];
      if (!inside_outline(b, ox + m00 * u + m01 * v, oy + m10 * u + m11 * v)) continue;
      out.point_a = a.location + u * ax + v * ay;
      out.point_b = out.point_a - out.gap * n;
      return true;
    }
  // A point of one outline inside the other: the faces overlap there.
  for (const auto& loop : a.loops)
    for (const Point2& v : loop) {
      if (!inside_outline(b, ox + m00 * v.x + m01 * v.y, oy + m10 * v.x + m11 * v.y)) continue;
      out.point_a = a.location + v.x * ax + v.y * ay;
      out.point_b = out.point_a - out.gap * n;
      return true;
    }
  for (const auto& loop : b.loops)
    for (const Point2& v : loop) {
      if (!inside_outline(a, px + n00 * v.x + n01 * v.y, py + n10 * v.x + n11 * v.y)) continue;
      out.point_b = b.location + v.x * bx + v.y * by;
      out.point_a = out.point_b + out.gap * n;
      return true;
    }
  return false;  // only edges crossing, or apart in the plane: the meshes decide
}

// A point of cylinder a's end circle about `centre` (eight tried, from direction `first`), within
// a's bounds, whose foot on b's plane lies inside b's outline: where that end stands over the
// face's material. False when none does.
bool end_point_over_face(const AnalyticPatch& a, const Vector3& centre, const Vector3& first, const AnalyticPatch& b,
                         Vector3& point) {
  const Vector3 x = perpendicular(a.axis, first), y = a.axis.cross(x);
  for (int k = 0; k < 8; ++k) {
    const Vector3 p = centre + a.radius * (kEighthTurns[k][0] * x + kEighthTurns[k][1] * y);
    if (!within_patch(a, p, 1e-3) || !within_patch(b, p - (p - b.location).dot(b.axis) * b.axis)) continue;
    point = p;
    return true;
  }
  return false;
}

// A cylinder (a shaft, or a bore's rim: either side) standing on a plane (b),
// its axis along the plane's normal: every point of its nearer end circle is
// at one height above the plane and the rest of it higher, so the gap is that
// height wherever one of those points lies over the face (eight tried; all
// over a hole: the meshes decide). A screw's head on a cover, the cover's bore
// under the head's face.
bool end_on_plane(const AnalyticPatch& a, const AnalyticPatch& b, AnalyticContact& out, const AnalyticTolerances& tol) {
  const Vector3& n = b.axis;
  const Vector3 centre = on_axis(a, a.axis.dot(n) > 0 ? a.axial_min : a.axial_max);
  const double height = (centre - b.location).dot(n);
  if (height > tol.reach) return out_of_reach(height, n, centre, out);  // the whole cylinder is that high
  Vector3 p;
  if (!end_point_over_face(a, centre, a.ref_dir, b, p)) return false;
  out.gap = height;
  out.normal = n;
  out.point_a = p;
  out.point_b = p - height * n;
  return true;
}

// A convex cylinder or sphere (a) against a plane (b).
bool convex_on_plane(const AnalyticPatch& a, const AnalyticPatch& b, AnalyticContact& out,
                     const AnalyticTolerances& tol) {
  const Vector3& n = b.axis;
  if (a.kind == SurfaceKind::Cylinder && (n - n.dot(a.axis) * a.axis).norm() < 1e-6)
    return end_on_plane(a, b, out, tol);
  if (a.side != MaterialSide::Convex) return false;
  Vector3 lowest;
  if (a.kind == SurfaceKind::Sphere) {
    lowest = a.location - a.radius * n;
  } else {
    const Vector3 w = n - n.dot(a.axis) * a.axis;  // not along the normal (end_on_plane above)
    const Vector3 down = w.normalized();
    // Height along n is linear in the axial coordinate: lowest at an end, or anywhere when parallel.
    const double slope = a.axis.dot(n);
    double s;
    if (std::abs(slope) < 1e-12) s = 0.5 * (a.axial_min + a.axial_max);
    else s = slope > 0 ? a.axial_min : a.axial_max;
    lowest = on_axis(a, s) - a.radius * down;
  }
  out.gap = (lowest - b.location).dot(n);
  if (out.gap > tol.reach) return out_of_reach(out.gap, n, lowest, out);  // its lowest point that high
  out.normal = n;
  out.point_a = lowest;
  out.point_b = lowest - out.gap * n;
  return within_patch(a, out.point_a) && within_patch(b, out.point_b);
}

// A shaft (convex cylinder a) through a face (plane b whose outline is annuli,
// or any outline when the shaft is in one of its round holes), its axis along
// the face's normal within the parallel tolerance and the face's plane crossing
// it or reaching an end: a shaft through a bearing's or a seal's face, in the
// hole at the bore's mouth, a screw's head on the cover. Its axis meets the plane at q,
// e from an annulus' centre: the annulus' rim is (hole radius - e) cos(tilt) - r
// from the shaft when q is in its hole, (e - outer) cos(tilt) - r when q lies
// beyond it (exact for parallel axes, a lower bound for a tilt: a rim point
// |p - q| from q is at least |p - q| cos(tilt) from the axis); q in an annulus'
// material (the shaft through the face itself) has no closed form here. The
// nearest rim is the contact, along the line from its centre to q.
bool shaft_through_plane(const AnalyticPatch& a, const AnalyticPatch& b, AnalyticContact& out,
                         const AnalyticTolerances& tol) {
  if (a.kind != SurfaceKind::Cylinder || a.side != MaterialSide::Convex || (b.annuli.empty() && b.round_holes.empty()))
    return false;
  const Vector3& n = b.axis;
  const double c = a.axis.dot(n);
  if (std::abs(c) < std::cos(tol.parallel)) return false;
  const double s_plane = (b.location - a.location).dot(n) / c;
  // The end nearer the plane, and how far the shaft stands off the plane on its body's side (the
  // side of the other end): negative when that end has crossed it (the whole shaft then leaves by
  // moving that far along the normal), less the end circle's drop for a tilt. A lower bound of
  // the distance like the rim's gap below; the answer is the larger of the two: the rim's when the
  // shaft runs through the hole, the end's when it stands on the face around the hole (a screw's
  // head on a cover) or ends in the face's plane (its shaft under the head).
  const double height_min = (on_axis(a, a.axial_min) - b.location).dot(n);
  const double height_max = (on_axis(a, a.axial_max) - b.location).dot(n);
  const bool min_nearer = std::abs(height_min) <= std::abs(height_max);
  const double body_side = (min_nearer ? height_max : height_min) > 0 ? 1.0 : -1.0;
  const double stand_off = body_side * (min_nearer ? height_min : height_max) -
                           a.radius * std::sqrt(std::max(0.0, 1 - c * c));
  // Not reaching the plane (beyond this, mm): the rim's gap alone would undercount the distance.
  constexpr double kEndReach = 1e-3;
  if (stand_off > kEndReach) return false;
  const Vector3 bx = b.ref_dir, by = b.axis.cross(b.ref_dir);
  const Vector3 q = on_axis(a, s_plane);
  const double qx = (q - b.location).dot(bx), qy = (q - b.location).dot(by);
  // A rim point p lies |p - q| from q in the plane, at least |p - q| |cos tilt| from the shaft's axis.
  const double cos_tilt = std::abs(c);
  double best = std::numeric_limits<double>::infinity(), best_rim = 0, best_ux = 1, best_uy = 0, best_cx = 0,
         best_cy = 0, best_side = 1;
  for (const AnalyticPatch::Annulus& k : b.annuli) {
    const double ex = qx - k.cx, ey = qy - k.cy, e = std::hypot(ex, ey);
    const double ux = e > 1e-12 ? ex / e : 1.0, uy = e > 1e-12 ? ey / e : 0.0;
    double gap, rim, side;
    if (e < k.inner) {
      gap = (k.inner - e) * cos_tilt - a.radius, rim = k.inner, side = 1;  // in its hole: the rim beyond q, on side u
    } else if (e > k.outer) {
      gap = (e - k.outer) * cos_tilt - a.radius, rim = k.outer, side = -1;  // beside it: its outer rim, towards q
    } else {
      return false;  // the axis through the face's material
    }
    if (gap < best) {
      best = gap, best_rim = rim, best_ux = ux, best_uy = uy, best_cx = k.cx, best_cy = k.cy, best_side = side;
    }
  }
  if (b.annuli.empty()) {
    // An outline of another shape: only a round hole around q settles it (the material lies outside
    // that circle; the holes do not overlap, so one at most holds q).
    for (const AnalyticPatch::Circle& h : b.round_holes) {
      const double ex = qx - h.cx, ey = qy - h.cy, e = std::hypot(ex, ey);
      if (e >= h.r) continue;
      best = (h.r - e) * cos_tilt - a.radius, best_rim = h.r, best_cx = h.cx, best_cy = h.cy, best_side = 1;
      best_ux = e > 1e-12 ? ex / e : 1.0, best_uy = e > 1e-12 ? ey / e : 0.0;
    }
    if (!std::isfinite(best)) return false;  // q on the face's material or beside it: the meshes decide
  }
  const Vector3 u = best_ux * bx + best_uy * by;
  // The end stands on (or sinks into) the face around the hole: along the normal. Only from outside
  // the face's material (a shaft from inside, ending in the face's plane, is the rim's: its bore's
  // overlap, not a pull towards its seat), and only for an end wider than the hole's room (a shaft
  // that fits, its end in the plane, goes on into the hole: its rim's gap, not a stop).
  constexpr double kFits = 1e-6;  // mm
  if (body_side > 0 && best < -kFits && stand_off > best) {
    // Only where the end circle lies over the face's material (eight points tried, from the side
    // of the nearest rim): a wide cylinder around a small face (a housing around a shaft's
    // shoulder) stands on nothing.
    Vector3 p;
    if (end_point_over_face(a, on_axis(a, min_nearer ? a.axial_min : a.axial_max), u, b, p)) {
      out.gap = stand_off;
      out.normal = body_side * n;  // a leaves towards its body's side
      out.point_a = p;
      out.point_b = p - stand_off * out.normal;
      return true;
    }
  }
  out.gap = best;
  out.normal = -best_side * u;  // a leaves the rim: away from it
  out.point_b = b.location + (best_cx + best_rim * best_ux) * bx + (best_cy + best_rim * best_uy) * by;
  out.point_a = q + best_side * a.radius * perpendicular(a.axis, u);
  return within_patch(a, out.point_a, 1e-3);
}

// A shaft (convex cylinder a) through a chamfer at a bore's mouth (concave cone
// b), axes near parallel: the cone's material lies outside its radius
// rho(t) = t tan(half-angle), which grows along its axis faster than the
// shaft's axis can drift off the cone's (tan(tilt) per unit of t; required),
// so the small rim is nearest. In the rim's plane the shaft's axis passes at q,
// e from the rim's centre: the gap is (rim - e) cos(tilt) - r (exact for
// parallel axes, a lower bound for a tilt, as in shaft_through_plane).
bool shaft_through_chamfer(const AnalyticPatch& a, const AnalyticPatch& b, AnalyticContact& out,
                           const AnalyticTolerances& tol) {
  if (a.kind != SurfaceKind::Cylinder || a.side != MaterialSide::Convex || b.kind != SurfaceKind::Cone ||
      b.side != MaterialSide::Concave || !(b.axial_min > 0))
    return false;
  const double c = a.axis.dot(b.axis), cos_tilt = std::abs(c);
  if (cos_tilt < std::cos(tol.parallel)) return false;
  const double sin_tilt = std::sqrt(std::max(0.0, 1 - c * c)), tan_half = std::tan(b.half_angle);
  if (tan_half * cos_tilt <= sin_tilt) return false;  // a cone as steep as the tilt: its far rim may be nearer
  const Vector3 centre = on_axis(b, b.axial_min);
  const double rim = least_radius(b);
  const double s_rim = (centre - a.location).dot(b.axis) / c;  // where the rim's plane crosses the shaft's axis
  constexpr double kEndSlack = 1e-6;  // mm: a rim at the shaft's end meets its edge (the meshes)
  if (s_rim <= a.axial_min + kEndSlack || s_rim >= a.axial_max - kEndSlack) return false;
  const Vector3 q = on_axis(a, s_rim);
  const Vector3 offset = q - centre;
  const double e = offset.norm();
  if (e >= rim) return false;  // the shaft's axis outside the rim: not through it
  const Vector3 u = e > 1e-12 ? Vector3(offset / e) : perpendicular(b.axis, b.ref_dir);
  out.gap = (rim - e) * cos_tilt - a.radius;
  out.normal = -u;  // a leaves the rim: away from it
  out.point_b = centre + rim * u;
  out.point_a = q + a.radius * perpendicular(a.axis, u);
  return within_patch(a, out.point_a, 1e-3) && within_patch(b, out.point_b, 1e-3);
}

// A shaft's chamfered end (convex cone a) in a bore (concave cylinder b), axes
// near parallel: a point of the cone at t is at most d(t) + rho(t) from the
// bore's axis (d: its axis point's distance to the bore's axis, which changes
// by at most sin(tilt) per unit of t while rho grows by tan(half-angle);
// required), so the large rim is nearest the wall: the gap is R - e - rim, e
// the large rim's centre off the bore's axis (exact for parallel axes, a lower
// bound for a tilt). Only with the large rim inside the bore's band (else the
// bore's mouth is nearest).
bool chamfer_in_bore(const AnalyticPatch& a, const AnalyticPatch& b, AnalyticContact& out,
                     const AnalyticTolerances& tol) {
  if (a.kind != SurfaceKind::Cone || a.side != MaterialSide::Convex || b.kind != SurfaceKind::Cylinder ||
      b.side != MaterialSide::Concave)
    return false;
  const double c = a.axis.dot(b.axis);
  if (std::abs(c) < std::cos(tol.parallel)) return false;
  const double sin_tilt = std::sqrt(std::max(0.0, 1 - c * c)), tan_half = std::tan(a.half_angle);
  if (tan_half <= sin_tilt) return false;
  const Vector3 centre = on_axis(a, a.axial_max);
  const double rim = widest_radius(a);
  const double s = (centre - b.location).dot(b.axis);
  constexpr double kEndSlack = 1e-6;  // mm
  if (s <= b.axial_min + kEndSlack || s >= b.axial_max - kEndSlack) return false;
  const Vector3 foot = on_axis(b, s);
  const Vector3 offset = centre - foot;
  const double e = offset.norm();
  if (e >= b.radius) return false;  // the cone's axis outside the bore: not in it
  const Vector3 u = e > 1e-12 ? Vector3(offset / e) : perpendicular(b.axis, b.ref_dir);
  out.gap = b.radius - e - rim;
  out.normal = -u;  // a leaves the wall: towards the bore's axis
  out.point_a = centre + rim * perpendicular(a.axis, u);
  out.point_b = foot + b.radius * u;
  return within_patch(a, out.point_a, 1e-3) && within_patch(b, out.point_b, 1e-3);
}

// A shaft (convex cylinder a) in a bore (concave cylinder b), axes near parallel:
// the signed radial gap at the end of their common band where the axes are farthest apart.
bool shaft_in_bore(const AnalyticPatch& a, const AnalyticPatch& b, AnalyticContact& out, const AnalyticTolerances& tol) {
  const double c = a.axis.dot(b.axis);
  if (std::abs(c) < std::cos(tol.parallel)) return false;
  const double base = (a.location - b.location).dot(b.axis);
  const double s1 = base + a.axial_min * c, s2 = base + a.axial_max * c;
  const double lo = std::max(std::min(s1, s2), b.axial_min), hi = std::min(std::max(s1, s2), b.axial_max);
  if (hi - lo <= 1e-9) return false;  // no common band: rims are closest
  double best_offset = -1;
  Vector3 best_u, best_shaft, best_s_point;
  double best_s = lo;
  for (double s : {lo, hi}) {
    const double t = (s - base) / c;
    const Vector3 shaft = on_axis(a, t);
    const Vector3 offset = shaft - on_axis(b, s);
    const double e = offset.norm();
    if (e > best_offset) {
      best_offset = e;
      best_u = e > 1e-12 ? Vector3(offset / e) : perpendicular(b.axis, b.ref_dir);
      best_shaft = shaft;
      best_s = s;
    }
  }
  (void)best_s_point;
  if (best_offset > b.radius) return false;  // the shaft's axis outside the bore: not in it
  out.gap = b.radius - a.radius - best_offset;
  out.point_a = best_shaft + a.radius * best_u;
  out.point_b = on_axis(b, best_s) + b.radius * best_u;
  out.normal = -best_u;
  // Exact for parallel axes; a tilt moves the contact off the band's end by about r sin(tilt).
  return within_patch(a, out.point_a, 1e-3) && within_patch(b, out.point_b, 1e-3);
}

// Closest points of two segments p0 + s d0 (s in [0, l0]) and p1 + t d1; false
// unless both lie strictly inside (else an end, a rim, is closest) or the lines are parallel.
bool segment_closest(const Vector3& p0, const Vector3& d0, double l0, const Vector3& p1, const Vector3& d1, double l1,
                     double& s, double& t) {
  const Vector3 r = p0 - p1;
  const double b = d0.dot(d1), c = d0.dot(r), f = d1.dot(r), denom = 1 - b * b;
  if (denom < 1e-12) {
    // Parallel: the middle of the common range.
    const double u0 = f, u1 = f + b * l0;  // p0 and p0 + l0 d0 in d1's coordinate from p1
    const double lo = std::max(std::min(u0, u1), 0.0), hi = std::min(std::max(u0, u1), l1);
    if (hi - lo <= 1e-9) return false;
    t = 0.5 * (lo + hi);
    s = t * b - c;  // p1 + t d1 projected on d0's line, from p0
    return s > 0 && s < l0;
  }
  s = (b * f - c) / denom;
  t = (f + b * s);
  return s > 1e-9 && s < l0 - 1e-9 && t > 1e-9 && t < l1 - 1e-9;
}

// Two convex revolution primitives reduced to cores (a segment or a point) and radii.
bool convex_cores(const AnalyticPatch& a, const AnalyticPatch& b, AnalyticContact& out) {
  Vector3 ca, cb;
  if (a.kind == SurfaceKind::Sphere && b.kind == SurfaceKind::Sphere) {
    ca = a.location;
    cb = b.location;
  } else if (a.kind == SurfaceKind::Cylinder && b.kind == SurfaceKind::Cylinder) {
    double s, t;
    if (!segment_closest(on_axis(a, a.axial_min), a.axis, a.axial_max - a.axial_min, on_axis(b, b.axial_min), b.axis,
                         b.axial_max - b.axial_min, s, t))
      return false;
    ca = on_axis(a, a.axial_min + s);
    cb = on_axis(b, b.axial_min + t);
  } else if (a.kind == SurfaceKind::Sphere && b.kind == SurfaceKind::Cylinder) {
    ca = a.location;
    const double t = (ca - b.location).dot(b.axis);
    if (t <= b.axial_min || t >= b.axial_max) return false;
    cb = on_axis(b, t);
  } else if (a.kind == SurfaceKind::Cylinder && b.kind == SurfaceKind::Sphere) {
    return swap_result(convex_cores(b, a, out), out);
  } else {
    return false;
  }
  const Vector3 d = ca - cb;
  const double dist = d.norm();
  if (dist < 1e-9) return false;  // concentric: every direction ties
  const Vector3 u = d / dist;
  out.gap = dist - a.radius - b.radius;
  out.normal = u;
  out.point_a = ca - a.radius * u;
  out.point_b = cb + b.radius * u;
  return within_patch(a, out.point_a) && within_patch(b, out.point_b);
}

// A shaft (convex cylinder a) beside a bore (concave cylinder b) it is not in:
// the bore's wall nearest the shaft is its near side, as for two shafts side by
// side (convex_cores, which reads no material side). Only while they are apart:
// a shaft reaching into a bore's cavity from the bore's material is no contact
// of theirs (the meshes decide).
bool shaft_beside_bore(const AnalyticPatch& a, const AnalyticPatch& b, AnalyticContact& out) {
  return convex_cores(a, b, out) && out.gap >= 0;
}

// Two revolution patches, one nested inside the other (a shaft inside a
// ring's outer surface, a bore inside a wider recess, a chamfer inside a
// bearing's outer ring), of any sides: a point of the inner one is at most its
// widest radius plus e from the outer one's axis (e: the inner axis' largest
// offset from the outer's along its length, at one of its ends; the centre's
// for a sphere), and the outer one's points are at least its least radius from
// it, so they are at least the difference apart. Beyond the reach that bound
// answers (AnalyticTolerances::reach); else no closed form here.
bool nested_out_of_reach(const AnalyticPatch& inner, const AnalyticPatch& outer, AnalyticContact& out,
                         const AnalyticTolerances& tol) {
  if (!std::isfinite(tol.reach) || !revolution(inner.kind) ||
      (outer.kind != SurfaceKind::Cylinder && outer.kind != SurfaceKind::Cone))
    return false;
  double e = 0;
  Vector3 offset = Vector3::Zero();
  auto farthest = [&](const Vector3& p) {
    const Vector3 d = p - outer.location;
    const Vector3 off = d - d.dot(outer.axis) * outer.axis;
    if (off.norm() >= e) e = off.norm(), offset = off;
  };
  if (inner.kind == SurfaceKind::Sphere) {
    farthest(inner.location);
  } else {
    if (std::abs(inner.axis.dot(outer.axis)) < std::cos(tol.parallel)) return false;
    farthest(on_axis(inner, inner.axial_min));
    farthest(on_axis(inner, inner.axial_max));
  }
  const double bound = least_radius(outer) - widest_radius(inner) - e;
  if (bound <= tol.reach) return false;
  const Vector3 u = e > 1e-12 ? Vector3(offset / e) : perpendicular(outer.axis, outer.ref_dir);
  return out_of_reach(bound, -u, on_axis(inner, inner.axial_min), out);
}

// A face (plane a) across a revolution patch's axis (b: its normal along the
// axis): every point of the face lies within its annuli's farthest outer rim
// (or the circle holding its outline) from where b's axis crosses
// the plane, so within that of b's axis (at most: a tilt brings it nearer), and
// b's points are at least b's least radius from it. Beyond the reach that
// bound answers (a shaft's end face inside a bearing's outer ring).
bool face_inside_revolution(const AnalyticPatch& a, const AnalyticPatch& b, AnalyticContact& out,
                            const AnalyticTolerances& tol) {
  if (!std::isfinite(tol.reach) || a.kind != SurfaceKind::Plane ||
      (b.kind != SurfaceKind::Cylinder && b.kind != SurfaceKind::Cone) || a.outline_radius < 0)
    return false;
  const double c = a.axis.dot(b.axis);
  if (std::abs(c) < std::cos(tol.parallel)) return false;
  const Vector3 q = b.location + ((a.location - b.location).dot(a.axis) / c) * b.axis;
  const Vector3 ax = a.ref_dir, ay = a.axis.cross(a.ref_dir);
  const double qx = (q - a.location).dot(ax), qy = (q - a.location).dot(ay);
  double reach = 0;  // in the plane, from q
  if (!a.annuli.empty()) {
    for (const AnalyticPatch::Annulus& k : a.annuli) reach = std::max(reach, std::hypot(k.cx - qx, k.cy - qy) + k.outer);
  } else {  // the circle holding the outline
    reach = std::hypot(a.outline_cx - qx, a.outline_cy - qy) + a.outline_radius;
  }
  // A point p of the face, |p - q| <= reach in the plane, is at most that from b's axis (q lies on it).
  const double bound = least_radius(b) - reach;
  if (bound <= tol.reach) return false;
  return out_of_reach(bound, -perpendicular(b.axis, b.ref_dir), a.location, out);
}

// A ball (convex sphere a) in a cup (concave sphere) or a bore (concave cylinder b).
bool ball_inside(const AnalyticPatch& a, const AnalyticPatch& b, AnalyticContact& out) {
  Vector3 centre;
  if (b.kind == SurfaceKind::Sphere) {
    centre = b.location;
  } else {
    const double t = (a.location - b.location).dot(b.axis);
    centre = on_axis(b, t);
  }
  const Vector3 d = a.location - centre;
  const double e = d.norm();
  if (e > b.radius) return false;  // the ball's centre outside the cup or bore
  const Vector3 u = e > 1e-12 ? Vector3(d / e) : perpendicular(b.axis, b.ref_dir);
  out.gap = b.radius - a.radius - e;
  out.normal = -u;
  out.point_a = a.location + a.radius * u;
  out.point_b = centre + b.radius * u;
  return within_patch(a, out.point_a) && within_patch(b, out.point_b);
}

// A plug (convex cone a) on its seat (concave cone b) of one half-angle, axes near parallel.
bool cone_seat(const AnalyticPatch& a, const AnalyticPatch& b, AnalyticContact& out, const AnalyticTolerances& tol) {
  if (std::abs(a.half_angle - b.half_angle) > tol.angle) return false;
  if (a.axis.dot(b.axis) < std::cos(tol.parallel)) return false;  // one opening direction
  const double alpha = b.half_angle, sin_a = std::sin(alpha), cos_a = std::cos(alpha);
  const Vector3 apart = a.location - b.location;
  const double delta = apart.dot(b.axis);
  const Vector3 lateral = apart - delta * b.axis;
  const double e = lateral.norm();
  const Vector3 u = e > 1e-12 ? Vector3(lateral / e) : perpendicular(b.axis, b.ref_dir);
  // a's band in b's axial coordinate (parallel axes: shifted by delta).
  const double lo = std::max(a.axial_min + delta, b.axial_min), hi = std::min(a.axial_max + delta, b.axial_max);
  if (hi - lo <= 1e-9) return false;  // chamfers at different radii: no band in common
  if (e > lo * std::tan(alpha)) return false;  // the plug's axis outside the seat
  // The tilt between the axes moves a's generator on side u; take the end of the band nearer the seat.
  double best = 1e300;
  for (double s : {lo, hi}) {
    const Vector3 seat = on_axis(b, s) + s * std::tan(alpha) * u;
    const Vector3 n = -cos_a * u + sin_a * b.axis;  // the seat's normal into the cavity
    // a's surface point on side u at this height: its axis point plus its radius there.
    const double t = (on_axis(b, s) - a.location).dot(a.axis);
    const Vector3 side = perpendicular(a.axis, u);
    const Vector3 plug = a.location + t * a.axis + t * std::tan(a.half_angle) * side;
    const double gap = (plug - seat).dot(n);
    if (gap < best) {
      best = gap;
      out.gap = gap;
      out.normal = n;
      out.point_b = seat;
      out.point_a = seat + gap * n;
    }
  }
  return within_patch(a, out.point_a, 1e-3) && within_patch(b, out.point_b, 1e-3);
}

bool closed_form(const AnalyticPatch& a, const AnalyticPatch& b, AnalyticContact& out,
                 const AnalyticTolerances& tol) noexcept;

// ---- bounds for any two patches out of reach (their kinds with or without a closed form)

// A plane's outline scanned chord by chord for a bound only up to this many chords: a cover's face
// with nine holes has thousands, and a pair a bound cannot decide from the circle holding them is
// rarely decided by them (it costs what the meshes save).
constexpr std::size_t kMostChordsScanned = 256;

// Heights (q - origin).d (d a unit vector) over the patch's points q: [lo, hi] holds them all. A
// plane by the circle holding its outline, or (`chords`) by its outline's vertices, each chord
// widened by its arc's swing; a cylinder or cone by its end circles (the height is linear along
// it); a sphere by its centre and radius. False for a torus, another surface, or a plane without
// an outline.
bool height_range(const AnalyticPatch& p, const Vector3& origin, const Vector3& d, bool chords, double& lo,
                  double& hi) {
  const double h0 = (p.location - origin).dot(d);
  switch (p.kind) {
    case SurfaceKind::Plane: {
      if (p.outline_radius < 0) return false;
      const Vector3 ax = p.ref_dir, ay = p.axis.cross(p.ref_dir);
      const double gx = ax.dot(d), gy = ay.dot(d), slope = std::hypot(gx, gy);
      if (!chords || slope < 1e-12) {
        const double centre = h0 + p.outline_cx * gx + p.outline_cy * gy;
        lo = centre - p.outline_radius * slope, hi = centre + p.outline_radius * slope;
        return true;
      }
      lo = 1e300, hi = -1e300;
      for (const AnalyticPatch::Chord& c : p.chords) {
        const double h = h0 + c.x * gx + c.y * gy, swing = std::sqrt(c.reach2) * slope;
        lo = std::min(lo, h - swing), hi = std::max(hi, h + swing);
      }
      return true;
    }
    case SurfaceKind::Cylinder:
    case SurfaceKind::Cone: {
      const double c = p.axis.dot(d), across = std::sqrt(std::max(0.0, 1 - c * c));
      const double r0 = std::abs(least_radius(p)) * across, r1 = std::abs(widest_radius(p)) * across;
      const double h_min = h0 + p.axial_min * c, h_max = h0 + p.axial_max * c;
      lo = std::min(h_min - r0, h_max - r1), hi = std::max(h_min + r0, h_max + r1);
      return true;
    }
    case SurfaceKind::Sphere:
      lo = h0 - p.radius, hi = h0 + p.radius;
      return true;
    default:
      return false;
  }
}

// height_range by the circle holding a plane's outline first, then (a plane of at most
// kMostChordsScanned chords) by its chords, until `decided(lo, hi)`: whether a range decided it.
template <class Decided>
bool height_range_deciding(const AnalyticPatch& p, const Vector3& origin, const Vector3& d, Decided decided, double& lo,
                           double& hi) {
  for (bool chords : {false, true}) {
    if (!height_range(p, origin, d, chords, lo, hi)) return false;
    if (decided(lo, hi)) return true;
    if (p.kind != SurfaceKind::Plane || p.chords.size() > kMostChordsScanned) return false;
  }
  return false;
}

// Patch a wholly on one side of plane b's plane: every point of b lies in that plane, so the pair
// is at least that far apart. In front of it, farther than the reach; behind it (where b's
// material is), deeper than any contact (AnalyticTolerances::max_depth: a patch behind it by less
// may be sunk into b's body, an overlap the meshes must see). The circle holding a plane's outline
// first, its chords only when the circle leaves it undecided.
bool off_plane(const AnalyticPatch& a, const AnalyticPatch& b, AnalyticContact& out, const AnalyticTolerances& tol) {
  if (b.kind != SurfaceKind::Plane) return false;
  const double behind = std::max(tol.reach, tol.max_depth);
  double lo, hi;
  auto apart = [&](double l, double h) { return l > tol.reach || h < -behind; };
  if (!height_range_deciding(a, b.location, b.axis, apart, lo, hi)) return false;
  return lo > tol.reach ? out_of_reach(lo, b.axis, a.location, out) : out_of_reach(-hi, -b.axis, a.location, out);
}

// Patch a's extent along revolution patch b's axis (any tilt) missing b's axial range by more than
// the reach: a shaft's end above a bearing's bore, chamfers and recesses at other heights, a hex
// socket's walls above a cover's rim.
bool beside_axial_range(const AnalyticPatch& a, const AnalyticPatch& b, AnalyticContact& out,
                        const AnalyticTolerances& tol) {
  if (b.kind != SurfaceKind::Cylinder && b.kind != SurfaceKind::Cone) return false;
  double lo, hi;
  auto apart = [&](double l, double h) { return std::max(b.axial_min - h, l - b.axial_max) > tol.reach; };
  if (!height_range_deciding(a, b.location, b.axis, apart, lo, hi)) return false;
  const double below = b.axial_min - hi, above = lo - b.axial_max;
  return out_of_reach(std::max(below, above), above > below ? b.axis : Vector3(-b.axis), a.location, out);
}

// Two revolution patches side by side, any sides: every point of each lies within its widest
// radius of its core (its axis between its ends; a sphere's centre), so they are at least the
// cores' distance less both radii apart (a screw's shank beside a cover's central chamfers; the
// cores' closest points by FCL's segment pair, degenerate segments and parallel ones included).
// Beside a concave one (a bore, whose body lies outside its radius) the other lies on that body's
// side: as behind a plane (off_plane), only beyond max_depth.
bool cores_apart(const AnalyticPatch& a, const AnalyticPatch& b, AnalyticContact& out, const AnalyticTolerances& tol) {
  if (!revolution(a.kind) || !revolution(b.kind)) return false;
  // A core as FCL's segments take it: its start and its extent (zero for a sphere's centre).
  auto start = [](const AnalyticPatch& p) { return p.kind == SurfaceKind::Sphere ? p.location : on_axis(p, p.axial_min); };
  auto extent = [](const AnalyticPatch& p) {
    return p.kind == SurfaceKind::Sphere ? Vector3::Zero().eval() : Vector3((p.axial_max - p.axial_min) * p.axis);
  };
  auto widest = [](const AnalyticPatch& p) { return std::max(std::abs(least_radius(p)), std::abs(widest_radius(p))); };
  Vector3 ca, cb, direction;
  fcl::detail::TriangleDistance<double>::segPoints(start(a), extent(a), start(b), extent(b), direction, ca, cb);
  const double apart = (ca - cb).norm() - widest(a) - widest(b);
  const bool beside_a_bore = a.side == MaterialSide::Concave || b.side == MaterialSide::Concave;
  if (apart <= (beside_a_bore ? std::max(tol.reach, tol.max_depth) : tol.reach)) return false;
  return out_of_reach(apart, (ca - cb).normalized(), ca, out);
}

// Any pair of analytic patches known farther apart than the reach by one of the bounds above (none
// without a reach).
bool beyond_reach(const AnalyticPatch& a, const AnalyticPatch& b, AnalyticContact& out,
                  const AnalyticTolerances& tol) {
  if (!std::isfinite(tol.reach)) return false;
  return off_plane(a, b, out, tol) || swap_result(off_plane(b, a, out, tol), out) ||
         beside_axial_range(a, b, out, tol) || swap_result(beside_axial_range(b, a, out, tol), out) ||
         cores_apart(a, b, out, tol);
}

}  // namespace

AnalyticPatch analytic_patch(const Partition& partition) {
  AnalyticPatch p;
  const SurfaceParams& s = partition.params;
  p.kind = s.kind;
  if (s.kind == SurfaceKind::Torus || s.kind == SurfaceKind::Other) {
    p.kind = SurfaceKind::Other;
    return p;
  }
  p.side = partition.side;
  p.location = to_vec(s.location.XYZ());
  p.axis = to_vec(s.axis.XYZ());
  p.ref_dir = to_vec(partition.extent.ref_dir.XYZ());
  p.radius = s.radius;
  p.half_angle = s.half_angle;
  p.axial_min = partition.extent.axial_min;
  p.axial_max = partition.extent.axial_max;
  for (const AngularInterval& i : partition.extent.angular) p.angular.push_back({i.start, i.span});
  for (const Polygon2& loop : partition.extent.outline) p.loops.push_back(loop);
  if (s.kind == SurfaceKind::Plane && p.loops.empty()) p.kind = SurfaceKind::Other;  // no outline: no bounds
  prepare_outline(p);
  if (revolution(s.kind) && p.angular.empty()) p.kind = SurfaceKind::Other;
  return p;
}

void prepare_outline(AnalyticPatch& patch) {
  patch.chords.clear();
  patch.outline_radius = -1;
  patch.annuli = outline_annuli(patch.loops);
  patch.slab_first.clear();
  patch.slab_chords.clear();
  patch.slab_count = 0;
  patch.outline_x0 = patch.outline_y0 = 1e300;
  patch.outline_x1 = patch.outline_y1 = -1e300;
  std::vector<std::size_t> loop_first;  // each loop's first chord
  for (const auto& loop : patch.loops) {
    const std::size_t n = loop.size();
    loop_first.push_back(patch.chords.size());
    for (std::size_t i = 0; i < n; ++i) {
      const Point2& p = loop[i];
      const Point2& r = loop[(i + 1) % n];
      AnalyticPatch::Chord c;
      c.x = p.x;
      c.y = p.y;
      c.ex = r.x - p.x;
      c.ey = r.y - p.y;
      c.x_end = r.x;
      c.y_end = r.y;
      c.length2 = c.ex * c.ex + c.ey * c.ey;
      // The arc bulges at most ~3|bulge| / (4 len) off its chord (the sagitta of a
      // circular arc up to a half circle, from its area).
      const double len = std::sqrt(c.length2);
      const double reach = (len > 0 ? 0.75 * std::abs(p.bulge) / len : std::abs(p.bulge)) + 1e-9;
      c.reach2 = reach * reach;
      c.x0 = std::min(p.x, r.x) - reach;
      c.x1 = std::max(p.x, r.x) + reach;
      c.y0 = std::min(p.y, r.y) - reach;
      c.y1 = std::max(p.y, r.y) + reach;
      patch.chords.push_back(c);
      patch.outline_x0 = std::min(patch.outline_x0, p.x);
      patch.outline_x1 = std::max(patch.outline_x1, p.x);
      patch.outline_y0 = std::min(patch.outline_y0, p.y);
      patch.outline_y1 = std::max(patch.outline_y1, p.y);
    }
  }
  loop_first.push_back(patch.chords.size());
  patch.round_holes = round_holes(patch, loop_first);
  if (!patch.chords.empty()) {
    patch.outline_cx = 0.5 * (patch.outline_x0 + patch.outline_x1);
    patch.outline_cy = 0.5 * (patch.outline_y0 + patch.outline_y1);
    for (const AnalyticPatch::Chord& c : patch.chords)
      patch.outline_radius =
          std::max(patch.outline_radius, std::hypot(c.x - patch.outline_cx, c.y - patch.outline_cy) + std::sqrt(c.reach2));
  }
  if (patch.chords.empty()) {
    patch.outline_x0 = 0, patch.outline_x1 = -1, patch.outline_y0 = 0, patch.outline_y1 = -1;
    return;
  }
  // Slabs over the vertices' y-range (points outside it are rejected by the box):
  // two slabs a chord, each chord in every slab its grown y-range meets.
  const std::size_t n = patch.chords.size();
  patch.slab_count = static_cast<int>(std::clamp<std::size_t>(2 * n, 1, 8192));
  patch.slab_y0 = patch.outline_y0;
  const double height = (patch.outline_y1 - patch.outline_y0) / patch.slab_count;
  patch.slab_height = height > 0 ? height : 1.0;
  std::vector<int> count(patch.slab_count + 1, 0);
  std::vector<std::pair<int, int>> span(n);
  for (std::size_t i = 0; i < n; ++i) {
    const AnalyticPatch::Chord& c = patch.chords[i];
    // Grown beyond rounding too: a y within rounding of a slab boundary may land in either slab.
    const double round = 1e-12 * (std::abs(c.y) + std::abs(c.ey) + patch.slab_height) + 1e-12;
    const double lo = c.y0 - round, hi = c.y1 + round;  // its y-range grown by its reach
    span[i] = {slab_of(patch, lo), slab_of(patch, hi)};
    for (int s = span[i].first; s <= span[i].second; ++s) ++count[s + 1];
  }
  for (int s = 0; s < patch.slab_count; ++s) count[s + 1] += count[s];
  patch.slab_first = count;
  patch.slab_chords.assign(count[patch.slab_count], 0);
  std::vector<int> fill(count.begin(), count.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    for (int s = span[i].first; s <= span[i].second; ++s) patch.slab_chords[fill[s]++] = static_cast<int>(i);
}

AnalyticPatch placed(const AnalyticPatch& patch, const Eigen::Isometry3d& motion) {
  AnalyticPatch out = patch;
  out.location = motion * patch.location;
  out.axis = motion.linear() * patch.axis;
  out.ref_dir = motion.linear() * patch.ref_dir;
  return out;
}

bool within_patch(const AnalyticPatch& patch, const Eigen::Vector3d& p, double slack) noexcept {
  const Vector3 d = p - patch.location;
  if (patch.kind == SurfaceKind::Plane) {
    const Vector3 y = patch.axis.cross(patch.ref_dir);
    const double x = d.dot(patch.ref_dir), yy = d.dot(y);
    if (patch.annuli.empty()) return inside_outline(patch, x, yy);
    // Annuli are exact (no arc swing to stay clear of): their closed rings, rims included to the
    // circles' tolerance (a bore's rim under a washer's inner rim, line to line).
    for (const AnalyticPatch::Annulus& k : patch.annuli) {
      const double r = std::hypot(x - k.cx, yy - k.cy);
      if (r >= k.inner - kCircleTolerance && r <= k.outer + kCircleTolerance) return true;
    }
    return false;
  }
  if (!revolution(patch.kind)) return false;
  const double axial = d.dot(patch.axis);
  if (axial < patch.axial_min - slack || axial > patch.axial_max + slack) return false;
  const Vector3 y = patch.axis.cross(patch.ref_dir);
  const double x = d.dot(patch.ref_dir), yy = d.dot(y);
  if (std::hypot(x, yy) < 1e-12) return true;  // on the axis (a pole): every angle
  double angle = std::atan2(yy, x);
  if (angle < 0) angle += kTwoPi;
  for (const AnalyticPatch::Arc& arc : patch.angular) {
    if (arc.span >= kTwoPi - kAngularSlack) return true;
    double from = angle - arc.start;
    from -= kTwoPi * std::floor(from / kTwoPi);
    if (from <= arc.span + kAngularSlack || from >= kTwoPi - kAngularSlack) return true;
  }
  return false;
}

bool analytic_contact(const AnalyticPatch& a, const AnalyticPatch& b, AnalyticContact& out,
                      const AnalyticTolerances& tol) noexcept {
  // Pairs known to be out of reach first, whatever their kinds (cheap, and most pairs near a part
  // are); then the closed form of the kinds. The bounds answer nothing a closed form would take as
  // a contact: their gaps exceed the reach, and on a face's or a bore's body side max_depth.
  if (beyond_reach(a, b, out, tol)) return true;
  if (!closed_form(a, b, out, tol)) return false;
  return out.gap >= -tol.max_depth;
}

namespace {
bool closed_form(const AnalyticPatch& a, const AnalyticPatch& b, AnalyticContact& out,
                 const AnalyticTolerances& tol) noexcept {
  using K = SurfaceKind;
  const K ka = a.kind, kb = b.kind;
  if (ka == K::Other || kb == K::Other) return false;
  if (ka == K::Plane && kb == K::Plane) return plane_plane(a, b, out, tol);
  if (kb == K::Plane && (ka == K::Cylinder || ka == K::Sphere))
    return swap_result(face_inside_revolution(b, a, out, tol), out) || shaft_through_plane(a, b, out, tol) ||
           convex_on_plane(a, b, out, tol);
  if (ka == K::Plane && (kb == K::Cylinder || kb == K::Sphere))
    return face_inside_revolution(a, b, out, tol) ||
           swap_result(shaft_through_plane(b, a, out, tol) || convex_on_plane(b, a, out, tol), out);
  if (widest_radius(a) <= widest_radius(b) ? nested_out_of_reach(a, b, out, tol)
                                           : swap_result(nested_out_of_reach(b, a, out, tol), out))
    return true;
  const bool convex_a = a.side == MaterialSide::Convex, convex_b = b.side == MaterialSide::Convex;
  if (ka == K::Cone || kb == K::Cone) {
    if (convex_a == convex_b) return false;
    if (ka == K::Cone && kb == K::Cone)
      return convex_a ? cone_seat(a, b, out, tol) : swap_result(cone_seat(b, a, out, tol), out);
    if (ka == K::Cylinder)  // b a cone
      return convex_a ? shaft_through_chamfer(a, b, out, tol) : swap_result(chamfer_in_bore(b, a, out, tol), out);
    if (kb == K::Cylinder)  // a a cone
      return convex_a ? chamfer_in_bore(a, b, out, tol) : swap_result(shaft_through_chamfer(b, a, out, tol), out);
    return false;
  }
  if (convex_a && convex_b) return convex_cores(a, b, out);
  if (convex_a == convex_b) return false;  // two concave surfaces: never the closest pair of solids
  // One convex inside one concave.
  const AnalyticPatch& inner = convex_a ? a : b;
  const AnalyticPatch& outer = convex_a ? b : a;
  bool ok = false;
  if (inner.kind == K::Cylinder && outer.kind == K::Cylinder)
    ok = shaft_in_bore(inner, outer, out, tol) || shaft_beside_bore(inner, outer, out);
  else if (inner.kind == K::Sphere) ok = ball_inside(inner, outer, out);
  else return false;  // a shaft in a cup: its rim is closest
  return convex_a ? ok : swap_result(ok, out);
}
}  // namespace

}  // namespace contactcore
