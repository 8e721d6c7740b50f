// SPDX-License-Identifier: GPL-3.0-or-later
// The shipped HID backend against the hidapi emulator, on the emulator's manual clock:
// every report, fault and answer is deterministic.
#include "hapticad/devices/hid/hid_device.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "alloc_counter.h"
#include "hapticad/devices/hid/hid_device_finder.h"
#include "hid_emulator.h"
#include "thread_stall.h"

namespace hapticad {
namespace {

using hidemu::Fault;
using hidemu::FaultWindow;
using hidemu::FirmwareConfig;

constexpr double kPlugTime = 100.0;  // emulator clock when the devices are plugged in

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

class HidOnEmulator : public ::testing::Test {
 protected:
  void SetUp() override {
    hidemu::Reset();
    hidemu::UseManualClock(kPlugTime);
  }
  void TearDown() override { hidemu::Reset(); }

  // Reads at loop time t (the emulator's clock follows), then writes `force` (and waits
  // for the device's writer thread to have written it before the clock moves on).
  ReadStatus Tick(HidDevice& d, double t, DeviceState* s, const Vec3& force = Vec3::Zero()) {
    hidemu::SetTime(kPlugTime + t);
    const ReadStatus status = d.ReadState(t, s);
    d.WriteForce(force);
    d.WaitUntilWritten();
    return status;
  }

  // Plugs in a device made by `c`, opens it on the emulator's clock and begins a session.
  static std::unique_ptr<HidDevice> OpenInSession(const FirmwareConfig& c) {
    hidemu::AddDevice(c);
    auto d = HidDevice::Open(c.path);
    d->set_clock(&hidemu::Now);
    d->BeginSession();
    return d;
  }

  std::string OpenError(const FirmwareConfig& c) {
    hidemu::AddDevice(c);
    try {
      HidDevice::Open(c.path);
    } catch (const DeviceError& e) {
      return e.what();
    }
    return "";
  }
};

TEST_F(HidOnEmulator, OpensNegotiatesAndRunsASession) {
  const int id = hidemu::AddDevice(FirmwareConfig{});
  auto d = HidDevice::Open("emu:0");
  d->set_clock(&hidemu::Now);
  EXPECT_EQ(d->info().kind, "hid");
  EXPECT_EQ(d->info().name, "HaptiCAD emulated 3-DOF device");
  EXPECT_DOUBLE_EQ(d->info().limits.max_stiffness_n_per_m, 2500.0);
  EXPECT_DOUBLE_EQ(d->info().limits.position_resolution_m, 10e-6);
  EXPECT_EQ(hidemu::GetSnapshot(id).version, 0x0100);
  EXPECT_FALSE(hidemu::GetSnapshot(id).session_open);
  d->BeginSession();
  EXPECT_TRUE(hidemu::GetSnapshot(id).session_open);
  d->EndSession();
  EXPECT_FALSE(hidemu::GetSnapshot(id).session_open);
}

TEST_F(HidOnEmulator, AWriterOnlySlowToBeScheduledDoesNotMakeADeviceRefuseASession) {
  // the writer kept from running 0.3 s before a session, outside hidapi: BeginSession()
  // waited 0.1 s for it and threw "is not taking commands: a write to it has waited 0.0 s"
  const int id = hidemu::AddDevice(FirmwareConfig{});
  auto d = HidDevice::Open("emu:0");
  d->set_clock(&hidemu::Now);
  ASSERT_GE(testing_stall::StallThreads("hid-writer", 0.3), 1);
  EXPECT_NO_THROW(d->BeginSession());
  EXPECT_TRUE(hidemu::GetSnapshot(id).session_open);
  ASSERT_GE(testing_stall::StallThreads("hid-writer", 0.3), 1);
  d->EndSession();  // waits for the close to reach the device
  EXPECT_FALSE(hidemu::GetSnapshot(id).session_open);
}

TEST_F(HidOnEmulator, RefusesAWrongProtocolVersionSayingWhatToUpdate) {
  FirmwareConfig newer;
  newer.version_min = 0x0200;
  newer.version_max = 0x0203;
  EXPECT_EQ(OpenError(newer),
            "cannot use the HID device emu:0: it speaks HaptiCAD HID protocol 2.0-2.3 and this "
            "HaptiCAD speaks 1.0; update HaptiCAD");
  FirmwareConfig older;
  older.path = "emu:old";
  older.version_min = older.version_max = 0x0009;
  EXPECT_TRUE(Contains(OpenError(older), "update the device's firmware"));
  // a device that lists 1.0 and then refuses it at negotiation: what it answered, not "()"
  FirmwareConfig liar;
  liar.path = "emu:liar";
  liar.refuse_sessions = true;
  const std::string refused = OpenError(liar);
  EXPECT_TRUE(Contains(refused,
                       "the HID device emu:liar refused HaptiCAD HID protocol 1.0, which it "
                       "lists (1.0-1.0): it answered version 0 with no session"))
      << refused;
  EXPECT_FALSE(Contains(refused, "()")) << refused;
}

TEST_F(HidOnEmulator, RefusesADeviceThatTakesALongerWatchdogThanAsked) {
  // a firmware with a fixed 1000 ms watchdog answered the host's 5 ms with 1000 and was
  // used as if it cut the force 5 ms after the servo loop stops: it would push for 1 s
  FirmwareConfig slow;
  slow.path = "emu:slow-watchdog";
  slow.fixed_watchdog_ms = 1000;
  const std::string refused = OpenError(slow);
  EXPECT_TRUE(Contains(refused,
                       "it took a watchdog of 1000 ms where 5 ms was asked, so it would go on "
                       "pushing with the last force for 1000 ms after the commands stop"))
      << refused;
  EXPECT_TRUE(Contains(refused, "update it")) << refused;
  // asked for its default (0): its stated 20 ms is what it may take
  FirmwareConfig stated;
  stated.path = "emu:stated";
  stated.fixed_watchdog_ms = 20;
  hidemu::AddDevice(stated);
  EXPECT_NO_THROW(HidDevice::Open(stated.path, 0));
  FirmwareConfig over;
  over.path = "emu:over-default";
  over.fixed_watchdog_ms = 21;
  hidemu::AddDevice(over);
  try {
    HidDevice::Open(over.path, 0);
    ADD_FAILURE() << "a device that took 21 ms where its default says 20 ms was opened";
  } catch (const DeviceError& e) {
    EXPECT_TRUE(Contains(e.what(), "it took a watchdog of 21 ms where 20 ms was asked"))
        << e.what();
  }
}

TEST_F(HidOnEmulator, AShorterWatchdogTheDeviceTookIsTheHostsStallBound) {
  // it drops the force 3 ms after the last command, not the 5 ms asked: the host says
  // zero force from then on too, and says 3 ms
  FirmwareConfig c;
  c.path = "emu:quick-watchdog";
  c.fixed_watchdog_ms = 3;
  c.faults.push_back(FaultWindow{Fault::kSlowWrite, 0.1, 1e9, 5.0});
  auto d = OpenInSession(c);
  DeviceState s;
  std::vector<ReadStatus> status(400, ReadStatus::kNoData);
  for (int i = 0; i < 400; ++i) {
    hidemu::SetTime(kPlugTime + i * 1e-3);
    status[i] = d->ReadState(i * 1e-3, &s);
    d->WriteForce(Vec3(0, 0, 1.0));
    if (i < 100) d->WaitUntilWritten();
    if (i == 100) {  // the writer is now stuck in the first write of the window
      while (hidemu::BlockedWrites() == 0) std::this_thread::yield();
    }
  }
  // (with the 5 ms bound, ticks 104 and 105 were still kOk)
  for (int i = 100; i <= 101; ++i) EXPECT_EQ(status[i], ReadStatus::kOk) << i;
  for (int i = 104; i < 350; ++i) EXPECT_EQ(status[i], ReadStatus::kDeviceFault) << i;
  EXPECT_TRUE(Contains(d->DescribeFault(), "its own watchdog drops the force after 3 ms"))
      << d->DescribeFault();
}

TEST_F(HidOnEmulator, ASessionRequestThatGoesUnansweredIsNotCalledAFirmwareRefusal) {
  // it answers its information report, then not the session request (usbhid gives up on
  // the control transfer): a USB problem to unplug for, not firmware to update
  hidemu::UseRealClock();
  FirmwareConfig c;
  c.path = "emu:mute";
  c.faults.push_back(FaultWindow{Fault::kSlowSession, 0.0, 1e9, 0.02});
  const std::string error = OpenError(c);
  EXPECT_TRUE(Contains(error,
                       "the HID device emu:mute did not answer the HaptiCAD HID protocol 1.0 "
                       "session request: setting the session report failed: Connection timed "
                       "out. Unplug it, plug it in again and open it again"))
      << error;
  EXPECT_FALSE(Contains(error, "update it")) << error;
  EXPECT_FALSE(Contains(error, "refused")) << error;
}

TEST_F(HidOnEmulator, OpensADeviceThatSpeaksOnlyLaterMinorVersionsOfMajorOne) {
  // minor versions are compatible (PROTOCOL.md section 2): a 1.1-1.2 device is asked for
  // 1.1, the 1.x nearest this host's 1.0 (it used to be asked for 1.0, refuse it, and
  // fail to open "although it lists it ()")
  FirmwareConfig c;
  c.version_min = 0x0101;
  c.version_max = 0x0102;
  const int id = hidemu::AddDevice(c);
  EXPECT_EQ(hid::DescribeInfoProblem(HidDevice::Probe("emu:0").report), "");
  std::unique_ptr<HidDevice> d;
  try {
    d = HidDevice::Open("emu:0");
  } catch (const DeviceError& e) {
    FAIL() << e.what();
  }
  EXPECT_EQ(d->protocol_version(), 0x0101);
  EXPECT_EQ(hidemu::GetSnapshot(id).version, 0x0101);
  d->set_clock(&hidemu::Now);
  d->BeginSession();
  EXPECT_TRUE(hidemu::GetSnapshot(id).session_open);
  EXPECT_EQ(hidemu::GetSnapshot(id).version, 0x0101);
  DeviceState s;
  Tick(*d, 0.0, &s);
  for (int i = 1; i <= 50; ++i) ASSERT_EQ(Tick(*d, i * 1e-3, &s), ReadStatus::kOk) << i;
  d->EndSession();
  EXPECT_FALSE(hidemu::GetSnapshot(id).session_open);
  // a device whose range takes in 1.0 is asked for 1.0
  FirmwareConfig wide;
  wide.path = "emu:wide";
  wide.version_min = 0x0005;
  wide.version_max = 0x0103;
  const int wide_id = hidemu::AddDevice(wide);
  EXPECT_EQ(HidDevice::Open("emu:wide")->protocol_version(), 0x0100);
  EXPECT_EQ(hidemu::GetSnapshot(wide_id).version, 0x0100);
}

TEST_F(HidOnEmulator, RefusesDevicesThatAreNotHapticOrStateImpossibleLimits) {
  FirmwareConfig c;
  c.max_force_n = 2000.0;  // (the wire holds up to 4294 N)
  EXPECT_TRUE(Contains(OpenError(c), "impossible maximum force (2000")) << OpenError(c);
  c = FirmwareConfig{};
  c.path = "emu:box";
  c.workspace_max_m.x() = c.workspace_min_m.x();
  EXPECT_TRUE(Contains(OpenError(c), "impossible workspace"));
  c = FirmwareConfig{};
  c.path = "emu:magic";
  c.magic = 0;
  EXPECT_TRUE(Contains(OpenError(c), "does not identify itself as a HaptiCAD protocol device"));
  c = FirmwareConfig{};
  c.path = "emu:6dof";
  c.dof = 6;
  EXPECT_TRUE(Contains(OpenError(c), "6 degrees of freedom"));
  hidemu::AddOtherDevice("emu:keyboard", 0x1209, 0x0001, 1, 6, "Keyboard");
  try {
    HidDevice::Open("emu:keyboard");
    FAIL();
  } catch (const DeviceError& e) {
    EXPECT_TRUE(Contains(e.what(), "probably not a HaptiCAD protocol device")) << e.what();
  }
  try {
    HidDevice::Open("emu:nowhere");
    FAIL();
  } catch (const DeviceError& e) {
    EXPECT_TRUE(Contains(e.what(), "cannot open the HID device emu:nowhere")) << e.what();
  }
}

TEST_F(HidOnEmulator, APermissionErrorSaysWhichUdevRuleLetsThisDeviceIn) {
  // HaptiCAD's rule covers the development ID; a product found by its usage page with a
  // VID:PID of its own is told the rule line with its IDs (the rule would not match it)
  FirmwareConfig prototype;
  prototype.path = "emu:prototype";
  prototype.deny_open = true;
  const std::string listed = OpenError(prototype);
  EXPECT_TRUE(Contains(listed,
                       "cannot open the HID device emu:prototype: Failed to open a device with "
                       "path 'emu:prototype': Permission denied. Install HaptiCAD's udev rule"))
      << listed;
  EXPECT_FALSE(Contains(listed, "70-hapticad-local")) << listed;
  FirmwareConfig product;
  product.path = "emu:product";
  product.vendor_id = 0x16c0;
  product.product_id = 0x05df;
  product.deny_open = true;
  const std::string own = OpenError(product);
  EXPECT_TRUE(Contains(own, "this device is 16c0:05df")) << own;
  EXPECT_TRUE(Contains(own, "ATTRS{idVendor}==\"16c0\", ATTRS{idProduct}==\"05df\"")) << own;
  EXPECT_FALSE(Contains(own, "Install HaptiCAD's udev rule")) << own;
  // a listing (Probe) says the same
  try {
    HidDevice::Probe("emu:product");
    FAIL();
  } catch (const DeviceError& e) {
    EXPECT_EQ(std::string(e.what()), own);
  }
}

TEST_F(HidOnEmulator, AnInterruptedReadIsNoDataForThatTickNotAnUnplug) {
  // a signal reaching the servo thread during hidapi's poll() (EINTR) used to end the
  // session as "unplugged"; the device is fine: that tick just has no new report
  FirmwareConfig c;
  c.faults.push_back(FaultWindow{Fault::kInterruptRead, 0.1, 0.1005});
  auto d = OpenInSession(c);
  DeviceState s;
  Tick(*d, 0.0, &s);
  for (int i = 1; i < 200; ++i) {
    ASSERT_EQ(Tick(*d, i * 1e-3, &s), ReadStatus::kOk) << i;
    if (i == 100) {
      EXPECT_NEAR(s.age_s, 0.001, 1e-9);  // the last report, a tick old
    } else if (i == 101) {
      EXPECT_EQ(s.age_s, 0.0);  // both reports read: none lost
    }
  }
  EXPECT_FALSE(d->unplugged());
  const HidLinkStats link = d->CalcLinkStats();
  EXPECT_EQ(link.reads_interrupted, 1u);
  EXPECT_EQ(link.reports_used, 199u);
  EXPECT_EQ(d->DescribeFault(), "");
  // a real unplug after it is still one, at once
  hidemu::Unplug(0);
  EXPECT_EQ(Tick(*d, 0.2, &s), ReadStatus::kUnplugged);
  EXPECT_TRUE(Contains(d->DescribeFault(), "device disconnected")) << d->DescribeFault();
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

TEST_F(HidOnEmulator, ACommandStuckInTheUsbStackIsAFaultThenALostDeviceAndNothingWaitsForIt) {
  // from 0.1 s every write blocks 5 s and times out, as usbhid's does when the device
  // stops taking output reports; the tick never waits for it
  FirmwareConfig c;
  c.path = "emu:stuck";
  c.faults.push_back(FaultWindow{Fault::kSlowWrite, 0.1, 1e9, 5.0});
  hidemu::AddDevice(c);
  auto d = HidDevice::Open(c.path);           // device watchdog 5 ms: the stall limit
  EXPECT_EQ(hidemu::OpenHandles(c.path), 2);  // the loop's reads, the writer's writes
  d->set_clock(&hidemu::Now);
  d->BeginSession();
  DeviceState s;
  for (int i = 0; i < 100; ++i) Tick(*d, i * 1e-3, &s, Vec3(0, 0, 1.0));
  std::vector<ReadStatus> status(400, ReadStatus::kNoData);
  double slowest_tick_s = 0.0;
  for (int i = 100; i < 400; ++i) {
    hidemu::SetTime(kPlugTime + i * 1e-3);
    const auto start = std::chrono::steady_clock::now();
    status[i] = d->ReadState(i * 1e-3, &s);
    d->WriteForce(Vec3(0, 0, 1.0));
    slowest_tick_s = std::max(slowest_tick_s, SecondsSince(start));
    if (i == 100) {  // the writer is now stuck in the first write of the window
      while (hidemu::BlockedWrites() == 0) std::this_thread::yield();
    }
  }
  EXPECT_LT(slowest_tick_s, 0.05);  // (the blocked write would hold a synchronous tick forever)
  for (int i = 100; i <= 103; ++i) EXPECT_EQ(status[i], ReadStatus::kOk) << i;
  // a command over the device's 5 ms watchdog: zero force (the device has dropped it too)
  for (int i = 107; i < 350; ++i) EXPECT_EQ(status[i], ReadStatus::kDeviceFault) << i;
  // 250 ms: the device stopped taking commands; lost for good
  const int lost_at = static_cast<int>(
      std::find(status.begin(), status.end(), ReadStatus::kUnplugged) - status.begin());
  EXPECT_GE(lost_at, 350);
  EXPECT_LE(lost_at, 351);
  for (int i = lost_at; i < 400; ++i) EXPECT_EQ(status[i], ReadStatus::kUnplugged) << i;
  EXPECT_TRUE(d->unplugged());
  const HidLinkStats link = d->CalcLinkStats();
  EXPECT_GE(link.commands_late_ticks, 243u);
  EXPECT_LE(link.commands_late_ticks, 245u);
  EXPECT_EQ(hidemu::BlockedWrites(), 1);
  EXPECT_EQ(d->DescribeFault(),
            "it stopped taking force commands: one waited 250 ms in the USB stack without "
            "being sent (the write to the device did not return); its own watchdog drops the "
            "force after 5 ms");
  // ending the session and closing the device do not wait for the stuck write
  auto start = std::chrono::steady_clock::now();
  d->EndSession();
  EXPECT_LT(SecondsSince(start), HidDevice::kEndSessionWaitS + 0.5);
  EXPECT_THROW(d->BeginSession(), DeviceError);
  start = std::chrono::steady_clock::now();
  d.reset();
  EXPECT_LT(SecondsSince(start), HidOutputWriter::kAbandonAfterS + 0.5);
  // the abandoned writer keeps its handle until its write returns (here: the device goes)
  EXPECT_EQ(hidemu::OpenHandles(c.path), 1);
  hidemu::Reset();
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (hidemu::OpenHandles(c.path) != 0 && std::chrono::steady_clock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_EQ(hidemu::OpenHandles(c.path), 0);
}

TEST_F(HidOnEmulator, ANewSessionWaitsForTheLastOnesStuckWriteOnlySoLong) {
  FirmwareConfig c;
  c.faults.push_back(FaultWindow{Fault::kSlowWrite, 0.1, 0.2, 5.0});
  const int id = hidemu::AddDevice(c);
  auto d = HidDevice::Open("emu:0");
  d->set_clock(&hidemu::Now);
  d->BeginSession();
  DeviceState s;
  for (int i = 0; i < 100; ++i) Tick(*d, i * 1e-3, &s, Vec3(0, 0, 1.0));
  hidemu::SetTime(kPlugTime + 0.1);
  d->ReadState(0.1, &s);
  d->WriteForce(Vec3(0, 0, 1.0));
  while (hidemu::BlockedWrites() == 0) std::this_thread::yield();
  d->EndSession();  // the close waits behind the stuck write
  EXPECT_TRUE(hidemu::GetSnapshot(id).session_open);
  try {
    d->BeginSession();
    FAIL();
  } catch (const DeviceError& e) {
    EXPECT_TRUE(Contains(e.what(), "emu:0 is not taking commands: a write to it has waited"))
        << e.what();
  }
  // the write times out at 5.1 s; then the close goes out, and a session can begin
  hidemu::SetTime(kPlugTime + 5.2);
  ASSERT_TRUE(d->WaitUntilWritten(5.0));
  d->BeginSession();
  EXPECT_TRUE(hidemu::GetSnapshot(id).session_open);
  EXPECT_EQ(hidemu::GetSnapshot(id).outputs_timed_out, 1u);
}

TEST_F(HidOnEmulator, ReadsPositionsAndVelocityOnTheDeviceClock) {
  FirmwareConfig c;
  c.hand_times_s = {0.0, 0.2, 1.2};  // the hand sweeps x at 40 mm/s after 0.2 s
  c.hand_positions_m = {Vec3(-0.02, 0, 0), Vec3(-0.02, 0, 0), Vec3(0.02, 0, 0)};
  const int id = hidemu::AddDevice(c);
  auto d = HidDevice::Open("emu:0");
  d->set_clock(&hidemu::Now);
  d->BeginSession();
  DeviceState s;
  // report 0 was sent at plug-in, before the session: flushed, so no data yet
  EXPECT_EQ(Tick(*d, 0.0, &s), ReadStatus::kNoData);
  for (int i = 1; i <= 700; ++i) ASSERT_EQ(Tick(*d, i * 1e-3, &s), ReadStatus::kOk) << i;
  const hidemu::Snapshot truth = hidemu::GetSnapshot(id);
  EXPECT_NEAR((s.position_d - truth.position_m).norm(), 0.0, 10e-6);  // one encoder step
  EXPECT_NEAR(s.velocity_d.x(), truth.velocity_m.x(), 2e-3);
  EXPECT_NEAR(s.velocity_d.x(), 0.04, 3e-3);
  EXPECT_NEAR(s.time_s, 0.699, 1e-9);  // the device's clock since the session's first report
  EXPECT_EQ(s.age_s, 0.0);
  const HidLinkStats link = d->CalcLinkStats();
  EXPECT_EQ(link.reports_used, 700u);
  EXPECT_EQ(link.malformed + link.not_newer + link.dropped, 0u);
}

TEST_F(HidOnEmulator, TheDeviceAppliesTheForceClampedToItsMaximum) {
  const int id = hidemu::AddDevice(FirmwareConfig{});
  auto d = HidDevice::Open("emu:0");
  d->set_clock(&hidemu::Now);
  d->BeginSession();
  DeviceState s;
  Tick(*d, 0.0, &s, Vec3(1.0, -2.0, 0.5));
  Tick(*d, 0.001, &s, Vec3(1.0, -2.0, 0.5));
  hidemu::Snapshot snap = hidemu::GetSnapshot(id);
  EXPECT_NEAR((snap.applied_force_n - Vec3(1.0, -2.0, 0.5)).norm(), 0.0, 1e-6);
  Tick(*d, 0.002, &s, Vec3(0, 0, 20.0));
  Tick(*d, 0.003, &s, Vec3(0, 0, 20.0));
  snap = hidemu::GetSnapshot(id);
  EXPECT_NEAR(snap.applied_force_n.z(), 8.0, 1e-9);  // the device's own clamp
  EXPECT_EQ(snap.outputs_rejected, 0u);
  d->EndSession();  // zero force, session closed
  hidemu::SetTime(kPlugTime + 0.004);
  snap = hidemu::GetSnapshot(id);
  EXPECT_EQ(snap.applied_force_n, Vec3::Zero());
  EXPECT_FALSE(snap.session_open);
}

TEST_F(HidOnEmulator, TheDeviceWatchdogZeroesTheForceWhenTheHostFallsSilent) {
  const int id = hidemu::AddDevice(FirmwareConfig{});
  auto d = HidDevice::Open("emu:0");  // asks the device for a 5 ms watchdog
  d->set_clock(&hidemu::Now);
  d->BeginSession();
  DeviceState s;
  for (int i = 0; i <= 10; ++i) Tick(*d, i * 1e-3, &s, Vec3(0, 0, 1.0));
  hidemu::SetTime(kPlugTime + 0.0149);  // 4.9 ms without a command
  EXPECT_NEAR(hidemu::GetSnapshot(id).applied_force_n.z(), 1.0, 1e-9);
  hidemu::SetTime(kPlugTime + 0.0152);  // 5.2 ms
  const hidemu::Snapshot snap = hidemu::GetSnapshot(id);
  EXPECT_EQ(snap.applied_force_n, Vec3::Zero());
  EXPECT_TRUE(snap.watchdog_tripped);
  EXPECT_EQ(snap.watchdog_trips, 1u);
  hidemu::SetTime(kPlugTime + 0.0162);  // the next report says so
  EXPECT_EQ(d->ReadState(0.0162, &s), ReadStatus::kDeviceFault);
  const HidLinkStats link = d->CalcLinkStats();
  EXPECT_GT(link.watchdog_reports, 0u);                  // the host is told, too
  EXPECT_EQ(link.device_faults, link.watchdog_reports);  // each counted once as a fault
}

TEST_F(HidOnEmulator, ASecondSessionOnADeviceLeftPluggedInHasItsForceAtOnce) {
  // Each Feel session opens the device anew. Its sequences started again at 1 while the
  // device remembered the last session's: it ignored every command for 3 s, the host
  // none the wiser, then the force jumped in from zero.
  const int id = hidemu::AddDevice(FirmwareConfig{});
  DeviceState s;
  double t = 0.0;
  for (int session = 0; session < 2; ++session) {
    hidemu::SetTime(kPlugTime + t);  // the time between: the device reports on
    auto d = HidDevice::Open("emu:0");
    d->set_clock(&hidemu::Now);
    d->BeginSession();
    const hidemu::Snapshot before = hidemu::GetSnapshot(id);
    for (int i = 0; i < 3000; ++i, t += 1e-3) {
      const ReadStatus status = Tick(*d, t, &s, Vec3(0, 0, 1.0));
      if (i > 2) {
        ASSERT_EQ(status, ReadStatus::kOk) << "session " << session << " tick " << i;
      }
    }
    const hidemu::Snapshot after = hidemu::GetSnapshot(id);
    EXPECT_NEAR(after.applied_force_n.z(), 1.0, 1e-9) << session;
    EXPECT_EQ(after.outputs_rejected, before.outputs_rejected) << session;
    EXPECT_GE(after.outputs_applied - before.outputs_applied, 2999u)
        << session;  // the last in flight
    d->EndSession();
    t += 0.5;
  }
}

TEST_F(HidOnEmulator, CommandsTheDeviceIgnoresAreAFaultAndSaidSo) {
  // A firmware that does not echo what it applied (offset 26 reads 0 when the second
  // session begins): the host cannot go on from the device's last sequence, its commands
  // are older, and the device applies none. Zero force after kCommandsIgnoredS, said.
  FirmwareConfig c;
  c.faults.push_back(FaultWindow{Fault::kZeroEcho, 2.01, 2.7});
  const int id = hidemu::AddDevice(c);
  DeviceState s;
  {
    auto first = HidDevice::Open("emu:0");
    first->set_clock(&hidemu::Now);
    first->BeginSession();
    for (int i = 0; i < 2000; ++i) Tick(*first, i * 1e-3, &s, Vec3(0, 0, 1.0));
    first->EndSession();
  }
  hidemu::SetTime(kPlugTime + 2.5);
  auto d = HidDevice::Open("emu:0");
  d->set_clock(&hidemu::Now);
  d->BeginSession();
  const hidemu::Snapshot before = hidemu::GetSnapshot(id);
  std::vector<ReadStatus> status;
  for (int i = 0; i < 300; ++i) status.push_back(Tick(*d, 2.5 + i * 1e-3, &s, Vec3(0, 0, 1.0)));
  const hidemu::Snapshot after = hidemu::GetSnapshot(id);
  EXPECT_EQ(after.outputs_applied, before.outputs_applied);  // the device took none
  EXPECT_EQ(after.applied_force_n, Vec3::Zero());
  // kOk while it may still be the link's delay; then a fault, also once the device's
  // echo (2001, the last session's close) comes back at 2.7 s: it is no command of this one
  // (the reports the host reads first are the oldest queued, from 2.0 s: hidraw keeps those)
  EXPECT_EQ(status[40], ReadStatus::kOk);
  for (int i = 52; i < 300; ++i) ASSERT_EQ(status[i], ReadStatus::kDeviceFault) << i;
  EXPECT_GT(d->CalcLinkStats().commands_ignored_ticks, 240u);
  EXPECT_TRUE(
      Contains(d->DescribeFault(), "the device applied none of the force commands sent in 50 ms"))
      << d->DescribeFault();
}

TEST_F(HidOnEmulator, AFaultBetweenTwoTicksIsThatTicksFault) {
  // a device reporting at 4 kHz whose amplifier faults for 0.6 ms between two ticks: the
  // reports after it were clean, and the tick said kOk, the force back at once
  FirmwareConfig c;
  c.report_rate_hz = 4000;
  c.faults.push_back(FaultWindow{Fault::kDeviceFault, 0.1002, 0.1008});
  auto d = OpenInSession(c);
  DeviceState s;
  std::vector<ReadStatus> status;
  for (int i = 0; i <= 103; ++i) status.push_back(Tick(*d, i * 1e-3, &s, Vec3(0, 0, 0.5)));
  EXPECT_EQ(status[100], ReadStatus::kOk);
  EXPECT_EQ(status[101], ReadStatus::kDeviceFault);  // reads the reports of 100.2-101 ms
  EXPECT_EQ(status[102], ReadStatus::kOk);
  EXPECT_GT(d->CalcLinkStats().device_faults, 0u);
}

// Runs 300 ticks with `window` over [100, 150) ms; returns the statuses and ages.
struct FaultRun {
  std::vector<ReadStatus> status;
  std::vector<double> age_s;
  std::vector<double> speed;
  HidLinkStats link;
  std::string fault;
};

class HidFaults : public HidOnEmulator {
 protected:
  FaultRun Run(Fault fault, double param = 0.0, double end_s = 0.15) {
    FirmwareConfig c;
    c.faults.push_back(FaultWindow{fault, 0.1, end_s, param});
    c.seed = 7;
    hidemu::AddDevice(c);
    auto d = HidDevice::Open("emu:0");
    d->set_clock(&hidemu::Now);
    d->BeginSession();
    FaultRun run;
    DeviceState s;
    for (int i = 0; i < 300; ++i) {
      run.status.push_back(Tick(*d, i * 1e-3, &s, Vec3(0, 0, 0.5)));
      run.age_s.push_back(s.age_s);
      run.speed.push_back(s.velocity_d.norm());
    }
    run.link = d->CalcLinkStats();
    run.fault = d->DescribeFault();
    return run;
  }
  // tick 0 has no data (the report sent at plug-in was flushed): count from tick 1
  static int CountOf(const FaultRun& run, ReadStatus status) {
    return static_cast<int>(std::count(run.status.begin() + 1, run.status.end(), status));
  }
};

TEST_F(HidFaults, TruncatedReportsAreRejectedAndTheDataAges) {
  const FaultRun run = Run(Fault::kTruncate, 10);
  EXPECT_EQ(run.link.malformed, 50u);
  EXPECT_EQ(CountOf(run, ReadStatus::kOk), 299);  // the backend says "ok but old"...
  EXPECT_NEAR(run.age_s[149], 0.050, 1e-9);       // ...and the loop's stale check zeroes it
  EXPECT_EQ(run.age_s[150], 0.0);
  EXPECT_TRUE(Contains(run.fault, "50 malformed")) << run.fault;
}

TEST_F(HidFaults, GarbageNeverBecomesAPosition) {
  const FaultRun run = Run(Fault::kGarbage);
  EXPECT_EQ(run.link.malformed, 50u);  // half had the right ID and length: the CRC caught them
  EXPECT_EQ(run.link.out_of_range, 0u);
  EXPECT_EQ(run.link.reports_used, 249u);
  for (double v : run.speed) EXPECT_LT(v, 0.05);
}

TEST_F(HidFaults, ReorderedReportsNeverGoBackInTime) {
  const FaultRun run = Run(Fault::kReorder);
  EXPECT_EQ(run.link.not_newer, 25u);  // the older of each swapped pair
  EXPECT_EQ(run.link.dropped, 25u);    // seen as a gap when the newer came first
  EXPECT_EQ(CountOf(run, ReadStatus::kOk), 299);
  for (std::size_t i = 1; i < run.age_s.size(); ++i) EXPECT_LE(run.age_s[i], 0.0011) << i;
}

TEST_F(HidFaults, DroppedReportsAreCountedAndTheRestUsed) {
  const FaultRun run = Run(Fault::kDrop, 0.3);
  EXPECT_GT(run.link.dropped, 5u);
  EXPECT_LT(run.link.dropped, 30u);
  EXPECT_EQ(run.link.reports_used + run.link.dropped, 299u);
  EXPECT_EQ(CountOf(run, ReadStatus::kOk), 299);
}

TEST_F(HidFaults, DuplicatedReportsAreUsedOnce) {
  const FaultRun run = Run(Fault::kDuplicate);
  EXPECT_EQ(run.link.not_newer, 50u);
  EXPECT_EQ(run.link.reports_used, 299u);
}

TEST_F(HidFaults, LateReportsShowTheirAge) {
  const FaultRun run = Run(Fault::kLate, 0.02);
  EXPECT_NEAR(run.age_s[119], 0.020, 1e-9);  // nothing newer than 99 ms until 120 ms
  // then each report arrives 20 ms after the device sent it, in order; the reports after
  // the window queue behind the late ones until 169 ms
  for (int i = 120; i < 169; ++i) EXPECT_NEAR(run.age_s[i], 0.020, 0.1e-3) << i;
  for (int i = 169; i < 300; ++i) EXPECT_LT(run.age_s[i], 0.1e-3) << i;
  EXPECT_EQ(run.link.dropped + run.link.malformed, 0u);
}

TEST_F(HidFaults, AStallShowsAsAgeAndResumesWithoutAGap) {
  const FaultRun run = Run(Fault::kStall);
  EXPECT_NEAR(run.age_s[149], 0.050, 1e-9);
  EXPECT_EQ(run.age_s[150], 0.0);
  EXPECT_EQ(run.link.dropped, 0u);
  EXPECT_EQ(run.link.reports_used, 249u);
}

TEST_F(HidFaults, AFrozenDeviceClockIsNotFreshData) {
  const FaultRun run = Run(Fault::kFreezeClock);
  EXPECT_EQ(run.link.not_newer, 49u);  // the first frozen stamp is still newer
  EXPECT_NEAR(run.age_s[149], 0.049, 1e-9);
}

TEST_F(HidFaults, ExtremeValuesAreOutOfRangeAndNeverFiltered) {
  const FaultRun run = Run(Fault::kExtreme);
  EXPECT_EQ(CountOf(run, ReadStatus::kOutOfRange), 50);
  for (int i = 100; i < 150; ++i) EXPECT_EQ(run.status[i], ReadStatus::kOutOfRange) << i;
  EXPECT_EQ(run.link.out_of_range, 50u);
  for (double v : run.speed) EXPECT_LT(v, 0.05);  // 2 m jumps never reached the velocity
}

TEST_F(HidFaults, ADeviceFaultOrMissingCalibrationIsReported) {
  FaultRun run = Run(Fault::kDeviceFault);
  EXPECT_EQ(CountOf(run, ReadStatus::kDeviceFault), 50);
  EXPECT_EQ(run.link.device_faults, 50u);
  hidemu::Reset();
  hidemu::UseManualClock(kPlugTime);
  run = Run(Fault::kNotHomed);
  EXPECT_EQ(CountOf(run, ReadStatus::kDeviceFault), 50);
}

TEST_F(HidFaults, UnplugIsFinalAndSaysWhy) {
  FirmwareConfig c;
  c.faults.push_back(FaultWindow{Fault::kUnplug, 0.1});
  hidemu::AddDevice(c);
  auto d = HidDevice::Open("emu:0");
  d->set_clock(&hidemu::Now);
  d->BeginSession();
  DeviceState s;
  for (int i = 1; i < 100; ++i) ASSERT_EQ(Tick(*d, i * 1e-3, &s), ReadStatus::kOk);
  for (int i = 100; i < 110; ++i) EXPECT_EQ(Tick(*d, i * 1e-3, &s), ReadStatus::kUnplugged);
  EXPECT_TRUE(d->unplugged());
  EXPECT_TRUE(Contains(d->DescribeFault(), "device disconnected")) << d->DescribeFault();
  EXPECT_TRUE(FindHidCandidates().empty());
  d->EndSession();  // must not throw or hang
  try {
    d->BeginSession();
    FAIL();
  } catch (const DeviceError& e) {
    EXPECT_TRUE(Contains(e.what(), "was unplugged")) << e.what();
  }
}

TEST_F(HidOnEmulator, DescribeFaultAsksHidapiNothingAndKeepsTheUnplugReason) {
  // DescribeFault() may be called from any thread while the servo thread reads and
  // writes; hidapi's error text is not thread-safe, so the reason for an unplug is taken
  // on the servo thread when it happens, and DescribeFault() never calls hid_error()
  FirmwareConfig c;
  c.faults.push_back(FaultWindow{Fault::kNotHomed, 0.05, 0.06});
  c.faults.push_back(FaultWindow{Fault::kUnplug, 0.1});
  hidemu::AddDevice(c);
  auto d = HidDevice::Open("emu:0");
  d->set_clock(&hidemu::Now);
  d->BeginSession();
  DeviceState s;
  for (int i = 0; i <= 55; ++i) Tick(*d, i * 1e-3, &s);
  std::uint64_t calls = hidemu::HidErrorCalls();
  EXPECT_TRUE(Contains(d->DescribeFault(), "not calibrated")) << d->DescribeFault();
  for (int i = 56; i < 100; ++i) Tick(*d, i * 1e-3, &s);
  EXPECT_EQ(d->DescribeFault(), "");  // good reports again: no fault to tell
  EXPECT_EQ(hidemu::HidErrorCalls(), calls);
  for (int i = 100; i < 105; ++i) EXPECT_EQ(Tick(*d, i * 1e-3, &s), ReadStatus::kUnplugged);
  calls = hidemu::HidErrorCalls();
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(d->DescribeFault(),
              "hidapi: hid_read_timeout: unexpected poll error (device disconnected)")
        << d->DescribeFault();
  }
  EXPECT_EQ(hidemu::HidErrorCalls(), calls);
  d->EndSession();
  EXPECT_EQ(d->DescribeFault(),
            "hidapi: hid_read_timeout: unexpected poll error (device disconnected)");
}

// The host stalls (a frozen process: nothing reads or writes) while the device reports
// on; hidraw keeps the 64 oldest reports. Returns the statuses of the ticks after it.
struct StallRun {
  std::vector<ReadStatus> status;
  std::vector<double> age_s;
  HidLinkStats before, after;
  std::string fault;
};
StallRun RunAHostStall(int rate_hz, double stall_s) {
  hidemu::Reset();
  hidemu::UseManualClock(kPlugTime);
  FirmwareConfig c;
  c.report_rate_hz = static_cast<std::uint16_t>(rate_hz);
  hidemu::AddDevice(c);
  auto d = HidDevice::Open("emu:0");
  d->set_clock(&hidemu::Now);
  d->BeginSession();
  DeviceState s;
  StallRun run;
  long i = 0;
  for (; i < 1000; ++i) {
    hidemu::SetTime(kPlugTime + i * 1e-3);
    d->ReadState(i * 1e-3, &s);
    d->WriteForce(Vec3(0, 0, 0.5));
    d->WaitUntilWritten();
  }
  run.before = d->CalcLinkStats();
  for (i = std::lround((1.0 + stall_s) * 1000); run.status.size() < 20; ++i) {
    hidemu::SetTime(kPlugTime + i * 1e-3);
    run.status.push_back(d->ReadState(i * 1e-3, &s));
    run.age_s.push_back(s.age_s);
    d->WriteForce(Vec3(0, 0, 0.5));
    d->WaitUntilWritten();
  }
  run.after = d->CalcLinkStats();
  run.fault = d->DescribeFault();
  return run;
}

TEST_F(HidOnEmulator, AfterAHostStallOverHalfTheSequenceRangeTheReportsAreUsedAtOnce) {
  // 20 kHz for 2 s and 1 kHz for 40 s: the 16-bit sequence moves on by more than 32767,
  // which alone would look like going back (it used to reject every healthy report for
  // 1.3 s at 20 kHz, and for 25 s at 1 kHz); the device's 32-bit clock tells
  for (const auto& [rate, stall] : {std::pair<int, double>{20000, 2.0}, {1000, 40.0}}) {
    SCOPED_TRACE(rate);
    const StallRun run = RunAHostStall(rate, stall);
    // the first tick reads the 64 reports queued at the start of the stall: old data (at
    // 1 kHz they also say the device's watchdog tripped)
    EXPECT_TRUE(run.status[0] != ReadStatus::kOk || run.age_s[0] > 1.0) << run.age_s[0];
    // from the next tick on, the reports sent after the stall are fresh data again
    for (std::size_t k = 1; k < run.status.size(); ++k) {
      EXPECT_EQ(run.status[k], ReadStatus::kOk) << k;
      EXPECT_LT(run.age_s[k], 1e-3) << k;
    }
    EXPECT_EQ(run.after.not_newer, run.before.not_newer);
    // the reports lost in the stall are counted (all but the 64 queued)
    const double lost = rate * stall - 64;
    EXPECT_NEAR(static_cast<double>(run.after.dropped - run.before.dropped), lost, 0.001 * lost);
    // and the device's watchdog, over once commands come again, is not said to be on
    EXPECT_FALSE(Contains(run.fault, "watchdog")) << run.fault;
  }
}

TEST_F(HidOnEmulator, ReadAndWriteDoNotAllocate) {
  hidemu::AddDevice(FirmwareConfig{});
  auto d = HidDevice::Open("emu:0");
  d->set_clock(&hidemu::Now);
  d->BeginSession();
  DeviceState s;
  Tick(*d, 0.0, &s);
  testing::AllocationCounter counter;
  for (int i = 1; i < 500; ++i) Tick(*d, i * 1e-3, &s, Vec3(0, 0, 0.2));
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_EQ(d->CalcLinkStats().reports_used, 499u);
}

}  // namespace
}  // namespace hapticad
