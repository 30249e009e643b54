// Stage 3, beside the contacts: solids that are not valid. A solid whose
// boundary crosses itself (a face bounded by a bowtie) gets wrong areas and
// contacts without any error, so it is named instead.
#pragma once

#include "contactcore/contacts.h"

namespace contactcore {

// On a result whose partitions are found (partitions, instance_of): checks
// each distinct shape once (instances share their source's verdict), on
// `threads` threads, as BRepCheck_Analyzer checks a face's wires for
// self-intersection (BRepCheck_Wire::SelfIntersect, the check that finds a
// self-intersecting solid; the analyzer's other checks cost about 10x more
// and are left out). Fills `invalid_bodies` (body order) and one message
// per invalid body naming it and its faces.
Status check_solids(const Assembly& assembly, ContactsResult& result, Progress* progress = nullptr, int threads = 0);

}  // namespace contactcore
