// Stage 3 (contacts), beside the surface contacts: point and line contacts
// (higher pairs) between a ball, a cylinder and a plane or cylinder of
// another radius, found from the partitions' analytic surfaces and checked
// on the faces themselves.
#pragma once

#include <vector>

#include "contactcore/contacts/contacts.h"

namespace contactcore {

// The higher pairs of one body pair (ia < ib) from their partitions, in
// partition order. May throw Standard_Failure from OCCT.
std::vector<HigherPair> find_higher_pairs(int ia, const BodyPartitions& a, int ib, const BodyPartitions& b,
                                          const Tolerances& tol);

}  // namespace contactcore
