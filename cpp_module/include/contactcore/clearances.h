// Clearance fits: the same surface (same type and axis or centre) on two
// bodies with radii differing by less than a gap, e.g. a nut on its bolt.
// Found beside contacts, never counted as contacts.
#pragma once

#include <utility>
#include <vector>

#include "contactcore/contacts.h"

namespace contactcore {

// Partition pairs of the given body pairs: a convex and a concave cylinder
// (or sphere, or cone with the same apex and angle... not cones: a cone with
// play is a different seat) on the same axis (centre), the concave radius
// larger by a gap in (linear tolerance, max_gap). Pairs that are already in
// contact through that fit are not repeated. Sorted by (body_a, body_b).
std::vector<Clearance> find_clearances(const std::vector<BodyPartitions>& partitions,
                                       const std::vector<std::pair<int, int>>& body_pairs,
                                       double max_gap, const Tolerances& tol);

}  // namespace contactcore
