// Stage 3 (contacts), beside the contacts: solids that are not valid. A solid whose
// boundary crosses itself, is open, turned inside out or encloses nothing
// gets wrong areas and contacts without any error, so it is named instead.
#pragma once

#include "contactcore/contacts/contacts.h"
#include "contactcore/contacts/contacts_memo.h"

namespace contactcore {

// InvalidBody::reason, exactly (docs/reliability.md), in the order the
// checks run (the first fault found is reported):
inline constexpr const char* kSelfIntersecting = "self-intersecting boundary";  // a face's wire crosses itself
inline constexpr const char* kOpenShell = "open shell";                  // an edge bounds one face only
inline constexpr const char* kMisorientedFaces = "faces turned inside out";  // against their neighbours
inline constexpr const char* kEdgesOffSurface = "edges off their faces";  // BRepCheck_Edge in the face
inline constexpr const char* kInsideOut = "inside out";    // negative volume (whole solid)
inline constexpr const char* kZeroVolume = "zero volume";  // encloses (almost) nothing (whole solid)
inline constexpr const char* kFailsAnalyzer = "fails BRepCheck_Analyzer";  // SolidChecks::Full only
inline constexpr const char* kFacesCrossing = "faces crossing each other";  // SolidChecks::Full only

// On a result whose partitions are found (partitions, instance_of): checks
// each distinct shape once (instances share their source's verdict), on
// `threads` threads: each face's wires for self-intersection
// (BRepCheck_Wire::SelfIntersect), every edge shared by two faces running
// opposite ways in them, every edge's curves against its faces'
// surfaces (BRepCheck_Edge), the signed volume against the surface area
// times the linear tolerance; with SolidChecks::Full, also the whole
// BRepCheck_Analyzer and the faces' intersections with each other
// (BOPAlgo_ArgumentAnalyzer's self-interference; together many times the
// cost of the quick checks). Fills `invalid_bodies` (body
// order; faces empty: the whole solid) and one message per invalid body.
// `known`: verdicts of an earlier run taken for the bodies whose `reusable`
// flag is set (their shape, partitions and checks the same); `kept`: this
// run's verdicts, per body (for find_contacts' memo).
Status check_solids(const Assembly& assembly, ContactsResult& result, Progress* progress = nullptr, int threads = 0,
                    SolidChecks checks = SolidChecks::Quick, const std::vector<char>* reusable = nullptr,
                    const SolidVerdicts* known = nullptr, SolidVerdicts* kept = nullptr);

}  // namespace contactcore
