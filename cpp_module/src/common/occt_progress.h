// Common to every stage. Our progress and Cancel inside OCCT's long calls (a STEP transfer, a
// solid's self-interference check): OCCT asks its Message_ProgressIndicator
// whether to stop (UserBreak) between its own steps, and that indicator
// answers from the caller's Progress.
#pragma once

#include <atomic>
#include <chrono>
#include <thread>

#include <Message_ProgressIndicator.hxx>
#include <Message_ProgressScope.hxx>

#include "contactcore/common/errors.h"

namespace contactcore::detail {

// Wraps the caller's progress for one stage and remembers a cancel. Its
// report() is what the stage's own loop calls (parallel_for, on the calling
// thread); poll() is what OCCT reaches through OcctBreak, on any thread: on
// the thread that made the watch (nobody else reports there) it asks the
// caller's progress itself, at most every 50 ms; elsewhere it only reads the
// cancel the calling thread has seen.
class CancelWatch final : public Progress {
 public:
  CancelWatch(Progress* inner, const char* stage) : inner_(inner), stage_(stage), owner_(std::this_thread::get_id()) {}
  bool report(const char* stage, double fraction) override {
    if (inner_ != nullptr && !inner_->report(stage, fraction)) cancelled_ = true;
    fraction_ = fraction;
    return !cancelled_;
  }
  bool cancelled() const { return cancelled_; }
  const char* stage() const { return stage_; }
  // `fraction` < 0: the stage's last reported fraction.
  bool poll(double fraction = -1) {
    if (!cancelled_ && inner_ != nullptr && std::this_thread::get_id() == owner_) {
      const auto now = std::chrono::steady_clock::now();
      if (now - last_poll_ >= std::chrono::milliseconds(50)) {
        last_poll_ = now;
        report(stage_, fraction < 0 ? fraction_.load() : fraction);
      }
    }
    return cancelled_;
  }

 private:
  Progress* inner_;
  const char* stage_;
  std::thread::id owner_;
  std::atomic<bool> cancelled_{false};
  std::atomic<double> fraction_{0.0};
  std::chrono::steady_clock::time_point last_poll_{};
};

// OCCT's side: UserBreak() answers from the watch; OCCT's position (0 to 1)
// is reported as the stage's fraction from `from` to `to` (from < 0: the
// stage's own fraction is kept, as when many calls share one stage).
class OcctBreak final : public Message_ProgressIndicator {
 public:
  explicit OcctBreak(CancelWatch& watch, double from = -1, double to = -1) : watch_(watch), from_(from), to_(to) {}
  Standard_Boolean UserBreak() override { return watch_.poll(fraction()); }
  void Show(const Message_ProgressScope&, const Standard_Boolean) override { watch_.poll(fraction()); }

 private:
  double fraction() const { return from_ < 0 ? -1 : from_ + (to_ - from_) * GetPosition(); }
  CancelWatch& watch_;
  double from_, to_;
};

}  // namespace contactcore::detail
