// Stage 1: bodies read before, gathered into a new assembly (a recompute
// whose unchanged bodies are not read again; contactwb.document.shapes).
#pragma once

#include <string>
#include <vector>

#include "contactcore/bodies/bodies.h"

namespace contactcore {

// An assembly of bodies read before (their shapes, and the mass caches they
// share, kept as they are), named by `names` (same order) and made unique as
// bodies_from_brep names them: the Assembly bodies_from_brep gives for the
// compound of their shapes, without the shapes crossing as BRep text again
// (a recompute passes only its moved and changed bodies' text).
// InvalidArgument when the counts differ or a body has no shape.
AssemblyResult assembly_of_bodies(std::vector<Body> bodies, const std::vector<std::string>& names);

}  // namespace contactcore
