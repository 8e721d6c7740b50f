// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/devices/servo_loop.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <thread>
#include <utility>

#include <gtest/gtest.h>

#include <unistd.h>

#include "alloc_counter.h"
#include "faulty_device.h"
#include "hapticad/devices/simulated_device.h"
#include "hapticad/devices/simulated_hand.h"
#include "syscall_counter.h"
#include "test_meshes.h"

namespace hapticad {
namespace {

ServoConfig Config(double rate_hz, std::size_t trace_capacity) {
  ServoConfig c;
  c.rate_hz = rate_hz;
  c.trace_capacity = trace_capacity;
  return c;
}

// A 100 mm box (mm in the soup) shifted along x, its top at `top` mm.
std::shared_ptr<ForceRenderer> BoxRenderer(const DeviceLimits& limits, double shift_x = 0.0,
                                           double top = 50.0) {
  auto scene = HapticScene::Build(
      testing::MakeBoxSoup(Vec3(-50 + shift_x, -50, -50), Vec3(50 + shift_x, 50, top)), 1e-3);
  return std::make_shared<ForceRenderer>(
      scene, std::make_shared<SurfaceTable>(),
      RenderLimits{limits.max_force_n, limits.max_stiffness_n_per_m});
}

class ServoOnBox : public ::testing::Test {
 protected:
  void SetUp() override {
    ScriptedPath path;  // down onto the top face, 1 mm in, slide 20 mm, up
    path.times_s = {0.0, 0.05, 0.10, 0.30, 0.35};
    path.positions = {Vec3(0, 0, 0.06), Vec3(0, 0, 0.049), Vec3(0, 0, 0.049), Vec3(0.02, 0, 0.049),
                      Vec3(0.02, 0, 0.06)};
    limits_.max_force_n = 8.0;
    limits_.max_stiffness_n_per_m = 3000.0;
    device_ = std::make_unique<SimulatedDevice>(path, limits_);
    renderer_ = BoxRenderer(limits_);
  }
  DeviceLimits limits_;
  std::unique_ptr<SimulatedDevice> device_;
  std::shared_ptr<ForceRenderer> renderer_;
};

// A simulated device lives on the loop's clock (Device::runs_on_loop_time): however the
// host schedules the thread, a late tick is waited for, never skipped or cut. So every
// tick from 0 to 300 ms runs at its whole period, none faults, and each is checked at
// the full force. (A real device's late tick: ALateTickIsWaitedForByASimulation...)
TEST_F(ServoOnBox, RunsAtItsRateAndRecordsEveryTick) {
  ServoLoop loop(*device_, *renderer_, Config(1000.0, 4096));
  const std::vector<TraceSample> trace = loop.RunFor(0.3);
  const ServoStats stats = loop.CalcStats();
  // ticks at 0, 1, ..., 300 ms (0.3 is not a multiple of 1e-3 in binary: the loop must
  // still include 300 ms), none after
  ASSERT_EQ(trace.size(), 301u);
  EXPECT_EQ(stats.ticks, 301u);
  EXPECT_EQ(stats.skipped_ticks, 0u);
  EXPECT_EQ(stats.trace_dropped, 0u);
  for (std::size_t i = 0; i < trace.size(); ++i) {
    ASSERT_NEAR(trace[i].time_s, static_cast<double>(i) * 1e-3, 1e-12) << i;
  }
  EXPECT_NEAR(trace.back().time_s, 0.3, 1e-12);
  // it touched the top face where the path goes under it, pressed 1 mm at the default
  // 0.4 N/mm, and sent that force ramped in from the session's start (0.2 s)
  int contact = 0;
  for (const TraceSample& s : trace) {
    const double t = s.time_s;
    EXPECT_EQ(s.flags & kDeviceFault, 0u) << t;
    // the tool where the path has it at the tick's loop time (identity mapping)
    const Vec3 tool = PathCursor(&device_->path()).Sample(t).position;
    EXPECT_NEAR((Vec3(s.device_m[0], s.device_m[1], s.device_m[2]) - tool).norm(), 0.0, 1e-12) << t;
    EXPECT_EQ((s.flags & kContact) != 0, tool.z() < 0.05) << t;
    if (!(s.flags & kContact)) continue;
    ++contact;
    EXPECT_EQ(s.cad_face, 5);
    if (t > 0.2 && t < 0.29) {
      EXPECT_NEAR(s.normal_force_n, 0.4, 1e-6) << t;  // the renderer's, before the ramp
      EXPECT_EQ(s.flags & kRamping, 0u) << t;
      EXPECT_NEAR(s.force_n[2], 0.4, 1e-6) << t;
    }
  }
  // the path is under the face from 46 ms on: 255 ticks to 300 ms
  EXPECT_EQ(contact, 255);
  EXPECT_FALSE(loop.running());
  EXPECT_EQ(loop.session_end(), SessionEnd::kFinished);
  EXPECT_EQ(loop.fault_message(), "");
  EXPECT_EQ(device_->last_force_d(), Vec3::Zero());  // the end leaves the device at zero force
}

TEST_F(ServoOnBox, StatisticsAreConsistentAndTheSchedulingIsReported) {
  ServoLoop loop(*device_, *renderer_, Config(1000.0, 4096));
  loop.RunFor(0.2);
  const ServoStats s = loop.CalcStats();
  // facts of the loop's clock, however slow the host: every tick of 0..200 ms ran (a
  // simulation waits for a late one), the last at 200 ms; and the host clock is never
  // behind the loop's (tick n starts n periods after the first at the earliest)
  EXPECT_EQ(s.ticks, 201u);
  EXPECT_EQ(s.ticks, loop.ticks());
  EXPECT_EQ(s.skipped_ticks, 0u);
  EXPECT_NEAR(s.elapsed_s, 0.2, 1e-12);
  EXPECT_GE(s.wall_s, s.elapsed_s);
  EXPECT_GT(s.achieved_rate_hz, 0.0);
  EXPECT_DOUBLE_EQ(s.achieved_rate_hz, static_cast<double>(s.ticks - 1) / s.wall_s);
  EXPECT_LE(s.period_jitter_p50_us, s.period_jitter_p99_us);
  EXPECT_LE(s.period_jitter_p99_us, s.period_jitter_max_us * 1.04);  // bins are 3 % wide
  EXPECT_LE(s.wake_latency_p50_us, s.wake_latency_p99_us);
  EXPECT_GT(s.tick_p50_us, 0.0);
  const std::string report = loop.realtime_report();
  EXPECT_TRUE(report.rfind("real-time scheduling: SCHED_FIFO", 0) == 0 ||
              report.rfind("normal scheduling:", 0) == 0)
      << report;
  EXPECT_EQ(s.realtime, report.rfind("real-time", 0) == 0);

  ServoConfig plain = Config(1000.0, 4096);
  plain.realtime_priority = 0;
  ServoLoop normal(*device_, *renderer_, plain);
  normal.RunFor(0.01);
  EXPECT_EQ(normal.realtime_report(), "normal scheduling: real-time scheduling was not requested");
  EXPECT_FALSE(normal.CalcStats().realtime);
}

TEST_F(ServoOnBox, TickDoesNotAllocate) {
  ServoLoop loop(*device_, *renderer_, Config(1000.0, 1024));
  loop.BeginTicks();
  loop.Tick(0.0);
  testing::AllocationCounter counter;
  for (int i = 1; i < 350; ++i) loop.Tick(i * 1e-3, 1e-3);
  EXPECT_EQ(counter.count(), 0u);
  std::vector<TraceSample> trace;
  EXPECT_EQ(loop.DrainTrace(&trace), 350u);
}

TEST_F(ServoOnBox, CountsSamplesLostToAFullRing) {
  ServoLoop loop(*device_, *renderer_, Config(1000.0, 8));
  for (int i = 0; i < 20; ++i) loop.Tick(i * 1e-3);
  EXPECT_EQ(loop.CalcStats().trace_dropped, 12u);
}

TEST_F(ServoOnBox, RejectsBadSettings) {
  EXPECT_THROW(ServoLoop(*device_, *renderer_, Config(0.0, 8)), std::invalid_argument);
  EXPECT_THROW(ServoLoop(*device_, *renderer_, Config(20000.0, 8)), std::invalid_argument);
  ServoConfig bad = Config(1000.0, 8);
  bad.safety.watchdog_s = -1.0;
  EXPECT_THROW(ServoLoop(*device_, *renderer_, bad), std::invalid_argument);
  bad = Config(1000.0, 8);
  bad.clutch_button = 40;
  EXPECT_THROW(ServoLoop(*device_, *renderer_, bad), std::invalid_argument);
  ServoLoop loop(*device_, *renderer_);
  WorkspaceMapping squash;
  squash.rotation_wd(0, 0) = 2.0;
  EXPECT_THROW(loop.SetMapping(squash), std::invalid_argument);
  EXPECT_THROW(loop.SetRenderer(nullptr), std::invalid_argument);
}

TEST_F(ServoOnBox, StopIsIdempotentAndStartTwiceIsAnError) {
  ServoLoop loop(*device_, *renderer_);
  loop.Start();
  EXPECT_THROW(loop.Start(), std::logic_error);
  loop.Stop();
  loop.Stop();
  EXPECT_FALSE(loop.running());
  EXPECT_EQ(loop.session_end(), SessionEnd::kStopped);
}

// A simulated hand above the box's top face (z = 50 mm), in a 0.2 m workspace.
class HandOnBox : public ::testing::Test {
 protected:
  void SetUp() override {
    limits_ = SimulatedHandLimits();
    limits_.workspace_min_d = Vec3::Constant(-0.1);
    limits_.workspace_max_d = Vec3::Constant(0.1);
    hand_ = std::make_unique<SimulatedHand>(limits_);
    hand_->SetTarget(Vec3(0, 0, 0.06));
    renderer_ = BoxRenderer(limits_);
  }
  // Runs ticks at 1 kHz on this thread from `*t` for `duration` s.
  static void RunTicks(ServoLoop& loop, double* t, double duration, std::vector<TraceSample>* out) {
    const long first = std::lround(*t * 1000.0);
    const long n = std::lround(duration * 1000.0);
    for (long i = first; i < first + n; ++i) loop.Tick(i * 1e-3, i == 0 ? 0.0 : 1e-3);
    *t = (first + n) * 1e-3;
    loop.DrainTrace(out);
  }
  // From the start of a session: the hand comes down on the top face and rests on it,
  // aiming 5 mm in.
  void RestOnTheTop(ServoLoop& loop, double* t, std::vector<TraceSample>* trace) {
    loop.BeginTicks();
    RunTicks(loop, t, 0.3, trace);
    hand_->SetTarget(Vec3(0, 0, 0.045));
    RunTicks(loop, t, 1.0, trace);
    ASSERT_TRUE(trace->back().flags & kContact);
  }
  DeviceLimits limits_;
  std::unique_ptr<SimulatedHand> hand_;
  std::shared_ptr<ForceRenderer> renderer_;
};

TEST_F(HandOnBox, TheForceStopsAHandAimingIntoThePart) {
  ServoLoop loop(*hand_, renderer_, Config(1000.0, 1 << 14));
  loop.BeginTicks();
  double t = 0.0;
  std::vector<TraceSample> trace;
  RunTicks(loop, &t, 0.3, &trace);
  // aim 5 mm into the top face: grip 400 N/m against the face's 400 N/m meet halfway
  hand_->SetTarget(Vec3(0, 0, 0.045));
  RunTicks(loop, &t, 1.5, &trace);
  const TraceSample& s = trace.back();
  EXPECT_TRUE(s.flags & kContact);
  EXPECT_EQ(s.cad_face, 5);
  EXPECT_NEAR(s.handle_d_m[2], 0.0475, 0.1e-3);
  EXPECT_NEAR(s.force_n[2], 1.0, 0.05);
  EXPECT_NEAR(hand_->true_state().position_d.z(), 0.0475, 0.1e-3);
  // what the hand feels is what was sent
  EXPECT_NEAR(hand_->true_state().force_d.z(), s.force_n[2], 1e-12);
}

TEST_F(HandOnBox, ForceRampsInAtTheStartOfASession) {
  hand_->SetTarget(Vec3(0, 0, 0.0485));  // starts 1.5 mm inside the box
  ServoLoop loop(*hand_, renderer_, Config(1000.0, 1 << 14));
  loop.BeginTicks();
  double t = 0.0;
  std::vector<TraceSample> trace;
  RunTicks(loop, &t, 0.3, &trace);
  // started inside the solid: the proxy starts on the top face, and the force that
  // pushes the hand out follows the ramp, so there is no jolt
  ASSERT_FALSE(trace.empty());
  for (const auto& s : trace) {
    ASSERT_GE(s.proxy_m[2], 0.05) << s.time_s;
    ASSERT_TRUE(s.flags & kContact) << s.time_s;
    ASSERT_GE(s.force_n[2], 0.0) << s.time_s;
    ASSERT_LE(s.force_n[2], s.normal_force_n * std::min(1.0, s.time_s / 0.2) + 1e-9) << s.time_s;
  }
  // the grip (400 N/m toward 1.5 mm inside) and the face (400 N/m) meet halfway
  EXPECT_NEAR(trace.back().handle_d_m[2], 0.04925, 0.05e-3);
  EXPECT_NEAR(trace.back().force_n[2], 0.3, 0.02);

  // start above and press: the force follows the ramp during the first 0.2 s
  auto hand2 = std::make_unique<SimulatedHand>(limits_);
  hand2->SetTarget(Vec3(0, 0, 0.0501));
  ServoLoop loop2(*hand2, renderer_, Config(1000.0, 1 << 14));
  loop2.BeginTicks();
  t = 0.0;
  trace.clear();
  RunTicks(loop2, &t, 0.02, &trace);
  hand2->SetTarget(Vec3(0, 0, 0.045));
  RunTicks(loop2, &t, 0.5, &trace);
  double max_ratio_before = 0.0;
  for (const auto& s : trace) {
    if (s.time_s < 0.2) {
      EXPECT_TRUE(s.flags & kRamping);
      // the sent force never exceeds the ramp's share of the rendered force
      if (s.normal_force_n > 1e-9) {
        max_ratio_before = std::max(max_ratio_before, s.force_n[2] / s.normal_force_n);
        EXPECT_LE(s.force_n[2] / s.normal_force_n, s.time_s / 0.2 + 1e-9);
      }
    } else {
      EXPECT_FALSE(s.flags & kRamping);
    }
  }
  EXPECT_GT(max_ratio_before, 0.5);
}

TEST_F(HandOnBox, AMappingScaleTheRendererWasNotBuiltForIsRefused) {
  // a renderer divides the stiffness by the scale it was built for: a mapping of 4 on a
  // renderer of 1 was felt at 4 times the device's stable stiffness
  ServoLoop loop(*hand_, renderer_, Config(1000.0, 1 << 12));
  WorkspaceMapping scaled;
  scaled.scale = 4.0;
  try {
    loop.SetMapping(scaled);
    FAIL() << "a mapping of another scale was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("the hand would feel 4 times its stiffness"),
              std::string::npos)
        << e.what();
  }
  // a renderer built for 4 is refused while the mapping is 1, taken once it is 4
  RenderLimits four{limits_.max_force_n, limits_.max_stiffness_n_per_m};
  four.workspace_scale = 4.0;
  auto scene =
      HapticScene::Build(testing::MakeBoxSoup(Vec3(-50, -50, -50), Vec3(50, 50, 50)), 1e-3);
  auto made_for_four =
      std::make_shared<ForceRenderer>(scene, std::make_shared<SurfaceTable>(), four);
  EXPECT_THROW(loop.SetRenderer(made_for_four), std::invalid_argument);
  ServoLoop other(*hand_, made_for_four, Config(1000.0, 1 << 12));
  EXPECT_THROW(other.BeginTicks(), std::logic_error);  // scale 4 with the identity mapping
  EXPECT_NO_THROW(other.SetMapping(scaled));
  EXPECT_NO_THROW(other.BeginTicks());
  EXPECT_THROW(other.SetRenderer(renderer_), std::invalid_argument);
}

TEST_F(HandOnBox, ASessionsTraceStartsAfresh) {
  // samples of the last session left undrained came first in the next one's trace
  ServoLoop loop(*hand_, renderer_, Config(1000.0, 1 << 12));
  loop.BeginTicks();
  for (int i = 0; i < 101; ++i) loop.Tick(i * 1e-3, i == 0 ? 0.0 : 1e-3);
  loop.BeginTicks();
  for (int i = 0; i < 21; ++i) loop.Tick(i * 1e-3, i == 0 ? 0.0 : 1e-3);
  std::vector<TraceSample> trace;
  EXPECT_EQ(loop.DrainTrace(&trace), 21u);
  EXPECT_EQ(trace.front().time_s, 0.0);
}

TEST_F(HandOnBox, TickWithHandMappingClutchAndSwapDoesNotAllocate) {
  ServoLoop loop(*hand_, renderer_, Config(1000.0, 1 << 12));
  auto other = BoxRenderer(limits_, 10.0);
  loop.BeginTicks();
  double t = 0.0;
  std::vector<TraceSample> trace;
  trace.reserve(4096);
  loop.Tick(0.0);
  loop.SetRenderer(other);  // allocates here, on the control thread, not in the tick
  WorkspaceMapping scaled;  // moved (a new scale needs a renderer made for it: a new loop)
  scaled.offset_w = Vec3(0.001, 0.0, 0.0);
  testing::AllocationCounter counter;
  for (int i = 1; i < 800; ++i) {
    t = i * 1e-3;
    if (i == 100) hand_->SetTarget(Vec3(0, 0, 0.04));
    if (i == 200) loop.SetMapping(scaled);
    if (i == 300) loop.SetClutch(true);
    if (i == 400) loop.SetClutch(false);
    loop.Tick(t, 1e-3);
    if (i % 100 == 0) loop.DrainTrace(&trace);
  }
  EXPECT_EQ(counter.count(), 0u);
  loop.DrainTrace(&trace);
  ASSERT_EQ(trace.size(), 800u);
  EXPECT_TRUE(trace[500].flags & kContact);  // pressing on the swapped-in box
  EXPECT_TRUE(trace[350].flags & kClutched);
}

TEST_F(HandOnBox, TickWithHandMappingClutchAndSwapMakesNoSystemCall) {
  ServoLoop loop(*hand_, renderer_, Config(1000.0, 1 << 12));
  loop.BeginTicks();
  loop.Tick(0.0);
  loop.SetRenderer(BoxRenderer(limits_, 10.0));
  WorkspaceMapping scaled;  // moved (a new scale needs a renderer made for it: a new loop)
  scaled.offset_w = Vec3(0.001, 0.0, 0.0);
  const long calls = testing::CountSystemCalls([&] {
    for (int i = 1; i < 800; ++i) {
      if (i == 100) hand_->SetTarget(Vec3(0, 0, 0.04));
      if (i == 200) loop.SetMapping(scaled);
      if (i == 300) loop.SetClutch(true);
      if (i == 400) loop.SetClutch(false);
      loop.Tick(i * 1e-3, 1e-3);
    }
  });
  EXPECT_EQ(calls, 0);
  // the counter does see system calls: a sleep and a getpid are two
  EXPECT_EQ(testing::CountSystemCalls([] {
              std::this_thread::sleep_for(std::chrono::microseconds(10));
              getpid();
            }),
            2);
}

TEST_F(HandOnBox, ASwappedRendererTakesOverWithoutAJolt) {
  ServoLoop loop(*hand_, renderer_, Config(1000.0, 1 << 14));
  double t = 0.0;
  std::vector<TraceSample> trace;
  RestOnTheTop(loop, &t, &trace);
  // the same box again, as after a material edit: contact carries on from the old proxy
  loop.SetRenderer(BoxRenderer(limits_));
  trace.clear();
  RunTicks(loop, &t, 0.5, &trace);
  for (const auto& s : trace) {
    EXPECT_TRUE(s.flags & kContact) << s.time_s;
    EXPECT_LE(s.force_n[2], 1.05) << s.time_s;
  }
  EXPECT_TRUE(trace[10].flags & kRamping);
  EXPECT_NEAR(trace.back().force_n[2], 1.0, 0.05);
}

TEST_F(HandOnBox, ASwappedOutSceneIsFreedWhenTheControlThreadAsks) {
  ServoLoop loop(*hand_, renderer_, Config(1000.0, 1 << 12));
  const std::weak_ptr<ForceRenderer> first = renderer_;
  renderer_.reset();
  loop.BeginTicks();
  loop.Tick(0.0);
  loop.SetRenderer(BoxRenderer(limits_, 5.0));
  EXPECT_FALSE(first.expired());  // the servo thread has not taken the new one yet
  EXPECT_EQ(loop.ReleaseReplacedRenderers(), 2u);
  loop.Tick(1e-3, 1e-3);
  EXPECT_FALSE(first.expired());  // freed on the control thread only
  EXPECT_EQ(loop.ReleaseReplacedRenderers(), 1u);
  EXPECT_TRUE(first.expired());
}

TEST_F(HandOnBox, ASceneThatGrewOverTheProxyPushesTheHandOutOfIt) {
  ServoLoop loop(*hand_, renderer_, Config(1000.0, 1 << 14));
  double t = 0.0;
  std::vector<TraceSample> trace;
  RestOnTheTop(loop, &t, &trace);
  ASSERT_NEAR(trace.back().proxy_m[2], 0.05, 1e-6);
  // the top face is extruded 5 mm while the hand rests on it: the old proxy and the hand
  // are now inside the part. The proxy restarts on the new top and the force, ramping
  // in, pushes the hand out (it used to restart inside: no force, the hand held in)
  loop.SetRenderer(BoxRenderer(limits_, 0.0, 55.0));
  trace.clear();
  RunTicks(loop, &t, 1.0, &trace);
  for (const auto& s : trace) {
    ASSERT_GE(s.proxy_m[2], 0.055) << s.time_s;
    ASSERT_GE(s.force_n[2], 0.0) << s.time_s;
  }
  EXPECT_TRUE(trace[10].flags & kRamping);
  // the grip toward 0.045 and the new face at 0.055, both 400 N/m, meet halfway
  EXPECT_TRUE(trace.back().flags & kContact);
  EXPECT_NEAR(trace.back().handle_d_m[2], 0.05, 0.1e-3);
  EXPECT_NEAR(trace.back().force_n[2], 2.0, 0.05);
}

// Reports the position the test sets, or the status it sets; keeps the last force.
class ScriptedDevice : public Device {
 public:
  const DeviceInfo& info() const override { return info_; }
  ReadStatus ReadState(double loop_time_s, DeviceState* state) override {
    if (status != ReadStatus::kOk) return status;
    state->time_s = loop_time_s;
    state->position_d = position;
    state->velocity_d = velocity;
    state->age_s = 0.0;
    return ReadStatus::kOk;
  }
  void WriteForce(const Vec3& force_d) override { force = force_d; }

  Vec3 position = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();
  ReadStatus status = ReadStatus::kOk;
  Vec3 force = Vec3::Zero();

 private:
  DeviceInfo info_{"sim", "scripted", "sim:scripted", DeviceLimits{}};
};

// A scripted device whose 50th reading holds the servo thread 8 ms, as a host that takes
// the thread off its core does (the watchdog is 5 ms); on the loop's clock or in real time.
class StallingDevice final : public ScriptedDevice {
 public:
  explicit StallingDevice(bool on_loop_time) : on_loop_time_(on_loop_time) {}
  ReadStatus ReadState(double loop_time_s, DeviceState* state) override {
    if (++reads_ == 50) std::this_thread::sleep_for(std::chrono::milliseconds(8));
    return ScriptedDevice::ReadState(loop_time_s, state);
  }
  bool runs_on_loop_time() const override { return on_loop_time_; }

 private:
  bool on_loop_time_;
  int reads_ = 0;
};

// A simulation's world waits for a late tick: nothing skipped, nothing cut. A real
// device went on pushing through the gap: the watchdog cuts the force, the lost ticks
// are skipped. The trace shows the host's gap either way.
TEST(ServoLoopClock, ALateTickIsWaitedForByASimulationAndCutForARealDevice) {
  for (const bool on_loop_time : {true, false}) {
    SCOPED_TRACE(on_loop_time ? "on the loop's clock" : "in real time");
    StallingDevice device(on_loop_time);
    device.position = Vec3(0, 0, 0.0495);  // 0.5 mm into the box's top face
    ServoLoop loop(device, BoxRenderer(device.info().limits), Config(1000.0, 1 << 12));
    const std::vector<TraceSample> trace = loop.RunFor(0.1);
    const ServoStats stats = loop.CalcStats();
    ASSERT_GE(trace.size(), 51u);
    // trace[49] read for 8 ms; trace[50] is the next tick that ran
    EXPECT_GE(trace[50].period_us, 8000.0);
    EXPECT_EQ(trace[49].flags & kDeviceFault, 0u);
    EXPECT_GT(trace[49].force_n[2], 0.0);
    if (on_loop_time) {
      EXPECT_EQ(trace.size(), 101u);
      EXPECT_EQ(stats.skipped_ticks, 0u);
      EXPECT_EQ(stats.faults.watchdog, 0u);
      EXPECT_NEAR(trace[50].time_s, 0.050, 1e-12);
      for (const TraceSample& s : trace) EXPECT_EQ(s.flags & kDeviceFault, 0u) << s.time_s;
      EXPECT_GT(trace[50].force_n[2], trace[49].force_n[2]);  // still ramping in
    } else {
      EXPECT_GE(stats.skipped_ticks, 7u);
      EXPECT_GE(stats.faults.watchdog, 1u);
      EXPECT_GE(trace[50].time_s, 0.057 - 1e-12);
      EXPECT_TRUE(trace[50].flags & kFaultWatchdog);
      EXPECT_EQ(trace[50].force_n[2], 0.0);
    }
    EXPECT_GE(stats.overruns, 1u);
  }
}

// Moves the scripted device in a straight line to `to`, 0.5 mm a tick, then holds it
// there for `hold` ticks; checks nothing.
void MoveTo(ServoLoop& loop, ScriptedDevice& device, const Vec3& to, double* t, int hold = 0) {
  const Vec3 from = device.position;
  const int steps = std::max(1, static_cast<int>(std::ceil((to - from).norm() / 0.5e-3)));
  for (int i = 1; i <= steps + hold; ++i, *t += 1e-3) {
    device.position = from + std::min(1.0, static_cast<double>(i) / steps) * (to - from);
    loop.Tick(*t, 1e-3);
  }
}

TEST(ServoLoopSessions, ARendererSwappedDuringAFaultDoesNotStartTheNextSessionAtTheOldProxy) {
  ScriptedDevice device;
  ServoLoop loop(device, BoxRenderer(device.info().limits), Config(1000.0, 1 << 12));
  // a session with the hand above the part (a 0.1 m box), in free space
  device.position = Vec3(0, 0, 0.06);
  loop.BeginTicks();
  double t = 0.0;
  for (int i = 0; i < 300; ++i, t += 1e-3) loop.Tick(t, 1e-3);
  // the device stops answering, and a new scene is adopted during the fault: the box
  // moved 30 mm along +x (x from -0.02 to 0.08 m; it still lies between the old proxy and
  // the hand below). The session ends there
  device.status = ReadStatus::kNoData;
  loop.SetRenderer(BoxRenderer(device.info().limits, 30.0));
  for (int i = 0; i < 10; ++i, t += 1e-3) loop.Tick(t, 1e-3);
  // the next session starts with the hand below the part, in free space: no force. (The
  // old proxy, above the part, would be held by the top face and push the hand up.)
  device.status = ReadStatus::kOk;
  device.position = Vec3(0, 0, -0.06);
  loop.BeginTicks();
  t = 0.0;
  for (int i = 0; i < 400; ++i, t += 1e-3) {
    loop.Tick(t, 1e-3);
    ASSERT_EQ(device.force, Vec3::Zero()) << t;
  }
  const TraceSample last = loop.latest();
  EXPECT_FALSE(last.flags & kContact);
  EXPECT_NEAR(last.proxy_m[2], -0.06, 1e-9);
  // and the part felt is the swapped one: under x = 0.065 m (only the new box), 1 mm up
  // into its bottom face the hand is pushed down by 0.4 N/mm x 1 mm; under x = -0.035 m
  // (only the old box) there is nothing
  MoveTo(loop, device, Vec3(0.065, 0, -0.06), &t);
  MoveTo(loop, device, Vec3(0.065, 0, -0.049), &t, 50);
  TraceSample pressed = loop.latest();
  EXPECT_TRUE(pressed.flags & kContact);
  EXPECT_EQ(pressed.cad_face, 4);  // -z
  EXPECT_NEAR(pressed.proxy_m[2], -0.05, 1e-6);
  EXPECT_NEAR(device.force.z(), -0.4, 1e-6);
  MoveTo(loop, device, Vec3(0.065, 0, -0.06), &t);
  MoveTo(loop, device, Vec3(-0.035, 0, -0.06), &t);
  MoveTo(loop, device, Vec3(-0.035, 0, -0.049), &t, 50);
  EXPECT_FALSE(loop.latest().flags & kContact);
  EXPECT_NEAR(loop.latest().proxy_m[2], -0.049, 1e-9);
  EXPECT_EQ(device.force, Vec3::Zero());
}

TEST(ServoLoopMapping, ANewMappingRestartsTheProxyAtTheToolAndRampsTheForceIn) {
  ScriptedDevice device;
  ServoLoop loop(device, BoxRenderer(device.info().limits), Config(1000.0, 1 << 12));
  device.position = Vec3(0, 0, 0.06);  // above the top face (z = 0.05), in free space
  loop.BeginTicks();
  double t = 0.0;
  for (int i = 0; i < 300; ++i, t += 1e-3) loop.Tick(t, 1e-3);
  ASSERT_NEAR(loop.latest().proxy_m[2], 0.06, 1e-9);
  // a new mapping puts the tool 14 cm lower, under the part, in free space: the proxy
  // restarts there (it used to stay above the part, catch on the top face and pull the
  // hand up with the full force)
  WorkspaceMapping lower;
  lower.offset_w = Vec3(0, 0, -0.14);
  loop.SetMapping(lower);
  for (int i = 0; i < 400; ++i, t += 1e-3) {
    loop.Tick(t, 1e-3);
    ASSERT_EQ(device.force, Vec3::Zero()) << t;
  }
  TraceSample last = loop.latest();
  EXPECT_FALSE(last.flags & kContact);
  EXPECT_NEAR(last.device_m[2], -0.08, 1e-9);
  EXPECT_NEAR(last.proxy_m[2], -0.08, 1e-9);
  // a mapping that puts the tool 2 mm into the top face: the proxy restarts on the face
  // (as at the start of a session) and the force ramps in from zero over 0.2 s
  WorkspaceMapping into;
  into.offset_w = Vec3(0, 0, -0.012);
  loop.SetMapping(into);
  std::vector<TraceSample> trace;
  loop.DrainTrace(&trace);
  trace.clear();
  const double adopted = t;
  for (int i = 0; i < 400; ++i, t += 1e-3) loop.Tick(t, 1e-3);
  loop.DrainTrace(&trace);
  ASSERT_EQ(trace.size(), 400u);
  for (const auto& s : trace) {
    ASSERT_TRUE(s.flags & kContact) << s.time_s;
    ASSERT_NEAR(s.proxy_m[2], 0.05, 1e-9) << s.time_s;
    const double ramp = std::min(1.0, (s.time_s - adopted) / 0.2);
    ASSERT_LE(s.force_n[2], 0.8 * ramp + 1e-6) << s.time_s;
    if (s.time_s - adopted < 0.2 - 1e-9) {
      ASSERT_TRUE(s.flags & kRamping) << s.time_s;
    }
  }
  EXPECT_EQ(trace.front().force_n[2], 0.0);
  EXPECT_NEAR(trace.back().force_n[2], 0.8, 1e-6);  // 400 N/m, 2 mm
  // pressing with 0.8 N, a mapping that puts the tool in free space again: the old
  // force stops in the first tick (it does not fade out pushing on nothing)
  loop.SetMapping(lower);
  loop.Tick(t, 1e-3);
  EXPECT_EQ(device.force, Vec3::Zero());
}

// The largest change of the force sent (z) from one tick to the next over `trace`.
double LargestStep(const std::vector<TraceSample>& trace, double before) {
  double step = 0.0;
  for (const auto& s : trace) {
    step = std::max(step, std::abs(s.force_n[2] - before));
    before = s.force_n[2];
  }
  return step;
}

TEST(ServoLoopTransitions, ASceneSwapNeverStepsTheForceAndTheClutchStopsItAtOnce) {
  ScriptedDevice device;  // 3.3 N, 400 N/m
  ServoLoop loop(device, BoxRenderer(device.info().limits), Config(1000.0, 1 << 12));
  device.position = Vec3(0, 0, 0.047);  // 3 mm into the top face: 1.2 N
  loop.BeginTicks();
  int i = 0;
  auto run = [&](int n) {
    std::vector<TraceSample> trace;
    loop.DrainTrace(&trace);
    const double before = loop.latest().force_n[2];
    trace.clear();
    for (const int end = i + n; i < end; ++i) loop.Tick(i * 1e-3, 1e-3);
    loop.DrainTrace(&trace);
    return std::make_pair(trace, before);
  };
  run(400);
  ASSERT_NEAR(loop.latest().force_n[2], 1.2, 1e-6);
  // the same box again (a material edit): the force carries on (it used to drop to zero
  // and ramp in again)
  loop.SetRenderer(BoxRenderer(device.info().limits));
  auto [swap, before_swap] = run(300);
  EXPECT_LT(LargestStep(swap, before_swap), 1e-9);
  EXPECT_TRUE(swap[10].flags & kRamping);
  // the top extruded to 55 mm: 8 mm in, 3.2 N, reached over the ramp, not in a step
  loop.SetRenderer(BoxRenderer(device.info().limits, 0.0, 55.0));
  auto [grown, before_grown] = run(300);
  EXPECT_LE(LargestStep(grown, before_grown), 2.0 / 200 + 1e-9);
  EXPECT_NEAR(grown.back().force_n[2], 3.2, 1e-6);
  // the clutch engaged under the pressing hand: the force stops at once (the hand now
  // moves the device freely; a fading push would act on nothing); released, it fades in
  loop.SetClutch(true);
  auto [held, before_held] = run(300);
  for (const auto& s : held) {
    ASSERT_EQ(s.force_n[2], 0.0) << s.time_s;
    ASSERT_TRUE(s.flags & kClutched) << s.time_s;
  }
  loop.SetClutch(false);
  auto [released, before_released] = run(300);
  EXPECT_LE(LargestStep(released, before_released), 3.2 / 200 + 1e-9);
  EXPECT_NEAR(released.back().force_n[2], 3.2, 1e-6);
  // the top lowered to 40 mm, under the hand at 47 mm: nothing backs the 3.2 N any more,
  // and it stops at once (it used to fade out over the ramp, pushing on nothing)
  loop.SetRenderer(BoxRenderer(device.info().limits, 0.0, 40.0));
  auto [lowered, before_lowered] = run(50);
  for (const auto& s : lowered) {
    ASSERT_FALSE(s.flags & kContact) << s.time_s;
    ASSERT_EQ(s.force_n[2], 0.0) << s.time_s;
  }
  // back to 55 mm, and the clutch engaged in the middle of the swap's blend: zero at once
  loop.SetRenderer(BoxRenderer(device.info().limits, 0.0, 55.0));
  run(300);
  loop.SetRenderer(BoxRenderer(device.info().limits, 0.0, 54.0));
  run(50);
  ASSERT_TRUE(loop.latest().flags & kRamping);
  loop.SetClutch(true);
  auto [clutched, before_clutched] = run(10);
  for (const auto& s : clutched) ASSERT_EQ(s.force_n[2], 0.0) << s.time_s;
}

TEST(ServoLoopSettings, ARateTooSlowForTheWatchdogOrTheStaleLimitIsRefused) {
  ScriptedDevice device;
  auto renderer = BoxRenderer(device.info().limits);
  EXPECT_DOUBLE_EQ(MinServoRateHz(SafetyConfig{}), 400.0);
  // 150 Hz: every 6.7 ms gap would trip the 5 ms watchdog, every tick a fault
  try {
    ServoLoop loop(device, renderer, Config(150.0, 8));
    FAIL() << "150 Hz accepted";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("rate 150 Hz"), std::string::npos) << message;
    EXPECT_NE(message.find("period 6.67 ms"), std::string::npos) << message;
    EXPECT_NE(message.find("watchdog of 5 ms"), std::string::npos) << message;
    EXPECT_NE(message.find("at least 400 Hz"), std::string::npos) << message;
  }
  EXPECT_THROW(ServoLoop(device, renderer, Config(100.0, 8)), std::invalid_argument);
  EXPECT_THROW(ServoLoop(device, renderer, Config(399.0, 8)), std::invalid_argument);
  EXPECT_NO_THROW(ServoLoop(device, renderer, Config(400.0, 8)));
  // a longer watchdog allows a slower loop, as long as the stale limit does too
  ServoConfig slow = Config(100.0, 8);
  slow.safety.watchdog_s = 0.02;
  try {
    ServoLoop loop(device, renderer, slow);
    FAIL() << "100 Hz accepted with a 5 ms stale limit";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("period 10 ms"), std::string::npos) << message;
    EXPECT_NE(message.find("stale-data limit of 5 ms"), std::string::npos) << message;
  }
  slow.safety.stale_after_s = 0.02;
  EXPECT_DOUBLE_EQ(MinServoRateHz(slow.safety), 100.0);
  EXPECT_NO_THROW(ServoLoop(device, renderer, slow));
}

TEST(ServoLoopFaults, ATickTheRendererRefusesIsAFaultCountedAndTheForceRampsBackIn) {
  DeviceLimits limits;
  limits.max_force_n = 8.0;
  limits.max_stiffness_n_per_m = 3000.0;
  ScriptedDevice device;
  // a box 100 m wide with its top at z = 10 m, felt through a scale of 200 (a 30 m model
  // fitted into the workspace): a 6 m/s handle (under the safety's 10 m/s) is 1200 m/s in
  // the world, over the renderer's 1 km/s bound
  auto scene =
      HapticScene::Build(testing::MakeBoxSoup(Vec3(-5e4, -5e4, -5e4), Vec3(5e4, 5e4, 1e4)), 1e-3);
  RenderLimits render{8.0, 3000.0};
  render.workspace_scale = 200.0;  // the face's 400 N/m at the handle: 2 N/m in the world
  auto renderer = std::make_shared<ForceRenderer>(scene, std::make_shared<SurfaceTable>(), render);
  ServoLoop loop(device, renderer, Config(1000.0, 1 << 12));
  WorkspaceMapping scaled;
  scaled.scale = 200.0;
  loop.SetMapping(scaled);
  loop.BeginTicks();
  device.position = Vec3(0, 0, 0.06);  // 12 m: above the top
  int i = 0;
  for (; i < 50; ++i) loop.Tick(i * 1e-3, 1e-3);
  device.position = Vec3(0, 0, 0.0425);  // 8.5 m: 1.5 m in, 3 N at 2 N/m
  for (; i < 400; ++i) loop.Tick(i * 1e-3, 1e-3);
  ASSERT_NEAR(loop.latest().force_n[2], 3.0, 1e-4);
  const ServoStats before = loop.CalcStats();
  std::vector<TraceSample> trace;
  loop.DrainTrace(&trace);
  trace.clear();
  device.velocity = Vec3(0, 0, -6.0);
  loop.Tick(i * 1e-3, 1e-3);
  ++i;
  device.velocity = Vec3::Zero();
  for (int k = 0; k < 300; ++k, ++i) loop.Tick(i * 1e-3, 1e-3);
  loop.DrainTrace(&trace);
  ASSERT_EQ(trace.size(), 301u);
  // the refused tick: zero force, a fault of its own
  EXPECT_TRUE(trace[0].flags & kInputFault);
  EXPECT_TRUE(trace[0].flags & kFaultRenderer);
  EXPECT_TRUE(trace[0].flags & kDeviceFault);
  EXPECT_EQ(trace[0].force_n[2], 0.0);
  // then the force ramps back in (it used to jump back to 3 N in the next tick)
  for (std::size_t k = 1; k < trace.size(); ++k) {
    const double ramp = std::min(1.0, (trace[k].time_s - trace[1].time_s) / 0.2);
    ASSERT_FALSE(trace[k].flags & kDeviceFault) << trace[k].time_s;
    ASSERT_LE(trace[k].force_n[2], 3.0001 * ramp + 1e-9) << trace[k].time_s;
  }
  EXPECT_TRUE(trace[1].flags & kRamping);
  EXPECT_LT(trace[10].force_n[2], 0.2);
  EXPECT_NEAR(trace.back().force_n[2], 3.0, 1e-4);
  const FaultCounts& faults = loop.CalcStats().faults;
  EXPECT_EQ(faults.renderer - before.faults.renderer, 1u);
  EXPECT_EQ(faults.zero_force_ticks - before.faults.zero_force_ticks, 1u);
}

TEST_F(HandOnBox, ARendererSwapReachesARunningLoop) {
  ServoLoop loop(*hand_, renderer_, Config(1000.0, 1 << 14));
  // Waits on the loop's own clock and trace; the deadline only bounds a broken run
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  auto wait_for = [&](auto done) {
    while (!done(loop.latest()) && std::chrono::steady_clock::now() < give_up) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return done(loop.latest());
  };
  loop.Start();
  // 50 ms of loop time: the hand, at 60 mm, is free above the 50 mm top
  ASSERT_TRUE(wait_for([](const TraceSample& s) { return s.time_s >= 0.05; }));
  const TraceSample before = loop.latest();
  EXPECT_FALSE(before.flags & kContact);
  // a burst of swaps (each one not yet taken gives way to the next), the last a box whose
  // top, at 65 mm, is over the hand: the proxy restarts on that top (ForceRenderer::Reset)
  for (int i = 0; i < 4; ++i) loop.SetRenderer(BoxRenderer(limits_, 1.0 * i));
  loop.SetRenderer(BoxRenderer(limits_, 0.0, 65.0));
  ASSERT_TRUE(wait_for([](const TraceSample& s) { return (s.flags & kContact) != 0; }))
      << "the new scene never reached the loop";
  const TraceSample after = loop.latest();
  loop.Stop();
  EXPECT_EQ(loop.session_end(), SessionEnd::kStopped);
  EXPECT_GT(after.time_s, before.time_s);
  EXPECT_EQ(after.cad_face, 5);
  EXPECT_NEAR(after.proxy_m[2], 0.065, 1e-6);  // on the new top, not the old one at 50 mm
  EXPECT_LT(after.device_m[2], 0.065);         // the hand under it
}

TEST_F(HandOnBox, ClutchFreezesTheToolAndShiftsTheMapping) {
  ServoLoop loop(*hand_, renderer_, Config(1000.0, 1 << 14));
  loop.BeginTicks();
  double t = 0.0;
  std::vector<TraceSample> trace;
  hand_->SetTarget(Vec3(0, 0, 0.08));
  RunTicks(loop, &t, 0.5, &trace);
  const double z_before = trace.back().device_m[2];
  loop.SetClutch(true);
  hand_->SetTarget(Vec3(0, 0, 0.07));  // lift the handle 10 mm... the tool stays
  trace.clear();
  RunTicks(loop, &t, 0.5, &trace);
  for (std::size_t i = 1; i < trace.size(); ++i) {
    EXPECT_TRUE(trace[i].flags & kClutched);
    EXPECT_EQ(trace[i].device_m[2], trace[0].device_m[2]);
    EXPECT_EQ(trace[i].force_n[2], 0.0);
  }
  EXPECT_NEAR(trace.back().handle_d_m[2], 0.07, 0.2e-3);
  loop.SetClutch(false);
  hand_->SetTarget(Vec3(0, 0, 0.08));
  trace.clear();
  RunTicks(loop, &t, 0.5, &trace);
  // released 10 mm lower, the handle is back where it was: the tool is 10 mm higher
  EXPECT_NEAR(loop.mapping().offset_w.z(), z_before - 0.07 + 0.0, 0.3e-3);
  EXPECT_NEAR(trace.back().device_m[2], z_before + 0.01, 0.3e-3);
}

TEST_F(HandOnBox, TheClutchButtonHoldsTheClutch) {
  testing::FaultyDevice with_buttons(hand_.get());
  ServoConfig config = Config(1000.0, 1 << 10);
  config.clutch_button = 2;
  ServoLoop loop(with_buttons, renderer_, config);
  loop.BeginTicks();
  with_buttons.SetButtons(0b011);  // other buttons do nothing
  loop.Tick(0.0);
  with_buttons.SetButtons(0b100);
  loop.Tick(0.001, 0.001);
  with_buttons.SetButtons(0);
  loop.Tick(0.002, 0.001);
  std::vector<TraceSample> trace;
  loop.DrainTrace(&trace);
  EXPECT_FALSE(trace[0].flags & kClutched);
  EXPECT_EQ(trace[0].buttons, 0b011u);
  EXPECT_TRUE(trace[1].flags & kClutched);
  EXPECT_FALSE(trace[2].flags & kClutched);
}

class FaultsOnBox : public HandOnBox {
 protected:
  // Presses on the top face for 1 s (in contact, at full force), then runs `duration`
  // more with the fault injected over [1.1, 1.1 + fault_s).
  std::vector<TraceSample> RunWith(testing::FaultyDevice::Fault fault, double fault_s,
                                   double duration, ServoConfig config = Config(1000.0, 1 << 14),
                                   ReadStatus status = ReadStatus::kOk) {
    faulty_ = std::make_unique<testing::FaultyDevice>(hand_.get());
    faulty_->Inject(fault, 1.1, 1.1 + fault_s, status);
    loop_ = std::make_unique<ServoLoop>(*faulty_, renderer_, config);
    loop_->BeginTicks();
    double t = 0.0;
    std::vector<TraceSample> trace;
    hand_->SetTarget(Vec3(0, 0, 0.06));
    RunTicks(*loop_, &t, 0.1, &trace);  // above the face
    hand_->SetTarget(Vec3(0, 0, 0.045));
    RunTicks(*loop_, &t, 1.0 + duration, &trace);
    return trace;
  }
  // Checks: zero force and `flag` during the fault, force back through a ramp after.
  void ExpectZeroDuringAndRampAfter(const std::vector<TraceSample>& trace, std::uint32_t flag,
                                    double fault_s) {
    int faulty = 0;
    for (const auto& s : trace) {
      const bool in_fault = s.time_s >= 1.1 - 1e-9 && s.time_s < 1.1 + fault_s - 1e-9;
      if (in_fault) {
        ++faulty;
        EXPECT_TRUE(s.flags & flag) << s.time_s;
        EXPECT_TRUE(s.flags & kDeviceFault) << s.time_s;
        EXPECT_EQ(Vec3(s.force_n[0], s.force_n[1], s.force_n[2]), Vec3::Zero()) << s.time_s;
      } else if (s.time_s > 1.1 + fault_s && s.time_s < 1.1 + fault_s + 0.19) {
        EXPECT_FALSE(s.flags & kDeviceFault) << s.time_s;
        EXPECT_TRUE(s.flags & kRamping) << s.time_s;  // no jolt on re-contact
      } else if (s.time_s > 0.5 && s.time_s < 1.1) {
        EXPECT_FALSE(s.flags & (kDeviceFault | kRamping)) << s.time_s;
        EXPECT_GT(s.force_n[2], 0.5) << s.time_s;
      }
    }
    EXPECT_EQ(faulty, static_cast<int>(std::lround(fault_s * 1000)));
  }
  std::unique_ptr<testing::FaultyDevice> faulty_;
  std::unique_ptr<ServoLoop> loop_;
};

TEST_F(FaultsOnBox, NaNFromTheDeviceZeroesTheForceAndIsCounted) {
  const auto trace = RunWith(testing::FaultyDevice::Fault::kNaN, 0.02, 0.5);
  ExpectZeroDuringAndRampAfter(trace, kFaultNonFinite, 0.02);
  EXPECT_EQ(loop_->CalcStats().faults.non_finite, 20u);
  EXPECT_EQ(loop_->CalcStats().faults.zero_force_ticks, 20u);
  // the NaN never reached the proxy
  for (const auto& s : trace) EXPECT_TRUE(std::isfinite(s.proxy_m[1])) << s.time_s;
}

TEST_F(FaultsOnBox, InfinityFromTheDeviceZeroesTheForceAndIsCounted) {
  const auto trace = RunWith(testing::FaultyDevice::Fault::kInf, 0.01, 0.3);
  ExpectZeroDuringAndRampAfter(trace, kFaultNonFinite, 0.01);
  EXPECT_EQ(loop_->CalcStats().faults.non_finite, 10u);
}

TEST_F(FaultsOnBox, ImpossiblePositionsAndSpeedsZeroTheForce) {
  auto trace = RunWith(testing::FaultyDevice::Fault::kFarAway, 0.015, 0.3);
  ExpectZeroDuringAndRampAfter(trace, kFaultOutOfRange, 0.015);
  EXPECT_EQ(loop_->CalcStats().faults.out_of_range, 15u);
  trace = RunWith(testing::FaultyDevice::Fault::kTooFast, 0.005, 0.3);
  ExpectZeroDuringAndRampAfter(trace, kFaultOutOfRange, 0.005);
}

TEST_F(FaultsOnBox, StaleDataZeroesTheForce) {
  const auto trace = RunWith(testing::FaultyDevice::Fault::kStale, 0.03, 0.3);
  ExpectZeroDuringAndRampAfter(trace, kFaultStale, 0.03);
  EXPECT_EQ(loop_->CalcStats().faults.stale, 30u);
}

TEST_F(FaultsOnBox, AFaultTheDeviceReportsZeroesTheForce) {
  const auto trace = RunWith(testing::FaultyDevice::Fault::kStatus, 0.01, 0.3,
                             Config(1000.0, 1 << 14), ReadStatus::kDeviceFault);
  ExpectZeroDuringAndRampAfter(trace, kFaultReported, 0.01);
  EXPECT_EQ(loop_->CalcStats().faults.reported, 10u);
}

TEST_F(FaultsOnBox, ALateLoopTripsTheWatchdog) {
  ServoLoop loop(*hand_, renderer_, Config(1000.0, 1 << 14));
  loop.BeginTicks();
  double t = 0.0;
  std::vector<TraceSample> trace;
  RunTicks(loop, &t, 0.1, &trace);
  hand_->SetTarget(Vec3(0, 0, 0.045));
  RunTicks(loop, &t, 1.0, &trace);
  ASSERT_GT(trace.back().force_n[2], 0.5);
  loop.Tick(t, 0.0049);          // within 5 ms: fine
  loop.Tick(t + 0.006, 0.0061);  // the loop missed 6 ms
  loop.Tick(t + 0.007, 0.001);
  trace.clear();
  loop.DrainTrace(&trace);
  ASSERT_EQ(trace.size(), 3u);
  EXPECT_FALSE(trace[0].flags & kDeviceFault);
  EXPECT_TRUE(trace[1].flags & kFaultWatchdog);
  EXPECT_EQ(trace[1].force_n[2], 0.0);
  EXPECT_TRUE(trace[2].flags & kRamping);
  EXPECT_LT(trace[2].force_n[2], 0.1);
  EXPECT_EQ(loop.CalcStats().faults.watchdog, 1u);
}

TEST_F(FaultsOnBox, UnplugZeroesTheForceInThatTickAndEndsTheSession) {
  testing::FaultyDevice faulty(hand_.get());
  faulty.Inject(testing::FaultyDevice::Fault::kStatus, 0.05, 1e9, ReadStatus::kUnplugged);
  hand_->SetTarget(Vec3(0, 0, 0.045));
  ServoLoop loop(faulty, renderer_, Config(1000.0, 1 << 14));
  const auto trace = loop.RunFor(2.0);
  EXPECT_FALSE(loop.running());
  EXPECT_EQ(loop.session_end(), SessionEnd::kUnplugged);
  ASSERT_FALSE(trace.empty());
  const TraceSample& last = trace.back();
  // ended in the tick that saw it: the first at or after 0.05 s (0.05 itself unless the
  // host held the loop's thread over it and the loop skipped that period)
  EXPECT_GE(last.time_s, 0.05 - 1e-9);
  ASSERT_GE(trace.size(), 2u);
  EXPECT_LT(trace[trace.size() - 2].time_s, 0.05 - 1e-9);
  EXPECT_TRUE(last.flags & kFaultUnplugged);
  EXPECT_EQ(Vec3(last.force_n[0], last.force_n[1], last.force_n[2]), Vec3::Zero());
  EXPECT_EQ(faulty.last_force_d(), Vec3::Zero());
  const std::string message = loop.fault_message();
  char at[48];
  std::snprintf(at, sizeof at, "was unplugged at %.3f s", last.time_s);
  EXPECT_NE(message.find(at), std::string::npos) << message;
  EXPECT_NE(message.find("Simulated hand"), std::string::npos) << message;
  EXPECT_NE(message.find("injected by the test"), std::string::npos) << message;
  EXPECT_EQ(loop.CalcStats().faults.unplugged, 1u);
  // the program carries on: the loop can start a new session
  faulty.Inject(testing::FaultyDevice::Fault::kNone, 0, 0);
  loop.Start();
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  EXPECT_TRUE(loop.running());
  loop.Stop();
  EXPECT_EQ(loop.session_end(), SessionEnd::kStopped);
  EXPECT_EQ(loop.fault_message(), "");
}

TEST_F(FaultsOnBox, FaultsThatLastEndTheSession) {
  testing::FaultyDevice faulty(hand_.get());
  faulty.Inject(testing::FaultyDevice::Fault::kStale, 0.05, 1e9);
  ServoConfig config = Config(1000.0, 1 << 14);
  config.safety.fault_timeout_s = 0.1;
  ServoLoop loop(faulty, renderer_, config);
  const auto trace = loop.RunFor(2.0);
  EXPECT_EQ(loop.session_end(), SessionEnd::kDeviceLost);
  EXPECT_LT(trace.back().time_s, 0.2);
  const std::string message = loop.fault_message();
  EXPECT_NE(message.find("gave no usable data for 0.1 s (stale data)"), std::string::npos)
      << message;
}

}  // namespace
}  // namespace hapticad
