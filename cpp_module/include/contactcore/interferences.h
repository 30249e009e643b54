// Stage 3, after the contacts: bodies whose material overlaps (press fits,
// duplicates placed in place) and bodies that are not usable solids. Neither
// may show up as contacts: two overlapping bodies are an interference, and a
// zero-volume "solid" touches nothing.
#pragma once

#include "contactcore/contacts.h"

namespace contactcore {

// On a result whose contacts are found (partitions, body_pairs, tolerances
// filled): fills `interferences` with the body pairs whose material overlaps
// (the same solid twice at one place; a shaft in a smaller coaxial bore,
// confirmed and measured by a Boolean common), notes zero-volume bodies and
// duplicates in `messages`, and drops the contacts of empty bodies and of
// second copies (they repeat the first copy's). A press-fitted pair keeps
// its real contacts (a shoulder on its seat).
//
// Cheap on touching assemblies (bolts in holes): only pairs whose boxes
// overlap deeper than the tolerance are looked at, through their partitions;
// a Boolean runs only on a press-fit candidate.
Status find_interferences(const Assembly& assembly, ContactsResult& result, Progress* progress = nullptr);

}  // namespace contactcore
