// Stage 3 (contacts), the per-candidate part: for one pair of partitions of two bodies
// with the same surface parameters, the test of the contact it makes and its
// real common area (planes, cylinders and cones, spheres and tori, balls in
// bores and grooves). The driver in contacts.cpp calls test_candidate.
#pragma once

#include <vector>

#include <Bnd_Box.hxx>

#include "contactcore/contacts/contacts.h"

namespace contactcore {

// What every candidate test reads: all bodies' partitions and the tolerances.
struct PairContext {
  const std::vector<BodyPartitions>& parts;
  const Tolerances& tol;
  double min_area_ratio;
};

// Boxes that meet once one is grown by `gap` (void boxes never meet).
inline bool boxes_meet(const Bnd_Box& a, const Bnd_Box& b, double gap) {
  if (a.IsVoid() || b.IsVoid()) return false;
  Bnd_Box grown = a;
  grown.Enlarge(gap);
  return !grown.IsOut(b);
}

// The region two plane outlines (in one frame) have in common: its area
// (exact on arcs, by the chords' bulges) and the length of its boundary.
struct CommonRegion {
  double area = 0;
  double perimeter = 0;
};
CommonRegion common_region(const std::vector<Polygon2>& a, const std::vector<Polygon2>& b, double tol);

// Tests one candidate pair (a from body ia, b from body ib, ia < ib) and
// appends the contact it makes, if any, to `out` (side a = body ia).
// A failed test (OCCT's Boolean common of two faces, or typing a piece of it)
// is a failed Status and appends nothing: the caller decides what to skip.
// OCCT may still throw from inside (or raise a signal): the caller runs it
// under run_guarded.
Status test_candidate(int ia, const Partition& a, int ib, const Partition& b, const PairContext& ctx,
                      std::vector<Contact>& out);

}  // namespace contactcore
