#include "contactcore/contacts.h"
#include "contactcore/clearances.h"

#include "contactcore/common_area.h"
#include "contactcore/instances.h"
#include "contactcore/parallel.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <exception>
#include <sstream>

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
  BroadPhase out;
  std::vector<Span> spans;
  spans.reserve(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    if (boxes[i].IsVoid()) continue;
    double x0, y0, z0, x1, y1, z1;
    boxes[i].Get(x0, y0, z0, x1, y1, z1);  // includes the box's own gap
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
  auto last = Clock::now();
  for (std::size_t i = 0; i < spans.size(); ++i) {
    if (progress && (i & 255) == 0 && Clock::now() - last > std::chrono::milliseconds(50)) {
      if (!progress->report("broad phase", static_cast<double>(i) / static_cast<double>(spans.size()))) {
        out.status = Status::failure(StatusCode::Cancelled, "cancelled");
        return out;
      }
      last = Clock::now();
    }
    for (std::size_t j = i + 1; j < spans.size() && spans[j].lo[axis] <= spans[i].hi[axis]; ++j) {
      const int a = spans[i].body, b = spans[j].body;
      if (!boxes_meet(boxes[a], boxes[b], gap)) continue;
      out.pairs.emplace_back(std::min(a, b), std::max(a, b));
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
  ContactsResult result;
  const auto cancelled = [&result]() {
    result.status = Status::failure(StatusCode::Cancelled, "cancelled");
    return result;
  };
  const std::size_t n = assembly.bodies.size();
  const int threads = options.threads;
  auto start = Clock::now();
  try {
    std::vector<Bnd_Box> boxes(n);
    if (!parallel_for(n, threads, progress, "partitions", [&](std::size_t i) {
          BRepBndLib::Add(assembly.bodies[i].shape, boxes[i], false);
        }, 16))
      return cancelled();
    Bnd_Box model_box;
    for (const Bnd_Box& box : boxes) model_box.Add(box);
    result.tolerances = resolve_tolerances(model_box, options.linear, options.angular);

    // Each distinct shape partitioned once (partition_shape only reads the
    // shapes, so bodies sharing TShapes through instancing can run
    // concurrently), then moved to the other placements of that shape.
    std::vector<int> sources(n);
    if (options.reuse_instances) {
      sources = instance_sources(assembly.bodies);
    } else {
      for (std::size_t i = 0; i < n; ++i) sources[i] = static_cast<int>(i);
    }
    const auto partition_body = [&](std::size_t i) {
      BodyPartitions& body = result.partitions[i];
      try {
        body = partition_shape(assembly.bodies[i].shape, result.tolerances);
      } catch (const Standard_Failure& failure) {
        body.status = Status::failure(StatusCode::GeometryError, std::string("OCCT: ") + failure.GetMessageString());
      } catch (const std::exception& error) {
        body.status = Status::failure(StatusCode::GeometryError, error.what());
      }
    };
    result.partitions.resize(n);
    std::vector<std::vector<CandidateKey>> keys(n);
    if (!parallel_for(n, threads, progress, "partitions", [&](std::size_t i) {
          if (sources[i] == static_cast<int>(i)) partition_body(i);
        }))
      return cancelled();
    if (!parallel_for(n, threads, progress, "partitions", [&](std::size_t i) {
          const int source = sources[i];
          if (source != static_cast<int>(i)) {
            const BodyPartitions& original = result.partitions[source];
            if (original.status.ok()) {
              result.partitions[i] = moved_partitions(
                  original, relative_motion(assembly.bodies[source], assembly.bodies[i]), assembly.bodies[i].shape);
            }
            if (!original.status.ok() || !result.partitions[i].status.ok()) partition_body(i);
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
    BroadPhase broad = broad_phase(boxes, result.tolerances.linear, options.max_body_pairs, progress);
    if (!broad.status.ok()) {
      result.status = broad.status;
      return result;
    }
    result.body_pairs = std::move(broad.pairs);
    result.times.broad_phase = seconds_since(start);

    // Candidates per chunk of body pairs, concatenated in pair order.
    start = Clock::now();
    constexpr std::size_t kPairChunk = 256;
    const std::size_t pair_chunks = (result.body_pairs.size() + kPairChunk - 1) / kPairChunk;
    std::vector<std::vector<Candidate>> chunk_candidates(pair_chunks);
    if (!parallel_for(pair_chunks, threads, progress, "candidates", [&](std::size_t c) {
          const std::size_t end = std::min(result.body_pairs.size(), (c + 1) * kPairChunk);
          for (std::size_t k = c * kPairChunk; k < end; ++k)
            pair_candidates(result.body_pairs[k].first, result.body_pairs[k].second, keys, result.partitions,
                            result.tolerances, chunk_candidates[c]);
        }))
      return cancelled();
    std::vector<Candidate> candidates;
    {
      std::size_t total = 0;
      for (const auto& chunk : chunk_candidates) total += chunk.size();
      candidates.reserve(total);
      for (auto& chunk : chunk_candidates) {
        candidates.insert(candidates.end(), chunk.begin(), chunk.end());
        std::vector<Candidate>().swap(chunk);
      }
    }
    result.candidates = candidates.size();
    result.times.candidates = seconds_since(start);

    // The tests, per chunk of candidates; a pair whose test throws is skipped
    // and recorded, the rest kept.
    start = Clock::now();
    const PairContext ctx{result.partitions, result.tolerances, options.min_area_ratio};
    constexpr std::size_t kCandidateChunk = 16;
    const std::size_t chunks = (candidates.size() + kCandidateChunk - 1) / kCandidateChunk;
    std::vector<std::vector<Contact>> chunk_contacts(chunks);
    std::vector<std::vector<SkippedPair>> chunk_skipped(chunks);
    if (!parallel_for(chunks, threads, progress, "contacts", [&](std::size_t chunk) {
          const std::size_t end = std::min(candidates.size(), (chunk + 1) * kCandidateChunk);
          for (std::size_t k = chunk * kCandidateChunk; k < end; ++k) {
            const Candidate& c = candidates[k];
            const Partition& pa = result.partitions[c.body_a].partitions[c.partition_a];
            const Partition& pb = result.partitions[c.body_b].partitions[c.partition_b];
            std::vector<Contact>& out = chunk_contacts[chunk];
            const std::size_t before = out.size();
            std::string failure;
            bool failed = false;
            try {
              if (options.candidate_hook) options.candidate_hook(c.body_a, c.partition_a, c.body_b, c.partition_b);
              test_candidate(c.body_a, pa, c.body_b, pb, ctx, out);
            } catch (const Standard_Failure& error) {
              failed = true;
              failure = std::string("OCCT: ") + error.GetMessageString();
            } catch (const std::exception& error) {
              failed = true;
              failure = error.what();
            }
            if (failed) {
              out.resize(before);  // nothing half-done from the failed pair
              chunk_skipped[chunk].push_back({c.body_a, c.body_b, c.partition_a, c.partition_b, pa.faces, pb.faces,
                                              failure.empty() ? "unknown error" : failure});
            }
          }
        }))
      return cancelled();
    for (std::size_t chunk = 0; chunk < chunks; ++chunk) {
      for (Contact& contact : chunk_contacts[chunk]) result.contacts.push_back(std::move(contact));
      for (SkippedPair& skipped : chunk_skipped[chunk]) {
        result.messages.push_back("skipped the candidate pair '" + assembly.bodies[skipped.body_a].name + "' " +
                                  faces_text(skipped.faces_a) + " / '" + assembly.bodies[skipped.body_b].name +
                                  "' " + faces_text(skipped.faces_b) + ": " + skipped.message);
        result.skipped.push_back(std::move(skipped));
      }
    }
    result.times.area = seconds_since(start);
  } catch (const Standard_Failure& failure) {
    result.status = Status::failure(StatusCode::GeometryError, std::string("OCCT: ") + failure.GetMessageString());
  }
  if (result.status.ok()) result.clearances = find_clearances(result.partitions, options.clearance_gap, result.tolerances);
  if (progress) progress->report("contacts", 1.0);
  return result;
}

}  // namespace contactcore
