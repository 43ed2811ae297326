#pragma once
// Hands the newest value of T from one writer thread to one reader thread
// without locks: a triple buffer. Neither side ever waits, spins or retries,
// so the receive thread cannot block the servo loop (and vice versa).
//
// Each of the three slots belongs to exactly one party at any time: the
// writer's back slot, the shared middle slot, the reader's front slot.
// Ownership moves only by an atomic exchange of the middle index (acquire-
// release), so the payload itself is never accessed by two threads at once.
// Copying T must not allocate for the hand-over to be allocation-free.
#include <atomic>
#include <cstdint>

namespace haptics {

template <typename T>
class LatestValue {
 public:
  LatestValue() = default;
  LatestValue(const LatestValue&) = delete;
  LatestValue& operator=(const LatestValue&) = delete;

  // Writer: the slot to fill before Publish(). Stays the writer's until then.
  T& WriteSlot() { return slots_[back_].value; }

  // Writer: makes the write slot the newest value. Returns true if the value
  // published before it was never taken by the reader (it is dropped).
  bool Publish() {
    const uint8_t previous =
        middle_.exchange(static_cast<uint8_t>(back_ | kFresh), std::memory_order_acq_rel);
    back_ = previous & kIndexMask;
    return (previous & kFresh) != 0;
  }

  // Writer: copy-in and publish.
  bool Write(const T& value) {
    WriteSlot() = value;
    return Publish();
  }

  // Before either side uses it: applies f to each of the three slots (e.g.
  // to size their buffers once, so that later copies never allocate).
  template <typename F>
  void ForEachSlot(F&& f) {
    for (Slot& slot : slots_) f(slot.value);
  }

  // Reader: whether a value was published since the last TakeNewest (a
  // peek; only the reader clears it).
  bool HasNew() const { return (middle_.load(std::memory_order_acquire) & kFresh) != 0; }

  // Reader: the newest value if one was published since the previous call,
  // else nullptr. The pointee stays valid and unchanged until the next call.
  const T* TakeNewest() {
    // A cheap check first; only the reader clears kFresh, so it stays set.
    if ((middle_.load(std::memory_order_relaxed) & kFresh) == 0) return nullptr;
    const uint8_t previous = middle_.exchange(front_, std::memory_order_acq_rel);
    front_ = previous & kIndexMask;
    return &slots_[front_].value;
  }

 private:
  static constexpr uint8_t kIndexMask = 0x3;
  static constexpr uint8_t kFresh = 0x4;
  // Separate cache lines: the writer and the reader touch different slots.
  struct alignas(64) Slot {
    T value{};
  };
  Slot slots_[3];
  alignas(64) std::atomic<uint8_t> middle_{1};
  alignas(64) uint8_t back_ = 0;  // writer only
  alignas(64) uint8_t front_ = 2;  // reader only
};

}  // namespace haptics
