// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: ServoLoop::Tick runs on the servo thread every period. No allocation, no
// lock, no system call other than the device's I/O, no Python (see servo_loop.h).
#include "hapticad/devices/servo_loop.h"

#include <sys/prctl.h>
#include <time.h>

#include <cerrno>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "hapticad/devices/realtime.h"

namespace hapticad {
namespace {

using Clock = std::chrono::steady_clock;

enum FaultIndex {
  kNoDataIdx,
  kStaleIdx,
  kOutOfRangeIdx,
  kNonFiniteIdx,
  kReportedIdx,
  kWatchdogIdx,
  kUnpluggedIdx,
  kRendererIdx,
  kZeroForceIdx,
  kClampedIdx,
  kThermalIdx,
  kNumFaultCounters
};

void CopyVec(const Vec3& v, double out[3]) {
  out[0] = v.x();
  out[1] = v.y();
  out[2] = v.z();
}

timespec ToTimespec(std::int64_t ns) {
  timespec ts;
  ts.tv_sec = static_cast<time_t>(ns / 1000000000);
  ts.tv_nsec = static_cast<long>(ns % 1000000000);
  return ts;
}

std::int64_t MonotonicNs() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);  // vDSO: no system call
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

void Bump(std::atomic<std::uint64_t>& counter) {
  counter.store(counter.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
}

ServoConfig CheckedConfig(ServoConfig config) {
  if (!(config.rate_hz >= 1.0 && config.rate_hz <= 10000.0)) {
    throw std::invalid_argument("servo loop: rate " + std::to_string(config.rate_hz) +
                                " Hz is outside 1..10000 Hz");
  }
  if (config.clutch_button < -1 || config.clutch_button > 31) {
    throw std::invalid_argument("servo loop: clutch button " +
                                std::to_string(config.clutch_button) + " is outside -1..31");
  }
  ValidateSafetyConfig(config.safety);
  // a gap over the watchdog (or data older than the stale limit) zeroes the force: the
  // period must leave a whole period's room for a late tick, or most ticks are faults
  const double min_rate_hz = MinServoRateHz(config.safety);
  if (config.rate_hz < min_rate_hz * (1.0 - 1e-12)) {
    char text[320];
    std::snprintf(text, sizeof text,
                  "servo loop: rate %g Hz (period %.3g ms) is too slow for the loop watchdog "
                  "of %g ms and the stale-data limit of %g ms: the period must be at most "
                  "half of each, or a tick that starts late cuts the force; use at least "
                  "%g Hz",
                  config.rate_hz, 1e3 / config.rate_hz, config.safety.watchdog_s * 1e3,
                  config.safety.stale_after_s * 1e3, std::ceil(min_rate_hz - 1e-9));
    throw std::invalid_argument(text);
  }
  return config;
}

}  // namespace

double MinServoRateHz(const SafetyConfig& safety) {
  return 2.0 / std::min(safety.watchdog_s, safety.stale_after_s);
}

const char* SessionEndName(SessionEnd end) {
  switch (end) {
    case SessionEnd::kNotStarted:
      return "not started";
    case SessionEnd::kRunning:
      return "running";
    case SessionEnd::kStopped:
      return "stopped";
    case SessionEnd::kFinished:
      return "finished";
    case SessionEnd::kUnplugged:
      return "unplugged";
    case SessionEnd::kDeviceLost:
      return "device lost";
  }
  return "unknown";
}

ServoLoop::ServoLoop(Device& device, ForceRenderer& renderer, ServoConfig config)
    : ServoLoop(device, std::shared_ptr<ForceRenderer>(&renderer, [](ForceRenderer*) {}), config) {}

ServoLoop::ServoLoop(Device& device, std::shared_ptr<ForceRenderer> renderer, ServoConfig config)
    : device_(device),
      config_(CheckedConfig(config)),
      safety_(device.info().limits, config_.safety),
      trace_(config_.trace_capacity),
      latest_(TraceSample{}) {
  if (!renderer) throw std::invalid_argument("servo loop: no renderer");
  renderer_scale_ = renderer->limits().workspace_scale;
  renderers_.Publish(std::move(renderer));
  current_ = renderers_.Take();  // no servo thread yet
  effective_mapping_.Write(mapping_);
}

ServoLoop::~ServoLoop() { Stop(); }

void ServoLoop::Start() { Launch(std::numeric_limits<double>::infinity()); }

namespace {

bool SameScale(double a, double b) { return std::abs(a - b) <= 1e-12 * std::max(a, b); }

std::string ScaleMismatch(double renderer_scale, double mapping_scale) {
  char text[256];
  std::snprintf(text, sizeof text,
                "servo loop: the renderer was built for workspace scale %g and the mapping's is "
                "%g: the hand would feel %g times its stiffness; build the renderer with the "
                "mapping's limits (render_limits_for)",
                renderer_scale, mapping_scale, mapping_scale / renderer_scale);
  return text;
}

}  // namespace

void ServoLoop::BeginTicks() {
  if (!SameScale(renderer_scale_, mapping_scale_)) {
    throw std::logic_error(ScaleMismatch(renderer_scale_, mapping_scale_));
  }
  device_.BeginSession();  // may throw DeviceError
  ResetStats();
  safety_.BeginSession(0.0);
  clutch_.Reset();
  end_requested_ = SessionEnd::kRunning;
  renderer_needs_reset_ = true;
  std::lock_guard<std::mutex> lock(fault_message_mutex_);
  fault_message_.clear();
}

void ServoLoop::Launch(double stop_at_s) {
  if (running()) throw std::logic_error("servo loop: already running");
  if (thread_.joinable()) thread_.join();
  BeginTicks();
  stop_requested_.store(false);
  session_end_.store(SessionEnd::kRunning, std::memory_order_release);
  running_.store(true, std::memory_order_release);
  {
    std::lock_guard<std::mutex> lock(start_mutex_);
    scheduled_ = false;
  }
  thread_ = std::thread(&ServoLoop::Run, this, stop_at_s);
  // the servo thread asks for its own scheduling before its first tick (the HID writer
  // copies it from that tick's command, once); this thread waits, blocked: a spin here
  // would hold the one CPU the real-time servo thread wants to hand back
  std::unique_lock<std::mutex> lock(start_mutex_);
  start_cv_.wait(lock, [this] { return scheduled_; });
  realtime_.store(start_report_.realtime, std::memory_order_relaxed);
  realtime_report_ = start_report_.message;
}

void ServoLoop::Stop() {
  stop_requested_.store(true);
  if (thread_.joinable()) thread_.join();
  running_.store(false, std::memory_order_release);
  renderers_.Release();
}

std::string ServoLoop::fault_message() const {
  std::lock_guard<std::mutex> lock(fault_message_mutex_);
  if (running()) return {};
  return fault_message_;
}

std::string ServoLoop::realtime_report() const { return realtime_report_; }

void ServoLoop::SetRenderer(std::shared_ptr<ForceRenderer> renderer) {
  if (!renderer) throw std::invalid_argument("servo loop: no renderer");
  // its stiffness is divided by the scale it was built for (ForceRenderer): another
  // scale than the mapping's is felt stiffer or softer than the device's stable limit
  if (!SameScale(renderer->limits().workspace_scale, mapping_scale_)) {
    throw std::invalid_argument(ScaleMismatch(renderer->limits().workspace_scale, mapping_scale_));
  }
  renderer_scale_ = renderer->limits().workspace_scale;
  // the servo thread (or the next Tick() when none runs) takes it from the handoff
  renderers_.Publish(std::move(renderer));
}

std::size_t ServoLoop::ReleaseReplacedRenderers() {
  renderers_.Release();
  return renderers_.owned();
}

void ServoLoop::SetMapping(const WorkspaceMapping& mapping) {
  ValidateWorkspaceMapping(mapping);
  // the first mapping of a loop may set the scale its renderer was built for (the loop
  // starts with the identity); after that the two change together only in a new loop
  if (!SameScale(mapping.scale, renderer_scale_)) {
    throw std::invalid_argument(ScaleMismatch(renderer_scale_, mapping.scale));
  }
  mapping_scale_ = mapping.scale;
  mapping_updates_.Write(mapping);
}

void ServoLoop::AdoptUpdates() {
  // a new renderer (a new scene): it starts at the old proxy, where the hand still
  // touches, and the force goes over the ramp from what was sent to what it renders
  ForceRenderer* next = renderers_.Take();
  if (next != current_) {
    reset_from_proxy_ = had_proxy_;
    current_ = next;
    renderer_needs_reset_ = true;
    safety_.RestartRamp(RampFrom::kLastSent);
  }
  // a new mapping: the old proxy says nothing about where the tool is now (it could be
  // far away, across the part). The proxy restarts at the tool, as at the start of a
  // session; the old force stops at once (no push the new contact does not back) and
  // the new one ramps in from zero
  if (mapping_updates_.has_news()) {
    mapping_ = mapping_updates_.Read();
    clutch_.Reset();
    renderer_needs_reset_ = true;
    reset_from_proxy_ = false;
    safety_.RestartRamp(RampFrom::kZero);
  }
}

void ServoLoop::Tick(double loop_time_s, double watchdog_gap_s, double wall_gap_s) {
  const auto start = Clock::now();
  AdoptUpdates();

  TraceSample sample{};
  sample.time_s = loop_time_s;
  sample.period_us = wall_gap_s * 1e6;
  sample.cad_face = -1;
  const ReadStatus status = device_.ReadState(loop_time_s, &state_);
  std::uint32_t faults = safety_.CheckReading(status, state_, watchdog_gap_s);

  RenderOutput out;
  std::uint32_t flags = 0;
  Vec3 tool_w = Vec3::Zero();
  Vec3 velocity_w = Vec3::Zero();
  if (faults == 0) {
    const bool held =
        clutch_requested_.load(std::memory_order_acquire) ||
        (config_.clutch_button >= 0 && (state_.buttons >> config_.clutch_button) & 1u);
    // engaged: the force stops at once (the hand moves the device freely, nothing
    // is to push it); released: it ramps in from zero
    if (clutch_.Update(held, state_.position_d, &mapping_) == Clutch::Event::kReleased) {
      safety_.RestartRamp(RampFrom::kZero);
    }
    if (clutch_.engaged()) {
      tool_w = clutch_.frozen_tool_w();
      flags |= kClutched;
      out.proxy_w = last_proxy_w_;
    } else {
      tool_w = mapping_.DeviceToWorld(state_.position_d);
      velocity_w = mapping_.VelocityToWorld(state_.velocity_d);
      if (renderer_needs_reset_) {
        // a restart tick: bounded, but up to some 200 sweeps (ForceRenderer::Reset)
        current_->Reset(reset_from_proxy_ ? last_proxy_w_ : tool_w);
        renderer_needs_reset_ = false;
        reset_from_proxy_ = false;
      }
      RenderInput input;
      input.position_w = tool_w;
      input.velocity_w = velocity_w;
      input.time_s = loop_time_s;
      current_->Render(input, &out);
      flags |= out.flags;
      last_proxy_w_ = out.proxy_w;
      had_proxy_ = true;
      // the renderer refused the input (and sent zero): a fault like any other, counted,
      // and the force ramps in again after it rather than jumping back
      if (out.flags & kInputFault) faults |= kFaultRenderer;
    }
    last_tool_w_ = tool_w;
  } else {
    tool_w = last_tool_w_;
    out.proxy_w = last_proxy_w_;
  }
  const Vec3 rendered_d =
      faults == 0 && !clutch_.engaged() ? mapping_.ForceToDevice(out.force_w) : Vec3::Zero();
  // a scene swap blends from the force last sent only while the hand touches something:
  // a face the edit took away, or the clutch, ends the old force at once
  if (!(out.flags & kContact) || clutch_.engaged()) safety_.DropBlend();
  const Vec3 force_d = safety_.Shape(loop_time_s, faults, rendered_d, &flags);
  device_.WriteForce(force_d);
  const auto end = Clock::now();

  CopyVec(tool_w, sample.device_m);
  CopyVec(velocity_w, sample.velocity_mps);
  CopyVec(out.proxy_w, sample.proxy_m);
  CopyVec(mapping_.ForceToWorld(force_d), sample.force_n);
  CopyVec(state_.position_d, sample.handle_d_m);
  sample.normal_force_n = out.normal_force_n;
  sample.tangential_force_n = out.tangential_force_n;
  sample.friction_force_n = out.friction_force_n;
  sample.texture_force_n = out.texture_force_n;
  sample.vibration_force_n = out.vibration_force_n;
  sample.cad_face = out.cad_face;
  sample.flags = flags;
  sample.buttons = state_.buttons;
  sample.tick_us = std::chrono::duration<double, std::micro>(end - start).count();
  if (!trace_.Push(sample)) Bump(trace_dropped_);
  latest_.Write(sample);
  effective_mapping_.Write(mapping_);
  CountFlags(flags);
  tick_time_.Record(std::chrono::duration_cast<std::chrono::nanoseconds>(end - start).count());
  Bump(ticks_);
  elapsed_s_.store(loop_time_s, std::memory_order_relaxed);

  if (faults & kFaultUnplugged) {
    end_requested_ = SessionEnd::kUnplugged;
  } else if (safety_.fault_timed_out()) {
    end_requested_ = SessionEnd::kDeviceLost;
  }
  if (end_requested_ != SessionEnd::kRunning && fault_time_s_ < 0.0) fault_time_s_ = loop_time_s;
  if (faults != 0) last_faults_ = faults;
}

void ServoLoop::CountFlags(std::uint32_t flags) {
  if (flags & kFaultNoData) Bump(fault_counts_[kNoDataIdx]);
  if (flags & kFaultStale) Bump(fault_counts_[kStaleIdx]);
  if (flags & kFaultOutOfRange) Bump(fault_counts_[kOutOfRangeIdx]);
  if (flags & kFaultNonFinite) Bump(fault_counts_[kNonFiniteIdx]);
  if (flags & kFaultReported) Bump(fault_counts_[kReportedIdx]);
  if (flags & kFaultWatchdog) Bump(fault_counts_[kWatchdogIdx]);
  if (flags & kFaultUnplugged) Bump(fault_counts_[kUnpluggedIdx]);
  if (flags & kFaultRenderer) Bump(fault_counts_[kRendererIdx]);
  if (flags & kDeviceFault) Bump(fault_counts_[kZeroForceIdx]);
  if (flags & kSafetyClamped) Bump(fault_counts_[kClampedIdx]);
  if (flags & kThermalLimited) Bump(fault_counts_[kThermalIdx]);
}

void ServoLoop::Run(double stop_at_s) {
  // no tick before the thread's scheduling is settled: the HID writer copies it from the
  // first tick's command, once (on one CPU it copied the normal policy, then kept it).
  // Asked here, by the thread itself, and handed to Launch() (off the ticks: it allocates)
  {
    RealtimeReport report = RequestRealtime(pthread_self(), config_.realtime_priority);
    std::lock_guard<std::mutex> lock(start_mutex_);
    start_report_ = std::move(report);
    scheduled_ = true;
  }
  start_cv_.notify_one();
  // a sleeping normal thread wakes up to 50 us late by default; ask for 1 us
  prctl(PR_SET_TIMERSLACK, 1000UL, 0, 0, 0);
  const auto period_ns = static_cast<std::int64_t>(std::llround(1e9 / config_.rate_hz));
  const std::int64_t t0 = MonotonicNs();
  std::int64_t deadline = t0;
  std::int64_t previous_start = 0;
  // compare in integer nanoseconds: 300 * 1e6 * 1e-9 is 0.30000000000000004 > 0.3
  const std::int64_t stop_at_ns =
      stop_at_s >= 9e9 ? std::numeric_limits<std::int64_t>::max() : std::llround(stop_at_s * 1e9);
  // a simulation waits for a late tick (Device::runs_on_loop_time): its clock goes a
  // period a tick, and the watchdog judges that clock's gap, not the host's
  const bool on_loop_time = device_.runs_on_loop_time();
  std::uint64_t tick = 0;
  SessionEnd end = SessionEnd::kStopped;
  double last_loop_time_s = 0.0;
  while (true) {
    if (stop_requested_.load(std::memory_order_relaxed)) break;
    // the loop clock is the tick's scheduled time, so a late tick does not skew a
    // simulated device's path
    const std::int64_t loop_time_ns = static_cast<std::int64_t>(tick) * period_ns;
    if (loop_time_ns > stop_at_ns) {
      end = SessionEnd::kFinished;
      break;
    }
    const std::int64_t now = MonotonicNs();
    wake_latency_.Record(now - deadline);
    double gap_s = 0.0;
    if (tick > 0) {
      const std::int64_t gap = now - previous_start;
      period_jitter_.Record(std::llabs(gap - period_ns));
      gap_s = static_cast<double>(gap) * 1e-9;
      wall_s_.store(static_cast<double>(now - t0) * 1e-9, std::memory_order_relaxed);
    }
    previous_start = now;
    last_loop_time_s = static_cast<double>(loop_time_ns) * 1e-9;
    Tick(last_loop_time_s, on_loop_time && tick > 0 ? static_cast<double>(period_ns) * 1e-9 : gap_s,
         gap_s);
    if (end_requested_ != SessionEnd::kRunning) {
      end = end_requested_;
      break;
    }
    ++tick;
    deadline += period_ns;
    const std::int64_t after = MonotonicNs();
    if (after > deadline + period_ns) {
      // more than a period behind: count it and go on from now rather than burst; a
      // device in real time skips the lost ticks, a simulation's world waited for them
      Bump(overruns_);
      const std::int64_t behind = (after - deadline) / period_ns;
      deadline += behind * period_ns;
      if (!on_loop_time) {
        tick += static_cast<std::uint64_t>(behind);
        skipped_ticks_.fetch_add(static_cast<std::uint64_t>(behind), std::memory_order_relaxed);
      }
    }
    const timespec ts = ToTimespec(deadline);
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
    }
  }
  FinishSession(end, last_loop_time_s);
}

void ServoLoop::FinishSession(SessionEnd end, double loop_time_s) {
  // off the tick: zero force first, then words for the user
  device_.WriteForce(Vec3::Zero());
  device_.EndSession();
  const DeviceInfo& info = device_.info();
  const std::string who = "the haptic device '" + info.name + "' (" + info.path + ")";
  char when[64];
  std::snprintf(when, sizeof when, "%.3f s", fault_time_s_ >= 0.0 ? fault_time_s_ : loop_time_s);
  const std::string detail = device_.DescribeFault();
  std::string message;
  if (end == SessionEnd::kUnplugged && device_.stopped_answering()) {
    message = "The session ended: " + who + " was lost at " + when +
              " and the force was zeroed in that tick" +
              (detail.empty() ? std::string() : " (" + detail + ")") +
              ". Unplug it, plug it back in and start again; your document is unchanged.";
  } else if (end == SessionEnd::kUnplugged) {
    message = "The session ended: " + who + " was unplugged at " + when +
              " and the force was zeroed in that tick" +
              (detail.empty() ? std::string() : " (" + detail + ")") +
              ". Plug it back in and start again; your document is unchanged.";
  } else if (end == SessionEnd::kDeviceLost) {
    std::string reasons;
    auto add = [&](std::uint32_t bit, const char* name) {
      if (last_faults_ & bit) reasons += (reasons.empty() ? "" : ", ") + std::string(name);
    };
    add(kFaultNoData, "no data");
    add(kFaultStale, "stale data");
    add(kFaultOutOfRange, "out-of-range values");
    add(kFaultNonFinite, "non-finite values");
    add(kFaultReported, "a fault reported by the device");
    add(kFaultWatchdog, "the servo loop missing its deadline");
    add(kFaultRenderer, "positions or speeds the renderer refused");
    std::snprintf(when, sizeof when, "%.1f s", config_.safety.fault_timeout_s);
    message = "The session ended: " + who + " gave no usable data for " + when + " (" + reasons +
              ")" + (detail.empty() ? std::string() : "; " + detail) +
              ". The force was held at zero throughout. Check the cable and the "
              "device, then start again; your document is unchanged.";
  }
  // readers on other threads take the lock too (the string is not atomic)
  std::lock_guard<std::mutex> lock(fault_message_mutex_);
  fault_message_ = std::move(message);
  session_end_.store(end, std::memory_order_release);
  running_.store(false, std::memory_order_release);
}

void ServoLoop::ResetStats() {
  ticks_.store(0);
  overruns_.store(0);
  skipped_ticks_.store(0);
  trace_dropped_.store(0);
  elapsed_s_.store(0.0);
  wall_s_.store(0.0);
  for (auto& c : fault_counts_) c.store(0);
  period_jitter_.Reset();
  wake_latency_.Reset();
  tick_time_.Reset();
  fault_time_s_ = -1.0;
  last_faults_ = 0;
  had_proxy_ = false;
  reset_from_proxy_ = false;  // a renderer adopted in the last session starts at the hand
  // the last session's samples not drained: the trace starts afresh (no servo thread
  // runs now, so this thread may take the consumer's side)
  TraceSample stale;
  while (trace_.Pop(&stale)) {
  }
}

std::size_t ServoLoop::DrainTrace(std::vector<TraceSample>* out) {
  std::size_t n = 0;
  TraceSample sample;
  while (trace_.Pop(&sample)) {
    out->push_back(sample);
    ++n;
  }
  return n;
}

ServoStats ServoLoop::CalcStats() const {
  static_assert(sizeof(fault_counts_) / sizeof(fault_counts_[0]) == kNumFaultCounters);
  ServoStats s;
  s.ticks = ticks_.load(std::memory_order_relaxed);
  s.overruns = overruns_.load(std::memory_order_relaxed);
  s.skipped_ticks = skipped_ticks_.load(std::memory_order_relaxed);
  s.trace_dropped = trace_dropped_.load(std::memory_order_relaxed);
  s.elapsed_s = elapsed_s_.load(std::memory_order_relaxed);
  s.wall_s = wall_s_.load(std::memory_order_relaxed);
  s.achieved_rate_hz =
      s.wall_s > 0.0 && s.ticks > 1 ? static_cast<double>(s.ticks - 1) / s.wall_s : 0.0;
  s.period_jitter_p50_us = period_jitter_.Percentile(0.50) * 1e-3;
  s.period_jitter_p99_us = period_jitter_.Percentile(0.99) * 1e-3;
  s.period_jitter_max_us = static_cast<double>(period_jitter_.max_ns()) * 1e-3;
  s.wake_latency_p50_us = wake_latency_.Percentile(0.50) * 1e-3;
  s.wake_latency_p99_us = wake_latency_.Percentile(0.99) * 1e-3;
  s.wake_latency_max_us = static_cast<double>(wake_latency_.max_ns()) * 1e-3;
  s.tick_p50_us = tick_time_.Percentile(0.50) * 1e-3;
  s.tick_p99_us = tick_time_.Percentile(0.99) * 1e-3;
  s.tick_max_us = static_cast<double>(tick_time_.max_ns()) * 1e-3;
  auto get = [&](int i) { return fault_counts_[i].load(std::memory_order_relaxed); };
  s.faults.no_data = get(kNoDataIdx);
  s.faults.stale = get(kStaleIdx);
  s.faults.out_of_range = get(kOutOfRangeIdx);
  s.faults.non_finite = get(kNonFiniteIdx);
  s.faults.reported = get(kReportedIdx);
  s.faults.watchdog = get(kWatchdogIdx);
  s.faults.unplugged = get(kUnpluggedIdx);
  s.faults.renderer = get(kRendererIdx);
  s.faults.zero_force_ticks = get(kZeroForceIdx);
  s.faults.clamped = get(kClampedIdx);
  s.faults.thermal_limited = get(kThermalIdx);
  s.realtime = realtime_.load(std::memory_order_relaxed);
  return s;
}

std::vector<TraceSample> ServoLoop::RunFor(double duration_s) {
  std::vector<TraceSample> samples;
  samples.reserve(static_cast<std::size_t>(duration_s * config_.rate_hz) + 16);
  Launch(duration_s);
  while (running()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    DrainTrace(&samples);
  }
  Stop();
  DrainTrace(&samples);
  return samples;
}

}  // namespace hapticad
