// SPDX-License-Identifier: GPL-3.0-or-later
// ServoLoop: the haptic servo thread. At a fixed rate on the monotonic clock it reads
// the device, maps the handle into the world (WorkspaceMapping, Clutch), renders a
// force, passes it through ForceSafety, writes it, and pushes a TraceSample into a
// preallocated lock-free ring that another thread drains. A tick the renderer refuses
// (kInputFault) is a fault to ForceSafety like a bad reading (kFaultRenderer): zero
// force, counted, and the force ramps in again after it.
//
// Hot path (Tick): no allocation, no lock, no system call but the device's I/O, no
// Python. tests/devices/servo_loop_test.cc proves the allocation part by counting.
// Every tick's work is bounded, but a restart tick does more: the first tick of a
// session, and the tick that takes a new renderer or mapping, restarts the proxy
// (ForceRenderer::Reset: up to 102 point sweeps across the scene, 198 where parts touch,
// and a few closest-point walks for a sphere, where a normal tick sweeps a few times).
//
// A late tick (the host held the thread off its core). A real device went on pushing
// with its last command through the gap: past SafetyConfig::watchdog_s the tick's force
// is cut (kFaultWatchdog) and ramps in again, and the lost ticks are skipped rather than
// run in a burst. A simulation (Device::runs_on_loop_time) waited with the loop: its
// clock goes on a period a tick, and nothing is cut or skipped.
//
// Threads. One control thread owns the loop: it calls Start(), Stop(), SetRenderer(),
// SetMapping(), SetClutch() and reads mapping() and latest(). Updates reach the servo
// thread lock-free (an atomic pointer hand-over for renderers, wait-free mailboxes for
// the rest) at its next tick. One consumer thread (it may be the control thread)
// calls DrainTrace(). CalcStats(), ticks(), running(), session_end() and fault_message()
// may be called from any thread.
//
// Session end. The loop ends a session itself when the device is unplugged (zero
// force in that same tick) or when faults last SafetyConfig::fault_timeout_s; then
// running() turns false and fault_message() says why, in a sentence for the user.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "hapticad/core/handoff.h"
#include "hapticad/core/rendering/force_renderer.h"
#include "hapticad/devices/clutch.h"
#include "hapticad/devices/device.h"
#include "hapticad/devices/latency_histogram.h"
#include "hapticad/devices/mailbox.h"
#include "hapticad/devices/realtime.h"
#include "hapticad/devices/safety.h"
#include "hapticad/devices/spsc_ring.h"
#include "hapticad/devices/trace_sample.h"
#include "hapticad/devices/workspace_mapping.h"

namespace hapticad {

struct ServoConfig {
  double rate_hz = 1000.0;               // MinServoRateHz(safety)..10000
  std::size_t trace_capacity = 1 << 16;  // samples buffered between drains
  int realtime_priority = 70;            // SCHED_FIFO priority to ask for; <= 0: do not ask
  int clutch_button = -1;                // device button that holds the clutch; -1: none
  SafetyConfig safety;
};

// The slowest rate the loop runs at with `safety`: its period must be at most half the
// loop watchdog and half the stale-data limit, so a tick that starts up to a period late
// is not yet a fault (at 200 Hz with the 5 ms defaults every tick's gap would be one).
// 400 Hz with the defaults.
double MinServoRateHz(const SafetyConfig& safety);

enum class SessionEnd : std::uint8_t {
  kNotStarted = 0,
  kRunning,
  kStopped,     // Stop() was called
  kFinished,    // RunFor() reached its duration
  kUnplugged,   // the device went away
  kDeviceLost,  // faults or missing data for fault_timeout_s
};
const char* SessionEndName(SessionEnd end);

struct FaultCounts {  // ticks with each reason for zero force (one tick may have several)
  std::uint64_t no_data = 0;
  std::uint64_t stale = 0;
  std::uint64_t out_of_range = 0;
  std::uint64_t non_finite = 0;
  std::uint64_t reported = 0;  // the device reported a fault
  std::uint64_t watchdog = 0;
  std::uint64_t unplugged = 0;
  std::uint64_t renderer = 0;          // the renderer refused the tick (kFaultRenderer)
  std::uint64_t zero_force_ticks = 0;  // ticks with any of the above
  std::uint64_t clamped = 0;           // ticks whose force the safety layer clamped
  std::uint64_t thermal_limited = 0;
};

struct ServoStats {
  std::uint64_t ticks = 0;
  std::uint64_t overruns = 0;  // times the loop fell more than a period behind
  // ticks skipped to catch up after an overrun; none for a device on the loop's clock
  // (Device::runs_on_loop_time: its world waited for the late tick)
  std::uint64_t skipped_ticks = 0;
  std::uint64_t trace_dropped = 0;  // samples lost to a full ring
  double elapsed_s = 0.0;           // loop clock at the last tick
  double wall_s = 0.0;              // monotonic time from the first to the last tick start
  double achieved_rate_hz = 0.0;    // (ticks - 1) / wall_s
  // |actual period - nominal period| between consecutive tick starts, us
  double period_jitter_p50_us = 0.0;
  double period_jitter_p99_us = 0.0;
  double period_jitter_max_us = 0.0;
  // tick start - its deadline (how late the thread woke), us
  double wake_latency_p50_us = 0.0;
  double wake_latency_p99_us = 0.0;
  double wake_latency_max_us = 0.0;
  // compute time of the tick (read, render, write), us
  double tick_p50_us = 0.0;
  double tick_p99_us = 0.0;
  double tick_max_us = 0.0;
  FaultCounts faults;
  bool realtime = false;  // SCHED_FIFO was granted
};

class ServoLoop {
 public:
  // `device` (and `renderer`) must outlive the loop. Throws std::invalid_argument for a
  // rate outside MinServoRateHz(config.safety)..10000 Hz (the message names the rate's
  // period and the watchdog and stale limits), invalid safety settings or device limits.
  ServoLoop(Device& device, ForceRenderer& renderer, ServoConfig config = {});
  ServoLoop(Device& device, std::shared_ptr<ForceRenderer> renderer, ServoConfig config = {});
  ~ServoLoop();
  ServoLoop(const ServoLoop&) = delete;
  ServoLoop& operator=(const ServoLoop&) = delete;

  // Begins a device session (may throw DeviceError: nothing started) and spawns the
  // servo thread, asking for real-time scheduling (realtime_report() says what came of
  // it). Statistics and the trace start afresh. Throws std::logic_error if running.
  void Start();
  // Idempotent: commands zero force, ends the device session and joins.
  void Stop();
  bool running() const { return running_.load(std::memory_order_acquire); }

  SessionEnd session_end() const { return session_end_.load(std::memory_order_acquire); }
  // Why the last session ended, for the user; empty while running or when stopped.
  std::string fault_message() const;
  std::string realtime_report() const;

  // Appends the samples recorded since the last drain. Returns how many. Non-blocking.
  std::size_t DrainTrace(std::vector<TraceSample>* out);
  // The statistics so far: reads the counters and computes six percentiles from the
  // latency histograms (up to two scans of their 1184 bins each). For the tick count
  // alone: ticks().
  ServoStats CalcStats() const;
  // Ticks run this session (skipped ones not counted).
  std::uint64_t ticks() const { return ticks_.load(std::memory_order_relaxed); }
  // The last tick's sample (control thread only).
  TraceSample latest() { return latest_.Read(); }

  // Swaps the renderer (a new scene, built on this thread): the servo thread takes it at
  // its next tick, starting it at the old proxy (or just outside the new scene's solid,
  // if that grew over it: ForceRenderer::Reset) and going over ForceSafety's ramp from
  // the force last sent to the new scene's (no step); the old one is released on this
  // thread, never on the servo thread (core/handoff.h). Never blocks; a renderer set and
  // not yet taken gives way to a newer one. A property edit needs no new renderer:
  // ForceRenderer::SetSurfaces.
  void SetRenderer(std::shared_ptr<ForceRenderer> renderer);
  // Control thread: frees the renderers (and their scenes) the servo thread has moved
  // past. SetRenderer() and Stop() do it too; a control thread that swaps big scenes
  // calls it from its polling, so an old scene does not wait for the next swap.
  // Returns how many renderers are still kept (the one in use and any set since).
  std::size_t ReleaseReplacedRenderers();
  // The renderer's RenderLimits::workspace_scale and the mapping's scale must agree (the
  // renderer divides the stiffness by the one it was built for; another scale is felt that
  // many times stiffer, beyond the device's stable limit): SetRenderer() and SetMapping()
  // throw std::invalid_argument for one that differs from the other's, and Start() throws
  // std::logic_error while they differ (a renderer of scale s and no mapping given yet).
  // Replaces the mapping (validated; throws std::invalid_argument). Taken at the next
  // tick; any clutch offset is dropped, the proxy restarts at the tool's new position
  // (as at the start of a session: ForceRenderer::Reset); the force sent stops and the
  // new one ramps in from zero.
  void SetMapping(const WorkspaceMapping& mapping);
  // The mapping in effect (clutch offsets included), as of the last tick.
  WorkspaceMapping mapping() { return effective_mapping_.Read(); }
  // Holds or releases the clutch (in addition to ServoConfig::clutch_button). Held, the
  // force stops at once; released, it ramps in from zero.
  void SetClutch(bool held) { clutch_requested_.store(held, std::memory_order_release); }

  // Runs the ticks at loop times 0, T, 2T, ... up to and including `duration_s` on the
  // servo thread (it stops itself), draining the trace every 10 ms; returns the trace.
  std::vector<TraceSample> RunFor(double duration_s);

  // One tick at loop time `loop_time_s`, `gap_s` after the previous tick started.
  // Public so tests can run it on their own thread (allocation counting, deterministic
  // replays); the servo thread calls it. BeginTicks() prepares a session for that.
  void Tick(double loop_time_s, double gap_s = 0.0) { Tick(loop_time_s, gap_s, gap_s); }
  void BeginTicks();

  const ServoConfig& config() const { return config_; }
  Device& device() { return device_; }

 private:
  // `watchdog_gap_s`: the gap the safety layer judges (the loop clock's for a device on
  // it); `wall_gap_s`: the host's, traced as period_us.
  void Tick(double loop_time_s, double watchdog_gap_s, double wall_gap_s);
  void Launch(double stop_at_s);
  void Run(double stop_at_s);
  void AdoptUpdates();
  void CountFlags(std::uint32_t flags);
  void FinishSession(SessionEnd end, double loop_time_s);
  void ResetStats();

  Device& device_;
  ServoConfig config_;
  ForceSafety safety_;
  SpscRing<TraceSample> trace_;
  std::thread thread_;

  // renderers: `current_` is the servo thread's; the handoff keeps them alive
  ForceRenderer* current_ = nullptr;
  Handoff<ForceRenderer> renderers_;

  // mapping and clutch: the servo thread's copy, updated through mailboxes
  WorkspaceMapping mapping_;
  Mailbox<WorkspaceMapping> mapping_updates_;
  // control thread's: the scales of the renderer and the mapping last given (must agree)
  double renderer_scale_ = 1.0;
  double mapping_scale_ = 1.0;
  Mailbox<WorkspaceMapping> effective_mapping_;
  std::atomic<bool> clutch_requested_{false};
  Clutch clutch_;

  // servo thread's per-session state
  DeviceState state_;
  Vec3 last_tool_w_ = Vec3::Zero();
  Vec3 last_proxy_w_ = Vec3::Zero();
  bool had_proxy_ = false;
  bool renderer_needs_reset_ = true;
  bool reset_from_proxy_ = false;  // a swapped-in renderer starts at the old proxy
  double fault_time_s_ = -1.0;     // loop time the session-ending fault happened
  std::uint32_t last_faults_ = 0;

  Mailbox<TraceSample> latest_;
  std::atomic<bool> running_{false};
  std::atomic<bool> stop_requested_{false};
  // the servo thread's scheduling, asked by itself before its first tick, for Launch()
  std::mutex start_mutex_;
  std::condition_variable start_cv_;
  bool scheduled_ = false;
  RealtimeReport start_report_;
  std::atomic<SessionEnd> session_end_{SessionEnd::kNotStarted};
  SessionEnd end_requested_ = SessionEnd::kRunning;  // servo thread's
  // written before running_ turns false, cleared when a session begins; off the tick,
  // under the mutex, which fault_message() (any thread) takes too
  mutable std::mutex fault_message_mutex_;
  std::string fault_message_;
  std::string realtime_report_;  // control thread's
  std::atomic<bool> realtime_{false};

  std::atomic<std::uint64_t> ticks_{0};
  std::atomic<std::uint64_t> overruns_{0};
  std::atomic<std::uint64_t> skipped_ticks_{0};
  std::atomic<std::uint64_t> trace_dropped_{0};
  std::atomic<double> elapsed_s_{0.0};
  std::atomic<double> wall_s_{0.0};
  std::atomic<std::uint64_t> fault_counts_[11] = {};  // FaultCounts, in its order
  LatencyHistogram period_jitter_;
  LatencyHistogram wake_latency_;
  LatencyHistogram tick_time_;
};

}  // namespace hapticad
