// SPDX-License-Identifier: GPL-3.0-or-later
// Handoff: hands objects built on a control thread (a new surface table, a new
// renderer) to the servo thread without a lock, and keeps every one alive until the
// servo thread has moved past it, so nothing is ever freed on the servo thread.
//
//   control thread                                servo thread, each tick
//   handoff.Publish(std::make_shared<T>(...))     T* current = handoff.Take();
//
// Take() is wait-free (an atomic load, a read, at most a store) and never allocates.
// Publish() allocates and frees, on the control thread. One control thread, one servo
// thread.
//
// Why nothing is freed under the servo thread: every published object gets the next
// sequence number; the servo thread only ever moves to newer ones and announces each
// it adopts in `adopted_`; the control thread frees only objects older than the one
// announced. The object in use, the one being adopted (newer than the announced one)
// and any newer waiting one all survive, however the two threads interleave.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

namespace hapticad {

template <class T>
class Handoff {
 public:
  // Control thread: `next` (non-null) is taken at the servo thread's next Take(). An
  // object published before and not yet taken is skipped (the newest wins).
  void Publish(std::shared_ptr<T> next) {
    auto entry = std::make_unique<Entry>(Entry{std::move(next), published_ + 1});
    const Entry* raw = entry.get();
    owned_.push_back(std::move(entry));  // may throw: then nothing is published
    ++published_;
    pending_.store(raw, std::memory_order_release);
    Release();
  }

  // Servo thread: the newest published object (null before the first Publish()).
  T* Take() {
    const Entry* e = pending_.load(std::memory_order_acquire);
    if (e != nullptr && e->seq > current_seq_) {
      adopted_.store(e->seq, std::memory_order_release);
      current_seq_ = e->seq;
      current_ = e->object.get();
    }
    return current_;
  }

  // Control thread: frees what the servo thread has moved past.
  void Release() {
    const std::uint64_t adopted = adopted_.load(std::memory_order_acquire);
    owned_.erase(std::remove_if(owned_.begin(), owned_.end(),
                                [&](const std::unique_ptr<Entry>& e) { return e->seq < adopted; }),
                 owned_.end());
  }

  // Control thread: objects kept alive (the one in use and any published since).
  std::size_t owned() const { return owned_.size(); }

 private:
  struct Entry {
    std::shared_ptr<T> object;
    std::uint64_t seq;
  };
  std::atomic<const Entry*> pending_{nullptr};  // the newest published
  std::atomic<std::uint64_t> adopted_{0};       // the newest the servo thread took
  std::vector<std::unique_ptr<Entry>> owned_;   // control thread only
  std::uint64_t published_ = 0;                 // control thread only
  T* current_ = nullptr;                        // servo thread only
  std::uint64_t current_seq_ = 0;               // servo thread only
};

}  // namespace hapticad
