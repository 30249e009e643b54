// The loop's collision query on the collision stage (collision.h): one
// CollisionPair per neighbour of the moving part, the engaged joint's
// partitions switched off by flags (no rebuild), a broad phase on the moving
// part's box. Replaces the haptics' own interim triangle models.
#pragma once

#include <memory>
#include <vector>

#include "contactcore/simulation/analytic_distance.h"
#include "contactcore/simulation/collision.h"
#include "contactcore/haptics/constraints.h"
#include "contactcore/haptics/realtime_contacts.h"

namespace contactcore::haptics {

class StageCollision : public CollisionQuery {
 public:
  // models: one per body (global frame), nullptr for a body without triangles.
  StageCollision(const std::vector<CollisionModelPtr>& models, int moving, const CollisionGroups& groups);
  // The meshes alone (touching coincident surfaces count, as they always did).
  bool collides(const Pose& pose, int group) noexcept override;
  int contacts(const Pose& pose, int group, double reach, ContactPoint* out, int capacity) noexcept override;
  double radius_about(const Vec3& centre) const noexcept override;
  // Closed forms (analytic_distance.h) for the pairs of analytic partitions,
  // the meshes for the rest: each query answers every analytic pair it can in
  // closed form and switches that pair off in the mesh query (the per-pair
  // mask), so a shaft in its line-to-line bore costs a few hundred flops
  // instead of a traversal of two coincident tessellations. `partitions`: one
  // per body, as the models were meshed from. Set-up (allocates); off again
  // with set_analytic(false) (the meshes alone, as before: benchmarks, tests).
  void use_analytic(const std::vector<BodyPartitions>& partitions);
  void set_analytic(bool enabled) { analytic_on_ = enabled && !moving_patches_.empty(); }
  bool analytic() const { return analytic_on_; }
  // The mesh queries on each body's one tree or (the default) one tree per partition
  // (CollisionPair::set_body_tree: the benchmark compares the two in the same run).
  void set_body_trees(bool enabled) {
    for (Neighbour& n : neighbours_) n.pair->set_body_tree(enabled);
  }
  // Of the last contacts() query: analytic pairs answered in closed form,
  // and pairs left to the meshes (profiling, tests).
  int last_closed_form_pairs() const { return closed_form_pairs_; }
  int last_mesh_fallback_pairs() const { return fallback_pairs_; }
  std::size_t triangle_count() const { return triangles_; }
  std::size_t moving_triangle_count() const { return moving_triangles_; }

 private:
  void switch_to(int group);
  struct Neighbour {
    int body = 0;
    std::unique_ptr<CollisionPair> pair;
    Eigen::AlignedBox3d box;
    // Analytic partition pairs (moving, other) worth a closed form, with the
    // other's patch and both partitions' bounding spheres (centre, radius).
    struct AnalyticPair {
      int moving = 0, other = 0;
      AnalyticPatch other_patch;
      Vec3 other_centre = Vec3::Zero();
      double other_radius = 0;
    };
    std::vector<AnalyticPair> analytic;
  };
  // Fills `out` with the neighbour's closed-form contacts' nearest, switching
  // the pairs answered off in its mesh pair. Returns whether one is within reach.
  bool analytic_contact_of(Neighbour& n, const Pose& pose, double reach, ContactPoint& out) noexcept;
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
  // The moving part's patches at its assembled placement, and placed at the
  // query's pose (same loops: only the frames are rewritten, no allocation).
  std::vector<AnalyticPatch> moving_patches_, moving_placed_;
  std::vector<Vec3> moving_centres_;
  std::vector<double> moving_radii_;
  bool analytic_on_ = false;
  int closed_form_pairs_ = 0, fallback_pairs_ = 0;
};

}  // namespace contactcore::haptics
