#include "contactcore/haptics/stage_collision.h"

namespace contactcore::haptics {

namespace {
Eigen::AlignedBox3d box_of(const TaggedMesh& mesh) {
  Eigen::AlignedBox3d box;
  for (const auto& v : mesh.vertices) box.extend(Vec3(v[0], v[1], v[2]));
  return box;
}
}  // namespace

StageCollision::StageCollision(const std::vector<CollisionModelPtr>& models, int moving,
                               const CollisionGroups& groups)
    : groups_(groups), moving_(moving) {
  for (std::size_t b = 0; b < models.size(); ++b) {
    if (!models[b]) continue;
    triangles_ += models[b]->triangle_count();
    if (static_cast<int>(b) == moving) continue;
  }
  if (!models[moving]) return;
  moving_triangles_ = models[moving]->triangle_count();
  moving_box_ = box_of(models[moving]->mesh());
  for (std::size_t b = 0; b < models.size(); ++b) {
    if (static_cast<int>(b) == moving || !models[b]) continue;
    Neighbour n;
    n.body = static_cast<int>(b);
    n.pair = std::make_unique<CollisionPair>(models[moving], models[b]);
    n.box = box_of(models[b]->mesh());
    neighbours_.push_back(std::move(n));
  }
  // The first queries grow the pairs' scratch buffers: do them here, not in the loop.
  for (int g = -1; g < groups_.count(); ++g) collides(Pose::Identity(), g);
  switch_to(-1);
}

void StageCollision::switch_to(int group) {
  if (group == current_group_) return;
  for (Neighbour& n : neighbours_) {
    n.pair->enable_all();
    if (group < 0) continue;
    for (std::size_t p = 0; p < groups_.moving_group.size(); ++p)
      if (groups_.moving_group[p] == group) n.pair->set_partition_enabled(0, static_cast<int>(p), false);
    for (int p : groups_.switched_off[group][n.body]) n.pair->set_partition_enabled(1, p, false);
  }
  current_group_ = group;
}

bool StageCollision::collides(const Pose& pose, int group) noexcept {
  if (group >= groups_.count()) group = -1;
  switch_to(group);
  Eigen::AlignedBox3d box;
  for (int i = 0; i < 8; ++i) box.extend(pose * moving_box_.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i)));
  RigidTransform place;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) place.rotation[3 * r + c] = pose.linear()(r, c);
    place.translation[r] = pose.translation()[r];
  }
  const RigidTransform still = RigidTransform::identity();
  for (Neighbour& n : neighbours_) {
    if (!box.intersects(n.box)) continue;
    n.pair->query(place, still, QueryKind::Intersect, result_);
    if (result_.intersecting) return true;
  }
  return false;
}

}  // namespace contactcore::haptics
