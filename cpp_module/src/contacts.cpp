#include "contactcore/contacts.h"

#include "contactcore/common_area.h"
#include "contactcore/interferences.h"

#include <algorithm>
#include <chrono>
#include <cmath>

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

}  // namespace

std::vector<std::pair<int, int>> broad_phase(const std::vector<Bnd_Box>& boxes, double gap) {
  struct Span {
    double xmin, xmax;
    int body;
  };
  std::vector<Span> spans;
  spans.reserve(boxes.size());
  for (size_t i = 0; i < boxes.size(); ++i) {
    if (boxes[i].IsVoid()) continue;
    double x0, y0, z0, x1, y1, z1;
    boxes[i].Get(x0, y0, z0, x1, y1, z1);
    spans.push_back({x0 - gap, x1 + gap, static_cast<int>(i)});
  }
  std::sort(spans.begin(), spans.end(), [](const Span& l, const Span& r) { return l.xmin < r.xmin; });
  std::vector<std::pair<int, int>> pairs;
  for (size_t i = 0; i < spans.size(); ++i) {
    for (size_t j = i + 1; j < spans.size() && spans[j].xmin <= spans[i].xmax; ++j) {
      const int a = spans[i].body, b = spans[j].body;
      if (boxes_meet(boxes[a], boxes[b], gap)) pairs.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

ContactsResult find_contacts(const Assembly& assembly, const ContactOptions& options, Progress* progress) {
  ContactsResult result;
  const auto cancelled = [&result]() {
    result.status = Status::failure(StatusCode::Cancelled, "cancelled");
    return result;
  };
  const size_t n = assembly.bodies.size();
  auto start = Clock::now();
  try {
    Bnd_Box model_box;
    for (const Body& body : assembly.bodies) BRepBndLib::Add(body.shape, model_box, false);
    result.tolerances = resolve_tolerances(model_box, options.linear, options.angular);
    result.status = check_tolerances(model_box, result.tolerances);
    if (!result.status.ok()) return result;

    result.partitions.reserve(n);
    for (size_t i = 0; i < n; ++i) {
      if (progress && !progress->report("partitions", static_cast<double>(i) / std::max<size_t>(n, 1)))
        return cancelled();
      result.partitions.push_back(partition_shape(assembly.bodies[i].shape, result.tolerances));
      Status& status = result.partitions.back().status;
      if (!status.ok()) {
        result.status = status;
        result.status.body = assembly.bodies[i].name;
        return result;
      }
    }
    result.times.partitions = seconds_since(start);

    start = Clock::now();
    std::vector<Bnd_Box> boxes;
    boxes.reserve(n);
    for (const BodyPartitions& body : result.partitions) boxes.push_back(body.box);
    result.body_pairs = broad_phase(boxes, result.tolerances.linear);
    result.times.broad_phase = seconds_since(start);

    start = Clock::now();
    std::vector<std::vector<CandidateKey>> keys(n);
    for (size_t i = 0; i < n; ++i) keys[i] = candidate_keys(result.partitions[i]);
    struct Candidate {
      int body_a, partition_a, body_b, partition_b;
    };
    std::vector<Candidate> candidates;
    for (const auto& [ia, ib] : result.body_pairs) {
      const auto& kb = keys[ib];
      for (const CandidateKey& k : keys[ia]) {
        const double window = k.group == 2 ? result.tolerances.angular : result.tolerances.linear;
        auto it = std::lower_bound(kb.begin(), kb.end(), CandidateKey{k.group, k.key - window, 0},
                                   [](const CandidateKey& l, const CandidateKey& r) {
                                     return l.group != r.group ? l.group < r.group : l.key < r.key;
                                   });
        for (; it != kb.end() && it->group == k.group && it->key <= k.key + window; ++it) {
          const Partition& pa = result.partitions[ia].partitions[k.partition];
          const Partition& pb = result.partitions[ib].partitions[it->partition];
          if (!boxes_meet(pa.box, pb.box, result.tolerances.linear)) continue;
          candidates.push_back({ia, k.partition, ib, it->partition});
        }
      }
    }
    result.candidates = candidates.size();
    result.times.candidates = seconds_since(start);

    start = Clock::now();
    const PairContext ctx{result.partitions, result.tolerances, options.min_area_ratio};
    for (size_t k = 0; k < candidates.size(); ++k) {
      if (progress && k % 64 == 0 &&
          !progress->report("contacts", static_cast<double>(k) / static_cast<double>(candidates.size())))
        return cancelled();
      const Candidate& c = candidates[k];
      try {
        test_candidate(c.body_a, result.partitions[c.body_a].partitions[c.partition_a], c.body_b,
                       result.partitions[c.body_b].partitions[c.partition_b], ctx, result.contacts);
      } catch (const Standard_Failure& failure) {
        result.status = Status::failure(StatusCode::GeometryError,
                                        std::string("OCCT: ") + failure.GetMessageString());
        result.status.body = assembly.bodies[c.body_a].name + "' / '" + assembly.bodies[c.body_b].name;
        return result;
      }
    }
    result.times.area = seconds_since(start);
    const Status interferences = find_interferences(assembly, result, progress);
    if (!interferences.ok()) {
      result.status = interferences;
      return result;
    }
  } catch (const Standard_Failure& failure) {
    result.status = Status::failure(StatusCode::GeometryError, std::string("OCCT: ") + failure.GetMessageString());
  }
  if (progress) progress->report("contacts", 1.0);
  return result;
}

}  // namespace contactcore
