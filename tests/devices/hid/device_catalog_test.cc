// SPDX-License-Identifier: GPL-3.0-or-later
// ListDevices and OpenDevice against the hidapi emulator (hid_emulator.h), on its
// manual clock: the simulated hand is always there, and HID devices are what the test
// plugs in (none, on a host without HaptiCAD hardware, is a case of its own).
#include "hapticad/devices/device_catalog.h"

#include <chrono>
#include <future>
#include <limits>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "hid_emulator.h"

namespace hapticad {
namespace {

using hidemu::Fault;
using hidemu::FaultWindow;
using hidemu::FirmwareConfig;

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

class Catalog : public ::testing::Test {
 protected:
  void SetUp() override {
    hidemu::Reset();
    hidemu::UseManualClock(100.0);
  }
  void TearDown() override { hidemu::Reset(); }
};

TEST_F(Catalog, ListsTheSimulatedHandThenEachDeviceWithItsLimitsOrWhyNot) {
  const int good = hidemu::AddDevice(FirmwareConfig{});
  FirmwareConfig newer;
  newer.path = "emu:1";
  newer.version_min = 0x0200;
  newer.version_max = 0x0201;
  hidemu::AddDevice(newer);
  const auto list = ListDevices();
  ASSERT_EQ(list.size(), 3u);
  EXPECT_EQ(list[0].info.kind, "sim");
  EXPECT_EQ(list[0].info.path, "sim:hand");
  EXPECT_TRUE(list[0].has_limits);
  EXPECT_EQ(list[1].info.kind, "hid");
  EXPECT_EQ(list[1].info.path, "emu:0");
  EXPECT_TRUE(list[1].has_limits);
  EXPECT_DOUBLE_EQ(list[1].info.limits.max_force_n, 8.0);
  EXPECT_DOUBLE_EQ(list[1].info.limits.workspace_max_d.z(), 0.08);
  EXPECT_EQ(list[1].protocol, "1.0-1.0");
  EXPECT_EQ(list[1].error, "");
  EXPECT_FALSE(list[2].has_limits);
  EXPECT_TRUE(Contains(list[2].error, "speaks HaptiCAD HID protocol 2.0-2.1")) << list[2].error;
  // listing changes nothing on a device (another program may be using it)
  EXPECT_FALSE(hidemu::GetSnapshot(good).session_open);
  EXPECT_EQ(hidemu::GetSnapshot(good).version, 0);
}

// On the manual clock a request the device does not answer blocks until the test moves
// the clock: a listing that waited for it would never come back.
TEST_F(Catalog, ADeviceThatDoesNotAnswerIsListedAsSuchAndHoldsUpNothing) {
  FirmwareConfig mute;
  mute.faults.push_back(
      FaultWindow{Fault::kSlowFeature, 0.0, std::numeric_limits<double>::infinity(), 5.0});
  hidemu::AddDevice(mute);  // emu:0
  FirmwareConfig good;
  good.path = "emu:1";
  hidemu::AddDevice(good);
  auto listing = std::async(std::launch::async, [] { return ListDevices(); });
  const bool came = listing.wait_for(std::chrono::seconds(30)) == std::future_status::ready;
  if (!came) hidemu::SetTime(200.0);  // lets the request time out, so the test ends
  ASSERT_TRUE(came) << "ListDevices waited for a device that does not answer";
  const auto list = listing.get();
  ASSERT_EQ(list.size(), 3u);
  EXPECT_EQ(list[1].info.path, "emu:0");
  EXPECT_FALSE(list[1].has_limits);
  EXPECT_TRUE(
      Contains(list[1].error, "did not answer its device information request within 500 ms"))
      << list[1].error;
  EXPECT_EQ(list[2].info.path, "emu:1");  // the device after it is read as ever
  EXPECT_TRUE(list[2].has_limits) << list[2].error;
  EXPECT_DOUBLE_EQ(list[2].info.limits.max_force_n, 8.0);
  // the probe still waits on emu:0; when the request times out it closes the device
  EXPECT_EQ(hidemu::OpenHandles("emu:0"), 1);
  // a listing meanwhile does not ask it again (another handle, another thread, another wait)
  auto again = std::async(std::launch::async, [] { return ListDevices(); });
  const bool came_again = again.wait_for(std::chrono::seconds(30)) == std::future_status::ready;
  if (!came_again) hidemu::SetTime(200.0);
  ASSERT_TRUE(came_again);
  const auto second = again.get();
  ASSERT_EQ(second.size(), 3u);
  EXPECT_TRUE(Contains(second[1].error, "an earlier request is still waiting")) << second[1].error;
  EXPECT_TRUE(second[2].has_limits);
  EXPECT_EQ(hidemu::OpenHandles("emu:0"), 1);
  hidemu::SetTime(106.0);
  for (int i = 0; i < 1000 && hidemu::OpenHandles("emu:0") != 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_EQ(hidemu::OpenHandles("emu:0"), 0);
}

// Devices that do not answer are waited for together: three of them hold a listing up
// one kProbeWaitS (0.5 s), where one after the other they held it up 1.5 s.
TEST_F(Catalog, DevicesThatDoNotAnswerAreWaitedForTogetherNotEachInTurn) {
  for (int i = 0; i < 3; ++i) {
    FirmwareConfig mute;
    mute.path = "emu:mute" + std::to_string(i);
    mute.faults.push_back(
        FaultWindow{Fault::kSlowFeature, 0.0, std::numeric_limits<double>::infinity(), 5.0});
    hidemu::AddDevice(mute);
  }
  FirmwareConfig good;
  good.path = "emu:good";
  hidemu::AddDevice(good);
  const auto began = std::chrono::steady_clock::now();
  auto listing = std::async(std::launch::async, [] { return ListDevices(); });
  const bool came = listing.wait_for(std::chrono::seconds(30)) == std::future_status::ready;
  const double took_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  hidemu::SetTime(200.0);  // the requests time out on the emulator's clock: the probes end
  ASSERT_TRUE(came);
  const auto list = listing.get();
  ASSERT_EQ(list.size(), 5u);
  for (std::size_t i = 1; i < 4; ++i) {
    EXPECT_TRUE(Contains(list[i].error, "did not answer its device information request"))
        << list[i].error;
  }
  EXPECT_TRUE(list[4].has_limits) << list[4].error;
  EXPECT_GE(took_s, kProbeWaitS);  // it did wait for them
  // one wait, not three: 2x kProbeWaitS of margin for a loaded machine, below the 3x of turns
  EXPECT_LT(took_s, 2.0 * kProbeWaitS) << "the devices were waited for one after the other";
  for (int i = 0; i < 1000 && hidemu::OpenHandles("emu:mute0") + hidemu::OpenHandles("emu:mute1") +
                                      hidemu::OpenHandles("emu:mute2") !=
                                  0;
       ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  for (int i = 0; i < 3; ++i)
    EXPECT_EQ(hidemu::OpenHandles("emu:mute" + std::to_string(i)), 0) << i;
}

TEST_F(Catalog, WithoutHidDevicesOnlyTheSimulatedHandIsListed) {
  for (const bool keyboard : {false, true}) {  // nothing plugged in; only a keyboard
    if (keyboard) hidemu::AddOtherDevice("emu:kbd", 0x046d, 0xc31c, 0x0001, 0x0006, "Keyboard");
    const auto list = ListDevices();
    ASSERT_EQ(list.size(), 1u) << keyboard;
    EXPECT_EQ(list[0].info.kind, "sim");
    EXPECT_EQ(list[0].info.path, "sim:hand");
    EXPECT_TRUE(list[0].has_limits);
    EXPECT_GT(list[0].info.limits.max_force_n, 0.0);
    EXPECT_EQ(list[0].protocol, "");
    EXPECT_EQ(list[0].error, "");
  }
}

TEST_F(Catalog, ADeviceThatCannotBeReadIsListedByItsProductOrAPlainName) {
  // HID interfaces of the known VID:PID that do not answer the information request
  hidemu::AddOtherDevice("emu:mute", 0x1209, 0x0001, 0x0001, 0x0006, "Prototype arm");
  hidemu::AddOtherDevice("emu:nameless", 0x1209, 0x0001, 0x0001, 0x0006, "");
  const auto list = ListDevices();
  ASSERT_EQ(list.size(), 3u);
  for (std::size_t i = 1; i < 3; ++i) {
    EXPECT_EQ(list[i].info.kind, "hid") << i;
    EXPECT_FALSE(list[i].has_limits) << i;
    EXPECT_EQ(list[i].protocol, "") << i;
    EXPECT_TRUE(Contains(list[i].error, "did not answer the HaptiCAD device information request"))
        << list[i].error;
    EXPECT_TRUE(Contains(list[i].error, list[i].info.path)) << list[i].error;
  }
  EXPECT_EQ(list[1].info.path, "emu:mute");
  EXPECT_EQ(list[1].info.name, "Prototype arm");
  EXPECT_EQ(list[2].info.path, "emu:nameless");
  EXPECT_EQ(list[2].info.name, "HaptiCAD protocol device");
}

TEST_F(Catalog, SaysTheProtocolVersionsADeviceSpeaks) {
  FirmwareConfig c;
  c.product = "Arm";
  c.version_min = 0x0100;
  c.version_max = 0x0102;
  hidemu::AddDevice(c);
  const auto list = ListDevices();
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[1].protocol, "1.0-1.2");
  EXPECT_EQ(list[1].info.name, "Arm");  // the name the device gives
}

TEST_F(Catalog, OpensWhatAListingNames) {
  hidemu::AddDevice(FirmwareConfig{});
  const auto list = ListDevices();
  ASSERT_EQ(list.size(), 2u);
  for (const DeviceListing& listing : list) {
    const auto device = OpenDevice(listing.info.path);
    EXPECT_EQ(device->info().kind, listing.info.kind);
    EXPECT_EQ(device->info().path, listing.info.path);
    EXPECT_EQ(device->info().name, listing.info.name);
    EXPECT_DOUBLE_EQ(device->info().limits.max_force_n, listing.info.limits.max_force_n);
  }
  // an unknown simulated device names the one there is; a HID path that is not there
  // says it cannot be opened
  try {
    OpenDevice("sim:nothing");
    ADD_FAILURE() << "opened sim:nothing";
  } catch (const DeviceError& e) {
    EXPECT_EQ(std::string(e.what()), "unknown simulated device 'sim:nothing' (there is sim:hand)");
  }
  try {
    OpenDevice("emu:gone");
    ADD_FAILURE() << "opened emu:gone";
  } catch (const DeviceError& e) {
    EXPECT_TRUE(Contains(e.what(), "cannot open the HID device emu:gone")) << e.what();
  }
}

// hidapi's global state (one error string, freed and replaced with no lock) is not
// thread-safe, and HaptiCAD calls into it from several threads: ListDevices' probe threads,
// and the workbench's worker opening a device while its panel lists devices. With each
// global call made slow, they overlap unless the backend makes them take turns.
TEST_F(Catalog, ListingWhileOpeningOnAnotherThreadTakesTurnsInHidapisGlobalState) {
  for (int i = 0; i < 3; ++i) {
    FirmwareConfig c;
    c.path = "emu:" + std::to_string(i);
    hidemu::AddDevice(c);
  }
  FirmwareConfig denied;  // a failed open reads hidapi's global error, then enumerates
  denied.path = "emu:denied";
  denied.deny_open = true;
  hidemu::AddDevice(denied);
  hidemu::SetGlobalCallDelay(0.002);
  for (int round = 0; round < 10; ++round) {
    auto listing = std::async(std::launch::async, [] { return ListDevices(); });
    const auto device = OpenDevice("emu:" + std::to_string(round % 3));
    EXPECT_EQ(device->info().path, "emu:" + std::to_string(round % 3));
    try {
      OpenDevice("emu:denied");
      ADD_FAILURE() << "opened emu:denied";
    } catch (const DeviceError& e) {
      EXPECT_TRUE(Contains(e.what(), "Permission denied")) << e.what();
    }
    const auto list = listing.get();
    ASSERT_EQ(list.size(), 5u);
    for (std::size_t i = 1; i < 4; ++i) EXPECT_TRUE(list[i].has_limits) << list[i].error;
    EXPECT_TRUE(Contains(list[4].error, "Permission denied")) << list[4].error;
  }
  EXPECT_EQ(hidemu::MaxConcurrentGlobalCalls(), 1)
      << "threads were inside hidapi's global state (hid_init, hid_enumerate, hid_open_path, "
         "hid_error(NULL)) at once";
}

}  // namespace
}  // namespace hapticad
