// Checks of a parsed STEP model before OCCT's transfer, which recurses
// through the assembly tree (30,000 nested levels overflow the stack; a cyclic
// reference never ends) and may crash on damaged entities.
#pragma once

#include <string>
#include <vector>

#include <StepData_StepModel.hxx>

namespace contactcore {

// Deeper assembly trees than this are refused (real ones have a few levels).
constexpr int kMaxAssemblyDepth = 200;

struct StepModelCheck {
  int assembly_depth = 0;             // longest chain of NEXT_ASSEMBLY_USAGE_OCCURRENCE
  std::string cycle;                  // "#5 -> #9 -> #5" when an assembly contains itself
  std::vector<std::string> damaged;   // "#12: unknown entity type NOT_A_TYPE" (first few)
  int damaged_count = 0;              // all damaged entities
  // "#684 (CARTESIAN_POINT)": points and directions whose coordinates are not
  // finite (or unreadable): OCCT's shape healing loops forever on some of them.
  std::vector<std::string> non_finite;
};

StepModelCheck check_step_model(const Handle(StepData_StepModel)& model);

// "#12: unknown entity type NOT_A_TYPE; #40: ..." (with "and N more").
std::string describe_damaged(const StepModelCheck& check);

// "#684 (CARTESIAN_POINT), #20 (DIRECTION)" (with "and N more").
std::string describe_non_finite(const StepModelCheck& check);

}  // namespace contactcore
