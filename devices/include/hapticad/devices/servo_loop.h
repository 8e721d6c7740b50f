// SPDX-License-Identifier: GPL-3.0-or-later
// ServoLoop: the haptic servo thread. At a fixed rate on the monotonic clock it reads
// the device, renders a force, writes it, and pushes a TraceSample into a preallocated
// lock-free ring that another thread drains.
//
// Hot path (Tick): no allocation, no lock, no I/O but the device's, no Python.
// tests/devices/servo_loop_test.cc proves the allocation part by counting.
//
// Threads: Start() spawns the servo thread, Stop() joins it; DrainTrace() and stats()
// may be called from any one other thread while it runs.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <thread>
#include <vector>

#include "hapticad/core/rendering/force_renderer.h"
#include "hapticad/devices/device.h"
#include "hapticad/devices/spsc_ring.h"
#include "hapticad/devices/trace_sample.h"

namespace hapticad {

struct ServoConfig {
  double rate_hz = 1000.0;               // 1..10000
  std::size_t trace_capacity = 1 << 16;  // samples buffered between drains
};

struct ServoStats {
  std::uint64_t ticks = 0;
  std::uint64_t overruns = 0;       // times the loop fell more than a period behind
  std::uint64_t skipped_ticks = 0;  // ticks skipped to catch up after an overrun
  std::uint64_t trace_dropped = 0;  // samples lost to a full ring
  double elapsed_s = 0.0;           // loop clock at the last tick
};

class ServoLoop {
 public:
  // `device` and `renderer` must outlive the loop. Throws std::invalid_argument for a
  // rate outside 1..10000 Hz.
  ServoLoop(Device& device, ForceRenderer& renderer, ServoConfig config = {});
  ~ServoLoop();
  ServoLoop(const ServoLoop&) = delete;
  ServoLoop& operator=(const ServoLoop&) = delete;

  void Start();  // throws std::logic_error if already running
  void Stop();   // idempotent; commands zero force and joins
  bool running() const { return running_.load(std::memory_order_acquire); }

  // Appends the samples recorded since the last drain. Returns how many.
  std::size_t DrainTrace(std::vector<TraceSample>* out);
  ServoStats stats() const;

  // Runs the ticks at loop times 0, T, 2T, ... up to and including `duration_s` on the
  // servo thread (it stops itself), draining the trace every 10 ms; returns the trace.
  std::vector<TraceSample> RunFor(double duration_s);

  // One tick at loop time `loop_time_s`. Public so tests can run it on their own
  // thread (allocation counting, deterministic replays); the servo thread calls it.
  void Tick(double loop_time_s);

  const ServoConfig& config() const { return config_; }

 private:
  void Launch(double stop_at_s);  // spawns the servo thread, which ends after stop_at_s
  void Run(double stop_at_s);

  Device& device_;
  ForceRenderer& renderer_;
  ServoConfig config_;
  SpscRing<TraceSample> trace_;
  std::thread thread_;
  std::atomic<bool> running_{false};
  std::atomic<bool> stop_requested_{false};
  std::atomic<std::uint64_t> ticks_{0};
  std::atomic<std::uint64_t> overruns_{0};
  std::atomic<std::uint64_t> skipped_ticks_{0};
  std::atomic<std::uint64_t> trace_dropped_{0};
  std::atomic<double> elapsed_s_{0.0};
};

}  // namespace hapticad
