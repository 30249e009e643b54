// Collision of the moving part against its neighbours on triangle models
// (FCL OBB-RSS trees), with the partitions of the engaged joint switched off:
// a shaft in a bore of its own diameter touches along the whole bore, which a
// triangle model would report as a collision at every tick. One model per
// body and per collision group (the same triangles less the group's
// partitions) is built at set-up, so a query only picks models.
// Until the collision stage (collision.h) lands in main, this is the haptic
// loop's own minimal version of it.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include <TopoDS_Shape.hxx>

#include "contactcore/haptics/constraints.h"
#include "contactcore/haptics/realtime_contacts.h"

namespace contactcore::haptics {

struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> triangle_partition;  // partition id of each triangle
};

// Tessellates a body (OCCT, set-up only) with each triangle tagged by the
// partition of its face. `deflection` mm, `angle` rad.
TriangleMesh tessellate(const TopoDS_Shape& shape, const BodyPartitions& partitions, double deflection,
                        double angle);

class MeshCollision : public CollisionQuery {
 public:
  // meshes: one per body, global (assembled) frame. groups: collision_groups().
  MeshCollision(const std::vector<TriangleMesh>& meshes, int moving, const CollisionGroups& groups);
  ~MeshCollision() override;
  bool collides(const Pose& pose, int group) noexcept override;
  std::size_t triangle_count() const { return triangles_; }
  std::size_t moving_triangle_count() const { return moving_triangles_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::size_t triangles_ = 0, moving_triangles_ = 0;
};

}  // namespace contactcore::haptics
