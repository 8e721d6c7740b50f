// SPDX-License-Identifier: GPL-3.0-or-later
// The whole chain a user's hand is in: the emulated device's firmware (a mass held by a
// hand, pressing into a box), the shipped HID backend, the servo loop with its safety
// layer and the renderer. Each fault of the issue is injected in the device and the
// test checks what the user would see and feel: the trace's force and flags, the
// loop's counters, the session's end and its message, and the force the device applied.
//
// Most tests drive the loop tick by tick on the emulator's manual clock (deterministic
// and fast); the last ones run the real servo thread on the real clock.
#include <dirent.h>
#include <sched.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "alloc_counter.h"
#include "hapticad/devices/hid/hid_device.h"
#include "hapticad/devices/servo_loop.h"
#include "hid_emulator.h"
#include "syscall_counter.h"
#include "test_meshes.h"

namespace hapticad {
namespace {

using hidemu::Fault;
using hidemu::FaultWindow;
using hidemu::FirmwareConfig;

constexpr double kPlugTime = 50.0;

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// A box whose top face is the device's z = 0 plane (identity mapping), and a hand that
// holds the handle 10 mm above it, then from 0.2 s pushes to 10 mm below it.
FirmwareConfig PressingDevice() {
  FirmwareConfig c;
  c.hand_times_s = {0.0, 0.2, 0.4};
  c.hand_positions_m = {Vec3(0, 0, 0.01), Vec3(0, 0, 0.01), Vec3(0, 0, -0.01)};
  c.seed = 11;
  return c;
}

std::shared_ptr<ForceRenderer> Box() {
  auto scene =
      HapticScene::Build(testing::MakeBoxSoup(Vec3(-50, -50, -100), Vec3(50, 50, 0)), 1e-3);
  return std::make_shared<ForceRenderer>(scene, std::make_shared<SurfaceTable>(),
                                         RenderLimits{8.0, 2500.0});
}

double Norm(const double f[3]) { return std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]); }

class HidServo : public ::testing::Test {
 protected:
  void SetUp() override {
    hidemu::Reset();
    hidemu::UseManualClock(kPlugTime);
  }
  void TearDown() override {
    loop_.reset();
    device_.reset();
    hidemu::Reset();
  }

  // Plugs in `config`, opens it and runs the loop tick by tick for `duration` s (or
  // until the session ends). Returns the trace.
  std::vector<TraceSample> Run(FirmwareConfig config, double duration, ServoConfig servo = {}) {
    id_ = hidemu::AddDevice(config);
    device_ = HidDevice::Open(config.path);
    device_->set_clock(&hidemu::Now);
    loop_ = std::make_unique<ServoLoop>(*device_, Box(), servo);
    loop_->BeginTicks();
    std::vector<TraceSample> trace;
    const long n = std::lround(duration * 1000);
    for (long i = 0; i < n; ++i) {
      const double t = i * 1e-3;
      hidemu::SetTime(kPlugTime + t);
      loop_->Tick(t, i == 0 ? 0.0 : 1e-3);
      device_->WaitUntilWritten();  // the writer thread's write, before the clock moves on
      loop_->DrainTrace(&trace);
      if (trace.back().flags & kFaultUnplugged) break;  // where the servo thread would stop
    }
    return trace;
  }

  // Over [start, end): every tick zero force with `flag`; for 150 ms after: ramping,
  // no fault; before the fault (at 1 s): pressing with the full force.
  void ExpectZeroForceDuring(const std::vector<TraceSample>& trace, double start, double end,
                             std::uint32_t flag) {
    int zero = 0;
    for (const auto& s : trace) {
      if (s.time_s >= start && s.time_s < end) {
        EXPECT_TRUE(s.flags & flag) << s.time_s;
        EXPECT_EQ(Norm(s.force_n), 0.0) << s.time_s;
        ++zero;
      } else if (s.time_s > end + 0.001 && s.time_s < end + 0.15) {
        EXPECT_FALSE(s.flags & kDeviceFault) << s.time_s;
        EXPECT_TRUE(s.flags & kRamping) << s.time_s;
      } else if (s.time_s > 0.8 && s.time_s < 1.0) {
        EXPECT_FALSE(s.flags & kDeviceFault) << s.time_s;
        EXPECT_GT(s.force_n[2], 1.0) << s.time_s;
      }
    }
    EXPECT_GT(zero, 0);
  }

  int id_ = -1;
  std::unique_ptr<HidDevice> device_;
  std::unique_ptr<ServoLoop> loop_;
};

TEST_F(HidServo, TheUserPressesOnTheSurfaceThroughTheDevice) {
  FirmwareConfig c = PressingDevice();
  c.transport_latency_s = 0.25e-3;  // each way, as a full-speed USB frame would add
  const auto trace = Run(c, 1.2);
  // the hand's 300 N/m spring meets the face's 400 N/m: 10 mm splits 4.3 / 5.7 mm
  const hidemu::Snapshot device = hidemu::GetSnapshot(id_);
  EXPECT_NEAR(device.position_m.z(), -0.0043, 0.3e-3);
  EXPECT_NEAR(device.applied_force_n.z(), 1.71, 0.1);
  EXPECT_NEAR(trace.back().force_n[2], device.applied_force_n.z(), 0.02);
  EXPECT_TRUE(trace.back().flags & kContact);
  EXPECT_EQ(loop_->CalcStats().faults.zero_force_ticks, 1u);  // the first tick: no data yet
  // round trip measured by the device: a report sent at k ms arrives at k + 0.25 ms, is
  // read by the tick at k + 1 ms, whose command arrives 0.25 ms later
  EXPECT_NEAR(device.round_trip_p50_s, 1.25e-3, 0.04e-3);
  EXPECT_NEAR(device_->CalcLinkStats().round_trip_p50_us, 1250, 40);
  EXPECT_EQ(device.outputs_rejected, 0u);
}

TEST_F(HidServo, UnplugZeroesTheForceInThatTickAndEndsTheSessionWithAMessage) {
  FirmwareConfig c = PressingDevice();
  c.faults.push_back(FaultWindow{Fault::kUnplug, 1.0});
  const auto trace = Run(c, 2.0);
  ASSERT_FALSE(trace.empty());
  const TraceSample& last = trace.back();
  EXPECT_NEAR(last.time_s, 1.0, 1e-9);
  EXPECT_TRUE(last.flags & kFaultUnplugged);
  EXPECT_EQ(Norm(last.force_n), 0.0);
  EXPECT_GT(trace[trace.size() - 2].force_n[2], 1.0);  // it was pressing a tick before
  // the servo thread would now end the session; the tick-driven test ends it the same way
  EXPECT_EQ(loop_->CalcStats().faults.unplugged, 1u);
  EXPECT_TRUE(device_->unplugged());
  EXPECT_TRUE(Contains(device_->DescribeFault(), "device disconnected"));
}

TEST_F(HidServo, AStallZeroesTheForceUntilDataComesBackThenRampsIn) {
  FirmwareConfig c = PressingDevice();
  c.faults.push_back(FaultWindow{Fault::kStall, 1.0, 1.03});
  const auto trace = Run(c, 1.4);
  // stale once the last report is over 5 ms old: 1.005 .. 1.029 (reports resume at 1.03)
  ExpectZeroForceDuring(trace, 1.0055, 1.0295, kFaultStale);
  EXPECT_GE(loop_->CalcStats().faults.stale, 24u);  // 1.005 is 5 ms after 0.999, give or take a bit
  EXPECT_LE(loop_->CalcStats().faults.stale, 26u);
  // the device got zero force from the host during the stall, not its last command
  EXPECT_GT(hidemu::GetSnapshot(id_).outputs_applied, 1300u);
}

TEST_F(HidServo, ADeviceThatStaysSilentEndsTheSession) {
  // the servo thread on the real clock: the session must end by itself
  hidemu::UseRealClock();
  FirmwareConfig c = PressingDevice();
  c.faults.push_back(FaultWindow{Fault::kStall, 0.0});  // never sends a report
  hidemu::AddDevice(c);
  auto device = HidDevice::Open(c.path);
  ServoConfig servo;
  servo.safety.fault_timeout_s = 0.5;
  ServoLoop loop(*device, Box(), servo);
  loop.Start();
  for (int i = 0; i < 400 && loop.running(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_FALSE(loop.running());
  EXPECT_EQ(loop.session_end(), SessionEnd::kDeviceLost);
  EXPECT_TRUE(Contains(loop.fault_message(), "gave no usable data for 0.5 s (no data)"))
      << loop.fault_message();
  EXPECT_EQ(loop.CalcStats().faults.zero_force_ticks, loop.ticks());  // never any force
}

TEST_F(HidServo, LateReportsZeroTheForce) {
  FirmwareConfig c = PressingDevice();
  c.faults.push_back(FaultWindow{Fault::kLate, 1.0, 1.05, 0.02});
  const auto trace = Run(c, 1.5);
  ExpectZeroForceDuring(trace, 1.0055, 1.0685, kFaultStale);
  EXPECT_GT(loop_->CalcStats().faults.stale, 55u);
}

TEST_F(HidServo, ReorderedDroppedAndDuplicatedReportsAreAbsorbed) {
  for (Fault fault : {Fault::kReorder, Fault::kDrop, Fault::kDuplicate}) {
    hidemu::Reset();
    hidemu::UseManualClock(kPlugTime);
    FirmwareConfig c = PressingDevice();
    c.faults.push_back(FaultWindow{fault, 1.0, 1.2, 0.3});
    const auto trace = Run(c, 1.4);
    // the user feels nothing: no tick without force after the start
    EXPECT_EQ(loop_->CalcStats().faults.zero_force_ticks, 1u) << static_cast<int>(fault);
    EXPECT_GT(trace.back().force_n[2], 1.0);
    const HidLinkStats link = device_->CalcLinkStats();
    EXPECT_GT(link.not_newer + link.dropped, 40u) << static_cast<int>(fault);
  }
}

TEST_F(HidServo, TruncatedAndGarbageReportsNeverReachTheForce) {
  for (Fault fault : {Fault::kTruncate, Fault::kGarbage}) {
    hidemu::Reset();
    hidemu::UseManualClock(kPlugTime);
    FirmwareConfig c = PressingDevice();
    c.faults.push_back(FaultWindow{fault, 1.0, 1.02, 12});
    const auto trace = Run(c, 1.4);
    ExpectZeroForceDuring(trace, 1.0055, 1.0195, kFaultStale);
    EXPECT_EQ(device_->CalcLinkStats().malformed, 20u);
    EXPECT_EQ(loop_->CalcStats().faults.out_of_range, 0u);
    // the handle the renderer saw moved smoothly from tick to tick (the hand moves under
    // 1 mm per ms): nothing of the garbage got through
    for (std::size_t i = 2; i < trace.size(); ++i) {
      if ((trace[i].flags | trace[i - 1].flags) & kDeviceFault) continue;
      const double step = std::hypot(trace[i].device_m[0] - trace[i - 1].device_m[0],
                                     trace[i].device_m[1] - trace[i - 1].device_m[1],
                                     trace[i].device_m[2] - trace[i - 1].device_m[2]);
      EXPECT_LT(step, 1e-3) << trace[i].time_s;
    }
  }
}

TEST_F(HidServo, ExtremeValuesZeroTheForceAndAreCounted) {
  FirmwareConfig c = PressingDevice();
  c.faults.push_back(FaultWindow{Fault::kExtreme, 1.0, 1.01});
  const auto trace = Run(c, 1.4);
  ExpectZeroForceDuring(trace, 1.0, 1.01, kFaultOutOfRange);
  EXPECT_EQ(loop_->CalcStats().faults.out_of_range, 10u);
  for (const auto& s : trace) {
    EXPECT_LT(std::abs(s.device_m[1]), 0.1) << s.time_s;  // never reached the renderer
    EXPECT_LT(Norm(s.velocity_mps), 1.0) << s.time_s;
  }
}

TEST_F(HidServo, AFaultTheDeviceReportsZeroesTheForce) {
  FirmwareConfig c = PressingDevice();
  c.faults.push_back(FaultWindow{Fault::kDeviceFault, 1.0, 1.01});
  const auto trace = Run(c, 1.4);
  ExpectZeroForceDuring(trace, 1.0, 1.01, kFaultReported);
  EXPECT_EQ(loop_->CalcStats().faults.reported, 10u);
}

TEST_F(HidServo, AFrozenDeviceClockIsStaleData) {
  FirmwareConfig c = PressingDevice();
  c.faults.push_back(FaultWindow{Fault::kFreezeClock, 1.0, 1.02});
  const auto trace = Run(c, 1.4);
  ExpectZeroForceDuring(trace, 1.0055, 1.0195, kFaultStale);
}

TEST_F(HidServo, LostCommandsTripTheDeviceWatchdogAndTheForceRampsBack) {
  FirmwareConfig c = PressingDevice();
  c.faults.push_back(FaultWindow{Fault::kDropOutput, 1.0, 1.05});
  Run(c, 1.03);
  hidemu::Snapshot device = hidemu::GetSnapshot(id_);
  EXPECT_TRUE(device.watchdog_tripped);  // 30 ms without a command: the device let go
  EXPECT_EQ(device.applied_force_n, Vec3::Zero());
  EXPECT_GT(device_->CalcLinkStats().watchdog_reports, 5u);  // and told the host...
  std::vector<TraceSample> trace;
  for (long i = 1030; i < 1300; ++i) {  // commands get through again from 1.05 s
    hidemu::SetTime(kPlugTime + i * 1e-3);
    loop_->Tick(i * 1e-3, 1e-3);
    device_->WaitUntilWritten();
  }
  loop_->DrainTrace(&trace);
  // ...which held the force at zero (no jolt when the device takes commands again)
  for (const auto& s : trace) {
    if (s.time_s < 1.05) {
      EXPECT_TRUE(s.flags & kFaultReported) << s.time_s;
      EXPECT_EQ(Norm(s.force_n), 0.0) << s.time_s;
    }
    if (s.time_s > 1.052 && s.time_s < 1.2) {
      EXPECT_TRUE(s.flags & kRamping) << s.time_s;
    }
  }
  device = hidemu::GetSnapshot(id_);
  EXPECT_FALSE(device.watchdog_tripped);
  EXPECT_EQ(device.watchdog_trips, 1u);
  EXPECT_GT(device.applied_force_n.z(), 1.0);
}

TEST_F(HidServo, ACommandHeldUpForAMomentIsAFaultAndTheForceRampsBack) {
  // one write at 1.0 s takes 20 ms (a device slow to take it): the loop goes on ticking,
  // commands zero force once the command is over the device's 5 ms watchdog, and ramps in
  // again when commands flow; the session goes on
  FirmwareConfig c = PressingDevice();
  c.faults.push_back(FaultWindow{Fault::kLateWrite, 1.0, 1.0005, 0.02});
  Run(c, 1.0);
  std::vector<TraceSample> trace;
  for (long i = 1000; i < 1300; ++i) {
    hidemu::SetTime(kPlugTime + i * 1e-3);
    loop_->Tick(i * 1e-3, 1e-3);
    // the write is done, or held up in the "kernel", before the clock moves on
    while (!device_->WaitUntilWritten(0.0) && hidemu::BlockedWrites() == 0) {
      std::this_thread::yield();
    }
  }
  loop_->DrainTrace(&trace);
  for (const auto& s : trace) {
    if (s.time_s > 1.0065 && s.time_s < 1.0195) {
      EXPECT_TRUE(s.flags & kFaultReported) << s.time_s;
      EXPECT_EQ(Norm(s.force_n), 0.0) << s.time_s;
    }
    if (s.time_s > 1.022 && s.time_s < 1.15) {
      EXPECT_TRUE(s.flags & kRamping) << s.time_s;
    }
  }
  EXPECT_GT(trace.back().force_n[2], 1.0);
  EXPECT_FALSE(trace.back().flags & kDeviceFault);
  EXPECT_FALSE(device_->unplugged());
  const HidLinkStats link = device_->CalcLinkStats();
  // 1.005 .. 1.020 (the tick at 1.020 reads before the writer wakes), give or take the ends
  EXPECT_GE(link.commands_late_ticks, 14u);
  EXPECT_LE(link.commands_late_ticks, 16u);
  EXPECT_GE(link.write_max_us, 0.0);
  EXPECT_GT(link.writes_superseded, 10u);
}

TEST_F(HidServo, AWrongProtocolVersionNeverStartsASession) {
  FirmwareConfig c = PressingDevice();
  c.version_min = c.version_max = 0x0200;
  const int id = hidemu::AddDevice(c);
  try {
    HidDevice::Open(c.path);
    FAIL();
  } catch (const DeviceError& e) {
    EXPECT_TRUE(Contains(e.what(), "update HaptiCAD")) << e.what();
  }
  hidemu::SetTime(kPlugTime + 1.0);
  EXPECT_FALSE(hidemu::GetSnapshot(id).session_open);
  EXPECT_EQ(hidemu::GetSnapshot(id).max_applied_force_n, 0.0);
}

TEST_F(HidServo, ALateTickDoesNotMakeTheReportsAfterItLookStale) {
  Run(PressingDevice(), 1.0);
  // the tick scheduled at 1.000 s runs 6 ms late; the loop then skips to 1.007 s
  hidemu::SetTime(kPlugTime + 1.006);
  loop_->Tick(1.000, 0.007);
  device_->WaitUntilWritten();
  for (long i = 1007; i < 1500; ++i) {
    hidemu::SetTime(kPlugTime + i * 1e-3);
    loop_->Tick(i * 1e-3, i == 1007 ? 0.001 : 1e-3);
    device_->WaitUntilWritten();
  }
  std::vector<TraceSample> trace;
  loop_->DrainTrace(&trace);
  EXPECT_EQ(loop_->CalcStats().faults.watchdog, 1u);  // the late tick itself
  EXPECT_EQ(loop_->CalcStats().faults.stale, 0u);     // nothing after it
  EXPECT_GT(trace.back().force_n[2], 1.0);
}

TEST_F(HidServo, ATickThroughTheHidBackendMakesNoSystemCallOfItsOwn) {
  // the emulator stands in for the kernel without system calls of its own, so what is
  // left is the backend's and the loop's: none (hidraw adds its poll, read and write)
  Run(PressingDevice(), 0.3);
  const long calls = testing::CountSystemCalls([this] {
    for (long i = 300; i < 800; ++i) {
      hidemu::SetTime(kPlugTime + i * 1e-3);
      loop_->Tick(i * 1e-3, 1e-3);
    }
  });
  EXPECT_EQ(calls, 0);
}

TEST_F(HidServo, ATickThroughTheHidBackendDoesNotAllocate) {
  FirmwareConfig c = PressingDevice();
  c.faults.push_back(FaultWindow{Fault::kGarbage, 0.5, 0.52});  // rejections too
  c.faults.push_back(FaultWindow{Fault::kStall, 0.6, 0.62});    // and stale ticks
  Run(c, 0.3);
  testing::AllocationCounter counter;
  for (long i = 300; i < 900; ++i) {
    hidemu::SetTime(kPlugTime + i * 1e-3);
    loop_->Tick(i * 1e-3, 1e-3);
    device_->WaitUntilWritten();
  }
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_GT(loop_->CalcStats().faults.stale, 10u);
  EXPECT_GT(device_->CalcLinkStats().malformed, 10u);
}

// The real servo thread, on the real clock.
class HidServoRealTime : public ::testing::Test {
 protected:
  void SetUp() override { hidemu::Reset(); }
  void TearDown() override { hidemu::Reset(); }
};

// The scheduling policy of this process's thread named `name` (-1 if none is).
int PolicyOfThread(const std::string& name) {
  DIR* tasks = opendir("/proc/self/task");
  int policy = -1;
  while (dirent* e = tasks ? readdir(tasks) : nullptr) {
    if (e->d_name[0] == '.') continue;
    std::ifstream comm(std::string("/proc/self/task/") + e->d_name + "/comm");
    std::string text;
    std::getline(comm, text);
    if (text == name) policy = sched_getscheduler(std::atoi(e->d_name));
  }
  if (tasks) closedir(tasks);
  return policy;
}

TEST_F(HidServoRealTime, TheWriterThreadRunsAsTheServoThreadDoesEvenOnOneCpu) {
  // The servo thread got SCHED_FIFO after it started; on one CPU its first tick ran
  // before that, and the writer copied the normal policy from that tick's command, once.
  cpu_set_t all, one;
  ASSERT_EQ(sched_getaffinity(0, sizeof all, &all), 0);
  CPU_ZERO(&one);
  CPU_SET(sched_getcpu(), &one);
  ASSERT_EQ(sched_setaffinity(0, sizeof one, &one), 0);  // the threads made now inherit it
  int realtime_runs = 0;
  for (int round = 0; round < 5; ++round) {
    hidemu::Reset();
    FirmwareConfig c = PressingDevice();
    hidemu::AddDevice(c);
    auto device = HidDevice::Open(c.path);
    ServoConfig config;
    config.realtime_priority = 10;
    ServoLoop loop(*device, Box(), config);
    const auto start = std::chrono::steady_clock::now();
    loop.Start();
    // a start flag spun on at SCHED_FIFO held the one CPU from the thread that was to set
    // it: Start() took the kernel's real-time throttling's 0.95 s, or never returned
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 0.5)
        << "round " << round;
    if (loop.CalcStats().realtime) {
      ++realtime_runs;
      // the writer takes the policy with the first command it writes: wait for that (it
      // copies once, so a wrong copy stays wrong however long this waits)
      int policy = -1;
      for (int i = 0; i < 100 && policy != SCHED_FIFO; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
        policy = PolicyOfThread("hid-writer");
      }
      EXPECT_EQ(policy, SCHED_FIFO) << "round " << round;
    }
    loop.Stop();
  }
  sched_setaffinity(0, sizeof all, &all);
  if (realtime_runs == 0)
    GTEST_SKIP() << "SCHED_FIFO not granted here: nothing for the writer to copy";
}

TEST_F(HidServoRealTime, ADeviceThatDoesNotAnswerTheSessionRequestIsRefusedWithinItsBound) {
  // from 0.3 s every feature-report request blocks 5 s and times out: BeginSession (the
  // Feel panel's Start) used to wait there on the calling thread, the GUI frozen 5 s
  FirmwareConfig c = PressingDevice();
  c.faults.push_back(FaultWindow{Fault::kSlowFeature, 0.3, 1e9, 5.0});
  hidemu::AddDevice(c);
  auto device = HidDevice::Open(c.path);  // before the window: it answers
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  const auto start = std::chrono::steady_clock::now();
  try {
    device->BeginSession();
    FAIL() << "a session opened on a device that did not answer";
  } catch (const DeviceError& e) {
    EXPECT_TRUE(Contains(e.what(), "did not answer the request to open a session within 1.0 s"))
        << e.what();
    EXPECT_TRUE(Contains(e.what(), "Unplug it, plug it in again")) << e.what();
  }
  const double waited =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(waited, HidDevice::kBeginSessionWaitS + 0.5);
  EXPECT_GE(waited, HidDevice::kBeginSessionWaitS - 0.05);
}

TEST_F(HidServoRealTime, AWriteStuckInTheKernelNeitherFreezesTheLoopNorHoldsUpItsEnd) {
  // from 0.5 s every write blocks 5 s and times out (usbhid's USB_CTRL_SET_TIMEOUT): the
  // loop used to freeze 5 s per write with the force unchanged and no fault, and Stop()
  // to wait ~12 s. Now the ticks go on, zero force, and the session ends by itself.
  FirmwareConfig c = PressingDevice();
  c.faults.push_back(FaultWindow{Fault::kSlowWrite, 0.5, 1e9, 5.0});
  hidemu::AddDevice(c);
  auto device = HidDevice::Open(c.path);
  ServoLoop loop(*device, Box());
  const auto start = std::chrono::steady_clock::now();
  loop.Start();
  while (loop.running() && std::chrono::steady_clock::now() - start < std::chrono::seconds(4)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const double ended_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_FALSE(loop.running());
  EXPECT_LT(ended_s, 0.5 + HidDevice::kCommandTimeoutS + 0.5);
  EXPECT_EQ(loop.session_end(), SessionEnd::kUnplugged);
  const std::string message = loop.fault_message();
  EXPECT_TRUE(Contains(message, "it stopped taking force commands: one waited 250 ms")) << message;
  // still attached: "lost", not "unplugged", and replugging is what frees it
  EXPECT_TRUE(Contains(message, "(emu:0) was lost at ")) << message;
  EXPECT_FALSE(Contains(message, "unplugged at")) << message;
  EXPECT_TRUE(Contains(message, "Unplug it, plug it back in and start again")) << message;
  const ServoStats stats = loop.CalcStats();
  EXPECT_LT(stats.tick_max_us, 20000.0);  // no tick waited for USB (it was 5 s)
  EXPECT_GT(stats.ticks, 650u);           // ticks went on through the stall
  std::vector<TraceSample> trace;
  loop.DrainTrace(&trace);
  ASSERT_FALSE(trace.empty());
  int zero_after_stall = 0;
  for (const auto& s : trace) {
    if (s.time_s > trace.back().time_s - 0.2) {  // well inside the stall
      EXPECT_EQ(Norm(s.force_n), 0.0) << s.time_s;
      ++zero_after_stall;
    }
  }
  EXPECT_GT(zero_after_stall, 100);
  auto t = std::chrono::steady_clock::now();
  loop.Stop();
  device.reset();
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count(), 0.5);
}

TEST_F(HidServoRealTime, StopDuringAStuckWriteReturnsWithinItsBound) {
  FirmwareConfig c = PressingDevice();
  c.faults.push_back(FaultWindow{Fault::kSlowWrite, 0.3, 1e9, 5.0});
  const int id = hidemu::AddDevice(c);
  auto device = HidDevice::Open(c.path);
  ServoLoop loop(*device, Box());
  loop.Start();
  while (hidemu::BlockedWrites() == 0 && loop.running()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(50));  // stuck, not yet given up
  EXPECT_TRUE(loop.running());
  const auto t = std::chrono::steady_clock::now();
  loop.Stop();
  const double stop_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  EXPECT_LT(stop_s, HidDevice::kEndSessionWaitS + 0.2) << stop_s;
  EXPECT_EQ(loop.session_end(), SessionEnd::kStopped);
  const auto d = std::chrono::steady_clock::now();
  device.reset();
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - d).count(),
            HidOutputWriter::kAbandonAfterS + 0.2);
  EXPECT_TRUE(hidemu::GetSnapshot(id).session_open);  // the close waits behind the write
}

TEST_F(HidServoRealTime, RunsAndEndsTheSessionWhenUnplugged) {
  FirmwareConfig c = PressingDevice();
  const int id = hidemu::AddDevice(c);
  auto device = HidDevice::Open(c.path);
  ServoLoop loop(*device, Box());
  loop.Start();
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  EXPECT_TRUE(loop.running());
  hidemu::Unplug(id);
  for (int i = 0; i < 200 && loop.running(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_FALSE(loop.running());
  EXPECT_EQ(loop.session_end(), SessionEnd::kUnplugged);
  const std::string message = loop.fault_message();
  EXPECT_TRUE(Contains(message,
                       "The session ended: the haptic device 'HaptiCAD emulated 3-DOF "
                       "device' (emu:0) was unplugged at "))
      << message;
  EXPECT_TRUE(Contains(message, "device disconnected")) << message;
  EXPECT_TRUE(Contains(message, "your document is unchanged")) << message;
  std::vector<TraceSample> trace;
  loop.DrainTrace(&trace);
  ASSERT_GT(trace.size(), 100u);
  EXPECT_TRUE(trace.back().flags & kFaultUnplugged);
  EXPECT_EQ(Norm(trace.back().force_n), 0.0);
  EXPECT_GT(device->CalcLinkStats().reports_used, 100u);
  loop.Stop();  // joins quietly
  EXPECT_EQ(loop.session_end(), SessionEnd::kUnplugged);
  EXPECT_THROW(loop.Start(), DeviceError);  // no new session on a device that is gone
  EXPECT_FALSE(loop.running());
}

}  // namespace
}  // namespace hapticad
