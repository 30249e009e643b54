// Joints per body pair: each contact's constraint wrenches, stacked, give the
// free twists as their null space; unilateral contacts give one-sided stops
// and the cone of directions in which one body can leave the other.
#include "contactcore/common/angles.h"
#include "contactcore/joints/joints.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "joints/twist_math.h"

namespace contactcore {

using namespace detail;

const char* to_string(ContactIntent intent) {
  switch (intent) {
    case ContactIntent::Unspecified: return "";
    case ContactIntent::Clearance: return "clearance";
    case ContactIntent::Transition: return "transition";
    case ContactIntent::Interference: return "interference";
    case ContactIntent::Bonded: return "bonded";
    case ContactIntent::Ignored: return "ignored";
    case ContactIntent::Threaded: return "threaded";
  }
  return "";
}

bool parse_intent(const std::string& text, ContactIntent& intent) {
  for (ContactIntent candidate : {ContactIntent::Clearance, ContactIntent::Transition, ContactIntent::Interference,
                                  ContactIntent::Bonded, ContactIntent::Ignored, ContactIntent::Threaded})
    if (text == to_string(candidate)) {
      intent = candidate;
      return true;
    }
  return false;
}

namespace {

const Partition& partition_of(const ContactsResult& r, int body, int id) {
  return r.partitions[body].partitions[id];
}

// Outward unit normal of a's material for a revolution contact at angle
// `theta` about a's axis (measured from a's ref_dir).
struct RevolutionFrame {
  Vec3 origin, axis, ref, side;  // side = axis x ref
  Vec3 radial(double theta) const { return std::cos(theta) * ref + std::sin(theta) * side; }
  double angle_of(const Vec3& d) const {
    double phi = std::atan2(d.dot(side), d.dot(ref));
    return phi < 0 ? phi + kTwoPi : phi;
  }
};

RevolutionFrame frame_of(const Partition& p) {
  RevolutionFrame f;
  f.origin = vec(p.params.location);
  f.axis = vec(p.params.axis);
  f.ref = vec(p.extent.ref_dir);
  f.ref = (f.ref - f.axis * f.axis.dot(f.ref)).normalized();
  f.side = f.axis.cross(f.ref);
  return f;
}

// The angular intervals both partitions cover, in a's frame.
std::vector<AngularInterval> common_angles(const Partition& a, const Partition& b) {
  const RevolutionFrame fa = frame_of(a), fb = frame_of(b);
  const bool same_sense = fa.axis.dot(fb.axis) > 0;
  std::vector<AngularInterval> mapped;
  for (const AngularInterval& in : b.extent.angular) {
    if (in.span >= kTwoPi - 1e-9) {
      mapped.push_back({0, kTwoPi});
      continue;
    }
    const double start = fa.angle_of(fb.radial(same_sense ? in.start : in.start + in.span));
    mapped.push_back({start, in.span});
  }
  std::vector<AngularInterval> common;
  overlap(a.extent.angular, unite(mapped), &common);
  return common;
}

// A circular cone of stop normals (all normals within `angle` of `axis`
// around a full turn: a full cone contact, a ball in a cup): its free
// directions are the circular cone about `axis` of half angle pi/2 - angle.
struct CircularStops {
  Vec3 axis;
  double angle = 0;
};

// Constraint rows and stop data of one contact.
struct ContactConstraints {
  std::vector<Vec6> rows;            // bilateral wrenches (local)
  std::vector<Vec3> bilateral_forces;  // directions of translation they forbid
  std::vector<OneSidedStop> stops;
  // When set, the free directions come from this exact cone, not from the
  // sampled stop normals (whose polygon would reach outside the true cone).
  std::vector<CircularStops> circles;
};

// Stops whose normals are sign * u for the directions u (from a ball's
// centre) within `angle` of `axis`: the cap's centre and `samples` around
// its rim, for the servo loop; the free-direction cone from the exact circle.
void add_cap_stops(int index, const Vec3& centre, double radius, const Vec3& axis, double angle, double sign,
                   int samples, ContactConstraints& out) {
  Vec3 u, v;
  perpendiculars(axis, u, v);
  out.stops.push_back({index, pnt(centre + radius * axis), dir(sign * axis)});
  for (int i = 0; i < samples; ++i) {
    const double theta = kTwoPi * i / samples;
    const Vec3 d = std::cos(angle) * axis + std::sin(angle) * (std::cos(theta) * u + std::sin(theta) * v);
    out.stops.push_back({index, pnt(centre + radius * d), dir(sign * d)});
  }
  out.circles.push_back({sign * axis, angle});
}

void add_axis_forces(const Frame& frame, const Vec3& p, const Vec3& axis, ContactConstraints& out) {
  Vec3 u, v;
  perpendiculars(axis, u, v);
  out.rows.push_back(frame.force_row(p, u));
  out.rows.push_back(frame.force_row(p, v));
}

void add_axis_moments(const Vec3& axis, ContactConstraints& out) {
  Vec3 u, v;
  perpendiculars(axis, u, v);
  out.rows.push_back(Frame::moment_row(u));
  out.rows.push_back(Frame::moment_row(v));
}

// Angles at which a unilateral revolution contact's normals are taken: the
// ends of each common interval (a partial contact's normals are positive
// combinations of those), or `samples` around a full turn.
std::vector<double> stop_angles(const std::vector<AngularInterval>& common, double span, int samples,
                                bool full) {
  std::vector<double> angles;
  if (full || common.empty() || span >= kTwoPi - 1e-6) {
    for (int i = 0; i < samples; ++i) angles.push_back(kTwoPi * i / samples);
    return angles;
  }
  for (const AngularInterval& in : common) {
    angles.push_back(in.start);
    angles.push_back(in.start + in.span);
  }
  return angles;
}

// A ball's region angle, a half turn within the angular tolerance taken as
// exactly one (a hemispherical cup, a half-open groove: the probes find the
// region's edges within the edges' own tolerance, 1e-7 rad beyond them).
double region_angle_of(const Contact& c) {
  return std::abs(c.region_angle - kPi / 2) <= c.tolerances.angular ? kPi / 2 : c.region_angle;
}

ContactConstraints constraints_of(const ContactsResult& result, int index, const Frame& frame,
                                  const JointOptions& options) {
  const Contact& c = result.contacts[index];
  ContactConstraints out;
  const Vec3 p = vec(c.point), d = vec(c.direction).normalized();
  switch (c.type) {
    case ContactType::PLF: {
      out.rows.push_back(frame.force_row(p, d));
      add_axis_moments(d, out);
      out.stops.push_back({index, c.point, c.direction});
      break;
    }
    case ContactType::CLJ:
    case ContactType::CJU: {
      const Partition& pa = partition_of(result, c.body_a, c.partition_a);
      const Partition& pb = partition_of(result, c.body_b, c.partition_b);
      add_axis_forces(frame, p, d, out);
      add_axis_moments(d, out);
      const bool cone = c.type == ContactType::CJU;
      if (cone) out.rows.push_back(frame.force_row(p, d));  // the seat stops the axial motion
      if (!cone && !c.partial) {
        Vec3 u, v;
        perpendiculars(d, u, v);
        out.bilateral_forces.push_back(u);
        out.bilateral_forces.push_back(v);
        break;
      }
      // Unilateral: normals of a's surface over the common span.
      const RevolutionFrame fa = frame_of(pa);
      const double sign = pa.side == MaterialSide::Convex ? 1.0 : -1.0;
      const double alpha = cone ? pa.params.half_angle : 0.0;
      const double mid = 0.5 * (pa.extent.axial_min + pa.extent.axial_max);
      const double radius = cone ? std::abs(mid) * std::tan(alpha) : pa.params.radius;
      for (double theta : stop_angles(common_angles(pa, pb), c.span, options.cone_samples, !c.partial)) {
        const Vec3 radial = fa.radial(theta);
        // Cone (axis from apex to opening): outward normal of the material inside is
        // cos(alpha) radial - sin(alpha) axis.
        const Vec3 normal = sign * (std::cos(alpha) * radial - std::sin(alpha) * fa.axis);
        const Vec3 at = fa.origin + fa.axis * mid + radial * radius;
        out.stops.push_back({index, pnt(at), dir(normal)});
      }
      // A full cone's normals make a circular cone about -sign sin(alpha)
      // axis, at pi/2 - alpha from it: its free directions are exact.
      if (cone && !c.partial && c.span >= kTwoPi - 1e-6 && std::abs(std::sin(alpha)) > 1e-12)
        out.circles.push_back({-sign * (std::sin(alpha) > 0 ? 1.0 : -1.0) * fa.axis, kPi / 2 - std::abs(alpha)});
      break;
    }
    case ContactType::SPF: {
      for (const Vec3& e : {Vec3(Vec3::UnitX()), Vec3(Vec3::UnitY()), Vec3(Vec3::UnitZ())})
        out.rows.push_back(frame.force_row(p, e));
      if (c.region_angle >= kPi - 1e-9) {  // held all around
        for (const Vec3& e : {Vec3(Vec3::UnitX()), Vec3(Vec3::UnitY()), Vec3(Vec3::UnitZ())})
          out.bilateral_forces.push_back(e);
        break;
      }
      // A cup: a's normals over the cap of the common region (out of a's
      // material: towards the centre when a is the cup, away when the ball).
      const Partition& pa = partition_of(result, c.body_a, c.partition_a);
      const double sign = pa.side == MaterialSide::Convex ? 1.0 : -1.0;
      add_cap_stops(index, p, c.radius, vec(c.region_axis), region_angle_of(c), sign, options.cone_samples, out);
      break;
    }
    case ContactType::LAF:
    case ContactType::SPT: {  // direction: bore axis, or the groove's tangent at the ball
      add_axis_forces(frame, p, d, out);
      Vec3 u, v;
      perpendiculars(d, u, v);
      if (c.region_angle >= kPi - 1e-9) {
        out.bilateral_forces.push_back(u);
        out.bilateral_forces.push_back(v);
        break;
      }
      // An open bore or groove: the arc's normals, in the plane across d,
      // are spanned by its ends and its middle (exact: a plane cone).
      const Partition& pa = partition_of(result, c.body_a, c.partition_a);
      const double sign = pa.side == MaterialSide::Convex ? 1.0 : -1.0;
      const Vec3 w = vec(c.region_axis), side = d.cross(w);
      const double half = region_angle_of(c);
      for (double phi : {-half, 0.0, half}) {
        const Vec3 r = std::cos(phi) * w + std::sin(phi) * side;
        out.stops.push_back({index, pnt(p + c.radius * r), dir(sign * r)});
      }
      break;
    }
    case ContactType::TRF: {
      add_axis_forces(frame, p, d, out);
      add_axis_moments(d, out);
      out.rows.push_back(frame.force_row(p, d));
      Vec3 u, v;
      perpendiculars(d, u, v);
      out.bilateral_forces.push_back(u);
      out.bilateral_forces.push_back(v);
      out.bilateral_forces.push_back(d);
      break;
    }
  }
  return out;
}

// A point contact: one force along the normal, one-sided; a line contact:
// that force at both ends of the line (it also holds the rotation across the
// line in the tangent plane); a circle: forces at `samples` points around it
// each along the normal turned with the point, their free directions from the
// exact circular cone of those normals (a ring of radial normals: none across
// the axis; one normal all round: that normal).
ContactConstraints constraints_of_higher(const ContactsResult& result, int index, const Frame& frame,
                                         int samples = 12) {
  const HigherPair& h = result.higher_pairs[index];
  ContactConstraints out;
  const auto add = [&](const gp_Pnt& at, const Vec3& n) {
    out.rows.push_back(frame.force_row(vec(at), n));
    OneSidedStop stop;
    stop.higher_pair = index;
    stop.point = at;
    stop.normal = dir(n);
    out.stops.push_back(stop);
  };
  if (!h.is_circle()) {
    add(h.start, vec(h.normal));
    if (h.is_line()) add(h.end, vec(h.normal));
    return out;
  }
  const Vec3 centre = vec(h.point), m = vec(h.axis).normalized(), n0 = vec(h.normal);
  const Vec3 r0 = (vec(h.start) - centre).normalized(), t0 = m.cross(r0);
  const double along = n0.dot(m), out_radial = n0.dot(r0);  // the normal's parts, the same all round
  const int count = std::max(samples, 3);
  for (int i = 0; i < count; ++i) {
    const double theta = kTwoPi * i / count;
    const Vec3 radial = std::cos(theta) * r0 + std::sin(theta) * t0;
    add(pnt(centre + h.radius * radial), (along * m + out_radial * radial).normalized());
  }
  // A cone on a rim: its normals meet at one point of the axis (to first
  // order a ball joint), but a cone is no sphere: tilted about that point,
  // the rim goes into the cone's material on every side (second order), so
  // the tilts are held, as a seated cone's are (CJU).
  if (h.type == HigherPairType::ConeOnCylinder) add_axis_moments(m, out);
  constexpr double kFlat = 1e-9;
  if (std::abs(out_radial) <= kFlat) {
    out.stops.resize(1);  // one normal all round: one stop says it
  } else if (std::abs(along) <= kFlat) {
    Vec3 u, v;
    perpendiculars(m, u, v);
    out.bilateral_forces.push_back(u);
    out.bilateral_forces.push_back(v);
  } else {
    out.circles.push_back({along > 0 ? m : Vec3(-m), std::acos(std::min(1.0, std::abs(along)))});
  }
  return out;
}

// Generators of {d in R^3 : f . d = 0 for bilateral f, n . d >= 0 for stop n}.
// A circular cone of normals as what the polyhedral computation below takes:
// the free cone about `axis` of half angle beta = pi/2 - angle, replaced by
// the polygon inscribed in it (its `samples` edges exactly on the cone, every
// direction it allows free: the safe side) as the half-spaces of its faces;
// a ray when beta is 0 (a hemispherical cup), nothing when beta < 0.
void add_circle(const CircularStops& circle, int samples, std::vector<Vec3>& bilateral, std::vector<Vec3>& normals) {
  constexpr double kFlat = 1e-7;  // radians
  const Vec3 m = circle.axis.normalized();
  const double beta = kPi / 2 - circle.angle;
  Vec3 u, v;
  perpendiculars(m, u, v);
  if (beta < -kFlat) {
    bilateral.insert(bilateral.end(), {m, u, v});
    return;
  }
  if (beta <= kFlat) {
    bilateral.insert(bilateral.end(), {u, v});
    normals.push_back(m);
    return;
  }
  std::vector<Vec3> edges;
  for (int i = 0; i < samples; ++i) {
    const double theta = kTwoPi * i / samples;
    edges.push_back(std::cos(beta) * m + std::sin(beta) * (std::cos(theta) * u + std::sin(theta) * v));
  }
  for (int i = 0; i < samples; ++i) {
    Vec3 n = edges[i].cross(edges[(i + 1) % samples]);
    if (n.dot(m) < 0) n = -n;
    normals.push_back(n.normalized());
  }
}

std::vector<gp_Dir> free_direction_cone(const std::vector<Vec3>& bilateral, const std::vector<Vec3>& normals) {
  constexpr double tol = 1e-7;
  Eigen::MatrixXd f(bilateral.size(), 3);
  for (size_t i = 0; i < bilateral.size(); ++i) f.row(i) = bilateral[i].transpose();
  const Eigen::MatrixXd basis = null_space(f, 1e-6);  // 3 x k
  const Eigen::Index k = basis.cols();
  std::vector<Vec3> out;
  if (k == 0) return {};
  std::vector<Eigen::VectorXd> m;  // normals within the free subspace
  for (const Vec3& n : normals) {
    Eigen::VectorXd mi = basis.transpose() * n;
    if (mi.norm() > 1e-6) m.push_back(mi.normalized());
  }
  Eigen::MatrixXd mm(m.size(), k);
  for (size_t i = 0; i < m.size(); ++i) mm.row(i) = m[i].transpose();
  const Eigen::MatrixXd lineality = null_space(mm, 1e-6);  // k x l
  const Eigen::MatrixXd pointed = m.empty() ? Eigen::MatrixXd(k, 0) : range_space(mm.transpose(), 1e-6);
  for (Eigen::Index j = 0; j < lineality.cols(); ++j) {
    out.push_back(basis * lineality.col(j));
    out.push_back(-(basis * lineality.col(j)));
  }
  const Eigen::Index q = pointed.cols();
  std::vector<Eigen::VectorXd> mq;  // normals in the pointed part's coordinates
  for (const auto& mi : m) mq.push_back(pointed.transpose() * mi);
  std::vector<Eigen::VectorXd> candidates;
  if (q == 1) {
    candidates.push_back(Eigen::VectorXd::Constant(1, 1.0));
    candidates.push_back(Eigen::VectorXd::Constant(1, -1.0));
  } else if (q == 2) {
    for (const auto& mi : mq) {
      Eigen::VectorXd perp(2);
      perp << -mi(1), mi(0);
      if (perp.norm() < 1e-9) continue;
      candidates.push_back(perp.normalized());
      candidates.push_back(-perp.normalized());
    }
  } else if (q == 3) {
    for (size_t i = 0; i < mq.size(); ++i)
      for (size_t j = i + 1; j < mq.size(); ++j) {
        const Vec3 c = Vec3(mq[i]).cross(Vec3(mq[j]));
        if (c.norm() < 1e-9) continue;
        candidates.push_back(c.normalized());
        candidates.push_back(-c.normalized());
      }
  }
  for (const auto& y : candidates) {
    bool feasible = true;
    for (const auto& mi : mq)
      if (mi.dot(y) < -tol) feasible = false;
    if (!feasible) continue;
    out.push_back(basis * (pointed * y));
  }
  // Unit, without repeats.
  std::vector<gp_Dir> unique;
  for (Vec3 d : out) {
    if (d.norm() < 1e-9) continue;
    d.normalize();
    const bool seen = std::any_of(unique.begin(), unique.end(),
                                  [&](const gp_Dir& u) { return vec(u).dot(d) > 1 - 1e-9; });
    if (!seen) unique.push_back(dir(d));
  }
  return unique;
}

}  // namespace

PairJoint joint_of_pair(const ContactsResult& result, int body_a, int body_b,
                        const std::vector<int>& contact_indices, const JointOptions& options,
                        const std::vector<int>& higher_pair_indices) {
  PairJoint joint;
  joint.body_a = body_a;
  joint.body_b = body_b;
  joint.contacts = contact_indices;
  joint.higher_pairs = higher_pair_indices;

  // The frame: centre of the contact points, size of their spread and patches.
  Frame frame;
  Vec3 sum = Vec3::Zero();
  for (int i : contact_indices) sum += vec(result.contacts[i].point);
  for (int i : higher_pair_indices) sum += vec(result.higher_pairs[i].point);
  const size_t count = contact_indices.size() + higher_pair_indices.size();
  if (count) frame.centre = sum / static_cast<double>(count);
  double length = 0;
  for (int i : contact_indices) {
    const Contact& c = result.contacts[i];
    length = std::max(length, (vec(c.point) - frame.centre).norm() + c.radius + std::sqrt(std::max(0.0, c.area)));
  }
  for (int i : higher_pair_indices) {
    const HigherPair& h = result.higher_pairs[i];
    length = std::max(length, (vec(h.point) - frame.centre).norm() + (h.is_circle() ? h.radius : 0.5 * h.length));
  }
  frame.length = length > 1e-9 ? length : 1.0;
  joint.frame_centre = pnt(frame.centre);
  joint.frame_length = frame.length;

  std::vector<Vec6> rows;
  std::vector<Vec3> bilateral, normals;
  // Surface contacts and higher pairs give their constraints alike.
  const auto take = [&](const ContactConstraints& cc) {
    rows.insert(rows.end(), cc.rows.begin(), cc.rows.end());
    bilateral.insert(bilateral.end(), cc.bilateral_forces.begin(), cc.bilateral_forces.end());
    if (cc.circles.empty()) {
      for (const OneSidedStop& s : cc.stops) normals.push_back(vec(s.normal));
    } else {
      for (const CircularStops& circle : cc.circles) add_circle(circle, options.cone_samples, bilateral, normals);
    }
    joint.stops.insert(joint.stops.end(), cc.stops.begin(), cc.stops.end());
  };
  for (int i : contact_indices) take(constraints_of(result, i, frame, options));
  for (int i : higher_pair_indices) take(constraints_of_higher(result, i, frame, options.cone_samples));
  Eigen::MatrixXd a(rows.size(), 6);
  for (size_t i = 0; i < rows.size(); ++i) a.row(i) = rows[i].transpose().normalized();
  const Eigen::MatrixXd free = null_space(a, options.rank_tolerance);
  const TwistSpace space = classify_local(free, frame, options.rank_tolerance);
  joint.type = space.type;
  joint.dof = space.dof;
  joint.free_twists = space.basis;
  joint.rotations = space.rotations;
  joint.translations = space.translations;
  joint.pitch = space.pitch;
  joint.free_directions = free_direction_cone(bilateral, normals);
  // A press fit or a bond among the pair's contacts: rigid, whatever the
  // surfaces would allow.
  const auto intent_of = [](const std::vector<ContactIntent>& intents, int i) {
    return i < static_cast<int>(intents.size()) ? intents[i] : ContactIntent::Unspecified;
  };
  bool rigid = false;
  for (int i : contact_indices) rigid = rigid || holds_rigid(intent_of(options.contact_intents, i));
  for (int i : higher_pair_indices) rigid = rigid || holds_rigid(intent_of(options.higher_pair_intents, i));
  if (rigid) {
    joint.annotated_rigid = true;
    joint.type = JointType::Rigid;
    joint.dof = 0;
    joint.free_twists.clear();
    joint.rotations.clear();
    joint.translations.clear();
    joint.pitch = 0;
    joint.stops.clear();
    joint.free_directions.clear();
  }
  return joint;
}

std::vector<gp_Dir> body_free_directions(const ContactsResult& contacts, const JointsResult& joints, int body,
                                         const JointOptions& options) {
  std::vector<Vec3> bilateral, normals;
  const Frame frame;  // only the force directions are used
  for (const PairJoint& joint : joints.joints) {
    if (joint.body_a != body && joint.body_b != body) continue;
    if (joint.annotated_rigid) return {};  // held by a press fit or a bond
    // Stops are written for b moving away from a: a moves away along -n.
    const double sign = joint.body_b == body ? 1.0 : -1.0;
    // A surface contact's or a higher pair's constraints, as seen by `body`.
    auto add = [&](const ContactConstraints& cc) {
      bilateral.insert(bilateral.end(), cc.bilateral_forces.begin(), cc.bilateral_forces.end());
      if (cc.circles.empty()) {
        for (const OneSidedStop& stop : cc.stops) normals.push_back(sign * vec(stop.normal));
      } else {
        for (CircularStops circle : cc.circles) {
          circle.axis *= sign;
          add_circle(circle, options.cone_samples, bilateral, normals);
        }
      }
    };
    for (int i : joint.contacts) add(constraints_of(contacts, i, frame, options));
    for (int i : joint.higher_pairs) add(constraints_of_higher(contacts, i, frame, options.cone_samples));
  }
  return free_direction_cone(bilateral, normals);
}

JointsResult find_joints(const Assembly& assembly, const ContactsResult& contacts, const JointOptions& options) {
  JointsResult out;
  if (contacts.partitions.size() != assembly.bodies.size()) {
    out.status = Status::failure(StatusCode::InvalidInput,
                                 "find_joints: the contacts were found on another assembly (" +
                                     std::to_string(contacts.partitions.size()) + " bodies, not " +
                                     std::to_string(assembly.bodies.size()) + ")");
    return out;
  }
  // Per body pair: its surface contacts, then its point and line contacts.
  std::map<std::pair<int, int>, std::pair<std::vector<int>, std::vector<int>>> by_pair;
  const auto ignored = [](const std::vector<ContactIntent>& intents, size_t i) {
    return i < intents.size() && intents[i] == ContactIntent::Ignored;
  };
  for (size_t i = 0; i < contacts.contacts.size(); ++i) {
    if (ignored(options.contact_intents, i)) continue;
    const Contact& c = contacts.contacts[i];
    by_pair[{std::min(c.body_a, c.body_b), std::max(c.body_a, c.body_b)}].first.push_back(static_cast<int>(i));
  }
  for (size_t i = 0; i < contacts.higher_pairs.size(); ++i) {
    if (ignored(options.higher_pair_intents, i)) continue;
    const HigherPair& h = contacts.higher_pairs[i];
    by_pair[{std::min(h.body_a, h.body_b), std::max(h.body_a, h.body_b)}].second.push_back(static_cast<int>(i));
  }
  out.joints.reserve(by_pair.size());
  for (const auto& [pair, indices] : by_pair) {
    PairJoint joint = joint_of_pair(contacts, pair.first, pair.second, indices.first, options, indices.second);
    out.joints.push_back(std::move(joint));
  }
  return out;
}

}  // namespace contactcore
