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
#include "contactcore/joints/joints.h"
#include "contactcore/simulation/meshes.h"

namespace contactcore {

using Direction = std::array<double, 3>;

struct DisassemblyPart {
  std::string name;
  CollisionModelPtr model;        // at the part's assembled place
  double volume = 0;              // ties between removable groups go to the smallest
  std::vector<Direction> directions;  // candidate directions besides the +-axes (e.g. joint free directions)
  // Directions tried only when no part or group can leave along the others (samples of the part's
  // cone of free directions): each costs a sweep of every remaining pair.
  std::vector<Direction> sampled_directions;
};

struct DisassemblyOptions {
  // mm: meshes closer than this touch, and a probe step must put a vertex deeper than this into
  // another part to count as blocked. Two tessellations of one surface (a shaft in its bore, the
  // chamfer beside it) cross by up to their chordal deviation, so it must exceed the deflection.
  // 0: twice the mesh deflection (disassemble); plan_disassembly needs it positive.
  double tolerance = 0;
  // The designer's intents, per contact (as the contacts given): parts joined by interference or
  // transition fits, bonds or threads come out as one sub-assembly. When nothing can leave, a
  // threaded cylindrical contact (a screw's thread, often drawn as a plain bore) is released: the
  // part it held leaves along its axis (unscrewed), the part it was screwed into stays blocked by
  // it until then. Bonded contacts (glued, welded, staked) are never released.
  std::vector<ContactIntent> contact_intents;
  // disassemble: directions sampled inside each part's cone of free directions
  // (body_free_directions: the cone's generators, the sums of two and the sum of all, the cone's
  // middle), as DisassemblyPart::sampled_directions, tried when nothing else can leave.
  bool sample_free_cones = true;
};

struct DisassemblyStep {
  std::vector<int> parts;  // moved together, ascending
  Direction direction{};   // unit
  // Parts outside the step that blocked its parts along `direction` in the assembly as it was
  // first (all removed before this step: why it is free now), ascending.
  std::vector<int> blocked_before;
  // Threaded cylindrical contacts released (unscrewed) for this step (indices of the contacts given).
  std::vector<int> released;
};

struct DisassemblyResult {
  Status status;
  std::vector<DisassemblyStep> steps;  // removal order; the last remaining part (the base) is not a step
  int base = -1;                       // the part left (the largest of the sub-assembly left), or -1 when the
                                       // sequence stops early
  std::vector<int> base_parts;         // every part left (a sub-assembly joined by annotated contacts)
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
// body_b) and name the partitions switched off between the two parts. Parts
// joined by annotated fits or bonds (options.contact_intents) are one unit.
// The unit of the largest part is the base and stays. At each step the
// removable groups (sink components of the units' blocking graph along a
// direction) are ranked as a mechanic would take them: fewest units first (a
// part or a sub-assembly on its own), useful first (it blocks a part still in
// place), then the one freed most recently
// (what blocked it along its way out was removed last: the front cover right
// after its screws), then the direction of the step before (no turning the
// assembly over), then the highest leverage (volume of the remaining parts it
// blocks over its own) and the lightest. When nothing can leave, the parts'
// sampled directions are added (once), then bonds are released (see
// DisassemblyOptions::contact_intents).
DisassemblyResult plan_disassembly(const std::vector<DisassemblyPart>& parts, const std::vector<Contact>& contacts,
                                   const DisassemblyOptions& options, Progress* progress = nullptr);

// The whole chain on an assembly: contacts, tessellation, collision models,
// then plan_disassembly with the contacts' axes and normals as candidate
// directions besides `extra_directions` (per body; may be empty).
// `contacts`: the contacts of `assembly` found already (with the same options), or null to find
// them; options.contact_intents index them.
DisassemblyResult disassemble(const Assembly& assembly, const ContactOptions& contact_options,
                              const MeshOptions& mesh_options, const DisassemblyOptions& options,
                              const std::vector<std::vector<Direction>>& extra_directions = {},
                              Progress* progress = nullptr, const ContactsResult* contacts = nullptr);

}  // namespace contactcore
