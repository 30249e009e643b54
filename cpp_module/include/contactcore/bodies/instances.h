// Stage 1 (bodies), instances: bodies that place one shape several times (a screw used 500
// times, a STEP product instanced) share its TShape. Their partitions are
// those of the first placement moved rigidly (moved_partitions, partitions.h),
// so the driver partitions each distinct shape once and moves the result to
// every other placement.
#pragma once

#include <vector>

#include <gp_Trsf.hxx>

#include "contactcore/bodies/bodies.h"

namespace contactcore {

// For each body, the index of the first body with the same TShape and
// orientation placed by a rigid motion away (no scaling, no mirror): the
// body whose results it can reuse. A body with none maps to itself.
std::vector<int> instance_sources(const std::vector<Body>& bodies);

// The rigid motion taking body `from`'s placement to body `to`'s.
gp_Trsf relative_motion(const Body& from, const Body& to);

}  // namespace contactcore
