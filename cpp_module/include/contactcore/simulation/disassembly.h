// Stage 5 (simulation), disassembly: blocking and removal order. For each part and candidate
// direction, the part is swept along the direction with collision queries
// against every other part (the partitions of their contacts switched off,
// the contact itself judged by its joint: a planar fit blocks motion into it,
// a cylindrical joint any motion off its axis); the directional blocking
// graphs then give the removal sequence, with the sub-assemblies that must
// move together (a sink strongly connected component of a blocking graph).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "contactcore/bodies/bodies.h"
#include "contactcore/simulation/collision.h"
#include "contactcore/contacts/contacts.h"
#include "contactcore/common/errors.h"
#include "contactcore/simulation/meshes.h"

namespace contactcore {

using Direction = std::array<double, 3>;

struct DisassemblyPart {
  std::string name;
  CollisionModelPtr model;        // at the part's assembled place
  double volume = 0;              // ties between removable groups go to the smallest
  std::vector<Direction> directions;  // candidate directions besides the +-axes (e.g. joint free directions)
};

struct DisassemblyOptions {
  // mm: meshes closer than this touch, and a probe step must put a vertex deeper than this into
  // another part to count as blocked. Two tessellations of one surface (a shaft in its bore, the
  // chamfer beside it) cross by up to their chordal deviation, so it must exceed the deflection.
  // 0: twice the mesh deflection (disassemble); plan_disassembly needs it positive.
  double tolerance = 0;
};

struct DisassemblyStep {
  std::vector<int> parts;  // moved together, ascending
  Direction direction{};   // unit
};

struct DisassemblyResult {
  Status status;
  std::vector<DisassemblyStep> steps;  // removal order; the last remaining part (the base) is not a step
  int base = -1;                       // the part left, or -1 when the sequence stops early
  bool complete = false;
  std::string reason;                  // why no sequence exists (when not complete)
  std::vector<std::string> messages;   // what was left out (faces OCCT could not mesh), for the user
  std::vector<Direction> directions;   // every candidate direction used
  // blocking[d][i]: parts that block part i along directions[d], ascending.
  std::vector<std::vector<std::vector<int>>> blocking;
};

// The candidate directions: the +-axes, then each given direction and its
// opposite, without repeats (unit vectors, within 1e-9).
std::vector<Direction> candidate_directions(const std::vector<DisassemblyPart>& parts);

// Blocking graphs and removal sequence. `contacts` index `parts` (body_a,
// body_b) and name the partitions switched off between the two parts. At
// each step the removable groups (sink components) go smallest first; among
// those of one size, the one of the highest leverage (volume of the remaining
// parts it blocks over its own: fasteners before what they hold), then the
// lightest.
DisassemblyResult plan_disassembly(const std::vector<DisassemblyPart>& parts, const std::vector<Contact>& contacts,
                                   const DisassemblyOptions& options, Progress* progress = nullptr);

// The whole chain on an assembly: contacts, tessellation, collision models,
// then plan_disassembly with the contacts' axes and normals as candidate
// directions besides `extra_directions` (per body; may be empty).
DisassemblyResult disassemble(const Assembly& assembly, const ContactOptions& contact_options,
                              const MeshOptions& mesh_options, const DisassemblyOptions& options,
                              const std::vector<std::vector<Direction>>& extra_directions = {},
                              Progress* progress = nullptr);

}  // namespace contactcore
