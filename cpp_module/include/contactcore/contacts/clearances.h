// Stage 3 (contacts), clearance fits: the same surface (same type and axis or centre) on two
// bodies with radii differing by less than a gap, e.g. a nut on its bolt.
// Found beside contacts, never counted as contacts.
#pragma once

#include <utility>
#include <vector>

#include "contactcore/contacts/contacts.h"

namespace contactcore {

// Partition pairs of bodies whose boxes come within `max_gap`: a convex and
// a concave cylinder on the same axis (overlapping along it) or sphere on the
// same centre, or two facing planes with overlapping outlines, whose gap
// (radial or normal) is in (linear tolerance, max_gap), with each body
// pair's tolerances (pair_tolerances). Also coaxial (concentric) overlaps:
// a convex cylinder or sphere larger than the concave one around it by a
// radial amount in the same range, reported with a negative gap (a press fit
// drawn at its real sizes). Sorted by bodies, then partitions.
std::vector<Clearance> find_clearances(const std::vector<BodyPartitions>& partitions, double max_gap);

}  // namespace contactcore
