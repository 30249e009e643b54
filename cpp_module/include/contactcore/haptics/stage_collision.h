// The loop's collision query on the collision stage (collision.h): one
// CollisionPair per neighbour of the moving part, the engaged joint's
// partitions switched off by flags (no rebuild), a broad phase on the moving
// part's box. Replaces the haptics' own interim triangle models.
#pragma once

#include <memory>
#include <vector>

#include "contactcore/simulation/collision.h"
#include "contactcore/haptics/constraints.h"
#include "contactcore/haptics/realtime_contacts.h"

namespace contactcore::haptics {

class StageCollision : public CollisionQuery {
 public:
  // models: one per body (global frame), nullptr for a body without triangles.
  StageCollision(const std::vector<CollisionModelPtr>& models, int moving, const CollisionGroups& groups);
  bool collides(const Pose& pose, int group) noexcept override;
  int contacts(const Pose& pose, int group, double reach, ContactPoint* out, int capacity) noexcept override;
  double radius_about(const Vec3& centre) const noexcept override;
  std::size_t triangle_count() const { return triangles_; }
  std::size_t moving_triangle_count() const { return moving_triangles_; }

 private:
  void switch_to(int group);
  struct Neighbour {
    int body = 0;
    std::unique_ptr<CollisionPair> pair;
    Eigen::AlignedBox3d box;
  };
  static RigidTransform placement(const Pose& pose);
  Eigen::AlignedBox3d moving_box_at(const Pose& pose, double inflate) const;
  std::vector<Vec3> moving_vertices_;
  std::vector<CollisionModelPtr> models_;
  std::vector<Neighbour> neighbours_;
  CollisionGroups groups_;
  Eigen::AlignedBox3d moving_box_;
  int moving_ = 0, current_group_ = -1;
  QueryResult result_;
  std::size_t triangles_ = 0, moving_triangles_ = 0;
};

}  // namespace contactcore::haptics
