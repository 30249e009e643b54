// Blocking by sweeps (conservative advancement with distance queries, a probe
// where the parts touch), then removal by sink components of the directional
// blocking graphs.
#include "contactcore/simulation/disassembly.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numeric>

#include <Standard_Failure.hxx>

#include "contactcore/joints/joints.h"
#include "contactcore/common/occt_guard.h"

namespace contactcore {

namespace {

constexpr double kParallel = 1e-9;

double dot(const Direction& a, const Direction& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

Direction unit(const Direction& d) {
  const double length = std::sqrt(dot(d, d));
  return length > 0 ? Direction{d[0] / length, d[1] / length, d[2] / length} : Direction{0, 0, 0};
}

void add_direction(std::vector<Direction>& directions, const Direction& d) {
  const Direction u = unit(d);
  if (dot(u, u) == 0) return;
  for (const Direction& known : directions)
    if (dot(known, u) > 1 - kParallel) return;
  directions.push_back(u);
}

struct Box {
  std::array<double, 3> min{}, max{};
};

Box mesh_box(const TaggedMesh& mesh) {
  Box box;
  box.min = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
             std::numeric_limits<double>::max()};
  box.max = {-box.min[0], -box.min[1], -box.min[2]};
  for (const auto& v : mesh.vertices)
    for (int k = 0; k < 3; ++k) {
      box.min[k] = std::min(box.min[k], v[k]);
      box.max[k] = std::max(box.max[k], v[k]);
    }
  return box;
}

// The projection [lo, hi] of a box on a direction.
std::pair<double, double> project(const Box& box, const Direction& d) {
  double lo = 0, hi = 0;
  for (int k = 0; k < 3; ++k) {
    const double a = box.min[k] * d[k], b = box.max[k] * d[k];
    lo += std::min(a, b);
    hi += std::max(a, b);
  }
  return {lo, hi};
}

// Does the box of `moving`, swept by s in [0, length] along d, reach more than tol into `fixed`?
// A vertex deeper than tol inside a part is deeper than tol inside its box (the way out to the
// box crosses the part's surface), so boxes that only touch or graze (the cubes of the next row
// beside a cube sliding out) cannot block.
bool sweep_meets(const Box& moving, const Direction& d, double length, const Box& fixed, double tol) {
  for (int k = 0; k < 3; ++k) {
    const double lo = moving.min[k] + std::min(0.0, d[k] * length), hi = moving.max[k] + std::max(0.0, d[k] * length);
    if (hi <= fixed.min[k] + tol || lo >= fixed.max[k] - tol) return false;
  }
  return true;
}

// Does a contact between `part` and the other part forbid moving `part` along d by itself?
bool contact_blocks(const Contact& c, int part, const Direction& d) {
  const Direction axis{c.direction.X(), c.direction.Y(), c.direction.Z()};
  switch (c.type) {
    case ContactType::PLF: {
      // `direction` is body_a's outward normal: moving along it pushes into the other part.
      const double into = part == c.body_a ? dot(d, axis) : -dot(d, axis);
      return into > kParallel;
    }
    case ContactType::CLJ:
    case ContactType::CJU:
    case ContactType::LAF:
      return std::abs(dot(d, axis)) < 1 - kParallel;  // only along the axis
    case ContactType::SPF:
    case ContactType::SPT:
    case ContactType::TRF:
      return true;  // a ball held in its cup or groove: no translation
  }
  return true;
}

// Strongly connected components (Tarjan, iterative); returns component of each node.
std::vector<int> components(const std::vector<std::vector<int>>& edges, int& count) {
  const int n = static_cast<int>(edges.size());
  std::vector<int> index(n, -1), low(n, 0), component(n, -1), stack;
  std::vector<char> on_stack(n, 0);
  int next_index = 0;
  count = 0;
  for (int root = 0; root < n; ++root) {
    if (index[root] >= 0) continue;
    std::vector<std::pair<int, std::size_t>> call{{root, 0}};
    index[root] = low[root] = next_index++;
    stack.push_back(root);
    on_stack[root] = 1;
    while (!call.empty()) {
      auto& [v, i] = call.back();
      if (i < edges[v].size()) {
        const int w = edges[v][i++];
        if (index[w] < 0) {
          index[w] = low[w] = next_index++;
          stack.push_back(w);
          on_stack[w] = 1;
          call.push_back({w, 0});
        } else if (on_stack[w]) {
          low[v] = std::min(low[v], index[w]);
        }
        continue;
      }
      if (low[v] == index[v]) {
        for (int w = -1; w != v;) {
          w = stack.back();
          stack.pop_back();
          on_stack[w] = 0;
          component[w] = count;
        }
        ++count;
      }
      const int done = v;
      call.pop_back();
      if (!call.empty()) low[call.back().first] = std::min(low[call.back().first], low[done]);
    }
  }
  return component;
}

}  // namespace

std::vector<Direction> candidate_directions(const std::vector<DisassemblyPart>& parts) {
  std::vector<Direction> directions;
  for (int k = 0; k < 3; ++k) {
    Direction plus{0, 0, 0}, minus{0, 0, 0};
    plus[k] = 1;
    minus[k] = -1;
    add_direction(directions, plus);
    add_direction(directions, minus);
  }
  for (const DisassemblyPart& part : parts)
    for (const Direction& d : part.directions) {
      add_direction(directions, d);
      add_direction(directions, {-d[0], -d[1], -d[2]});
    }
  return directions;
}

DisassemblyResult plan_disassembly(const std::vector<DisassemblyPart>& parts, const std::vector<Contact>& contacts,
                                   const DisassemblyOptions& options, Progress* progress) {
  DisassemblyResult result;
  const int n = static_cast<int>(parts.size());
  for (const DisassemblyPart& part : parts)
    if (!part.model) {
      result.status = Status::failure(StatusCode::InvalidInput, "part without a collision model");
      result.status.body = part.name;
      return result;
    }
  for (const Contact& c : contacts)
    if (c.body_a < 0 || c.body_a >= n || c.body_b < 0 || c.body_b >= n || c.body_a == c.body_b) {
      result.status = Status::failure(StatusCode::InvalidInput, "a contact refers to a missing part");
      return result;
    }
  if (!(options.tolerance > 0) || !std::isfinite(options.tolerance)) {
    result.status = Status::failure(StatusCode::InvalidArgument, "the disassembly tolerance must be a positive, finite "
                                                                 "length in mm");
    return result;
  }
  result.directions = candidate_directions(parts);
  const int directions = static_cast<int>(result.directions.size());
  result.blocking.assign(directions, std::vector<std::vector<int>>(n));
  if (n == 0) {
    result.complete = true;
    return result;
  }

  std::vector<Box> boxes(n);
  for (int i = 0; i < n; ++i) boxes[i] = mesh_box(parts[i].model->mesh());
  // A part is blocked when a probe puts it deeper than the tolerance into
  // another: at half the thinnest part's thickness or more, that part can
  // never be seen inside another, and a sweep through it passes (issue 25:
  // tolerance 1e9 gave a "complete" sequence cutting into the front cover).
  {
    int thinnest = -1;
    double thickness = std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i) {
      double side = std::numeric_limits<double>::infinity();
      for (int k = 0; k < 3; ++k) side = std::min(side, boxes[i].max[k] - boxes[i].min[k]);
      if (side > 0 && side < thickness) thickness = side, thinnest = i;
    }
    if (thinnest >= 0 && options.tolerance >= thickness / 2) {
      char text[300];
      std::snprintf(text, sizeof text,
                    "the disassembly tolerance %g mm is at least half the thinnest part's thickness ('%s', %g mm): "
                    "no overlap with it could be seen; at most %g mm",
                    options.tolerance, parts[thinnest].name.c_str(), thickness, thickness / 2);
      result.status = Status::failure(StatusCode::InvalidArgument, text);
      return result;
    }
  }
  // Contacts of each unordered pair.
  std::vector<std::vector<std::vector<int>>> pair_contacts(n, std::vector<std::vector<int>>(n));
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    pair_contacts[contacts[k].body_a][contacts[k].body_b].push_back(static_cast<int>(k));
    pair_contacts[contacts[k].body_b][contacts[k].body_a].push_back(static_cast<int>(k));
  }
  const double tol = options.tolerance;

  // Is a triangle centroid of i, moved by t along d, deeper than tol inside j? The vertex depth
  // misses faces crossing without a vertex inside: a cube pushed into a cube of the same section
  // has all its corners on the other's faces.
  auto centroid_inside = [&](int i, int j, double t, const Direction& d, CollisionPair& pair) {
    const TaggedMesh& mesh = parts[i].model->mesh();
    const Box& target = boxes[j];
    for (const auto& triangle : mesh.triangles) {
      std::array<double, 3> c{};
      for (int k = 0; k < 3; ++k)
        for (int v : triangle) c[k] += mesh.vertices[v][k] / 3;
      bool in_box = true;
      for (int k = 0; k < 3 && in_box; ++k) {
        c[k] += t * d[k];
        in_box = c[k] > target.min[k] + tol && c[k] < target.max[k] - tol;
      }
      if (in_box && pair.depth_inside(1, RigidTransform::identity(), c) > tol) return true;
    }
    return false;
  };

  // Does `j` block `i` moving along d? Local: the contacts; global: a sweep.
  QueryResult query;
  auto blocks = [&](int i, int j, const Direction& d) {
    for (int k : pair_contacts[i][j])
      if (contact_blocks(contacts[k], i, d)) return true;
    const auto [lo_i, hi_i] = project(boxes[i], d);
    const auto [lo_j, hi_j] = project(boxes[j], d);
    const double clear = hi_j - lo_i + tol;  // beyond this, i is past j along d
    if (clear <= 0 || !sweep_meets(boxes[i], d, clear, boxes[j], tol)) return false;
    CollisionPair pair(parts[i].model, parts[j].model);
    for (int k : pair_contacts[i][j]) {
      const Contact& c = contacts[k];
      pair.set_partition_enabled(0, i == c.body_a ? c.partition_a : c.partition_b, false);
      pair.set_partition_enabled(1, i == c.body_a ? c.partition_b : c.partition_a, false);
    }
    const RigidTransform fixed = RigidTransform::identity();
    const double probe = std::max(2 * tol, clear / 64);
    for (double s = 0; s < clear;) {
      pair.query(RigidTransform::translated(s * d[0], s * d[1], s * d[2]), fixed, QueryKind::Distance, query);
      if (query.distance > probe) {
        s += query.distance - tol / 2;  // nothing can be met before
        continue;
      }
      // Near or touching: does moving on by a probe step cut into j? Faces that only touch along
      // edges (beside a planar fit being slid along) put no vertex inside the other part. (Creeping
      // by the distance instead would take thousands of steps along a part sliding past another.)
      const double t = s + probe;
      const RigidTransform moved = RigidTransform::translated(t * d[0], t * d[1], t * d[2]);
      pair.query(moved, fixed, QueryKind::Penetration, query);
      if (query.intersecting && (query.depth > tol || centroid_inside(i, j, t, d, pair))) return true;
      s = t;
    }
    return false;
  };

  try {
    for (int i = 0; i < n; ++i) {
      if (progress && !progress->report("blocking", static_cast<double>(i) / n)) {
        result.status = Status::failure(StatusCode::Cancelled, "cancelled while finding what blocks each part");
        return result;
      }
      for (int di = 0; di < directions; ++di)
        for (int j = 0; j < n; ++j)
          if (j != i && blocks(i, j, result.directions[di])) result.blocking[di][i].push_back(j);
    }
  } catch (const Standard_Failure& failure) {
    result.status = Status::failure(StatusCode::GeometryError, std::string("OCCT: ") + failure.GetMessageString());
    return result;
  }

  // Removal: at each step, over all directions, the sink components of the
  // blocking graph restricted to the remaining parts (nothing outside them
  // blocks them); the smallest, then the lightest, goes first.
  std::vector<char> remaining(n, 1);
  int left = n;
  // holds[j]: the parts j blocks in some direction; scratch marks for the leverage sums.
  std::vector<std::vector<int>> holds(n);
  for (int di = 0; di < directions; ++di)
    for (int k = 0; k < n; ++k)
      for (int j : result.blocking[di][k]) holds[j].push_back(k);
  for (auto& list : holds) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  std::vector<char> in_group(n, 0);
  std::vector<long> counted(n, -1);
  long stamp = 0;
  while (left > 1) {
    if (progress && !progress->report("sequence", 1.0 - static_cast<double>(left) / n)) {
      result.status = Status::failure(StatusCode::Cancelled, "cancelled while ordering the removal");
      return result;
    }
    std::vector<int> alive;
    std::vector<int> local(n, -1);
    for (int i = 0; i < n; ++i)
      if (remaining[i]) {
        local[i] = static_cast<int>(alive.size());
        alive.push_back(i);
      }
    bool found = false;
    DisassemblyStep best;
    double best_volume = 0;
    double best_leverage = 0;
    for (int di = 0; di < directions; ++di) {
      std::vector<std::vector<int>> edges(alive.size());
      for (std::size_t a = 0; a < alive.size(); ++a)
        for (int j : result.blocking[di][alive[a]])
          if (remaining[j]) edges[a].push_back(local[j]);
      int count = 0;
      const std::vector<int> component = components(edges, count);
      std::vector<char> sink(count, 1);
      std::vector<std::vector<int>> members(count);
      for (std::size_t a = 0; a < alive.size(); ++a) {
        members[component[a]].push_back(alive[a]);
        for (int b : edges[a])
          if (component[b] != component[a]) sink[component[a]] = 0;
      }
      for (int c = 0; c < count; ++c) {
        if (!sink[c] || static_cast<int>(members[c].size()) == left) continue;
        double volume = 0;
        for (int i : members[c]) volume += parts[i].volume;
        for (int i : members[c]) in_group[i] = 1;
        // Leverage: the volume of the remaining parts the group blocks in some direction, over its
        // own volume. Fasteners (small, holding much) come first.
        double held = 0;
        for (int j : members[c])
          for (int k : holds[j])
            if (remaining[k] && !in_group[k] && counted[k] != stamp) {
              counted[k] = stamp;
              held += parts[k].volume;
            }
        ++stamp;
        for (int i : members[c]) in_group[i] = 0;
        const double leverage = held / std::max(volume, 1e-12);
        const bool better =
            !found || members[c].size() < best.parts.size() ||
            (members[c].size() == best.parts.size() &&
             (leverage > best_leverage * (1 + 1e-9) ||
              (leverage >= best_leverage * (1 - 1e-9) && volume < best_volume - 1e-9)));
        if (better) {
          found = true;
          best.parts = members[c];
          std::sort(best.parts.begin(), best.parts.end());
          best.direction = result.directions[di];
          best_volume = volume;
          best_leverage = leverage;
        }
      }
    }
    if (!found) {
      std::string names;
      for (int i : alive) names += (names.empty() ? "" : ", ") + parts[i].name;
      result.reason = "no part or group of the remaining parts (" + names +
                      ") can leave along any candidate direction: they interlock";
      return result;
    }
    for (int i : best.parts) remaining[i] = 0;
    left -= static_cast<int>(best.parts.size());
    result.steps.push_back(best);
  }
  for (int i = 0; i < n; ++i)
    if (remaining[i]) result.base = i;
  result.complete = true;
  if (progress) progress->report("sequence", 1.0);
  return result;
}

DisassemblyResult disassemble(const Assembly& assembly, const ContactOptions& contact_options,
                              const MeshOptions& mesh_options, const DisassemblyOptions& options,
                              const std::vector<std::vector<Direction>>& extra_directions, Progress* progress) {
  DisassemblyResult result;
  // A signal inside OCCT while a body is measured or meshed fails the call
  // naming the body (find_contacts guards its own stages).
  const OcctGuard guard;
  {
    std::vector<TopoDS_Shape> shapes;
    std::vector<std::string> names;
    for (const Body& body : assembly.bodies) shapes.push_back(body.shape), names.push_back(body.name);
    result.status = check_triangle_budget(shapes, names, mesh_options);
    if (!result.status.ok()) return result;
  }
  const ContactsResult found = find_contacts(assembly, contact_options, progress);
  if (!found.status.ok()) {
    result.status = found.status;
    return result;
  }
  std::vector<DisassemblyPart> parts(assembly.bodies.size());
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const Body& body = assembly.bodies[i];
    parts[i].name = body.name;
    MeshResult meshed;
    std::string failure;
    if (!run_guarded([&] {
          parts[i].volume = mass_properties(body.shape).volume;
          meshed = mesh_body(body.shape, found.partitions[i], mesh_options);
        }, failure, "OCCT: "))
      meshed.status = Status::failure(StatusCode::GeometryError, failure);
    for (const FaceFailure& failed : meshed.failed_faces)
      result.messages.push_back("body '" + body.name + "': Face" + std::to_string(failed.face) +
                                " not meshed (" + failed.message + "): its collision model has a hole there");
    if (!meshed.status.ok()) {
      result.status = meshed.status;
      result.status.body = body.name;
      return result;
    }
    CollisionModelResult built = build_collision_model(meshed.mesh);
    if (!built.status.ok()) {
      result.status = built.status;
      result.status.body = body.name;
      return result;
    }
    parts[i].model = built.model;
    if (i < extra_directions.size()) parts[i].directions = extra_directions[i];
  }
  // Each contact's axis (joints) or normal (planar fits) is a way out for its parts, and so is
  // every free translation of the pair joints (b leaves a along d, a leaves b along -d).
  for (const Contact& c : found.contacts) {
    const Direction d{c.direction.X(), c.direction.Y(), c.direction.Z()};
    parts[c.body_a].directions.push_back(d);
    parts[c.body_b].directions.push_back(d);
  }
  const JointsResult joints = find_joints(assembly, found);
  if (joints.status.ok())
    for (const PairJoint& joint : joints.joints)
      for (const gp_Dir& d : joint.free_directions) {
        parts[joint.body_b].directions.push_back({d.X(), d.Y(), d.Z()});
        parts[joint.body_a].directions.push_back({-d.X(), -d.Y(), -d.Z()});
      }
  DisassemblyOptions resolved = options;
  if (resolved.tolerance == 0) resolved.tolerance = 2 * mesh_options.deflection;  // 0: the default
  // anything else not positive and finite is refused by plan_disassembly
  DisassemblyResult planned = plan_disassembly(parts, found.contacts, resolved, progress);
  planned.messages.insert(planned.messages.begin(), result.messages.begin(), result.messages.end());
  return planned;
}

}  // namespace contactcore
