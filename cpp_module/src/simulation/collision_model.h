// Stage 5 (simulation): the inside of a CollisionModel (private to the collision sources): one
// FCL OBBRSS hierarchy over the whole body (its leaves' primitive ids are the mesh's triangles, whose
// partition the mesh tags), one per partition, and the mesh's normals, pseudo-normals
// and adjacency that the penetration flood and the warm start walk.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>

#include "contactcore/simulation/collision.h"

namespace contactcore {

struct CollisionModel::Impl {
  struct Sub {
    std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> bvh;  // null when the partition has no triangles
    std::vector<int> triangle;         // local triangle -> mesh triangle
    std::vector<int> parent;           // BVH node -> its parent node (-1 for the root): front pull-up
    Eigen::Vector3d center{0, 0, 0};   // local axis-aligned box
    Eigen::Vector3d half{-1, -1, -1};
  };
  TaggedMesh mesh;
  // Every triangle in one hierarchy, in mesh order (a leaf's primitiveId() is the mesh triangle,
  // mesh.triangle_partition[] its partition), on the mesh's vertices: the point queries (the
  // penetration flood's closest points, depth_inside) judge against the whole surface, so they
  // walk one tree instead of one per partition.
  std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> body;
  // Per node of `body`: bit (p % 64) set for each partition p among its leaves, so that a traversal
  // skips node pairs holding no partition pair it wants (exact up to 64 partitions, conservative above).
  std::vector<std::uint64_t> body_partitions;
  std::vector<Sub> subs;                     // one per partition
  std::vector<Eigen::Vector3d> normals;      // unit normal of each triangle
  // Angle-weighted pseudo-normals (Baerentzen and Aanaes): the sign of
  // (p - closest) . normal tells inside from outside wherever the closest
  // point falls, face, edge or vertex.
  std::vector<Eigen::Vector3d> vertex_normals;
  std::vector<Eigen::Vector3d> edge_normals;  // 3 per triangle, edge (v[k], v[k+1])
  std::vector<int> adjacency_start, adjacency;  // vertex -> neighbouring vertices (CSR)
  std::vector<int> local_triangle;              // mesh triangle -> its index in its partition's Sub
  std::vector<int> corner_start, corner_of;     // vertex -> mesh triangles using it (CSR)
};

}  // namespace contactcore
