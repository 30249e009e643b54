// Stage 1 (bodies): checks of a parsed STEP model before OCCT's transfer, which recurses
// through the assembly tree (30,000 nested levels overflow the stack; a cyclic
// reference never ends) and may crash on damaged entities.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <StepData_StepModel.hxx>

class Interface_Graph;

namespace contactcore {

// Deeper assembly trees than this are refused (real ones have a few levels).
constexpr int kMaxAssemblyDepth = 200;
// Longer chains of entity references than this are refused: OCCT's transfer
// recurses along them (8,000 nested GEOMETRIC_SETs or MAPPED_ITEMs overflow the
// stack; nested GEOMETRIC_SETs also cost time quadratic in their depth). Real
// files have 11 to 16 levels; an assembly of mapped items adds 3 a level.
constexpr int kMaxReferenceDepth = 1000;

// Default limit of the instances an assembly may expand to (CLI --max-bodies):
// counted on the parsed model before OCCT's transfer expands anything (an
// assembly of 30 levels each using the level below twice is 2^30 instances).
constexpr std::size_t kDefaultMaxBodies = 1'000'000;

struct StepModelCheck {
  int assembly_depth = 0;             // longest chain of NEXT_ASSEMBLY_USAGE_OCCURRENCE
  // Leaf instances the assembly tree expands to (each usage of a product
  // counts its own instances; a DAG is measured in linear time, never walked
  // path by path), summed over the root products; 0 without assemblies.
  double assembly_instances = 0;
  // The most items one container (GEOMETRIC_SET, MAPPED_ITEM, its
  // REPRESENTATION_MAP and REPRESENTATION) expands to through nested
  // containers, as OCCT's transfer expands them, and which entity that is.
  double largest_expansion = 0;
  std::string largest_container;
  std::string cycle;                  // "#5 -> #9 -> #5" when an assembly contains itself
  std::vector<std::string> damaged;   // "#12: unknown entity type NOT_A_TYPE" (first few)
  int damaged_count = 0;              // all damaged entities
  // "#684 (CARTESIAN_POINT)": points and directions whose coordinates are not
  // finite (or unreadable): OCCT's shape healing loops forever on some of them.
  std::vector<std::string> non_finite;
  // "#10 -> #9002 -> #9001 -> #10" when an entity refers to itself through others.
  std::string reference_cycle;
  int reference_depth = 0;            // entities on the longest chain of references
  std::string deepest_entity;         // where that chain starts ("#3")
};

// `graph`: the model's reference graph (the reader's work session has it, and
// reuses it for the transfer).
StepModelCheck check_step_model(const Handle(StepData_StepModel)& model, const Interface_Graph& graph);

// Entity identifiers defined more than once ("#455 = ..." twice), found in
// the file's text before OCCT parses it. OCCT 7.6 resolves references in such
// a file with a second pass (StepData_StepReaderData::SetEntityNumbers) that
// reads its scratch arrays uninitialised: valgrind reports 3,082 such reads on
// one; its time then depends on what earlier work left in the heap (a 0.6 s
// file took over 30 s in a long process). They are refused instead.
struct DuplicateIdentifiers {
  std::vector<std::string> listed;    // "#455 (again on line 790)" (first few)
  int count = 0;                      // all repeated definitions
};

DuplicateIdentifiers find_duplicate_identifiers(const std::string& path);

// "#455 (again on line 790), #456 (again on line 791)" (with "and N more").
std::string describe_duplicates(const DuplicateIdentifiers& duplicates);

// "#12: unknown entity type NOT_A_TYPE; #40: ..." (with "and N more").
std::string describe_damaged(const StepModelCheck& check);

// "#684 (CARTESIAN_POINT), #20 (DIRECTION)" (with "and N more").
std::string describe_non_finite(const StepModelCheck& check);

}  // namespace contactcore
