// The independent judge of a haptic trial's recorded path: at each recorded
// pose the moving part's B-rep is placed and intersected with every other
// body by OCCT (BRepAlgoAPI_Common: the overlap volume; the overlap's depth as
// the thinnest side of its optimal oriented box), never with the loop's own
// meshes or figures.
#pragma once

#include <string>
#include <vector>

#include "contactcore/bodies/bodies.h"
#include "contactcore/haptics/trial.h"

namespace contactcore::testing {

struct PathOverlap {
  double max_volume = 0;   // mm^3, the largest overlap volume at one sample
  double max_depth = 0;    // mm, the deepest overlap at one sample
  double worst_t = -1;     // s, where the deepest overlap is
  std::string worst_body;  // with which body
  int samples_checked = 0;
};

// Overlap of the part `part` (its assembled shape placed by each sample's
// offset about `centre`) with the other bodies, at every `stride`-th sample
// and the last. Overlaps under `volume_floor` mm^3 (touching faces) count as none.
PathOverlap check_path(const Assembly& assembly, const std::string& part, const haptics::Vec3& centre,
                       const std::vector<haptics::TrialSample>& path, int stride = 1,
                       double volume_floor = 1e-6);

// One pose (offset translate mm, rotate degrees about global axes through centre).
PathOverlap check_pose(const Assembly& assembly, const std::string& part, const haptics::Vec3& centre,
                       const haptics::Vec3& translate, const haptics::Vec3& rotate_deg, double volume_floor = 1e-6);

}  // namespace contactcore::testing
