// Single-writer single-reader triple buffer: the writer never waits, the
// reader always gets the latest complete value, and neither side ever
// retries (a seqlock's reader spins while the writer is preempted mid-write:
// on a SCHED_FIFO loop thread sharing a core with that writer, for ever).
#pragma once

#include <atomic>

namespace contactcore::haptics {

template <class T>
class TripleBuffer {
 public:
  void write(const T& value) {
    slots_[back_] = value;
    back_ = middle_.exchange(back_ | kFresh, std::memory_order_acq_rel) & kIndex;
  }
  // The latest value written (the same one again if nothing new came).
  const T& read() {
    if (middle_.load(std::memory_order_acquire) & kFresh)
      front_ = middle_.exchange(front_, std::memory_order_acq_rel) & kIndex;
    return slots_[front_];
  }

 private:
  static constexpr int kFresh = 4, kIndex = 3;
  T slots_[3]{};
  std::atomic<int> middle_{1};
  int back_ = 0;   // writer's
  int front_ = 2;  // reader's
};

}  // namespace contactcore::haptics
