// Stage 3 (contacts), after the contacts: bodies whose material overlaps (press fits,
// duplicates placed in place) and bodies that are not usable solids. Neither
// may show up as contacts: two overlapping bodies are an interference, and a
// zero-volume "solid" touches nothing.
#pragma once

#include "contactcore/contacts/contacts.h"

namespace contactcore {

// On a result whose contacts are found (partitions, body_pairs, tolerances,
// instance_of filled): fills `interferences` with the body pairs whose
// material overlaps, with the common volume, notes zero-volume bodies and
// duplicates in `messages`, and drops the contacts of empty bodies and of
// second copies (they repeat the first copy's). An overlapping pair keeps
// every contact it has (a press-fitted tongue seated on its slot's floor, a
// shoulder on its seat); the interference is reported beside them. Only pairs whose boxes overlap deeper than the tolerance are looked
// at, on `threads` threads (0: all cores; the result is the same); of the pairs
// placed alike (pair_key.h: instances of the same two shapes in the same
// relative placement, through instance_of) only the first is tested, the
// others take its outcome. Each tested pair goes through:
//  1. the same solid twice at one place: its volume;
//  2. a coaxial press fit (a shaft larger than its bore by at most 50 % of the
//     bore's radius, over a common axial range): proven by the ring between
//     the radii, measured from the partitions (press_fit_volume); the volume
//     (chamfers and counterbores around the shaft share material too) sliced
//     exactly about the fit's axis when one body is a solid of revolution
//     about it and the other one within its reach (coaxial_overlap.h),
//     otherwise by the region Boolean of step 4, the ring when that fails;
//  3. a proof from the partitions that they share no material (separation.h):
//     the common case, touching bodies, ends here;
//  4. otherwise vertices, edge midpoints and face points of each body
//     classified in the other; none inside: whether their boundaries cross
//     (boundary_crossing.h, complete for solids). A point inside or a
//     crossing: the Boolean common gives the volume (below 1e-6 of the
//     smaller body: a touch), of the region that can overlap: when the
//     common box of the two is a small part of a body's box, each body is
//     first cut down to that box (interferences.cpp, region_common_volume).
Status find_interferences(const Assembly& assembly, ContactsResult& result, Progress* progress = nullptr,
                          int threads = 0);

// The reference the pass is checked against (tests, benchmarks): the pass as
// it was before issue 24, every body pair whose boxes (BRepBndLib, not the
// partitions') overlap deeper than the pair's tolerance settled by the
// Boolean common of the two whole solids (above 1e-6 of the smaller body's
// volume: an interference), on `threads` threads. Bodies thinner than their
// tolerance are left out; copies in place are not singled out (each pair
// with a copy is measured like any other). Seconds on solids of B-spline
// faces: never on the analysis path.
std::vector<Interference> whole_solid_interferences(const Assembly& assembly, const ContactsResult& result,
                                                    int threads = 0);

// The material two bodies share through coaxial press fits (step 2), mm^3; 0 when none.
double press_fit_volume(const BodyPartitions& a, const BodyPartitions& b, const Tolerances& tol);

}  // namespace contactcore
