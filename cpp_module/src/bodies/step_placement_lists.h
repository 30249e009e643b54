// Stage 1 (bodies): the STEP text the read by products hands OCCT's parser.
// OCCT 7.6's parser appends each argument of a record by walking the list
// built so far (StepFile_ReadData::CreateNewArg), so a list of N arguments
// costs N^2 / 2 steps. An assembly's SHAPE_REPRESENTATION lists the placement
// (AXIS2_PLACEMENT_3D) of every part it holds (FreeCAD and OCCT write it so):
// at 100,000 parts that one list is the read's only superlinear cost. The read
// by products takes placements from the ITEM_DEFINED_TRANSFORMATIONs and asks
// of a representation's items only whether they hold geometry and whether a
// placement is among them, so such a list is shortened to its first item and
// the items taken out are kept here, where those questions are answered.
#pragma once

#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace contactcore {

struct ShortenedPlacementLists {
  // The text with each SHAPE_REPRESENTATION whose items are two or more
  // AXIS2_PLACEMENT_3D left with its first; empty when no list was shortened.
  std::string text;
  // Per shortened SHAPE_REPRESENTATION (its #number), the #numbers taken out of its list.
  std::unordered_map<int, std::vector<int>> removed;
  bool changed() const { return !removed.empty(); }
};

// One pass over the text (records split at ';' outside strings and comments).
// Records it does not read exactly (complex entities, other types, a list
// holding anything but references to AXIS2_PLACEMENT_3D) are left as written.
ShortenedPlacementLists shorten_placement_lists(std::string_view text);

}  // namespace contactcore
