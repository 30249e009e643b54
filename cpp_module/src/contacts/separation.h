// Stage 3 (contacts), part of the interference pass: a cheap proof that two bodies whose boxes
// overlap have no material in common, from their partitions alone (no point
// classification, no Boolean). Most body pairs of an assembly only touch, so
// this is what keeps the pass cheap.
#pragma once

#include <vector>

#include <gp_Dir.hxx>
#include <gp_Pnt.hxx>

#include "contactcore/partitions/partitions.h"

namespace contactcore {

// A line about which two bodies are seen in cylindrical coordinates (r, z).
struct SeparationAxis {
  gp_Pnt origin;
  gp_Dir direction;
};

// Where a partition can lie about an axis: r in [r0, r1], z in [z0, z1]
// (never smaller than the truth: exact for coaxial cylinders, cones, planes
// across or along the axis; the partition's box otherwise; a surface of
// revolution's range always cut down to its box's, so a domed end, the cap
// of a large sphere, reaches no farther along the axis than the cap does).
struct Shadow {
  double r0 = 0, r1 = 0, z0 = 0, z1 = 0;
  // r has no minimum inside the partition (a cross hole away from the
  // axis): its smallest r is on its edges, so no less than its neighbours'.
  bool r0_on_edges = false;
};

// Per partition, the partitions sharing an edge with it (itself excluded).
std::vector<std::vector<int>> partition_neighbours(const BodyPartitions& body);

// `outlines`: the body holding the plane outlines of `body`'s partitions
// (itself, or the source of an instance: same plane frames). `neighbours`
// (partition_neighbours, or empty) tightens r0 where it lies on edges.
std::vector<Shadow> partition_shadows(const BodyPartitions& body, const BodyPartitions& outlines,
                                      const SeparationAxis& axis, double linear,
                                      const std::vector<std::vector<int>>& neighbours = {});

// True when the two bodies provably share no material (beyond `linear`):
// about one of the axes of their revolution partitions (or along one of their
// plane normals), a curve r = f(z) monotone in z has one body's faces on its
// axis side and the other's beyond (a shaft with a shoulder on one side of a
// bearing; a plane between two stacked parts).
// The boundary of each body's projection lies in the projection of its
// faces, so the faces' shadows bound the bodies' shadows: the test is sound.
bool provably_apart(const BodyPartitions& a, const BodyPartitions& a_outlines, const BodyPartitions& b,
                    const BodyPartitions& b_outlines, const Tolerances& tol);

}  // namespace contactcore
