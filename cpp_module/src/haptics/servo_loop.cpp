#include "contactcore/haptics/servo_loop.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <cerrno>
#include <fstream>
#include <mutex>
#include <string>

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include "contactcore/contacts/contacts.h"
#include "contactcore/haptics/spacemouse.h"

namespace contactcore::haptics {

const char* to_string(ControlMode mode) { return mode == ControlMode::Rate ? "rate" : "position"; }

const char* to_string(Watchdog reason) {
  switch (reason) {
    case Watchdog::None: return "none";
    case Watchdog::Disabled: return "disabled";
    case Watchdog::Unplugged: return "unplugged";
    case Watchdog::Stale: return "stale";
    case Watchdog::Overrun: return "overrun";
  }
  return "?";
}

Wrench clamp_to_device(const Wrench& wrench, const DeviceCapabilities& caps) {
  Wrench out;
  if (caps.force_output) {
    out.force = wrench.force;
    const double f = out.force.norm();
    if (f > caps.max_force) out.force *= caps.max_force / f;
  }
  if (caps.torque_output) {
    out.torque = wrench.torque;
    const double t = out.torque.norm();
    if (t > caps.max_torque) out.torque *= caps.max_torque / t;
  }
  return out;
}

namespace {
constexpr std::size_t kHistogramBins = 40000;  // 0.25 us each: up to 10 ms
constexpr double kBinUs = 0.25;

// The p-th percentile (0..100, us) of a kBinUs-bin histogram: the middle of
// the first bin where the running count reaches p % of the total; 0 if empty.
double histogram_percentile_us(const std::vector<std::uint32_t>& histogram, double p) {
  std::uint64_t total = 0;
  for (auto n : histogram) total += n;
  if (total == 0) return 0;
  const double wanted = p / 100.0 * total;
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i < histogram.size(); ++i) {
    seen += histogram[i];
    if (seen >= wanted) return (static_cast<double>(i) + 0.5) * kBinUs;
  }
  return static_cast<double>(histogram.size()) * kBinUs;
}
constexpr std::size_t kMaxEvents = 256;

double limited(double value, double limit) { return limit > 0 ? std::min(value, limit) : value; }

// ---- real-time hygiene helpers (thread set-up and the sleep; never inside a tick)

double seconds_of(const timespec& t) { return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec); }

timespec monotonic_now() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t;
}

void advance(timespec& t, long long ns) {
  const long long total = static_cast<long long>(t.tv_nsec) + ns;
  t.tv_sec += static_cast<time_t>(total / 1000000000LL);
  t.tv_nsec = static_cast<long>(total % 1000000000LL);
}

bool earlier(const timespec& a, const timespec& b) {
  return a.tv_sec < b.tv_sec || (a.tv_sec == b.tv_sec && a.tv_nsec < b.tv_nsec);
}

// Whether mlockall(MCL_FUTURE) is safe: with CAP_IPC_LOCK or an unlimited
// RLIMIT_MEMLOCK no later allocation can fail for being locked.
bool may_lock_all_memory() {
  rlimit limit{};
  if (getrlimit(RLIMIT_MEMLOCK, &limit) == 0 && limit.rlim_cur == RLIM_INFINITY) return true;
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("CapEff:", 0) == 0) {
      const unsigned long long caps = std::stoull(line.substr(7), nullptr, 16);
      return (caps >> 14) & 1ULL;  // CAP_IPC_LOCK
    }
  return false;
}

// mlockall is per process: counted, so the last loop to stop unlocks.
std::mutex g_lock_mutex;
int g_lock_users = 0;
bool g_locked = false;

bool lock_process_memory() {
  std::lock_guard<std::mutex> lock(g_lock_mutex);
  if (g_lock_users == 0) {
    int flags = MCL_CURRENT | MCL_FUTURE;
#ifdef MCL_ONFAULT
    // Lock pages as they are touched, not every reserved mapping of a large
    // process (FreeCAD's) up front; the loop touches its own memory first.
    flags |= MCL_ONFAULT;
#endif
    g_locked = may_lock_all_memory() && mlockall(flags) == 0;
  }
  if (!g_locked) return false;
  ++g_lock_users;
  return true;
}

void unlock_process_memory() {
  std::lock_guard<std::mutex> lock(g_lock_mutex);
  if (g_lock_users > 0 && --g_lock_users == 0 && g_locked) {
    munlockall();
    g_locked = false;
  }
}

// Touches the stack the loop will use, so its pages are present (and locked).
void prefault_stack() {
  volatile unsigned char stack[64 * 1024];
  for (std::size_t i = 0; i < sizeof stack; i += 4096) stack[i] = 0;
}
}  // namespace

ServoLoop::ServoLoop(Device& device, const ServoConfig& config, const Pose& initial_pose)
    : device_(device),
      config_(config),
      caps_(device.capabilities()),
      period_(1.0 / config.rate_hz),
      proxy_(initial_pose),
      stiffness_(config.stiffness),
      angular_stiffness_(config.angular_stiffness),
      damping_(config.damping),
      angular_damping_(config.angular_damping),
      friction_(config.friction > 0 ? config.friction : 0.0),
      step_histogram_(kHistogramBins, 0),
      jitter_histogram_(kHistogramBins, 0) {
  events_.reserve(kMaxEvents);
  last_.proxy = proxy_;
  last_.target = proxy_;
  snapshots_.write(last_);
}

ServoLoop::~ServoLoop() { stop(); }

void ServoLoop::hold_to(const JointState& joint) {
  joint_ = joint;
  engaged_ = true;
  held_ = true;
  engaged_ticks_ = 0;
  event_logged_ = true;  // chosen, not found: not an engagement
  carried_count_ = 0;
  proxy_ = snap_to_joint(joint_, proxy_);
  engaged_axial_ = (proxy_ * config_.centre).dot(joint_.axis);
}

void ServoLoop::release_joint() {
  engaged_ = held_ = false;
  joint_ = JointState{};
  carried_count_ = 0;
}

void ServoLoop::request_hold(const JointState& joint) {
  HoldRequest r;
  r.serial = ++request_serial_;
  r.hold = true;
  r.joint = joint;
  hold_requests_.write(r);
}

void ServoLoop::request_release() {
  HoldRequest r;
  r.serial = ++request_serial_;
  hold_requests_.write(r);
}

void ServoLoop::engage(const JointState& joint) {
  joint_ = joint;
  engaged_ = true;
  ++engagements_;
  engaged_axial_ = (proxy_ * config_.centre).dot(joint_.axis);
  engaged_ticks_ = 0;
  event_logged_ = false;
  carried_count_ = 0;  // contacts on the joint's own surfaces no longer hold
}

Pose ServoLoop::interpolate(const Pose& a, const Pose& b, double s) const {
  const Vec3 c = config_.centre;
  const Eigen::Quaterniond qa(a.linear()), qb(b.linear());
  Pose out = Pose::Identity();
  out.linear() = qa.slerp(s, qb).toRotationMatrix();
  const Vec3 ca = a * c, cb = b * c;
  out.translation() = ca + s * (cb - ca) - out.linear() * c;
  return out;
}

Mat3 ServoLoop::metric_rotation() const {
  if (config_.inertia_per_mass.isZero()) return config_.length_scale * config_.length_scale * Mat3::Identity();
  const Mat3& r = proxy_.linear();
  return r * config_.inertia_per_mass * r.transpose();
}

bool ServoLoop::on_joint_rim(const ContactPoint& contact, const JointState* joint) const {
  if (!joint || joint->radius <= 0 ||
      (joint->kind != JointKind::Cylindrical && joint->kind != JointKind::Revolute))
    return false;
  const Vec3 r = contact.point - joint->point;
  const double radial = (r - r.dot(joint->axis) * joint->axis).norm();
  return std::abs(radial - joint->radius) <= config_.joint_rim_band;
}

double ServoLoop::depth_at(const Pose& pose, const JointState* joint) {
  probe_count_ = 0;
  if (!collision_) return 0;
  const int n = collision_->contacts(pose, joint ? joint->group : -1, config_.contact_skin, probe_.data(), kMaxContacts);
  double deepest = 0;
  for (int i = 0; i < n; ++i) {
    if (on_joint_rim(probe_[i], joint)) continue;
    probe_[probe_count_++] = probe_[i];
    deepest = std::max(deepest, -probe_[i].gap);
  }
  return deepest;
}

double ServoLoop::gather_contacts(const Pose& pose, double reach) {
  constraint_count_ = 0;
  deepest_body_ = -1;
  if (!collision_) return 0;
  const int group = engaged_ ? joint_.group : -1;
  int n = collision_->contacts(pose, group, reach, measured_.data(), kMaxContacts);
  const JointState* joint = engaged_ ? &joint_ : nullptr;
  int kept = 0;
  guided_count_ = 0;
  for (int i = 0; i < n; ++i) {
    if (!on_joint_rim(measured_[i], joint)) measured_[kept++] = measured_[i];
    else guided_bodies_[guided_count_++] = measured_[i].body;  // one answer per body
  }
  n = kept;
  measured_count_ = n;
  double deepest = 0;
  for (int i = 0; i < n; ++i) {
    constraint_set_[constraint_count_++] = measured_[i];
    if (-measured_[i].gap > deepest) {
      deepest = -measured_[i].gap;
      deepest_body_ = measured_[i].body;
    }
  }
  // The last ticks' contacts, carried on the part: a tilted pin touches a
  // bore at two points while the query returns one per body. Not those of a
  // body now answered on the engaged joint's rim: a plane through a point
  // fixed on the part is a stale linearisation there (Screw-1's 45-degree tip
  // measured against the cover's hole edge just before its rim reached it held
  // the screw at the mouth until that contact was 30 ticks old).
  for (int i = 0; i < carried_count_ && constraint_count_ < static_cast<int>(constraint_set_.size()); ++i) {
    const CarriedContact& k = carried_[i];
    if (std::find(guided_bodies_.begin(), guided_bodies_.begin() + guided_count_, k.body) !=
        guided_bodies_.begin() + guided_count_)
      continue;
    ContactPoint c;
    c.point = pose * k.local;
    c.normal = k.normal;
    c.gap = k.normal.dot(c.point - k.anchor);
    c.body = k.body;
    if (c.gap < reach) constraint_set_[constraint_count_++] = c;
  }
  carried_used_ = constraint_count_ - n;
  return deepest;
}

void ServoLoop::carry_contacts(const Pose& measured_at) {
  // The measured contacts first, then the older ones not near a newer one.
  constexpr int kCarryTicks = 30;
  constexpr double kSame = 0.2;  // mm: one contact
  std::array<CarriedContact, kMaxContacts> next{};
  int count = 0;
  const Pose inverse = measured_at.inverse();
  for (int i = 0; i < constraint_count_ && count < kMaxContacts; ++i) {
    if (i >= measured_count_ && i < measured_count_ + carried_used_) continue;  // carried: aged below
    const ContactPoint& c = constraint_set_[i];
    CarriedContact k;
    k.local = inverse * c.point;
    k.anchor = c.point - c.gap * c.normal;
    k.normal = c.normal;
    k.body = c.body;
    bool duplicate = false;
    for (int j = 0; j < count && !duplicate; ++j) duplicate = (next[j].local - k.local).norm() < kSame;
    if (!duplicate && c.gap < 1.0) next[count++] = k;
  }
  for (int i = 0; i < carried_count_ && count < kMaxContacts; ++i) {
    CarriedContact k = carried_[i];
    if (++k.age > kCarryTicks) continue;
    bool duplicate = false;
    for (int j = 0; j < count && !duplicate; ++j) duplicate = (next[j].local - k.local).norm() < kSame;
    if (!duplicate) next[count++] = k;
  }
  carried_ = next;
  carried_count_ = count;
}

Pose ServoLoop::move_proxy(const Pose& target, double dt, double spent_lin, double spent_ang) {
  const Vec3 c = config_.centre;
  const Vec3 c0 = proxy_ * c;
  Vec6 xi = twist_between(proxy_, target, c);
  // Speed limits keep each tick's motion small (the swept check below, capture).
  const double lin = xi.head<3>().norm(), ang = xi.tail<3>().norm();
  const double max_lin = std::max(0.0, config_.max_speed * dt - spent_lin);
  const double max_ang = std::max(0.0, config_.max_angular_speed * dt - spent_ang);
  if (lin > max_lin) xi.head<3>() *= max_lin / lin;
  if (ang > max_ang) xi.tail<3>() *= max_ang / ang;

  Mat6 basis;
  const int free = engaged_ ? free_twists(joint_, c0, basis) : (basis.setIdentity(), 6);
  Mat6 metric = Mat6::Zero();
  metric.topLeftCorner<3, 3>().setIdentity();
  metric.bottomRightCorner<3, 3>() = metric_rotation();

  // Conservative advancement: no point of the part moves further than the
  // bound; nothing nearer than it is left out of the contact set.
  const double bound = xi.head<3>().norm() + xi.tail<3>().norm() * part_radius_;
  const double reach = bound + config_.max_pushout + 4 * config_.contact_skin;
  const double depth0 = gather_contacts(proxy_, reach);
  const double allowed = std::max(config_.penetration_tolerance, depth0);
  if (ticks_ == 0) start_penetration_ = depth0;

  std::array<ProxyConstraint, 2 * kMaxContacts + kMaxStops> rows{};
  int row_count = 0;
  auto add_contact = [&](const ContactPoint& k) {
    if (row_count >= static_cast<int>(rows.size())) return;
    ProxyConstraint& r = rows[row_count++];
    r.row = contact_row(k.point, k.normal, c0);
    // Keep the skin; an overlap is pushed out at a bounded speed.
    r.bound = std::min(config_.contact_skin - k.gap, config_.max_pushout);
  };
  for (int i = 0; engaged_ && i < joint_.stop_count; ++i) {
    // normal . p <= limit at the stop's point p: -normal . dp >= normal . p - limit.
    const Stop& stop = joint_.stops[i];
    const Vec3 p0 = stop_point(stop, proxy_, c);
    ProxyConstraint& r = rows[row_count++];
    r.row = contact_row(p0, -stop.normal, c0);
    r.bound = stop.normal.dot(p0) - stop.limit;
  }
  for (int i = 0; i < constraint_count_; ++i) add_contact(constraint_set_[i]);

  // Coulomb friction, a friction cone on the proxy: with the hand's whole
  // offset (not speed-limited) the frictionless solve gives the slip along
  // the surfaces and the constraints' load (the hand's push into them); the
  // part sticks while the slip is at most mu times the load and otherwise
  // slides by the excess, ending on the cone's edge. Both in the mass metric
  // (translations: mm of the hand's offset; the coupling's stiffness, the same
  // along and across, cancels out of the force ratio).
  const double mu = friction_.load(std::memory_order_relaxed);
  if (mu > 0 && row_count > 0) {
    const Vec6 whole = twist_between(proxy_, target, c);
    const ProxyStep free_step = solve_proxy_step(whole, metric, basis, free, rows.data(), row_count);
    if (free_step.active > 0) {
      const double slip = std::sqrt(free_step.twist.dot(metric * free_step.twist));
      const double kept = slip > 0 ? std::max(0.0, 1.0 - mu * free_step.load / slip) : 0.0;
      xi = kept * free_step.twist;
      const double l = xi.head<3>().norm(), a = xi.tail<3>().norm();
      if (l > max_lin) xi.head<3>() *= max_lin / l;
      if (a > max_ang) xi.tail<3>() *= max_ang / a;
    }
  }

  last_.blocked = false;
  Pose candidate = proxy_;
  const JointState* joint = engaged_ ? &joint_ : nullptr;
  for (int round = 0; round < 4; ++round) {
    const ProxyStep step = solve_proxy_step(xi, metric, basis, free, rows.data(), row_count);
    last_.blocked = last_.blocked || step.active > 0;
    // The nearest twist in the mass metric can move the centre a hair more
    // than the limit asked (rotation and translation are coupled in the
    // metric; a centre off the joint's axis turns with the part): scaled back
    // (a scaled feasible step stays feasible), so the speed bound holds exactly.
    Vec6 twist = step.twist;
    const double step_lin = twist.head<3>().norm(), step_ang = twist.tail<3>().norm();
    const double scale = std::min({1.0, step_lin > max_lin ? max_lin / step_lin : 1.0,
                                   step_ang > max_ang ? max_ang / step_ang : 1.0});
    twist *= scale;
    candidate = apply_twist(proxy_, twist, c);
    if (engaged_) candidate = snap_to_joint(joint_, candidate);
    for (int i = 0; i < joint_.stop_count && engaged_; ++i) {
      const Stop& stop = joint_.stops[i];
      const double over = stop.normal.dot(stop_point(stop, candidate, c)) - stop.limit;
      if (over > 0) {
        candidate.translation() -= over * stop.normal;
        last_.blocked = true;
      }
    }
    if (!collision_ || constraint_count_ == 0) break;  // nothing within reach: the step is free
    // No point of the part moves more than `moved` (translation of the centre
    // plus the turn times the part's radius), and a depth inside a fixed body
    // changes at most by that much: when even then it stays within what is
    // allowed the end pose's query could only pass, and is not made. A part
    // held still (Screw-1 seated, the hand pushing it into its seat) then
    // makes one contact query per tick instead of two.
    const Vec6 moved_twist = twist_between(proxy_, candidate, c);
    const double moved = moved_twist.head<3>().norm() + moved_twist.tail<3>().norm() * part_radius_;
    if (depth0 + moved <= allowed) {
      ++end_checks_skipped_;
      break;
    }
    // The end pose, checked: contacts the linearised set missed join it (moved
    // back onto the proxy's pose) and the step is solved again.
    const double depth1 = depth_at(candidate, joint);
    if (depth1 <= allowed) break;
    const Pose back = proxy_ * candidate.inverse();
    bool added = false;
    for (int i = 0; i < probe_count_; ++i) {
      if (-probe_[i].gap <= allowed) continue;
      ContactPoint k = probe_[i];
      const Vec3 at_proxy = back * k.point;
      k.gap -= k.normal.dot(k.point - at_proxy);
      k.point = at_proxy;
      add_contact(k);
      if (constraint_count_ < static_cast<int>(constraint_set_.size())) constraint_set_[constraint_count_++] = k;
      added = true;
    }
    last_.blocked = true;
    if (round == 3 || !added) {
      // Last resort (a contact the linearisation cannot hold): as far along the
      // solved step as stays within the allowed depth.
      double ok = 0, bad = 1;
      for (int k = 0; k < config_.collision_bisections; ++k) {
        const double mid = 0.5 * (ok + bad);
        if (depth_at(interpolate(proxy_, candidate, mid), joint) <= allowed) ok = mid;
        else bad = mid;
      }
      candidate = ok > 0 ? interpolate(proxy_, candidate, ok) : proxy_;
      break;
    }
  }
  carry_contacts(proxy_);
  return candidate;
}

void ServoLoop::tick(double now, bool wall_clock) {
  const double started = steady_seconds();
  const double dt = period_;
  const Vec3 c = config_.centre;
  const DeviceSample sample = device_.read(now);
  {
    const HoldRequest& request = hold_requests_.read();  // one atomic load when nothing is new
    if (request.serial != applied_serial_) {
      applied_serial_ = request.serial;
      if (request.hold) hold_to(request.joint);
      else release_joint();
    }
  }

  Watchdog reason = Watchdog::None;
  const bool enabled = enabled_.load(std::memory_order_relaxed);
  if (!enabled) reason = Watchdog::Disabled;
  else if (!sample.connected) reason = Watchdog::Unplugged;
  else if (!sample.at_rest && now - sample.time > config_.stale_after) reason = Watchdog::Stale;
  else if (overrun_pending_) reason = Watchdog::Overrun;
  overrun_pending_ = false;

  // Gains within what the device renders stably.
  const double k = limited(stiffness_.load(std::memory_order_relaxed), caps_.max_stiffness);
  const double kr = limited(angular_stiffness_.load(std::memory_order_relaxed), caps_.max_angular_stiffness);
  const double b = limited(damping_.load(std::memory_order_relaxed), caps_.max_damping);
  const double br = angular_damping_.load(std::memory_order_relaxed);

  Pose target = proxy_;
  Vec6 device_velocity = Vec6::Zero();
  Wrench coupling;
  if (reason == Watchdog::None) {
    if (caps_.control == ControlMode::Position) {
      // A clutch: after disable or unplugging, the device picks up where the part is.
      if (!was_enabled_) anchor_ = proxy_ * sample.pose.inverse();
      target = anchor_ * sample.pose;
      device_velocity.head<3>() = anchor_.linear() * sample.velocity.head<3>();
      device_velocity.tail<3>() = anchor_.linear() * sample.velocity.tail<3>();
    } else {
      Vec6 rate;
      rate.head<3>() = config_.rate_frame * sample.axes.head<3>() * config_.rate_speed;
      rate.tail<3>() = config_.rate_frame * sample.axes.tail<3>() * config_.rate_angular_speed;
      target = apply_twist(proxy_, rate * dt, c);
      device_velocity = rate;
    }
    was_enabled_ = true;

    // Engagement: capture near a joint (once re-armed after a break-away),
    // probed where the part is (the proxy), never where the hand is.
    double snap_lin = 0, snap_ang = 0;
    if (finder_ && !engaged_) {
      JointState found;
      if (finder_->capture(proxy_, found)) {
        if (rearm_) {
          // The snap is a jump within the capture distance and angle: taken
          // when it leaves the part no deeper in any other body (the joint's
          // own surfaces off; touching a coplanar face is no overlap).
          const Pose snapped = snap_to_joint(found, proxy_);
          // A shaft at its bore's mouth is held by nothing yet: its snap is
          // this tick's motion, within the proxy's speed limits (no jump),
          // checked halfway as well as at its end; the step below gets what
          // is left of the limits. Further off, the hand brings it closer.
          const Vec6 jump = twist_between(proxy_, snapped, c);
          const bool within = !found.at_mouth || (jump.head<3>().norm() <= config_.max_speed * dt &&
                                                  jump.tail<3>().norm() <= config_.max_angular_speed * dt);
          if (within) {
            const double before = std::max(config_.penetration_tolerance, depth_at(proxy_, &found));
            if (depth_at(snapped, &found) <= before &&
                (!found.at_mouth || depth_at(interpolate(proxy_, snapped, 0.5), &found) <= before)) {
              engage(found);
              engaged_at_ = now;
              proxy_ = snapped;
              if (found.at_mouth) {
                snap_lin = jump.head<3>().norm();
                snap_ang = jump.tail<3>().norm();
              }
            }
          }
        }
      } else {
        rearm_ = true;
      }
    }

    const Pose next = move_proxy(target, dt, snap_lin, snap_ang);
    proxy_velocity_ = twist_between(proxy_, next, c) / dt;
    proxy_ = next;

    // Virtual coupling: the device is pulled towards the proxy.
    coupling.force = k * (proxy_ * c - target * c) + b * (proxy_velocity_.head<3>() - device_velocity.head<3>());
    coupling.torque = kr * rotation_vector(proxy_.linear() * target.linear().transpose()) +
                      br * (proxy_velocity_.tail<3>() - device_velocity.tail<3>());

    if (engaged_ && !held_) {
      // The hand pulls across the joint's free directions: break away above the threshold.
      const Vec3 pull = -coupling.force;
      Vec3 across = pull;
      if (joint_.kind == JointKind::Cylindrical || joint_.kind == JointKind::Prismatic)
        across -= pull.dot(joint_.axis) * joint_.axis;
      if (joint_.kind == JointKind::Planar) {
        // Every force is free (slides, lift-off) or held by the stop: the
        // hand breaks a face away by tilting it (torque over the length scale).
        const Vec3 tilt = -coupling.torque;
        across = (tilt - tilt.dot(joint_.axis) * joint_.axis) / config_.length_scale;
      }
      // A shaft inside its bore cannot leave it sideways: a bore joint ends
      // only when the part has left the bore (still_engaged below). At the
      // bore's mouth (not entered yet) nothing holds it: it breaks away.
      bool entered = true;
      const bool kept = !finder_ || finder_->still_engaged(proxy_, joint_, &entered);
      const bool in_bore = joint_.contact_type == static_cast<int>(ContactType::CLJ) &&
                           (joint_.kind == JointKind::Cylindrical || joint_.kind == JointKind::Revolute) && entered;
      if (!in_bore && across.norm() > config_.breakaway_force) {
        engaged_ = false;
        rearm_ = false;
      } else if (!kept) {
        engaged_ = false;
      }
    }
  } else {
    was_enabled_ = reason == Watchdog::Stale || reason == Watchdog::Overrun ? was_enabled_ : false;
    proxy_velocity_.setZero();
  }

  Wrench rendered = reason == Watchdog::None ? clamp_to_device(coupling, caps_) : Wrench{};
  if (reason == Watchdog::None) {
    rendered.stiffness = k;
    rendered.damping = b;
  }
  if (reason == Watchdog::None) device_.write(rendered);
  else device_.halt();

  // The overlap measured at this tick's start pose (the contact set), the
  // joint's deviation and stop overshoot.
  double penetration = reason == Watchdog::None ? std::max(0.0, -min_gap_of_measured()) : last_.penetration;
  if (engaged_) penetration = std::max(penetration, joint_deviation(joint_, proxy_));
  for (int i = 0; engaged_ && i < joint_.stop_count; ++i)
    penetration = std::max(penetration, joint_.stops[i].normal.dot(stop_point(joint_.stops[i], proxy_, c)) -
                                            joint_.stops[i].limit);
  max_penetration_ = std::max(max_penetration_, penetration);
  if (engaged_ && !held_) {
    ++engaged_ticks_;
    if (!event_logged_ && engaged_ticks_ >= static_cast<std::uint64_t>(config_.engaged_after_ticks)) {
      event_logged_ = true;
      if (events_.size() < events_.capacity()) events_.push_back(EngagementEvent{engaged_at_, joint_});
    }
  } else if (!engaged_) {
    engaged_ticks_ = 0;
  }
  max_force_ = std::max(max_force_, rendered.force.norm());

  ++ticks_;
  const double step_us = (steady_seconds() - started) * 1e6;
  step_max_us_ = std::max(step_max_us_, step_us);
  ++step_histogram_[std::min<std::size_t>(static_cast<std::size_t>(step_us / kBinUs), kHistogramBins - 1)];
  if (step_us > period_ * 1e6) {
    ++overruns_;
    ++long_steps_;
    overrun_pending_ = wall_clock && !config_.lockstep;
  }

  last_.proxy = proxy_;
  last_.target = target;
  last_.wrench = rendered;
  last_.coupling = coupling;
  last_.joint = joint_;
  last_.engaged = engaged_;
  last_.held = held_;
  last_.device_connected = sample.connected;
  last_.enabled = enabled;
  last_.watchdog = reason;
  last_.ticks = ticks_;
  last_.overruns = overruns_;
  last_.time = now;
  last_.rate_hz = rate_hz();
  last_.jitter_us = jitter_us();
  last_.last_step_us = step_us;
  last_.insertion_depth = engaged_ ? (proxy_ * c).dot(joint_.axis) - engaged_axial_ : 0.0;
  last_.penetration = penetration;
  last_.max_penetration = max_penetration_;
  last_.start_penetration = start_penetration_;
  last_.engaged_ticks = engaged_ticks_;
  last_.contact_count = constraint_count_;
  last_.deepest_body = deepest_body_;
  last_.max_force = max_force_;
  last_.engagements = engagements_;
  last_.axes = sample.axes;
  last_.late_wakeups = late_wakeups_;
  last_.max_wake_latency_us = wake_latency_max_us_;
  last_.memory_locked = memory_locked_.load(std::memory_order_relaxed);
  last_.realtime_priority = got_priority_.load(std::memory_order_relaxed);
  snapshots_.write(last_);
}

void ServoLoop::step_lockstep() { tick(static_cast<double>(ticks_) * period_, false); }

bool ServoLoop::start() {
  if (thread_.joinable()) return false;
  stop_ = false;
  memory_locked_ = config_.lock_memory && lock_process_memory();
  thread_ = std::thread([this] { run(); });
  return true;
}

void ServoLoop::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  if (memory_locked_.exchange(false)) unlock_process_memory();
}

void ServoLoop::run() {
  if (config_.realtime_priority > 0) {
    // A haptic loop wants a real-time class; without the privilege it runs as it is.
    sched_param param{};
    param.sched_priority = config_.realtime_priority;
    got_priority_ = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param) == 0;
  }
  // A normal thread's timer slack (50 us by default) delays every wake-up
  // by that much; a real-time class has none. Measured on this VM (idle,
  // clock_nanosleep to 1 ms deadlines): wake-up latency p50 118 us with the
  // default slack, 68 us with 1 ns; over 100 us late: 94-100 % of wake-ups
  // against 1 %. The setting is the thread's own (prctl(2)).
  if (prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL) == 0) timer_slack_ns_ = prctl(PR_GET_TIMERSLACK, 0UL, 0UL, 0UL, 0UL);
  prefault_stack();
  // Absolute deadlines on CLOCK_MONOTONIC (the clock steady_seconds reads):
  // a relative sleep accumulates each tick's duration and wake-up latency,
  // and CLOCK_REALTIME jumps with the wall clock.
  const long long period_ns = std::llround(period_ * 1e9);
  timespec deadline = monotonic_now();
  const double origin = seconds_of(deadline);
  start_time_ = 0;
  bool slept = false;
  while (!stop_.load(std::memory_order_relaxed)) {
    const timespec woke = monotonic_now();
    if (slept) {
      const double latency_us = (seconds_of(woke) - seconds_of(deadline)) * 1e6;
      ++wake_count_;
      wake_latency_sum_us_ += latency_us;
      wake_latency_max_us_ = std::max(wake_latency_max_us_, latency_us);
      if (latency_us > config_.late_wakeup_us) {
        ++late_wakeups_;
        ++overruns_;  // a late wake-up is an overrun too: the device waited
      }
    }
    const double now = seconds_of(woke) - origin;
    if (ticks_ > 0) note_period(now);
    last_tick_start_ = now;
    tick(now, true);
    advance(deadline, period_ns);
    const timespec after = monotonic_now();
    slept = earlier(after, deadline);
    if (!slept) {
      deadline = after;  // behind (an overrun, counted by the tick): no burst of catch-up ticks
    } else {
      while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &deadline, nullptr) == EINTR) {
      }
    }
  }
  device_.halt();
}

void ServoLoop::note_period(double now) {
  // Welford's running mean and variance of the tick period, and its jitter histogram.
  const double p = now - last_tick_start_;
  ++period_count_;
  const double delta = p - period_mean_;
  period_mean_ += delta / period_count_;
  period_m2_ += delta * (p - period_mean_);
  const double off_us = std::abs(p - period_) * 1e6;
  ++jitter_histogram_[std::min<std::size_t>(static_cast<std::size_t>(off_us / kBinUs), kHistogramBins - 1)];
}

double ServoLoop::jitter_percentile_us(double p) const {
  if (config_.lockstep) return 0;
  return histogram_percentile_us(jitter_histogram_, p);
}

double ServoLoop::rate_hz() const {
  if (config_.lockstep) return 0;
  return period_count_ > 0 && period_mean_ > 0 ? 1.0 / period_mean_ : 0.0;
}

double ServoLoop::jitter_us() const {
  if (config_.lockstep || period_count_ < 2) return 0;
  return std::sqrt(period_m2_ / (period_count_ - 1)) * 1e6;
}

double ServoLoop::step_percentile_us(double p) const {
  return histogram_percentile_us(step_histogram_, p);
}

}  // namespace contactcore::haptics
