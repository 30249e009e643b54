// Stage 3 (contacts) again on an assembly of which most bodies did not change
// (a recompute after moving one part): what a run of find_contacts keeps for
// the next one, and the run that reuses it.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include <Bnd_Box.hxx>
#include <TopoDS_Shape.hxx>

#include "contactcore/contacts/contacts.h"

namespace contactcore {

// Each body's verdict of the solid checks (validity.h): its fault (reason
// empty: none) and the text of a check that failed (empty: none), as
// check_solids finds them for an instance's source.
struct SolidVerdicts {
  std::vector<InvalidBody> verdicts;
  std::vector<std::string> failures;
};

// What find_contacts (the overload below) keeps of its run: each body's
// shape (the same TopoDS_Shape: same OCCT shape, same location and
// orientation) with the tolerances it was partitioned with, the body its
// partitions were moved from, its partitions; the contacts and failed
// candidates of each body pair whose candidates were tested (before being
// copied to the pairs placed alike); the point and line contacts of each
// body pair with the run's tolerances.
struct ContactsMemo {
  std::vector<TopoDS_Shape> shapes;
  std::vector<Bnd_Box> shape_boxes;  // each source body's shape's box (BRepBndLib, before partitioning)
  std::vector<Tolerances> body_tolerances;
  std::vector<int> sources;  // instance_sources of the run
  std::vector<BodyPartitions> partitions;
  std::vector<int> instance_of;
  double min_area_ratio = 0;
  Tolerances tolerances;  // ContactsResult::tolerances of the run
  struct PairTests {
    std::vector<Contact> contacts;  // without their regions
    std::vector<SkippedPair> skipped;
    std::size_t candidates = 0;  // candidate partition pairs
  };
  std::map<std::pair<int, int>, PairTests> tested;
  struct PairHigher {
    std::vector<HigherPair> pairs;
    std::string failure;
  };
  std::map<std::pair<int, int>, PairHigher> higher;
  SolidChecks checks = SolidChecks::Quick;
  SolidVerdicts solids;  // the solid checks' verdicts, per body
  // What the last run reused: bodies whose partitions, body pairs whose
  // candidate tests, body pairs whose point and line contacts.
  std::size_t reused_bodies = 0, reused_tested_pairs = 0, reused_higher_pairs = 0;
  std::size_t reused_solid_checks = 0;  // bodies whose solid checks the last run reused
};

// find_contacts, reusing what `memo` kept of the last run for what depends
// only on bodies that did not change since (the same shape, location and
// orientation at the same index, partitioned with the same tolerances): their
// partitions and solid checks (with the same SolidChecks), the candidate
// tests of a body pair of two such bodies (when that pair was tested itself,
// not copied from a pair placed alike, in both runs), and their point and
// line contacts (with the same tolerances); an unchanged shape's box. The
// result is the one find_contacts gives without the memo, to the last bit;
// the memo is then refilled with this run (left empty when it fails).
ContactsResult find_contacts(const Assembly& assembly, const ContactOptions& options, Progress* progress,
                             ContactsMemo* memo);

}  // namespace contactcore
