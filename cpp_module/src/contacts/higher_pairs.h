// Stage 3 (contacts), beside the surface contacts: point, line and circle
// contacts (higher pairs) of a ball, a cylinder, a cone or a ring (torus) on a
// plane or a cylinder (contacts.h lists the types), found from the
// partitions' analytic surfaces and checked on the faces themselves.
#pragma once

#include <vector>

#include "contactcore/contacts/contacts.h"

namespace contactcore {

// The higher pairs of one body pair (ia < ib) from their partitions, in
// partition order. May throw Standard_Failure from OCCT.
std::vector<HigherPair> find_higher_pairs(int ia, const BodyPartitions& a, int ib, const BodyPartitions& b,
                                          const Tolerances& tol);

}  // namespace contactcore
