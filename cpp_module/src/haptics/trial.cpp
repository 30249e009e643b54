#include "contactcore/haptics/trial.h"

#include <chrono>
#include <cstdio>
#include <cmath>
#include <set>
#include <thread>

#include <BRepBndLib.hxx>
#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <Standard_Failure.hxx>

#include "contactcore/common/occt_guard.h"

namespace contactcore::haptics {

std::unique_ptr<TrialScene> TrialScene::build(const Assembly& assembly, const std::string& part,
                                              const SceneOptions& options, Status& status, Progress* progress) {
  const auto started = std::chrono::steady_clock::now();
  std::unique_ptr<TrialScene> scene(new TrialScene());
  int moving = -1;
  for (std::size_t i = 0; i < assembly.bodies.size(); ++i) {
    scene->names_.push_back(assembly.bodies[i].name);
    if (assembly.bodies[i].name == part) moving = static_cast<int>(i);
  }
  if (moving < 0) {
    std::string names;
    for (const auto& n : scene->names_) names += (names.empty() ? "" : ", ") + n;
    status = Status::failure(StatusCode::InvalidInput, "no body named '" + part + "' (bodies: " + names + ")");
    status.body = part;
    return nullptr;
  }
  scene->moving_ = moving;
  scene->part_name_ = part;
  // A signal inside OCCT while a body is partitioned or meshed fails the
  // build naming the body. The servo loop and the queries run no OCCT.
  const OcctGuard guard;
  try {
    // Partitions with the same tolerances the contact stage uses: each body's own.
    const ContactOptions defaults;
    const std::size_t n = assembly.bodies.size();
    for (std::size_t i = 0; i < n; ++i) {
      std::string failure;
      Tolerances tol;
      status = body_tolerances(assembly.bodies[i].shape, defaults.linear, defaults.angular, tol);
      if (!status.ok()) {
        status.body = assembly.bodies[i].name;
        return nullptr;
      }
      scene->partitions_.emplace_back();
      if (!run_guarded([&] { scene->partitions_.back() = partition_shape(assembly.bodies[i].shape, tol); }, failure,
                       "OCCT: ")) {
        status = Status::failure(StatusCode::GeometryError, failure);
        status.body = assembly.bodies[i].name;
        return nullptr;
      }
      if (progress && !progress->report("partitions", double(i + 1) / n)) {
        status = Status::failure(StatusCode::Cancelled, "cancelled");
        return nullptr;
      }
    }
    {
      GProp_GProps props;
      BRepGProp::VolumeProperties(assembly.bodies[moving].shape, props);
      const gp_Pnt centre = props.CentreOfMass();
      scene->centre_ = Vec3(centre.X(), centre.Y(), centre.Z());
      const gp_Mat inertia = props.MatrixOfInertia();  // about the centre of mass
      if (props.Mass() > 0)
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) scene->inertia_per_mass_(r, c) = inertia(r + 1, c + 1) / props.Mass();
    }
    scene->contacts_ = std::make_unique<RealtimeContacts>(scene->partitions_, moving, options.capture);
    scene->groups_ = collision_groups(*scene->contacts_);
    scene->finder_ = std::make_unique<ContactJointFinder>(*scene->contacts_, scene->groups_.moving_group,
                                                          scene->centre_);
    // Triangle models of the collision stage (meshes.h, collision.h).
    std::vector<CollisionModelPtr> models(n);
    MeshOptions mesh_options;
    mesh_options.deflection = options.deflection;
    mesh_options.angle = options.angle;
    for (std::size_t i = 0; i < n; ++i) {
      mesh_options.max_edge_length = static_cast<int>(i) == moving ? options.moving_max_edge : 0.0;
      MeshResult mesh;
      std::string failure;
      if (!run_guarded([&] { mesh = mesh_body(assembly.bodies[i].shape, scene->partitions_[i], mesh_options); }, failure,
                       "OCCT: "))
        mesh.status = Status::failure(StatusCode::GeometryError, failure);
      if (!mesh.status.ok()) {
        status = mesh.status;
        status.body = assembly.bodies[i].name;
        return nullptr;
      }
      CollisionModelResult model = build_collision_model(mesh.mesh);
      if (!model.status.ok()) {
        status = model.status;
        status.body = assembly.bodies[i].name;
        return nullptr;
      }
      models[i] = model.model;
      if (progress && !progress->report("collision models", double(i + 1) / n)) {
        status = Status::failure(StatusCode::Cancelled, "cancelled");
        return nullptr;
      }
    }
    scene->collision_ = std::make_unique<StageCollision>(models, moving, scene->groups_);
    if (options.analytic) scene->collision_->use_analytic(scene->partitions_);
  } catch (const Standard_Failure& failure) {
    status = Status::failure(StatusCode::GeometryError, "OCCT: " + occt_failure_text(failure));
    status.body = part;
    return nullptr;
  }
  scene->setup_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  status = Status::success();
  return scene;
}

namespace {
// A point and line contact's stop moved from the contact point p to the
// centre of the part's surface there, along the normal: the ball's centre,
// the point of a roller's or a cone's axis (q = p - rho n, rho > 0). That
// point keeps its height while the part rolls, turns or slides, so the stop
// holds exactly; a stop whose point is on no such surface (the part is the
// plane) stays at the contact point.
void centre_stop(const std::vector<SurfaceProxy>& surfaces, Stop& stop) {
  constexpr double kOn = 1e-3;  // mm
  const Vec3 p = stop.part_point, n = stop.normal;
  for (const SurfaceProxy& m : surfaces) {
    if (m.side != MaterialSide::Convex) continue;
    Vec3 q;
    if (m.kind == SurfaceKind::Sphere) {
      q = m.location;
    } else if (m.kind == SurfaceKind::Cylinder || m.kind == SurfaceKind::Cone) {
      q = m.location + (p - m.location).dot(m.axis) * m.axis;  // p's foot on the axis
    } else {
      continue;
    }
    const double rho = (p - q).dot(n);
    if (rho <= kOn || (p - rho * n - q).norm() > kOn) continue;
    if (m.kind != SurfaceKind::Cone && std::abs(rho - m.radius) > kOn) continue;
    stop.part_point = q;
    stop.limit = n.dot(q);
    return;
  }
}
}  // namespace

void TrialScene::attach_collision_group(JointState& joint) const {
  joint.group = -1;
  if (joint.kind == JointKind::HigherPair) {
    // No collision group: the surfaces stay in the collision response (a
    // ball touches its plane at no partition it shares a group with).
    for (int k = 0; k < joint.stop_count; ++k)
      if (joint.stops[k].on_part_point) centre_stop(contacts_->moving_surfaces(), joint.stops[k]);
    return;
  }
  const double tol = contacts_->tolerances().distance, cos_tol = std::cos(contacts_->tolerances().angle);
  const bool bore = joint.kind == JointKind::Cylindrical || joint.kind == JointKind::Revolute;
  // The part's surface on the joint: on its axis (centre, plane) and, among
  // those, one whose group switches off a surface of the body the joint is
  // with (a shaft has several coaxial cylinders: the one in that body's bore).
  int fallback = -1;
  double fallback_radius = 0;
  for (const SurfaceProxy& m : contacts_->moving_surfaces()) {
    if (m.partition < 0 || m.partition >= static_cast<int>(groups_.moving_group.size())) continue;
    const int group = groups_.moving_group[m.partition];
    if (group < 0) continue;
    const Vec3 r = m.location - joint.point;
    bool on = false;
    switch (joint.kind) {
      case JointKind::Cylindrical:
      case JointKind::Revolute:
        on = (m.kind == SurfaceKind::Cylinder || m.kind == SurfaceKind::Cone) &&
             std::abs(m.axis.dot(joint.axis)) > cos_tol && (r - r.dot(joint.axis) * joint.axis).norm() < tol;
        break;
      case JointKind::Spherical:
        on = m.kind == SurfaceKind::Sphere && r.norm() < tol;
        break;
      case JointKind::Planar:
        on = m.kind == SurfaceKind::Plane && m.axis.dot(joint.axis) < -cos_tol && std::abs(r.dot(joint.axis)) < tol;
        break;
      default:
        break;
    }
    if (!on) continue;
    const double radius = bore && m.kind == SurfaceKind::Cylinder ? m.radius : 0.0;
    bool with_the_body = false;
    for (int k = 0; k < joint.body_count; ++k) {
      const int b = joint.bodies[k];
      with_the_body |= b >= 0 && b < static_cast<int>(groups_.switched_off[group].size()) &&
                       !groups_.switched_off[group][b].empty();
    }
    // A cylinder in the body's bore first (a cone there is a chamfer).
    if (with_the_body && (!bore || m.kind == SurfaceKind::Cylinder)) {
      joint.group = group;
      joint.radius = radius;
      return;
    }
    if (fallback < 0) {
      fallback = group;
      fallback_radius = radius;
    }
  }
  joint.group = fallback;
  joint.radius = fallback_radius;
}

TrialResult run_trial(TrialScene& scene, const TrialScript& script, const TrialOptions& options, bool realtime) {
  TrialResult result;
  const Vec3 c = scene.centre();
  auto pose_of = [&](const ScriptKey& k) {
    return offset_pose(k.translate, Vec3(rad(k.rotate_deg.x()), rad(k.rotate_deg.y()), rad(k.rotate_deg.z())), c);
  };
  std::vector<HandKey> keys;
  for (const ScriptKey& k : script.hand) {
    HandKey h;
    h.t = k.t;
    h.pose = pose_of(k);
    keys.push_back(h);
  }
  const Pose start = pose_of(script.start);
  SimulatedHand hand(HandScript(keys), options.hand, c, start);
  ServoConfig config = options.servo;
  config.centre = c;
  config.lockstep = !realtime;
  if (config.inertia_per_mass.isZero()) config.inertia_per_mass = scene.inertia_per_mass();
  ServoLoop loop(options.device ? *options.device : static_cast<Device&>(hand), config, start);
  loop.set_joint_finder(&scene.finder());
  loop.set_collision(&scene.collision());
  if (options.hold) loop.hold_to(*options.hold);

  const double duration = options.device ? options.duration : (keys.empty() ? 0.0 : keys.back().t) + options.settle;
  const auto total = static_cast<std::uint64_t>(duration * config.rate_hz + 0.5);
  // Joints as they engage, and the further bodies the part enters on the same
  // joint (a shaft reaching its second bearing): real-time contacts at the
  // recorded poses, outside the loop.
  std::set<std::pair<int, int>> seen;
  std::vector<LiveContact> live(256);
  auto note = [&](int body, int type, JointKind kind, double t) {
    if (!seen.insert({body, type}).second) return;
    EngagedJoint j;
    j.with = scene.body_names()[body];
    j.type = to_string(static_cast<ContactType>(type));
    j.joint = to_string(kind);
    j.time = t;
    result.joints_engaged.push_back(j);
  };
  auto track = [&](const ServoSnapshot& s) {
    // Joints held at least engaged_after_ticks consecutive ticks only.
    if (!s.engaged || s.held || s.engaged_ticks < static_cast<std::uint64_t>(config.engaged_after_ticks)) return;
    for (int k = 0; k < s.joint.body_count; ++k) note(s.joint.bodies[k], s.joint.contact_type, s.joint.kind, s.time);
    const int n = scene.contacts().update(s.proxy, live.data(), static_cast<int>(live.size()));
    for (int i = 0; i < n; ++i) {
      const LiveContact& lc = live[i];
      if (static_cast<int>(lc.type) != s.joint.contact_type) continue;
      const SurfaceProxy& o = scene.contacts().surfaces(lc.body)[lc.other_index];
      const Vec3 r = o.location - s.joint.point;
      if (std::abs(o.axis.dot(s.joint.axis)) > 0.9999 && (r - r.dot(s.joint.axis) * s.joint.axis).norm() < 1e-3)
        note(lc.body, lc.type == ContactType::CLJ ? s.joint.contact_type : static_cast<int>(lc.type), s.joint.kind, s.time);
    }
  };
  auto record = [&](const ServoSnapshot& s) {
    TrialSample sample;
    sample.t = s.time;
    Vec3 r;
    offset_of(s.proxy, c, sample.translate, r);
    sample.rotate_deg = Vec3(deg(r.x()), deg(r.y()), deg(r.z()));
    sample.force = s.wrench.force;
    sample.engaged = s.engaged;
    sample.penetration = s.penetration;
    result.path.push_back(sample);
  };
  if (!realtime) {
    for (std::uint64_t i = 0; i < total; ++i) {
      loop.step_lockstep();
      const bool sample = i % std::max(1, options.record_every) == 0 || i + 1 == total;
      if (sample) track(loop.last());
      if (options.record_every > 0 && sample) record(loop.last());
    }
  } else {
    loop.start();
    result.memory_locked = loop.memory_locked();
    const auto period = std::chrono::duration<double>(options.record_every > 0 ? options.record_every / config.rate_hz : 0.01);
    while (loop.snapshot().ticks < total) {
      std::this_thread::sleep_for(period);
      const ServoSnapshot s = loop.snapshot();
      track(s);
      if (options.record_every > 0) record(s);
    }
    loop.stop();
  }
  const ServoSnapshot& last = loop.last();
  result.realtime = realtime;
  result.realtime_priority = loop.got_realtime_priority();
  result.ticks = loop.ticks();
  result.sim_time_s = loop.sim_time_s();
  result.rate_hz = loop.rate_hz();
  result.step_p50_us = loop.step_percentile_us(50);
  result.step_p99_us = loop.step_percentile_us(99);
  result.step_max_us = loop.step_max_us();
  result.jitter_p50_us = loop.jitter_percentile_us(50);
  result.jitter_p99_us = loop.jitter_percentile_us(99);
  result.overruns = loop.overruns();
  result.long_steps = loop.long_steps();
  result.late_wakeups = loop.late_wakeups();
  result.start_penetration_mm = last.start_penetration;
  result.final_penetration_mm = last.penetration;
  Vec3 r;
  offset_of(last.proxy, c, result.final_translate, r);
  result.final_rotate_deg = Vec3(deg(r.x()), deg(r.y()), deg(r.z()));
  result.max_penetration_mm = last.max_penetration;
  result.max_force_n = last.max_force;
  for (const EngagementEvent& e : loop.engagement_events())
    for (int k = 0; k < e.joint.body_count; ++k) note(e.joint.bodies[k], e.joint.contact_type, e.joint.kind, e.time);
  std::stable_sort(result.joints_engaged.begin(), result.joints_engaged.end(),
                   [](const EngagedJoint& a, const EngagedJoint& b) { return a.time < b.time; });
  result.setup_seconds = scene.setup_seconds();
  result.status = Status::success();
  if (result.final_penetration_mm > kLeftInsideMm) {
    // Never a silent success with the part inside another body.
    const std::string other = last.deepest_body >= 0 ? scene.body_names()[last.deepest_body] : "another body";
    char text[256];
    std::snprintf(text, sizeof text, "the part ends %.4f mm inside %s (it started %.4f mm inside)",
                  result.final_penetration_mm, other.c_str(), result.start_penetration_mm);
    result.status = Status::failure(StatusCode::InvalidInput, text);
    result.status.body = scene.part_name();
  }
  return result;
}

}  // namespace contactcore::haptics
