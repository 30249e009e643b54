// Assembly mobility: every pair's bilateral constraints at once, one part
// grounded. Sparse by construction: passive spins are found per body, rigid
// groups are merged pairwise with union-find (a bolt seated in its plate, two
// plates held by two bolts), and what remains is solved per connected
// component of the group graph: directly along a spanning tree when the
// component has no loop, by a dense SVD of that component only otherwise.
#include <algorithm>
#include <cmath>
#include <optional>
#include <numeric>
#include <unordered_map>

#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <TopLoc_Location.hxx>
#include <gp_Mat.hxx>
#include <gp_Trsf.hxx>

#include "contactcore/joints/joints.h"
#include "contactcore/common/occt_guard.h"
#include "common/union_find.h"
#include "joints/twist_math.h"

namespace contactcore {

using namespace detail;

namespace {

Eigen::Matrix3d skew(const Vec3& a) {
  Eigen::Matrix3d m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

// Twists in the frame at `from` -> the frame at `to` (same length).
Eigen::Matrix<double, 6, 6> move_twists(const Vec3& from, const Vec3& to, double length) {
  Eigen::Matrix<double, 6, 6> m = Eigen::Matrix<double, 6, 6>::Identity();
  m.block<3, 3>(3, 0) = -skew((to - from) / length);  // v_to = v_from + w x (to - from)
  return m;
}

int rank_of(const Eigen::MatrixXd& m, double tol) { return static_cast<int>(range_space(m, tol).cols()); }

// Intersection of two column spaces.
Eigen::MatrixXd intersect(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double tol) {
  if (a.cols() == 0 || b.cols() == 0) return Eigen::MatrixXd(6, 0);
  Eigen::MatrixXd ab(6, a.cols() + b.cols());
  ab << a, -b;
  const Eigen::MatrixXd x = null_space(ab, tol);
  return range_space(a * x.topRows(a.cols()), tol);
}

Eigen::MatrixXd concat(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  Eigen::MatrixXd out(6, a.cols() + b.cols());
  out << a, b;
  return out;
}

// Mass, centre and inertia (about the centre) of a body's solids. Placed
// copies of one part share their TShape: computed once per TShape at the
// identity placement, then moved (centre) and rotated (inertia).
struct MassData {
  double mass = 0;
  Vec3 centre = Vec3::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

class MassCache {
 public:
  MassData of(const TopoDS_Shape& shape) {
    const gp_Trsf trsf = shape.Location().Transformation();
    if (std::abs(trsf.ScaleFactor() - 1.0) > 1e-12) return compute(shape);
    const void* key = shape.TShape().get();
    auto it = cache_.find(key);
    if (it == cache_.end()) it = cache_.emplace(key, compute(shape.Located(TopLoc_Location()))).first;
    const MassData& local = it->second;
    MassData out;
    out.mass = local.mass;
    gp_Pnt centre(local.centre.x(), local.centre.y(), local.centre.z());
    out.centre = vec(centre.Transformed(trsf));
    Eigen::Matrix3d rotation;
    const gp_Mat r = trsf.VectorialPart();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) rotation(i, j) = r.Value(i + 1, j + 1);
    out.inertia = rotation * local.inertia * rotation.transpose();
    return out;
  }

 private:
  static MassData compute(const TopoDS_Shape& shape) {
    GProp_GProps props;
    // A signal inside OCCT (under assembly_mobility's OcctGuard) is a Standard_Failure.
    with_occt_signals([&] { BRepGProp::VolumeProperties(shape, props); });
    MassData out;
    out.mass = props.Mass();
    out.centre = vec(props.CentreOfMass());
    const gp_Mat m = props.MatrixOfInertia();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) out.inertia(i, j) = m.Value(i + 1, j + 1);
    return out;
  }
  std::unordered_map<const void*, MassData> cache_;
};

// Whether a body is balanced about a line: its centre of mass on the line
// and the line an axis of symmetry of its inertia (the two moments across it
// equal). Such a body spinning about the line moves no mass around.
bool balanced_about(const MassData& m, const Vec3& point, const Vec3& direction) {
  if (m.mass <= 0) return false;
  const Vec3 d = direction.normalized();
  const double scale = m.inertia.trace();
  const double radius = std::sqrt(scale / m.mass);  // radius of gyration, for the distance test
  const Vec3 off = (m.centre - point) - d * d.dot(m.centre - point);
  if (off.norm() > 1e-4 * radius) return false;
  Vec3 u, v;
  perpendiculars(d, u, v);
  const double tol = 1e-4 * scale;
  const Eigen::Matrix3d& j = m.inertia;
  return std::abs(u.dot(j * u) - v.dot(j * v)) <= tol && std::abs(u.dot(j * v)) <= tol &&
         std::abs(u.dot(j * d)) <= tol && std::abs(v.dot(j * d)) <= tol;
}

struct Edge {  // one body pair, constraints on t_b - t_a, rows in the frame at `centre`
  int a = 0, b = 0;
  Vec3 centre;
  Eigen::MatrixXd rows;  // (6 - dof) x 6
};

struct Solver {
  const JointsResult& joints;
  const ContactsResult& contacts;
  double tol;
  double length = 1;
  int n = 0;
  std::vector<Edge> edges;
  std::vector<std::vector<int>> edges_of;  // per body
  std::vector<Vec3> centre;                // per body (group frames use their root's)
  std::vector<Eigen::MatrixXd> passive;    // per body: spins, 6 x p in the body frame
  std::vector<std::vector<FreeRotation>> spins;
  std::vector<Eigen::MatrixXd> ambiguity;  // per group root: spins shared by all its bodies
  std::vector<Eigen::MatrixXd> motion;     // per group root: twists relative to the ground
  UnionFind groups{0};
  MassCache masses;

  Solver(const JointsResult& j, const ContactsResult& c, double t) : joints(j), contacts(c), tol(t) {}

  Eigen::MatrixXd rows_at(const Edge& e, const Vec3& to) const {
    return e.rows * move_twists(to, e.centre, length);
  }

  void build_edges() {
    std::vector<double> lengths;
    for (const PairJoint& j : joints.joints) lengths.push_back(j.frame_length);
    if (!lengths.empty()) {
      std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
      length = std::max(lengths[lengths.size() / 2], 1e-6);
    }
    edges_of.assign(n, {});
    std::vector<Vec3> sum(n, Vec3::Zero());
    std::vector<int> count(n, 0);
    for (const PairJoint& j : joints.joints) {
      Edge e;
      e.a = j.body_a, e.b = j.body_b;
      Frame frame;
      frame.centre = vec(j.frame_centre);
      frame.length = length;
      e.centre = frame.centre;
      Mat6X free(6, j.free_twists.size());
      for (size_t i = 0; i < j.free_twists.size(); ++i) free.col(i) = frame.to_local(j.free_twists[i]);
      e.rows = j.free_twists.empty() ? Eigen::MatrixXd(Eigen::MatrixXd::Identity(6, 6))
                                     : constraint_rows(free, tol);
      edges_of[e.a].push_back(static_cast<int>(edges.size()));
      edges_of[e.b].push_back(static_cast<int>(edges.size()));
      for (int body : {e.a, e.b}) sum[body] += e.centre, ++count[body];
      edges.push_back(std::move(e));
    }
    centre.resize(n);
    for (int i = 0; i < n; ++i) centre[i] = count[i] ? Vec3(sum[i] / count[i]) : Vec3::Zero();
  }

  // Rotations a body can make alone, about the axes of its revolution and
  // sphere contacts, every neighbour held still, the body balanced about them.
  void find_passive_spins(const Assembly& assembly, int ground) {
    passive.assign(n, Eigen::MatrixXd(6, 0));
    spins.assign(n, {});
    for (int body = 0; body < n; ++body) {
      if (body == ground || edges_of[body].empty()) continue;
      std::vector<FreeRotation> candidates;
      for (int e : edges_of[body]) {
        const PairJoint& j = joints.joints[e];
        for (int ci : j.contacts) {
          const Contact& c = contacts.contacts[ci];
          switch (c.type) {
            case ContactType::CLJ:
            case ContactType::CJU:
            case ContactType::TRF: candidates.push_back({c.point, c.direction}); break;
            case ContactType::SPF:
            case ContactType::LAF:
            case ContactType::SPT:
              for (const gp_Dir& d : {gp_Dir(1, 0, 0), gp_Dir(0, 1, 0), gp_Dir(0, 0, 1)})
                candidates.push_back({c.point, d});
              break;
            case ContactType::PLF: break;
          }
        }
      }
      Eigen::MatrixXd basis(6, 0);
      std::optional<MassData> mass;
      for (const FreeRotation& axis : candidates) {
        const Vec3 d = vec(axis.direction), p = vec(axis.point);
        Vec6 spin;  // rotation about the line, in the body frame
        spin << d, (p - centre[body]).cross(d) / length;
        bool free = true;
        for (int e : edges_of[body]) {
          const Eigen::VectorXd residual = rows_at(edges[e], centre[body]) * spin;
          if (residual.norm() > 1e-6 * std::max(1.0, spin.norm())) free = false;
        }
        if (!free) continue;
        if (!mass) mass = masses.of(assembly.bodies[body].shape);
        if (!balanced_about(*mass, p, d)) continue;
        const Eigen::MatrixXd grown = concat(basis, spin);
        if (rank_of(grown, 1e-6) > basis.cols()) {
          basis = range_space(grown, 1e-6);
          spins[body].push_back(axis);
        }
      }
      passive[body] = basis;
    }
  }

  Eigen::MatrixXd moved(const Eigen::MatrixXd& twists, int from_body, int to_body) const {
    return move_twists(centre[from_body], centre[to_body], length) * twists;
  }

  // Relative twists allowed between two groups (in g's frame) by the edges between them.
  Eigen::MatrixXd relative_freedom(int g, const std::vector<int>& between) const {
    Eigen::MatrixXd stacked(0, 6);
    for (int e : between) {
      const Eigen::MatrixXd r = rows_at(edges[e], centre[g]);
      Eigen::MatrixXd grown(stacked.rows() + r.rows(), 6);
      grown << stacked, r;
      stacked = std::move(grown);
    }
    return null_space(stacked, tol);
  }

  // Merges g and h when everything they may do relative to each other is made
  // of their own passive spins; returns true when merged.
  bool try_merge(int g, int h, const Eigen::MatrixXd& relative /* in g's frame */) {
    const Eigen::MatrixXd spins_both = concat(ambiguity[g], moved(ambiguity[h], h, g));
    if (relative.cols() > 0 && rank_of(concat(spins_both, relative), 1e-6) > rank_of(spins_both, 1e-6))
      return false;
    ambiguity[g] = intersect(ambiguity[g], moved(ambiguity[h], h, g), 1e-6);
    groups.attach(h, g);
    return true;
  }

  std::unordered_map<long long, std::vector<int>> group_edges() {
    std::unordered_map<long long, std::vector<int>> by_pair;
    for (size_t e = 0; e < edges.size(); ++e) {
      int g = groups.find(edges[e].a), h = groups.find(edges[e].b);
      if (g == h) continue;
      if (g > h) std::swap(g, h);
      by_pair[(static_cast<long long>(g) << 32) | h].push_back(static_cast<int>(e));
    }
    return by_pair;
  }

  void merge_pairwise() {
    ambiguity = passive;
    for (bool changed = true; changed;) {
      changed = false;
      std::vector<char> touched(n, 0);
      for (const auto& [key, between] : group_edges()) {
        const int g = static_cast<int>(key >> 32), h = static_cast<int>(key & 0xffffffff);
        if (touched[g] || touched[h]) continue;
        if (try_merge(g, h, relative_freedom(g, between))) touched[g] = touched[h] = 1, changed = true;
      }
    }
  }
};

}  // namespace

MobilityResult assembly_mobility(const Assembly& assembly, const ContactsResult& contacts,
                                 const JointsResult& joints, const MobilityOptions& options,
                                 Progress* progress) {
  MobilityResult out;
  const int n = static_cast<int>(assembly.bodies.size());
  if (n == 0) return out;
  const OcctGuard guard;  // the bodies' volumes and inertia: a signal inside OCCT is an error
  int ground = options.ground;
  if (ground >= n) {
    out.status = Status::failure(StatusCode::InvalidInput,
                                 "ground body index " + std::to_string(ground) + " out of range");
    return out;
  }
  Solver s(joints, contacts, options.rank_tolerance);
  if (ground < 0) {
    double best = -1;
    for (int i = 0; i < n; ++i) {
      const double volume = s.masses.of(assembly.bodies[i].shape).mass;
      if (volume > best) best = volume, ground = i;
    }
  }
  out.ground = ground;
  for (const PairJoint& j : joints.joints)
    if (j.body_a < 0 || j.body_b >= n || j.body_a >= j.body_b) {
      out.status = Status::failure(StatusCode::InvalidInput,
                                   "assembly_mobility: a joint names bodies " + std::to_string(j.body_a) + " and " +
                                       std::to_string(j.body_b) + ", not of this assembly's " + std::to_string(n));
      return out;
    }
  if (progress && !progress->report("mobility", 0.0)) {
    out.status = Status::failure(StatusCode::Cancelled, "cancelled");
    return out;
  }

  s.n = n;
  s.groups = UnionFind(n);
  s.build_edges();
  s.find_passive_spins(assembly, ground);
  s.merge_pairwise();
  // Each group's shared spins counted once (before the loops merge more groups).
  int ambiguity_count = 0;
  for (int i = 0; i < n; ++i)
    if (s.groups.find(i) == i) ambiguity_count += static_cast<int>(s.ambiguity[i].cols());
  if (progress && !progress->report("mobility", 0.5)) {
    out.status = Status::failure(StatusCode::Cancelled, "cancelled");
    return out;
  }

  // The group graph, its components, and each group's motion.
  const int ground_group = s.groups.find(ground);
  s.motion.assign(n, Eigen::MatrixXd(6, 0));
  auto by_pair = s.group_edges();
  std::unordered_map<int, std::vector<std::pair<int, std::vector<int>>>> neighbours;
  for (const auto& [key, between] : by_pair) {
    const int g = static_cast<int>(key >> 32), h = static_cast<int>(key & 0xffffffff);
    neighbours[g].push_back({h, between});
    neighbours[h].push_back({g, between});
  }
  std::vector<int> roots;
  for (int i = 0; i < n; ++i)
    if (s.groups.find(i) == i) roots.push_back(i);
  std::vector<char> seen(n, 0);
  int component_dof = 0;
  std::vector<int> order = roots;
  // Components starting from the ground's, so the ground is their root.
  std::stable_partition(order.begin(), order.end(), [&](int g) { return g == ground_group; });
  for (int start : order) {
    if (seen[start]) continue;
    std::vector<int> members{start};
    seen[start] = 1;
    int edge_count = 0;
    for (size_t k = 0; k < members.size(); ++k)
      for (const auto& [h, between] : neighbours[members[k]]) {
        ++edge_count;
        if (!seen[h]) seen[h] = 1, members.push_back(h);
      }
    edge_count /= 2;
    const bool grounded = start == ground_group;
    const int m = static_cast<int>(members.size());
    if (edge_count == m - 1) {
      // A tree: each group moves as its parent plus the freedom of the edge between them.
      s.motion[start] = grounded ? Eigen::MatrixXd(6, 0) : Eigen::MatrixXd(Eigen::MatrixXd::Identity(6, 6));
      component_dof += grounded ? 0 : 6;
      std::unordered_map<int, char> placed{{start, 1}};
      for (int g : members)
        for (const auto& [h, between] : neighbours[g]) {
          if (placed.count(h)) continue;
          placed[h] = 1;
          const Eigen::MatrixXd relative = s.relative_freedom(g, between);
          component_dof += static_cast<int>(relative.cols());
          s.motion[h] = s.moved(range_space(concat(s.motion[g], relative), 1e-6), g, h);
        }
      // BFS order of `members` guarantees parents come first.
    } else {
      // Loops: the component's groups at once (6 unknowns each, the ground's fixed).
      std::unordered_map<int, int> column;
      for (int g : members)
        if (!(grounded && g == ground_group)) column[g] = static_cast<int>(column.size()) * 6;
      std::vector<Eigen::MatrixXd> blocks;
      std::vector<std::pair<int, int>> owners;
      Eigen::Index rows = 0;
      for (int g : members)
        for (const auto& [h, between] : neighbours[g]) {
          if (h < g) continue;
          const Eigen::MatrixXd relative = s.relative_freedom(g, between);
          const Eigen::MatrixXd c = relative.cols() ? Eigen::MatrixXd(constraint_rows(relative, 1e-6))
                                                    : Eigen::MatrixXd(Eigen::MatrixXd::Identity(6, 6));
          blocks.push_back(c);
          owners.push_back({g, h});
          rows += c.rows();
        }
      Eigen::MatrixXd a = Eigen::MatrixXd::Zero(rows, column.size() * 6);
      Eigen::Index row = 0;
      for (size_t b = 0; b < blocks.size(); ++b) {
        const auto [g, h] = owners[b];
        // c (t_h moved to g - t_g) = 0
        if (column.count(h)) a.block(row, column[h], blocks[b].rows(), 6) = blocks[b] * move_twists(s.centre[h], s.centre[g], s.length);
        if (column.count(g)) a.block(row, column[g], blocks[b].rows(), 6) -= blocks[b];
        row += blocks[b].rows();
      }
      const Eigen::MatrixXd nulls = a.cols() ? null_space(a, options.rank_tolerance) : Eigen::MatrixXd(0, 0);
      component_dof += static_cast<int>(nulls.cols());
      for (int g : members)
        s.motion[g] = column.count(g) ? range_space(nulls.middleRows(column[g], 6), 1e-6) : Eigen::MatrixXd(6, 0);
      // Groups that the loops hold together (relative motion made of their
      // spins only), to a fixed point. A merged group moves as the root it keeps.
      const auto twist_of = [&](int root, Eigen::Index k) {
        return column.count(root) ? Vec6(nulls.col(k).segment<6>(column[root])) : Vec6(Vec6::Zero());
      };
      for (bool changed = true; changed;) {
        changed = false;
        for (int g : members)
          for (const auto& [h, between] : neighbours[g]) {
            const int rg = s.groups.find(g), rh = s.groups.find(h);
            if (rg == rh) continue;
            const bool keep_g = rg == ground_group || (rh != ground_group && rg < rh);
            const int keep = keep_g ? rg : rh, drop = keep_g ? rh : rg;
            Eigen::MatrixXd relative(6, nulls.cols());
            for (Eigen::Index k = 0; k < nulls.cols(); ++k)
              relative.col(k) = move_twists(s.centre[drop], s.centre[keep], s.length) * twist_of(drop, k) -
                                twist_of(keep, k);
            if (s.try_merge(keep, drop, range_space(relative, 1e-6))) changed = true;
          }
      }
    }
  }

  // Groups: the ground's first, then by their smallest body.
  std::vector<int> root_order;
  for (int i = 0; i < n; ++i) {
    const int r = s.groups.find(i);
    if (std::find(root_order.begin(), root_order.end(), r) == root_order.end()) root_order.push_back(r);
  }
  std::stable_partition(root_order.begin(), root_order.end(),
                        [&](int r) { return r == s.groups.find(ground); });
  std::unordered_map<int, int> index_of;
  for (int r : root_order) index_of[r] = static_cast<int>(out.groups.size()), out.groups.push_back({});
  out.group_of_body.resize(n);
  int passive_count = 0;
  for (int i = 0; i < n; ++i) {
    const int g = index_of[s.groups.find(i)];
    out.groups[g].push_back(i);
    out.group_of_body[i] = g;
    passive_count += static_cast<int>(s.passive[i].cols());
    for (const FreeRotation& axis : s.spins[i]) out.passive_spins.push_back({i, axis});
  }
  out.passive = passive_count;
  out.dof = component_dof + passive_count - ambiguity_count;

  for (int r : root_order) {
    GroupMotion gm;
    gm.group = index_of[r];
    // The group's twists modulo the spins all its bodies share.
    const Eigen::MatrixXd& shared = s.ambiguity[r];
    Eigen::MatrixXd twists = s.motion[r];
    if (shared.cols() > 0 && twists.cols() > 0)
      twists = (Eigen::MatrixXd::Identity(6, 6) - shared * shared.transpose()) * twists;
    Frame frame;
    frame.centre = s.centre[r];
    frame.length = s.length;
    const TwistSpace space = classify_local(twists, frame, 1e-6);
    gm.type = space.type;
    gm.dof = space.dof;
    gm.rotations = space.rotations;
    gm.translations = space.translations;
    gm.pitch = space.pitch;
    for (int body : out.groups[gm.group])
      for (const FreeRotation& axis : s.spins[body]) gm.passive_spins.push_back({body, axis});
    out.group_motions.push_back(std::move(gm));
  }

  // Connected components of the contact graph.
  UnionFind parts(n);
  for (const Edge& e : s.edges) parts.attach(e.a, e.b);
  std::unordered_map<int, int> component_of;
  for (int i = 0; i < n; ++i) {
    const int r = parts.find(i);
    if (!component_of.count(r)) component_of[r] = static_cast<int>(out.components.size()), out.components.push_back({});
    out.components[component_of[r]].push_back(i);
  }
  if (progress) progress->report("mobility", 1.0);
  return out;
}

}  // namespace contactcore
