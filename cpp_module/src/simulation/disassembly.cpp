// Blocking by sweeps (conservative advancement with distance queries, a probe
// where the parts touch), then removal by sink components of the directional
// blocking graphs.
#include "contactcore/simulation/disassembly.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <optional>

#include <Standard_Failure.hxx>

#include "contactcore/joints/joints.h"
#include "contactcore/common/occt_guard.h"
#include "common/union_find.h"
#include "simulation/point3.h"

namespace contactcore {

namespace {

constexpr double kParallel = 1e-9;

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
  int directions = static_cast<int>(result.directions.size());
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

  // Blocking lists of the directions from `first` on, for the parts still in place (`alive`).
  const auto compute_blocking = [&](int first, const std::vector<char>& alive) {
    try {
      for (int i = 0; i < n; ++i) {
        if (progress && !progress->report("blocking", static_cast<double>(i) / n)) {
          result.status = Status::failure(StatusCode::Cancelled, "cancelled while finding what blocks each part");
          return false;
        }
        if (!alive[i]) continue;
        for (int di = first; di < directions; ++di)
          for (int j = 0; j < n; ++j)
            if (j != i && alive[j] && blocks(i, j, result.directions[di])) result.blocking[di][i].push_back(j);
      }
    } catch (const Standard_Failure& failure) {
      result.status = Status::failure(StatusCode::GeometryError, std::string("OCCT: ") + failure.GetMessageString());
      return false;
    }
    return true;
  };
  if (!compute_blocking(0, std::vector<char>(n, 1))) return result;

  // Removal. Units: the parts joined by annotated fits and bonds (not released ones), moved as
  // one. At each step, over all directions, the sink components of the units' blocking graph
  // restricted to what remains (nothing outside them blocks them), ranked as the header says.
  const auto intent_of = [&](std::size_t k) {
    return k < options.contact_intents.size() ? options.contact_intents[k] : ContactIntent::Unspecified;
  };
  std::vector<char> remaining(n, 1);
  std::vector<char> released(contacts.size(), 0);
  std::vector<int> removed_at(n, -1);  // the step that removed each part
  // holder[i]: the parts i is still held by through a released bond (a screw's thread): i is
  // blocked by them along every direction until they are gone.
  std::vector<std::vector<int>> held_by(n), holding(n);  // holding[j]: the parts j holds so
  std::vector<int> unit_of(n);
  const auto make_units = [&] {
    detail::UnionFind joined(n);
    for (std::size_t k = 0; k < contacts.size(); ++k)
      if (!released[k] && holds_rigid(intent_of(k))) joined.unite(contacts[k].body_a, contacts[k].body_b);
    for (int i = 0; i < n; ++i) unit_of[i] = joined.find(i);
  };
  make_units();
  // Calls visit(j) for each part blocking part i along direction di (before anything is
  // removed): the sweeps' and the released bonds'.
  const auto for_each_blocker = [&](int di, int i, auto&& visit) {
    for (int j : result.blocking[di][i]) visit(j);
    for (int j : held_by[i]) visit(j);
  };
  // holds[j]: the parts j blocks in some direction.
  std::vector<std::vector<int>> holds(n);
  for (int di = 0; di < directions; ++di)
    for (int k = 0; k < n; ++k)
      for (int j : result.blocking[di][k]) holds[j].push_back(k);
  for (auto& list : holds) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  // The base: the unit of the largest part, held still (the housing a mechanic works on).
  int largest = 0;
  for (int i = 1; i < n; ++i)
    if (parts[i].volume > parts[largest].volume) largest = i;
  struct Candidate {
    std::vector<int> parts;
    int units = 0;           // units moving together (1: a part or a sub-assembly on its own)
    int direction = -1;
    bool useful = false;
    int freed_at = -1;       // the last step that removed one of its blockers along this way out
    int group_freed_at = -1;  // the step after which the group could leave some way: the least freed_at
    bool same_direction = false;
    std::size_t blockers = 0;  // parts that blocked it this way at first
    double leverage = 0, volume = 0;
  };
  const auto better = [](const Candidate& a, const Candidate& b) {  // is a to be taken before b?
    if (a.units != b.units) return a.units < b.units;
    if (a.useful != b.useful) return a.useful;
    if (a.group_freed_at != b.group_freed_at) return a.group_freed_at > b.group_freed_at;
    if (a.same_direction != b.same_direction) return a.same_direction;
    if (a.leverage > b.leverage * (1 + 1e-9)) return true;
    if (a.leverage < b.leverage * (1 - 1e-9)) return false;
    return a.volume < b.volume - 1e-9;
  };
  int left = n;
  std::vector<char> in_group(n, 0);
  std::vector<long> counted(n, -1);
  long stamp = 0;
  // The best removable group with the units as they are, or none.
  // Of the ways out of one group, the one it was free along first, then the previous step's
  // direction, then the one fewest parts blocked at first.
  const auto better_way = [](const Candidate& a, const Candidate& b) {
    if (a.freed_at != b.freed_at) return a.freed_at < b.freed_at;
    if (a.same_direction != b.same_direction) return a.same_direction;
    return a.blockers < b.blockers;
  };
  const auto best_candidate = [&](std::optional<Candidate>& best) {
    best.reset();
    std::vector<Candidate> found;  // the best way out of each group
    std::map<std::vector<int>, std::size_t> group_index;
    std::vector<int> units;  // unit roots of the remaining parts
    std::vector<int> local(n, -1);
    for (int i = 0; i < n; ++i)
      if (remaining[i] && local[unit_of[i]] < 0) {
        local[unit_of[i]] = static_cast<int>(units.size());
        units.push_back(unit_of[i]);
      }
    if (units.size() < 2) return;
    std::vector<std::vector<int>> members(units.size());
    for (int i = 0; i < n; ++i)
      if (remaining[i]) members[local[unit_of[i]]].push_back(i);
    const Direction* previous = result.steps.empty() ? nullptr : &result.steps.back().direction;
    for (int di = 0; di < directions; ++di) {
      std::vector<std::vector<int>> edges(units.size());
      for (std::size_t u = 0; u < units.size(); ++u) {
        for (int i : members[u])
          for_each_blocker(di, i, [&](int j) {
            if (remaining[j] && unit_of[j] != units[u]) edges[u].push_back(local[unit_of[j]]);
          });
        std::sort(edges[u].begin(), edges[u].end());
        edges[u].erase(std::unique(edges[u].begin(), edges[u].end()), edges[u].end());
      }
      int count = 0;
      const std::vector<int> component = components(edges, count);
      std::vector<char> sink(count, 1);
      std::vector<std::vector<int>> parts_of(count);
      std::vector<int> units_of(count, 0);
      for (std::size_t u = 0; u < units.size(); ++u) {
        ++units_of[component[u]];
        if (units[u] == unit_of[largest]) sink[component[u]] = 0;  // the base stays
        parts_of[component[u]].insert(parts_of[component[u]].end(), members[u].begin(), members[u].end());
        for (int v : edges[u])
          if (component[v] != component[u]) sink[component[u]] = 0;
      }
      for (int c = 0; c < count; ++c) {
        if (!sink[c] || static_cast<int>(parts_of[c].size()) == left) continue;
        Candidate candidate;
        candidate.units = units_of[c];
        candidate.parts = parts_of[c];
        std::sort(candidate.parts.begin(), candidate.parts.end());
        candidate.direction = di;
        for (int i : candidate.parts) in_group[i] = 1;
        for (int i : candidate.parts) {
          candidate.volume += parts[i].volume;
          for_each_blocker(di, i, [&](int j) {
            if (!in_group[j]) candidate.freed_at = std::max(candidate.freed_at, removed_at[j]);
          });
        }
        // Useful: it blocks a part still in place. Leverage: the volume of those over its own.
        double held = 0;
        const auto count_held = [&](int k) {
          if (remaining[k] && !in_group[k] && counted[k] != stamp) {
            counted[k] = stamp;
            held += parts[k].volume;
            candidate.useful = true;
          }
        };
        for (int j : candidate.parts) {
          for (int k : holds[j]) count_held(k);
          for (int k : holding[j]) count_held(k);
        }
        ++stamp;
        for (int i : candidate.parts) in_group[i] = 0;
        candidate.leverage = held / std::max(candidate.volume, 1e-12);
        candidate.same_direction = previous != nullptr && dot(*previous, result.directions[di]) > 1 - kParallel;
        for (int i : candidate.parts) candidate.blockers += result.blocking[di][i].size() + held_by[i].size();
        const auto known = group_index.find(candidate.parts);
        if (known == group_index.end()) {
          candidate.group_freed_at = candidate.freed_at;
          group_index.emplace(candidate.parts, found.size());
          found.push_back(std::move(candidate));
        } else {
          Candidate* same = &found[known->second];
          const int group_freed_at = std::min(same->group_freed_at, candidate.freed_at);
          if (better_way(candidate, *same)) *same = std::move(candidate);
          same->group_freed_at = group_freed_at;
        }
      }
    }
    for (Candidate& candidate : found)
      if (!best || better(candidate, *best)) best = std::move(candidate);
  };
  const auto units_left = [&] {
    std::vector<char> seen(n, 0);
    int count = 0;
    for (int i = 0; i < n; ++i)
      if (remaining[i] && !seen[unit_of[i]]) seen[unit_of[i]] = 1, ++count;
    return count;
  };
  bool sampled = false;
  while (units_left() > 1) {
    if (progress && !progress->report("sequence", 1.0 - static_cast<double>(left) / n)) {
      result.status = Status::failure(StatusCode::Cancelled, "cancelled while ordering the removal");
      return result;
    }
    std::optional<Candidate> best;
    best_candidate(best);
    if (!best && !sampled) {
      // Nothing leaves along the axes, normals and joint directions: add the directions sampled
      // inside the remaining parts' free cones (once: they do not change), with their blocking.
      sampled = true;
      const int first = directions;
      for (int i = 0; i < n; ++i)
        if (remaining[i])
          for (const Direction& d : parts[i].sampled_directions) add_direction(result.directions, d);
      directions = static_cast<int>(result.directions.size());
      if (directions > first) {
        result.blocking.resize(directions, std::vector<std::vector<int>>(n));
        if (!compute_blocking(first, remaining)) return result;
        for (int di = first; di < directions; ++di)
          for (int k = 0; k < n; ++k)
            for (int j : result.blocking[di][k]) holds[j].push_back(k);
        for (auto& list : holds) {
          std::sort(list.begin(), list.end());
          list.erase(std::unique(list.begin(), list.end()), list.end());
        }
        best_candidate(best);
      }
    }
    std::vector<int> released_now;
    if (!best) {
      // Nothing can leave: undo one fastening a mechanic can undo, a threaded cylindrical contact
      // (a screw in its thread, often drawn as a plain bore), the smallest part first, if that
      // lets a group out. The part it held is the one on its own after the release (else the
      // smaller). Bonded contacts (glued, welded, staked) are never undone: their parts come out
      // as one sub-assembly or stay with the base.
      std::vector<int> bonds;
      for (std::size_t k = 0; k < contacts.size(); ++k) {
        const Contact& c = contacts[k];
        if (!released[k] && intent_of(k) == ContactIntent::Threaded && c.type == ContactType::CLJ &&
            remaining[c.body_a] && remaining[c.body_b])
          bonds.push_back(static_cast<int>(k));
      }
      const auto smaller = [&](int k) {
        return std::min(parts[contacts[k].body_a].volume, parts[contacts[k].body_b].volume);
      };
      std::stable_sort(bonds.begin(), bonds.end(), [&](int x, int y) { return smaller(x) < smaller(y) - 1e-9; });
      for (int k : bonds) {
        released[k] = 1;
        make_units();
        const Contact& c = contacts[k];
        int unit_a = 0, unit_b = 0;
        for (int i = 0; i < n; ++i)
          if (remaining[i]) unit_a += unit_of[i] == unit_of[c.body_a], unit_b += unit_of[i] == unit_of[c.body_b];
        const bool a_held = unit_a != unit_b ? unit_a < unit_b : parts[c.body_a].volume <= parts[c.body_b].volume;
        const int fastener = a_held ? c.body_a : c.body_b, host = a_held ? c.body_b : c.body_a;
        held_by[host].push_back(fastener);
        holding[fastener].push_back(host);
        best_candidate(best);
        if (best) {
          released_now.push_back(k);
          break;
        }
        held_by[host].pop_back();
        holding[fastener].pop_back();
        released[k] = 0;
        make_units();
      }
    }
    if (!best) {
      std::string names;
      for (int i = 0; i < n; ++i)
        if (remaining[i]) names += (names.empty() ? "" : ", ") + parts[i].name;
      result.reason = "no part or group of the remaining parts (" + names +
                      ") can leave along any candidate direction: they interlock";
      return result;
    }
    DisassemblyStep step;
    step.parts = best->parts;
    step.direction = result.directions[best->direction];
    step.released = released_now;
    for (int i : step.parts) in_group[i] = 1;
    for (int i : step.parts)
      for_each_blocker(best->direction, i, [&](int j) {
        if (!in_group[j]) step.blocked_before.push_back(j);
      });
    for (int i : step.parts) in_group[i] = 0;
    std::sort(step.blocked_before.begin(), step.blocked_before.end());
    step.blocked_before.erase(std::unique(step.blocked_before.begin(), step.blocked_before.end()),
                              step.blocked_before.end());
    for (int i : step.parts) {
      remaining[i] = 0;
      removed_at[i] = static_cast<int>(result.steps.size());
    }
    left -= static_cast<int>(step.parts.size());
    result.steps.push_back(std::move(step));
  }
  for (int i = 0; i < n; ++i)
    if (remaining[i]) result.base_parts.push_back(i);
  result.base = largest;
  result.complete = true;
  if (progress) progress->report("sequence", 1.0);
  return result;
}

DisassemblyResult disassemble(const Assembly& assembly, const ContactOptions& contact_options,
                              const MeshOptions& mesh_options, const DisassemblyOptions& options,
                              const std::vector<std::vector<Direction>>& extra_directions, Progress* progress,
                              const ContactsResult* contacts) {
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
  ContactsResult found_here;
  if (contacts == nullptr) found_here = find_contacts(assembly, contact_options, progress);
  const ContactsResult& found = contacts != nullptr ? *contacts : found_here;
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
    if (meshed.status.ok() && meshed.mesh.triangles.empty() && !meshed.failed_faces.empty())
      // OCCT's mesher failed on every face. Its per-face catch also swallows out-of-memory
      // (Standard_OutOfMemory): under a 120 MB limit the motor's front cover came back empty and was
      // then refused as "an empty mesh" (exit 3, as if the file were bad). Say what happened.
      meshed.status = Status::failure(StatusCode::GeometryError,
                                      "OCCT could not tessellate any of the body's " +
                                          std::to_string(meshed.failed_faces.size()) +
                                          " faces (its mesher fails so when memory runs out too)");
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
  JointOptions joint_options;
  joint_options.contact_intents = options.contact_intents;
  const JointsResult joints = find_joints(assembly, found, joint_options);
  if (joints.status.ok()) {
    for (const PairJoint& joint : joints.joints)
      for (const gp_Dir& d : joint.free_directions) {
        parts[joint.body_b].directions.push_back({d.X(), d.Y(), d.Z()});
        parts[joint.body_a].directions.push_back({-d.X(), -d.Y(), -d.Z()});
      }
    // Beyond the axes and normals: directions inside each part's cone of free directions (a
    // block in a corner leaves along the diagonal as well as along each wall).
    if (options.sample_free_cones)
      for (std::size_t i = 0; i < parts.size(); ++i) {
        const std::vector<gp_Dir> cone = body_free_directions(found, joints, static_cast<int>(i), joint_options);
        Direction middle{0, 0, 0};
        for (std::size_t a = 0; a < cone.size(); ++a) {
          const Direction u{cone[a].X(), cone[a].Y(), cone[a].Z()};
          parts[i].sampled_directions.push_back(u);
          for (int k = 0; k < 3; ++k) middle[k] += u[k];
          for (std::size_t b = a + 1; b < cone.size(); ++b) {
            const Direction sum{u[0] + cone[b].X(), u[1] + cone[b].Y(), u[2] + cone[b].Z()};
            if (dot(sum, sum) > 1e-12) parts[i].sampled_directions.push_back(sum);  // made unit when added
          }
        }
        if (cone.size() > 2 && dot(middle, middle) > 1e-12) parts[i].sampled_directions.push_back(middle);
      }
  }
  DisassemblyOptions resolved = options;
  if (resolved.tolerance == 0) resolved.tolerance = 2 * mesh_options.deflection;  // 0: the default
  // anything else not positive and finite is refused by plan_disassembly
  DisassemblyResult planned = plan_disassembly(parts, found.contacts, resolved, progress);
  planned.messages.insert(planned.messages.begin(), result.messages.begin(), result.messages.end());
  return planned;
}

}  // namespace contactcore
