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
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

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
      step_histogram_(kHistogramBins, 0) {
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
  proxy_ = snap_to_joint(joint_, proxy_);
  engaged_axial_ = (proxy_ * config_.centre).dot(joint_.axis);
}

void ServoLoop::release_joint() {
  engaged_ = held_ = false;
  joint_ = JointState{};
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

void ServoLoop::engage(const JointState& joint, double now) {
  joint_ = joint;
  engaged_ = true;
  ++engagements_;
  engaged_axial_ = (proxy_ * config_.centre).dot(joint_.axis);
  if (events_.size() < events_.capacity()) events_.push_back(EngagementEvent{now, joint});
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

Pose ServoLoop::limit_and_constrain(const Pose& target, double dt) {
  const Vec3 c = config_.centre;
  Vec6 xi = twist_between(proxy_, target, c);
  // Speed limits keep each tick's motion small (collision bisection, capture).
  const double lin = xi.head<3>().norm(), ang = xi.tail<3>().norm();
  const double max_lin = config_.max_speed * dt, max_ang = config_.max_angular_speed * dt;
  if (lin > max_lin) xi.head<3>() *= max_lin / lin;
  if (ang > max_ang) xi.tail<3>() *= max_ang / ang;

  if (engaged_) {
    Eigen::Matrix<double, 6, 6> basis;
    const int n = free_twists(joint_, proxy_ * c, basis);
    if (n == 0) {
      xi.setZero();
    } else if (n < 6) {
      // Weighted least squares: the free motion nearest the commanded one.
      Vec6 w;
      const double l2 = config_.length_scale * config_.length_scale;
      w << 1, 1, 1, l2, l2, l2;
      using Cols = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>;
      using Square = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
      using Column = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;
      const Cols s = basis.leftCols(n);
      const Square m = s.transpose() * w.asDiagonal() * s;
      const Column rhs = s.transpose() * (w.asDiagonal() * xi);
      const Column q = m.ldlt().solve(rhs);
      xi = s * q;
    }
  }
  Pose candidate = apply_twist(proxy_, xi, c);
  if (engaged_) candidate = snap_to_joint(joint_, candidate);
  last_.blocked = false;
  for (int i = 0; i < joint_.stop_count && engaged_; ++i) {
    const Stop& stop = joint_.stops[i];
    const double over = stop.normal.dot(candidate * c) - stop.limit;
    if (over > 0) {
      candidate.translation() -= over * stop.normal;
      last_.blocked = true;
    }
  }
  if (collision_ && collision_->collides(candidate, engaged_ ? joint_.group : -1)) {
    // Bisection between the free proxy and the candidate: keep the last free pose.
    double free = 0, hit = 1;
    for (int k = 0; k < config_.collision_bisections; ++k) {
      const double mid = 0.5 * (free + hit);
      if (collision_->collides(interpolate(proxy_, candidate, mid), engaged_ ? joint_.group : -1))
        hit = mid;
      else
        free = mid;
    }
    candidate = free > 0 ? interpolate(proxy_, candidate, free) : proxy_;
    last_.blocked = true;
  }
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

    // Engagement: capture near a joint (once re-armed after a break-away).
    if (finder_ && !engaged_) {
      JointState found;
      const Pose probe = interpolate(proxy_, target, 1.0);
      if (finder_->capture(probe, found)) {
        if (rearm_) {
          engage(found, now);
          // The snap is a jump only within the capture distance.
          const Pose snapped = snap_to_joint(joint_, proxy_);
          if (!collision_ || !collision_->collides(snapped, joint_.group)) proxy_ = snapped;
          else engaged_ = false;
        }
      } else {
        rearm_ = true;
      }
    }

    const Pose next = limit_and_constrain(target, dt);
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
      if (across.norm() > config_.breakaway_force) {
        engaged_ = false;
        rearm_ = false;
      } else if (finder_ && !finder_->still_engaged(proxy_, joint_)) {
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

  double penetration = engaged_ ? joint_deviation(joint_, proxy_) : 0.0;
  for (int i = 0; engaged_ && i < joint_.stop_count; ++i)
    penetration = std::max(penetration, joint_.stops[i].normal.dot(proxy_ * c) - joint_.stops[i].limit);
  max_penetration_ = std::max(max_penetration_, penetration);
  max_force_ = std::max(max_force_, rendered.force.norm());

  ++ticks_;
  const double step_us = (steady_seconds() - started) * 1e6;
  step_max_us_ = std::max(step_max_us_, step_us);
  ++step_histogram_[std::min<std::size_t>(static_cast<std::size_t>(step_us / kBinUs), kHistogramBins - 1)];
  if (step_us > period_ * 1e6) {
    ++overruns_;
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
      if (latency_us > config_.late_wakeup_us) ++late_wakeups_;
    }
    const double now = seconds_of(woke) - origin;
    if (ticks_ > 0) {
      // Welford's running mean and variance of the tick period.
      const double p = now - last_tick_start_;
      ++period_count_;
      const double delta = p - period_mean_;
      period_mean_ += delta / period_count_;
      period_m2_ += delta * (p - period_mean_);
    }
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

double ServoLoop::rate_hz() const {
  if (config_.lockstep) return config_.rate_hz;
  return period_count_ > 0 && period_mean_ > 0 ? 1.0 / period_mean_ : 0.0;
}

double ServoLoop::jitter_us() const {
  if (config_.lockstep || period_count_ < 2) return 0;
  return std::sqrt(period_m2_ / (period_count_ - 1)) * 1e6;
}

double ServoLoop::step_percentile_us(double p) const {
  std::uint64_t total = 0;
  for (auto n : step_histogram_) total += n;
  if (total == 0) return 0;
  const double wanted = p / 100.0 * total;
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i < step_histogram_.size(); ++i) {
    seen += step_histogram_[i];
    if (seen >= wanted) return (static_cast<double>(i) + 0.5) * kBinUs;
  }
  return static_cast<double>(step_histogram_.size()) * kBinUs;
}

}  // namespace contactcore::haptics
