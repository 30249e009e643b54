// Checks of a parsed STEP model before OCCT's transfer, which recurses
// through the assembly tree (30,000 nested levels overflow the stack; a cyclic
// reference never ends) and may crash on damaged entities.
#pragma once

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

struct StepModelCheck {
  int assembly_depth = 0;             // longest chain of NEXT_ASSEMBLY_USAGE_OCCURRENCE
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

// "#12: unknown entity type NOT_A_TYPE; #40: ..." (with "and N more").
std::string describe_damaged(const StepModelCheck& check);

// "#684 (CARTESIAN_POINT), #20 (DIRECTION)" (with "and N more").
std::string describe_non_finite(const StepModelCheck& check);

}  // namespace contactcore
