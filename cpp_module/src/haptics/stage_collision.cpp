#include "contactcore/haptics/stage_collision.h"

#include <algorithm>
#include <cmath>

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
  models_ = models;
  for (std::size_t b = 0; b < models.size(); ++b) {
    if (!models[b]) continue;
    triangles_ += models[b]->triangle_count();
    if (static_cast<int>(b) == moving) continue;
  }
  if (!models[moving]) return;
  moving_triangles_ = models[moving]->triangle_count();
  moving_box_ = box_of(models[moving]->mesh());
  for (const auto& v : models[moving]->mesh().vertices) moving_vertices_.emplace_back(v[0], v[1], v[2]);
  for (std::size_t b = 0; b < models.size(); ++b) {
    if (static_cast<int>(b) == moving || !models[b]) continue;
    Neighbour n;
    n.body = static_cast<int>(b);
    n.pair = std::make_unique<CollisionPair>(models[moving], models[b]);
    n.box = box_of(models[b]->mesh());
    neighbours_.push_back(std::move(n));
  }
  // The first queries grow the pairs' scratch buffers: do them here, not in the loop.
  ContactPoint scratch[kMaxContacts];
  for (int g = -1; g < groups_.count(); ++g) {
    collides(Pose::Identity(), g);
    contacts(Pose::Identity(), g, 1.0, scratch, kMaxContacts);
  }
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
  const Eigen::AlignedBox3d box = moving_box_at(pose, 0.0);
  const RigidTransform place = placement(pose);
  const RigidTransform still = RigidTransform::identity();
  for (Neighbour& n : neighbours_) {
    if (!box.intersects(n.box)) continue;
    // The meshes alone, every pair on (contacts() leaves its closed-form pairs off).
    for (const Neighbour::AnalyticPair& pair : n.analytic) n.pair->set_pair_enabled(pair.moving, pair.other, true);
    n.pair->query(place, still, QueryKind::Intersect, result_);
    if (result_.intersecting) return true;
  }
  return false;
}


RigidTransform StageCollision::placement(const Pose& pose) {
  RigidTransform place;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) place.rotation[3 * r + c] = pose.linear()(r, c);
    place.translation[r] = pose.translation()[r];
  }
  return place;
}

Eigen::AlignedBox3d StageCollision::moving_box_at(const Pose& pose, double inflate) const {
  Eigen::AlignedBox3d box;
  for (int i = 0; i < 8; ++i) box.extend(pose * moving_box_.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i)));
  box.min().array() -= inflate;
  box.max().array() += inflate;
  return box;
}

double StageCollision::radius_about(const Vec3& centre) const noexcept {
  double r = 0;
  for (const Vec3& v : moving_vertices_) r = std::max(r, (v - centre).norm());
  return r;
}

namespace {
// Unit normal of a mesh triangle (the mesh's winding: outwards), world frame.
Vec3 triangle_normal(const TaggedMesh& mesh, int triangle, const Mat3& rotation) {
  const auto& t = mesh.triangles[triangle];
  const auto& a = mesh.vertices[t[0]];
  const auto& b = mesh.vertices[t[1]];
  const auto& c = mesh.vertices[t[2]];
  const Vec3 pa(a[0], a[1], a[2]), pb(b[0], b[1], b[2]), pc(c[0], c[1], c[2]);
  const Vec3 n = (pb - pa).cross(pc - pa);
  return n.norm() > 0 ? Vec3(rotation * n.normalized()) : Vec3::UnitZ();
}
Vec3 triangle_centroid(const TaggedMesh& mesh, int triangle, const Pose& pose) {
  const auto& t = mesh.triangles[triangle];
  Vec3 sum = Vec3::Zero();
  for (int k = 0; k < 3; ++k) sum += Vec3(mesh.vertices[t[k]][0], mesh.vertices[t[k]][1], mesh.vertices[t[k]][2]);
  return pose * (sum / 3.0);
}
}  // namespace

namespace {
// Bounding sphere of a partition's box (its faces' tolerance included).
void bounding_sphere(const Partition& p, Vec3& centre, double& radius) {
  if (p.box.IsVoid()) {
    centre = Vec3::Zero();
    radius = -1;
    return;
  }
  double x0, y0, z0, x1, y1, z1;
  p.box.Get(x0, y0, z0, x1, y1, z1);
  centre = Vec3(x0 + x1, y0 + y1, z0 + z1) / 2;
  radius = 0.5 * Vec3(x1 - x0, y1 - y0, z1 - z0).norm();
}

// Kinds analytic_contact() answers: a closed form for most pairs of planes, cylinders, cones and
// spheres (it still says no where the closest pair leaves the bounds), and for any of them a lower
// bound of the gap once it is beyond the query's reach (AnalyticTolerances::reach: a hex socket's
// walls above a cover, a shank beside the cover's central chamfers). A torus or another surface:
// the meshes.
bool closed_form_kinds(const AnalyticPatch& a, const AnalyticPatch& b) {
  auto analytic = [](SurfaceKind k) {
    return k == SurfaceKind::Plane || k == SurfaceKind::Cylinder || k == SurfaceKind::Cone || k == SurfaceKind::Sphere;
  };
  return analytic(a.kind) && analytic(b.kind);
}
}  // namespace

void StageCollision::use_analytic(const std::vector<BodyPartitions>& partitions) {
  if (partitions.size() != models_.size() || !models_[moving_]) return;
  const BodyPartitions& moving = partitions[moving_];
  if (static_cast<int>(moving.partitions.size()) != models_[moving_]->partition_count()) return;
  moving_patches_.clear();
  moving_centres_.clear();
  moving_radii_.clear();
  for (const Partition& p : moving.partitions) {
    moving_patches_.push_back(analytic_patch(p));
    Vec3 c;
    double r;
    bounding_sphere(p, c, r);
    moving_centres_.push_back(c);
    moving_radii_.push_back(r);
  }
  moving_placed_ = moving_patches_;
  for (Neighbour& n : neighbours_) {
    n.analytic.clear();
    const BodyPartitions& other = partitions[n.body];
    if (static_cast<int>(other.partitions.size()) != models_[n.body]->partition_count()) continue;
    for (std::size_t j = 0; j < other.partitions.size(); ++j) {
      const AnalyticPatch patch = analytic_patch(other.partitions[j]);
      for (std::size_t i = 0; i < moving_patches_.size(); ++i) {
        if (moving_radii_[i] < 0 || !closed_form_kinds(moving_patches_[i], patch)) continue;
        Neighbour::AnalyticPair pair;
        pair.moving = static_cast<int>(i);
        pair.other = static_cast<int>(j);
        pair.other_patch = patch;
        bounding_sphere(other.partitions[j], pair.other_centre, pair.other_radius);
        if (pair.other_radius < 0) continue;
        n.analytic.push_back(std::move(pair));
      }
    }
  }
  analytic_on_ = true;
}

bool StageCollision::analytic_contact_of(Neighbour& n, const Pose& pose, double reach, ContactPoint& out) noexcept {
  bool found = false;
  AnalyticContact c;
  AnalyticTolerances tolerances;
  tolerances.reach = reach;
  for (Neighbour::AnalyticPair& pair : n.analytic) {
    CollisionPair& mesh = *n.pair;
    if (!mesh.partition_enabled(0, pair.moving) || !mesh.partition_enabled(1, pair.other)) continue;
    // Bounding spheres farther apart than the reach: no closed form needed; the pair stays with the
    // meshes, whose boxes prune it for free (switched off, the penetration flood would skip a vertex
    // sunk deeper than the reach whose nearest surface is that partition: see set_pair_enabled).
    const double apart =
        (pose * moving_centres_[pair.moving] - pair.other_centre).norm() - moving_radii_[pair.moving] - pair.other_radius;
    if (apart > reach) {
      mesh.set_pair_enabled(pair.moving, pair.other, true);
      continue;
    }
    if (!analytic_contact(moving_placed_[pair.moving], pair.other_patch, c, tolerances)) {
      mesh.set_pair_enabled(pair.moving, pair.other, true);
      ++fallback_pairs_;
      continue;
    }
    // Answered (out of reach ones perhaps by a lower bound of their gap: AnalyticTolerances::reach).
    mesh.set_pair_enabled(pair.moving, pair.other, false);
    ++closed_form_pairs_;
    if (c.gap > reach || (found && c.gap >= out.gap)) continue;
    out.point = c.point_a;
    out.normal = c.normal;
    out.gap = c.gap;
    out.body = n.body;
    found = true;
  }
  return found;
}

int StageCollision::contacts(const Pose& pose, int group, double reach, ContactPoint* out, int capacity) noexcept {
  if (group >= groups_.count()) group = -1;
  switch_to(group);
  if (!models_[moving_]) return 0;
  const Eigen::AlignedBox3d box = moving_box_at(pose, reach);
  const RigidTransform place = placement(pose);
  const RigidTransform still = RigidTransform::identity();
  const TaggedMesh& moving_mesh = models_[moving_]->mesh();
  int n = 0;
  closed_form_pairs_ = fallback_pairs_ = 0;
  if (analytic_on_)
    for (std::size_t i = 0; i < moving_patches_.size(); ++i) {
      AnalyticPatch& placed_patch = moving_placed_[i];
      placed_patch.location = pose * moving_patches_[i].location;
      placed_patch.axis = pose.linear() * moving_patches_[i].axis;
      placed_patch.ref_dir = pose.linear() * moving_patches_[i].ref_dir;
    }
  for (Neighbour& nb : neighbours_) {
    if (n >= capacity) break;
    if (!box.intersects(nb.box)) continue;
    ContactPoint closed;
    if (!analytic_on_)  // the closed forms switched off since they last left pairs to them: the meshes answer all
      for (const Neighbour::AnalyticPair& pair : nb.analytic) nb.pair->set_pair_enabled(pair.moving, pair.other, true);
    const bool closed_found = analytic_on_ && analytic_contact_of(nb, pose, reach, closed);
    nb.pair->set_distance_limit(closed_found ? std::max(0.0, closed.gap) : reach);
    nb.pair->query(place, still, QueryKind::Penetration, result_);
    ContactPoint& c = out[n];
    c.body = nb.body;
    // The closed form's contact unless the meshes found one at least as near.
    const bool mesh_nearer = result_.depth > 0 ? -result_.depth < closed.gap
                             : result_.intersecting ? 0.0 < closed.gap
                                                    : std::isfinite(result_.distance) && result_.distance < closed.gap;
    if (closed_found && !mesh_nearer) {
      c = closed;
    } else if (result_.depth > 0) {
      // Overlapping: the deepest point and the way out.
      c.point = Vec3(result_.depth_point_a[0], result_.depth_point_a[1], result_.depth_point_a[2]);
      c.normal = Vec3(result_.direction[0], result_.direction[1], result_.direction[2]);
      c.gap = -result_.depth;
    } else if (result_.intersecting) {
      // Touching (coplanar faces, tessellations crossing without a vertex
      // inside): no gap, the other body's face normal out.
      if (result_.triangle_a < 0 || result_.triangle_b < 0) continue;
      c.point = triangle_centroid(moving_mesh, result_.triangle_a, pose);
      c.normal = triangle_normal(models_[nb.body]->mesh(), result_.triangle_b, Mat3::Identity());
      c.gap = 0;
    } else if (std::isfinite(result_.distance) && result_.distance <= reach) {
      c.point = Vec3(result_.point_a[0], result_.point_a[1], result_.point_a[2]);
      const Vec3 other(result_.point_b[0], result_.point_b[1], result_.point_b[2]);
      const Vec3 d = c.point - other;
      c.normal = d.norm() > 1e-9 ? Vec3(d.normalized())
                                 : triangle_normal(models_[nb.body]->mesh(), result_.triangle_b, Mat3::Identity());
      c.gap = result_.distance;
    } else {
      continue;
    }
    ++n;
  }
  return n;
}

}  // namespace contactcore::haptics
