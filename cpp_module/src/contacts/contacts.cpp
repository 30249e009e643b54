#include "contactcore/contacts/contacts.h"
#include "contactcore/contacts/contacts_memo.h"
#include "contactcore/common/out_of_memory.h"
#include "contactcore/contacts/clearances.h"

#include "contacts/common_area.h"
#include "contactcore/bodies/instances.h"
#include "contacts/higher_pairs.h"
#include "contacts/interferences.h"
#include "contacts/pair_key.h"
#include "contactcore/common/occt_guard.h"
#include "contactcore/common/parallel.h"
#include "contacts/validity.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <exception>
#include <sstream>
#include <tuple>

#include <BRepBndLib.hxx>
#include <Standard_Failure.hxx>
#include <gp_Vec.hxx>

namespace contactcore {

const char* to_string(ContactType type) {
  switch (type) {
    case ContactType::PLF: return "PLF";
    case ContactType::CLJ: return "CLJ";
    case ContactType::CJU: return "CJU";
    case ContactType::SPF: return "SPF";
    case ContactType::LAF: return "LAF";
    case ContactType::SPT: return "SPT";
    case ContactType::TRF: return "TRF";
  }
  return "?";
}

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Sort key of a partition for candidate search: partitions that can touch
// have equal keys within tolerance (planes: distance of the plane from the
// origin; cylinders, spheres: radius; cones: half angle; tori: minor radius,
// which is also the radius of a ball in the groove).
struct CandidateKey {
  int group;  // 0 plane, 1 round (cylinder, sphere, torus minor), 2 cone
  double key;
  int partition;
};

int key_group(SurfaceKind kind) {
  switch (kind) {
    case SurfaceKind::Plane: return 0;
    case SurfaceKind::Cylinder:
    case SurfaceKind::Sphere:
    case SurfaceKind::Torus: return 1;
    case SurfaceKind::Cone: return 2;
    default: return -1;
  }
}

std::vector<CandidateKey> candidate_keys(const BodyPartitions& body) {
  std::vector<CandidateKey> keys;
  for (const Partition& p : body.partitions) {
    const int group = key_group(p.params.kind);
    if (group < 0) continue;
    double key = 0;
    switch (p.params.kind) {
      case SurfaceKind::Plane:
        key = std::abs(gp_Vec(p.params.location.XYZ()).Dot(gp_Vec(p.params.axis)));
        break;
      case SurfaceKind::Cone: key = p.params.half_angle; break;
      case SurfaceKind::Torus: key = p.params.minor_radius; break;
      default: key = p.params.radius; break;
    }
    keys.push_back({group, key, p.id});
  }
  std::sort(keys.begin(), keys.end(), [](const CandidateKey& l, const CandidateKey& r) {
    return l.group != r.group ? l.group < r.group : l.key < r.key;
  });
  return keys;
}

struct Candidate {
  int body_a, partition_a, body_b, partition_b;
};

bool same_key(const CandidateKey& l, const CandidateKey& r) {
  return l.group != r.group ? l.group < r.group : l.key < r.key;
}

// Partition pairs of one body pair whose sort keys agree and boxes meet.
void pair_candidates(int ia, int ib, const std::vector<std::vector<CandidateKey>>& keys,
                     const std::vector<BodyPartitions>& parts, const Tolerances& tol,
                     std::vector<Candidate>& out) {
  const auto& kb = keys[ib];
  for (const CandidateKey& k : keys[ia]) {
    const double window = k.group == 2 ? tol.angular : tol.linear;
    auto it = std::lower_bound(kb.begin(), kb.end(), CandidateKey{k.group, k.key - window, 0}, same_key);
    for (; it != kb.end() && it->group == k.group && it->key <= k.key + window; ++it) {
      const Partition& pa = parts[ia].partitions[k.partition];
      const Partition& pb = parts[ib].partitions[it->partition];
      if (!boxes_meet(pa.box, pb.box, tol.linear)) continue;
      out.push_back({ia, k.partition, ib, it->partition});
    }
  }
}

std::string faces_text(const std::vector<int>& faces) {
  std::string text;
  for (int f : faces) text += (text.empty() ? "Face" : ",Face") + std::to_string(f);
  return text;
}

// Span of a box along each axis, grown by `gap`, for the sweep.
struct Span {
  std::array<double, 3> lo, hi;
  int body;
};

// Pairs of intervals [lo, hi] that overlap along `axis`: the sweep's work on it.
std::size_t overlapping_along(std::vector<Span>& spans, int axis) {
  std::vector<double> los(spans.size());
  for (std::size_t i = 0; i < spans.size(); ++i) los[i] = spans[i].lo[axis];
  std::sort(los.begin(), los.end());
  std::sort(spans.begin(), spans.end(), [axis](const Span& l, const Span& r) { return l.lo[axis] < r.lo[axis]; });
  std::size_t count = 0;
  for (std::size_t i = 0; i < spans.size(); ++i) {
    const auto end = std::upper_bound(los.begin(), los.end(), spans[i].hi[axis]);
    count += static_cast<std::size_t>(end - los.begin()) - (i + 1);
  }
  return count;
}

}  // namespace

BroadPhase broad_phase(const std::vector<Bnd_Box>& boxes, double gap, std::size_t max_pairs, Progress* progress) {
  return broad_phase(boxes, std::vector<double>(boxes.size(), gap), max_pairs, progress);
}

BroadPhase broad_phase(const std::vector<Bnd_Box>& boxes, const std::vector<double>& gaps, std::size_t max_pairs,
                       Progress* progress) {
  BroadPhase out;
  std::vector<Span> spans;
  spans.reserve(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    if (boxes[i].IsVoid()) continue;
    double x0, y0, z0, x1, y1, z1;
    boxes[i].Get(x0, y0, z0, x1, y1, z1);  // includes the box's own gap
    const double gap = gaps[i];  // spans grown by each body's own gap: a superset of the pairs below
    spans.push_back({{x0 - gap, y0 - gap, z0 - gap}, {x1 + gap, y1 + gap, z1 + gap}, static_cast<int>(i)});
  }
  // Sweep along the axis on which the fewest spans overlap: an assembly
  // stacked along z (a motor) sweeps on x or y, a plate row on y or z.
  int axis = 0;
  std::size_t work = static_cast<std::size_t>(-1);
  for (int k = 0; k < 3; ++k) {
    const std::size_t along = overlapping_along(spans, k);
    if (along < work) work = along, axis = k;
  }
  std::sort(spans.begin(), spans.end(), [axis](const Span& l, const Span& r) { return l.lo[axis] < r.lo[axis]; });
  using Clock = std::chrono::steady_clock;
  auto last = Clock::now() - std::chrono::seconds(1);  // report at the start too
  for (std::size_t i = 0; i < spans.size(); ++i) {
    if (progress && (i & 255) == 0 && Clock::now() - last > std::chrono::milliseconds(50)) {
      if (!progress->report("broad phase", static_cast<double>(i) / static_cast<double>(spans.size()))) {
        out.status = Status::failure(StatusCode::Cancelled, "cancelled");
        return out;
      }
      last = Clock::now();
    }
    for (std::size_t j = i + 1; j < spans.size() && spans[j].lo[axis] <= spans[i].hi[axis]; ++j) {
      const int a = std::min(spans[i].body, spans[j].body), b = std::max(spans[i].body, spans[j].body);
      // In index order (boxes' own gaps differ); a pair's gap is the coarser of its two.
      if (!boxes_meet(boxes[a], boxes[b], std::max(gaps[a], gaps[b]))) continue;
      out.pairs.emplace_back(a, b);
      if (out.pairs.size() > max_pairs) {
        std::ostringstream message;
        message << "more than " << max_pairs << " body pairs have meeting boxes (up to " << work
                << " may): the bodies overlap heavily (copies placed on top of each other?); "
                   "raise the limit (ContactOptions::max_body_pairs, CLI --max-pairs) to go on";
        out.status = Status::failure(StatusCode::InvalidInput, message.str());
        return out;
      }
    }
  }
  std::sort(out.pairs.begin(), out.pairs.end());
  return out;
}

ContactsResult find_contacts(const Assembly& assembly, const ContactOptions& options, Progress* progress) {
  return find_contacts(assembly, options, progress, nullptr);
}

namespace {

bool same_tolerances(const Tolerances& a, const Tolerances& b) {
  return a.linear == b.linear && a.angular == b.angular;
}

}  // namespace

ContactsResult find_contacts(const Assembly& assembly, const ContactOptions& options, Progress* progress,
                             ContactsMemo* memo) {
  ContactsResult result;
  // The memo of the last run, taken (this run refills it on success only).
  ContactsMemo last, next;
  std::vector<int> memo_sources;      // this run's instance sources, for the memo
  std::size_t memo_reused_bodies = 0;
  if (memo) {
    last = std::move(*memo);
    *memo = ContactsMemo{};
  }
  const auto cancelled = [&result]() {
    result.status = Status::failure(StatusCode::Cancelled, "cancelled");
    return result;
  };
  const std::size_t n = assembly.bodies.size();
  const int threads = options.threads;
  auto start = Clock::now();
  // OCCT dereferences null handles on some damaged shapes: with its signal
  // handler installed for the whole call, a fault in a body's partitioning or
  // a pair's test fails that body or pair (run_guarded in each worker item),
  // not the process.
  const OcctGuard guard;
  try {
    // Bodies that instance one shape (a TShape placed by rigid motions).
    std::vector<int> sources(n);
    if (options.reuse_instances) {
      sources = instance_sources(assembly.bodies);
    } else {
      for (std::size_t i = 0; i < n; ++i) sources[i] = static_cast<int>(i);
    }

    // The model's box, for the tolerances: instances take their source's
    // box moved (exact for translations, a little larger when turned).
    std::vector<Bnd_Box> boxes(n);
    std::vector<std::string> box_failures(n);
    // A source body whose shape is the memo's (the same OCCT shape, location
    // and orientation), a source then too: the memo's box.
    std::vector<char> known_box(n, 0);
    if (last.shapes.size() == n && last.shape_boxes.size() == n)
      for (std::size_t i = 0; i < n; ++i)
        known_box[i] = sources[i] == static_cast<int>(i) && last.sources[i] == sources[i] &&
                       last.shapes[i].IsEqual(assembly.bodies[i].shape) && !last.shape_boxes[i].IsVoid();
    if (!parallel_for(n, threads, progress, "partitions", [&](std::size_t i) {
          if (known_box[i]) {
            boxes[i] = last.shape_boxes[i];
          } else if (sources[i] == static_cast<int>(i)) {
            run_guarded([&] { BRepBndLib::Add(assembly.bodies[i].shape, boxes[i], false); }, box_failures[i], "OCCT: ");
          }
        }, 16))
      return cancelled();
    if (memo) next.shape_boxes = boxes;
    for (std::size_t i = 0; i < n; ++i) {
      if (box_failures[i].empty()) continue;
      result.status = Status::failure(StatusCode::GeometryError, box_failures[i]);
      result.status.body = assembly.bodies[i].name;
      return result;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const int source = sources[i];
      if (source != static_cast<int>(i) && !boxes[source].IsVoid())
        boxes[i] = boxes[source].Transformed(relative_motion(assembly.bodies[source], assembly.bodies[i]));
    }
    // A value the caller gives is checked against the whole model (as
    // before); the defaults are each body's own (body_tolerances: a part far
    // away or a huge one changes nothing about the others), instances taking
    // their source's. A body pair is compared with the coarser of its two.
    Bnd_Box model_box;
    for (const Bnd_Box& box : boxes) model_box.Add(box);
    const Tolerances requested{options.linear.value_or(Tolerances{}.linear),
                               options.angular.value_or(Tolerances{}.angular)};
    result.status = check_tolerances(options.linear ? model_box : Bnd_Box(), requested);
    if (!result.status.ok()) return result;
    std::vector<Tolerances> body_tol(n);
    for (std::size_t i = 0; i < n; ++i) {
      const Status status = body_tolerances(boxes[sources[i]], options.linear, options.angular, body_tol[i]);
      if (!status.ok()) {
        result.status = status;
        result.status.body = assembly.bodies[i].name;
        return result;
      }
    }
    // Reported: the caller's value, or the coarsest body's.
    result.tolerances = requested;
    if (!options.linear && n > 0) {
      result.tolerances.linear = 0;
      for (const Tolerances& t : body_tol) result.tolerances.linear = std::max(result.tolerances.linear, t.linear);
    }

    // Each distinct shape partitioned once (partition_shape only reads the
    // shapes, so bodies sharing TShapes through instancing can run
    // concurrently), then moved to the other placements of that shape.
    const auto partition_body = [&](std::size_t i) {
      BodyPartitions& body = result.partitions[i];
      std::string failure;
      if (!run_guarded([&] { body = partition_shape(assembly.bodies[i].shape, body_tol[i]); }, failure, "OCCT: "))
        body.status = Status::failure(StatusCode::GeometryError, failure);
    };
    result.partitions.resize(n);
    result.instance_of.resize(n);
    for (std::size_t i = 0; i < n; ++i) result.instance_of[i] = static_cast<int>(i);
    // The bodies that did not change since the memo's run (the same shape at
    // the same index, the same tolerances, the same instance source), and
    // those whose partitions are reused: unchanged, as their source is.
    std::vector<char> unchanged(n, 0), reused(n, 0);
    if (last.shapes.size() == n) {
      for (std::size_t i = 0; i < n; ++i)
        unchanged[i] = last.shapes[i].IsEqual(assembly.bodies[i].shape) &&
                       same_tolerances(last.body_tolerances[i], body_tol[i]) && last.sources[i] == sources[i] &&
                       last.partitions[i].status.ok();
      for (std::size_t i = 0; i < n; ++i) {
        if (!unchanged[i] || !unchanged[sources[i]]) continue;
        reused[i] = 1;
        result.partitions[i] = last.partitions[i];
        result.instance_of[i] = last.instance_of[i];
      }
    }
    if (memo) {
      memo_sources = sources;
      for (std::size_t i = 0; i < n; ++i) memo_reused_bodies += reused[i] ? 1 : 0;
    }
    std::vector<std::vector<CandidateKey>> keys(n);
    if (!parallel_for(n, threads, progress, "partitions", [&](std::size_t i) {
          if (sources[i] == static_cast<int>(i) && !reused[i]) partition_body(i);
        }))
      return cancelled();
    if (!parallel_for(n, threads, progress, "partitions", [&](std::size_t i) {
          const int source = sources[i];
          if (source != static_cast<int>(i) && !reused[i]) {
            const BodyPartitions& original = result.partitions[source];
            if (original.status.ok()) {
              std::string failure;
              if (!run_guarded([&] {
                    result.partitions[i] = moved_partitions(
                        original, relative_motion(assembly.bodies[source], assembly.bodies[i]), assembly.bodies[i].shape);
                  }, failure, "OCCT: "))
                result.partitions[i].status = Status::failure(StatusCode::GeometryError, failure);
            }
            if (!original.status.ok() || !result.partitions[i].status.ok()) {
              partition_body(i);
            } else {
              result.instance_of[i] = source;
            }
          }
          if (result.partitions[i].status.ok()) keys[i] = candidate_keys(result.partitions[i]);
        }, 8))
      return cancelled();
    for (std::size_t i = 0; i < n; ++i) {
      if (!result.partitions[i].status.ok()) {
        result.status = result.partitions[i].status;
        result.status.body = assembly.bodies[i].name;
        return result;
      }
    }
    result.times.partitions = seconds_since(start);

    start = Clock::now();
    for (std::size_t i = 0; i < n; ++i) boxes[i] = result.partitions[i].box;
    std::vector<double> gaps(n);
    for (std::size_t i = 0; i < n; ++i) gaps[i] = body_tol[i].linear;
    BroadPhase broad = broad_phase(boxes, gaps, options.max_body_pairs, progress);
    if (!broad.status.ok()) {
      result.status = broad.status;
      return result;
    }
    result.body_pairs = std::move(broad.pairs);
    result.times.broad_phase = seconds_since(start);

    // Body pairs placed alike (the same two shapes, the second placed the
    // same way relative to the first: a bolt in each of 500 plates) make the
    // same contacts, moved: each such group is tested once, on its first pair.
    const std::vector<std::pair<int, int>>& pairs = result.body_pairs;
    std::vector<std::size_t> representative(pairs.size());
    if (options.reuse_instances) {
      representative = first_pairs_placed_alike(pairs.size(), [&](std::size_t k) {
        const auto [ia, ib] = pairs[k];
        return pair_key(sources[ia], sources[ib], assembly.bodies[ia], assembly.bodies[ib],
                        std::max(body_tol[ia].linear, body_tol[ib].linear));
      });
    } else {
      for (std::size_t k = 0; k < pairs.size(); ++k) representative[k] = k;
    }
    std::vector<std::size_t> tested;  // the pairs whose candidates are tested, in order
    for (std::size_t k = 0; k < pairs.size(); ++k)
      if (representative[k] == k) tested.push_back(k);
    // A pair of two bodies whose partitions are reused, tested itself in the
    // memo's run too: its contacts and failures are the memo's.
    std::vector<const ContactsMemo::PairTests*> known(pairs.size(), nullptr);
    if (!options.candidate_hook && last.min_area_ratio == options.min_area_ratio) {
      for (std::size_t k : tested) {
        if (!reused[pairs[k].first] || !reused[pairs[k].second]) continue;
        const auto found = last.tested.find(pairs[k]);
        if (found != last.tested.end()) known[k] = &found->second;
      }
    }
    start = Clock::now();
    std::vector<std::vector<Candidate>> pair_candidates_of(pairs.size());
    if (!parallel_for(tested.size(), threads, progress, "candidates", [&](std::size_t t) {
          if (known[tested[t]]) return;  // counted below from the memo's
          const auto [ia, ib] = pairs[tested[t]];
          pair_candidates(ia, ib, keys, result.partitions, pair_tolerances(result.partitions[ia], result.partitions[ib]),
                          pair_candidates_of[tested[t]]);
        }, 64))
      return cancelled();
    std::vector<std::size_t> candidate_counts(pairs.size(), 0);
    for (std::size_t k : tested) candidate_counts[k] = known[k] ? known[k]->candidates : pair_candidates_of[k].size();
    for (std::size_t k = 0; k < pairs.size(); ++k) result.candidates += candidate_counts[representative[k]];
    result.times.candidates = seconds_since(start);

    // The tests; a pair whose test fails is skipped and recorded, the rest kept.
    start = Clock::now();
    std::vector<std::vector<Contact>> pair_contacts(pairs.size());
    std::vector<std::vector<SkippedPair>> pair_skipped(pairs.size());
    if (!parallel_for(tested.size(), threads, progress, "contacts", [&](std::size_t t) {
          const std::size_t k = tested[t];
          if (known[k]) {
            pair_contacts[k] = known[k]->contacts;
            pair_skipped[k] = known[k]->skipped;
            return;
          }
          const Tolerances pair_tol = pair_tolerances(result.partitions[pairs[k].first], result.partitions[pairs[k].second]);
          const PairContext ctx{result.partitions, pair_tol, options.min_area_ratio};
          std::vector<Contact>& out = pair_contacts[k];
          const auto test = [&](const Candidate& c) {
            if (options.candidate_hook) options.candidate_hook(c.body_a, c.partition_a, c.body_b, c.partition_b);
            return test_candidate(c.body_a, result.partitions[c.body_a].partitions[c.partition_a], c.body_b,
                                  result.partitions[c.body_b].partitions[c.partition_b], ctx, out);
          };
          // One signal guard for the body pair (a setjmp per candidate costs
          // 0.1-0.2 us, as much as a quick test); when a test fails (a failed
          // Status, an OCCT exception or a signal), the pair's candidates are
          // tested again one by one to skip only it.
          std::string failure;
          bool all_passed = true;
          if (run_guarded([&] {
                for (const Candidate& c : pair_candidates_of[k])
                  if (!test(c).ok()) {
                    all_passed = false;
                    return;
                  }
              }, failure, "OCCT: ") && all_passed) {
            std::vector<Candidate>().swap(pair_candidates_of[k]);
            return;
          }
          out.clear();
          for (const Candidate& c : pair_candidates_of[k]) {
            const std::size_t before = out.size();
            Status tested;
            const bool returned = run_guarded([&] { tested = test(c); }, failure, "OCCT: ");
            if (returned && !tested.ok()) failure = tested.message;
            if (!returned || !tested.ok()) {
              out.resize(before);  // nothing half-done from the failed pair
              const Partition& pa = result.partitions[c.body_a].partitions[c.partition_a];
              const Partition& pb = result.partitions[c.body_b].partitions[c.partition_b];
              pair_skipped[k].push_back({c.body_a, c.body_b, c.partition_a, c.partition_b, pa.faces, pb.faces,
                                         failure.empty() ? "unknown error" : failure});
            }
          }
          std::vector<Candidate>().swap(pair_candidates_of[k]);
        }, 4))
      return cancelled();
    if (memo) {
      for (std::size_t k : tested) {
        next.reused_tested_pairs += known[k] ? 1 : 0;
        next.tested[pairs[k]] = ContactsMemo::PairTests{pair_contacts[k], pair_skipped[k], candidate_counts[k]};
      }
    }
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const std::size_t r = representative[k];
      const auto [ia, ib] = pairs[k];
      const gp_Trsf motion = r == k ? gp_Trsf() : relative_motion(assembly.bodies[pairs[r].first], assembly.bodies[ia]);
      for (const Contact& found : pair_contacts[r]) {
        result.contacts.push_back(found);
        if (r == k) continue;
        Contact& moved = result.contacts.back();
        moved.body_a = ia, moved.body_b = ib;
        moved.point.Transform(motion);
        moved.direction.Transform(motion);
      }
      for (SkippedPair skipped : pair_skipped[r]) {
        skipped.body_a = ia, skipped.body_b = ib;
        result.messages.push_back("skipped the candidate pair '" + assembly.bodies[ia].name + "' " +
                                  faces_text(skipped.faces_a) + " / '" + assembly.bodies[ib].name + "' " +
                                  faces_text(skipped.faces_b) + ": " + skipped.message);
        result.skipped.push_back(std::move(skipped));
      }
    }
    // Pairs in order, then partitions: the order does not hang on rounding
    // (partitions with nearly equal keys meet in either order).
    std::stable_sort(result.contacts.begin(), result.contacts.end(), [](const Contact& l, const Contact& r) {
      return std::tie(l.body_a, l.body_b, l.partition_a, l.partition_b) <
             std::tie(r.body_a, r.body_b, r.partition_a, r.partition_b);
    });
    // Point and line contacts, apart from the surface contacts: every body
    // pair (a pair that fails is skipped with a message, like a candidate).
    {
      std::vector<std::vector<HigherPair>> higher(pairs.size());
      std::vector<std::string> higher_failures(pairs.size());
      // A pair of two bodies whose partitions are reused, with the same
      // tolerances as the memo's run: its point and line contacts are the memo's.
      std::vector<const ContactsMemo::PairHigher*> known_higher(pairs.size(), nullptr);
      if (same_tolerances(last.tolerances, result.tolerances)) {
        for (std::size_t k = 0; k < pairs.size(); ++k) {
          if (!reused[pairs[k].first] || !reused[pairs[k].second]) continue;
          const auto found = last.higher.find(pairs[k]);
          if (found != last.higher.end()) known_higher[k] = &found->second;
        }
      }
      if (!parallel_for(pairs.size(), threads, progress, "contacts", [&](std::size_t k) {
            if (known_higher[k]) {
              higher[k] = known_higher[k]->pairs;
              higher_failures[k] = known_higher[k]->failure;
              return;
            }
            // Plain variables: clang 14 cannot capture a structured binding (make fuzz builds with it).
            const std::size_t ia = pairs[k].first, ib = pairs[k].second;
            run_guarded([&] { higher[k] = find_higher_pairs(ia, result.partitions[ia], ib, result.partitions[ib],
                                                            result.tolerances); },
                        higher_failures[k], "OCCT: ");
          }, 16))
        return cancelled();
      if (memo) {
        for (std::size_t k = 0; k < pairs.size(); ++k) {
          next.reused_higher_pairs += known_higher[k] ? 1 : 0;
          next.higher[pairs[k]] = ContactsMemo::PairHigher{higher[k], higher_failures[k]};
        }
      }
      for (std::size_t k = 0; k < pairs.size(); ++k) {
        if (!higher_failures[k].empty())
          result.messages.push_back("skipped the point and line contacts of '" + assembly.bodies[pairs[k].first].name +
                                    "' and '" + assembly.bodies[pairs[k].second].name + "': " + higher_failures[k]);
        for (HigherPair& pair : higher[k]) result.higher_pairs.push_back(std::move(pair));
      }
    }
    result.times.area = seconds_since(start);
    start = Clock::now();
    const bool known_checks = last.checks == options.solid_checks;
    if (memo) {
      next.checks = options.solid_checks;
      for (std::size_t i = 0; i < n; ++i)
        next.reused_solid_checks += known_checks && reused[i] && result.instance_of[i] == static_cast<int>(i) ? 1 : 0;
    }
    const Status checked = check_solids(assembly, result, progress, threads, options.solid_checks,
                                        known_checks ? &reused : nullptr, &last.solids, memo ? &next.solids : nullptr);
    result.times.validity = seconds_since(start);
    if (!checked.ok()) {
      result.status = checked;
      return result;
    }
    start = Clock::now();
    const Status interferences = find_interferences(assembly, result, progress, threads);
    result.times.interferences = seconds_since(start);
    if (!interferences.ok()) {
      result.status = interferences;
      return result;
    }
    if (options.regions) {
      const Status regions = find_common_regions(assembly, result, options.region_bodies, threads, progress);
      if (!regions.ok()) {
        result.status = regions;
        return result;
      }
    }
  } catch (const Standard_OutOfMemory&) {
    result.status = Status::failure(StatusCode::OutOfMemory, "out of memory");
  } catch (const std::bad_alloc&) {
    result.status = Status::failure(StatusCode::OutOfMemory, "out of memory");
  } catch (const Standard_Failure& failure) {
    result.status = Status::failure(StatusCode::GeometryError, "OCCT: " + occt_failure_text(failure));
  }
  if (result.status.ok()) result.clearances = find_clearances(result.partitions, options.clearance_gap);
  if (memo && result.status.ok()) {
    // Kept for the next run: every body's shape, tolerances, source and partitions.
    const std::size_t n = assembly.bodies.size();
    next.shapes.reserve(n);
    for (const Body& body : assembly.bodies) next.shapes.push_back(body.shape);
    next.body_tolerances.reserve(n);
    for (const BodyPartitions& body : result.partitions) next.body_tolerances.push_back(body.tolerances);
    next.sources = std::move(memo_sources);
    next.partitions = result.partitions;
    next.instance_of = result.instance_of;
    next.min_area_ratio = options.min_area_ratio;
    next.tolerances = result.tolerances;
    next.reused_bodies = memo_reused_bodies;
    *memo = std::move(next);
  }
  if (progress) progress->report("contacts", 1.0);
  return result;
}

}  // namespace contactcore
