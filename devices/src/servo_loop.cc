// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: ServoLoop::Tick runs on the servo thread every period. No allocation, no
// lock, no I/O other than the device's, no Python (see servo_loop.h).
#include "hapticad/devices/servo_loop.h"

#include <time.h>

#include <cerrno>

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace hapticad {
namespace {

using Clock = std::chrono::steady_clock;

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
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

}  // namespace

ServoLoop::ServoLoop(Device& device, ForceRenderer& renderer, ServoConfig config)
    : device_(device), renderer_(renderer), config_(config), trace_(config.trace_capacity) {
  if (!(config_.rate_hz >= 1.0 && config_.rate_hz <= 10000.0)) {
    throw std::invalid_argument("servo loop: rate " + std::to_string(config_.rate_hz) +
                                " Hz is outside 1..10000 Hz");
  }
}

ServoLoop::~ServoLoop() { Stop(); }

void ServoLoop::Start() { Launch(std::numeric_limits<double>::infinity()); }

void ServoLoop::Launch(double stop_at_s) {
  if (running()) throw std::logic_error("servo loop: already running");
  if (thread_.joinable()) thread_.join();
  stop_requested_.store(false);
  running_.store(true, std::memory_order_release);
  thread_ = std::thread(&ServoLoop::Run, this, stop_at_s);
}

void ServoLoop::Stop() {
  stop_requested_.store(true);
  if (thread_.joinable()) thread_.join();
  running_.store(false, std::memory_order_release);
}

void ServoLoop::Tick(double loop_time_s) {
  const auto start = Clock::now();
  TraceSample sample{};
  sample.time_s = loop_time_s;
  DeviceState state;
  RenderOutput out;
  if (device_.ReadState(loop_time_s, &state)) {
    RenderInput input;
    input.position_w = state.position_w;
    input.velocity_w = state.velocity_w;
    input.time_s = loop_time_s;
    renderer_.Render(input, &out);
    CopyVec(state.position_w, sample.device_m);
    CopyVec(state.velocity_w, sample.velocity_mps);
  } else {
    out.flags = kDeviceFault;
  }
  device_.WriteForce(out.force_w);
  const auto end = Clock::now();

  CopyVec(out.proxy_w, sample.proxy_m);
  CopyVec(out.force_w, sample.force_n);
  sample.normal_force_n = out.normal_force_n;
  sample.tangential_force_n = out.tangential_force_n;
  sample.friction_force_n = out.friction_force_n;
  sample.texture_force_n = out.texture_force_n;
  sample.vibration_force_n = out.vibration_force_n;
  sample.cad_face = out.cad_face;
  sample.flags = out.flags;
  sample.tick_us = std::chrono::duration<double, std::micro>(end - start).count();
  if (!trace_.Push(sample)) trace_dropped_.fetch_add(1, std::memory_order_relaxed);
  ticks_.fetch_add(1, std::memory_order_relaxed);
  elapsed_s_.store(loop_time_s, std::memory_order_relaxed);
}

void ServoLoop::Run(double stop_at_s) {
  const auto period_ns = static_cast<std::int64_t>(std::llround(1e9 / config_.rate_hz));
  const std::int64_t t0 = MonotonicNs();
  std::int64_t deadline = t0;
  // compare in integer nanoseconds: 300 * 1e6 * 1e-9 is 0.30000000000000004 > 0.3
  const std::int64_t stop_at_ns =
      stop_at_s >= 9e9 ? std::numeric_limits<std::int64_t>::max() : std::llround(stop_at_s * 1e9);
  std::uint64_t tick = 0;
  while (!stop_requested_.load(std::memory_order_relaxed)) {
    // the loop clock is the tick's scheduled time, so a late tick does not skew a
    // simulated device's path
    const std::int64_t loop_time_ns = static_cast<std::int64_t>(tick) * period_ns;
    if (loop_time_ns > stop_at_ns) break;
    Tick(static_cast<double>(loop_time_ns) * 1e-9);
    ++tick;
    deadline += period_ns;
    const std::int64_t now = MonotonicNs();
    if (now > deadline + period_ns) {
      // more than a period behind: count it and skip the lost ticks rather than burst
      overruns_.fetch_add(1, std::memory_order_relaxed);
      const std::int64_t behind = (now - deadline) / period_ns;
      deadline += behind * period_ns;
      tick += static_cast<std::uint64_t>(behind);
      skipped_ticks_.fetch_add(static_cast<std::uint64_t>(behind), std::memory_order_relaxed);
    }
    const timespec ts = ToTimespec(deadline);
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
    }
  }
  device_.WriteForce(Vec3::Zero());
  running_.store(false, std::memory_order_release);
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

ServoStats ServoLoop::stats() const {
  ServoStats s;
  s.ticks = ticks_.load(std::memory_order_relaxed);
  s.overruns = overruns_.load(std::memory_order_relaxed);
  s.skipped_ticks = skipped_ticks_.load(std::memory_order_relaxed);
  s.trace_dropped = trace_dropped_.load(std::memory_order_relaxed);
  s.elapsed_s = elapsed_s_.load(std::memory_order_relaxed);
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
