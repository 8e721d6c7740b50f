// SPDX-License-Identifier: GPL-3.0-or-later
// FindHidCandidates against the hidapi emulator (hid_emulator.h): hidapi's real C API
// over emulated devices, so what is enumerated is what the test plugs in, and a host
// without HaptiCAD hardware enumerates the same.
#include "hapticad/devices/hid/hid_device_finder.h"

#include <string>

#include <gtest/gtest.h>

#include "hid_emulator.h"

namespace hapticad {
namespace {

using hidemu::FirmwareConfig;

class HidFinder : public ::testing::Test {
 protected:
  void SetUp() override {
    hidemu::Reset();
    hidemu::UseManualClock(100.0);
  }
  void TearDown() override { hidemu::Reset(); }
};

TEST_F(HidFinder, FindsDevicesByUsagePageOrKnownIdAndNothingElse) {
  FirmwareConfig by_usage;
  by_usage.path = "emu:usage";
  by_usage.vendor_id = 0x1234;
  by_usage.product_id = 0x5678;
  hidemu::AddDevice(by_usage);
  FirmwareConfig by_id;
  by_id.path = "emu:id";
  by_id.usage_page = 0;
  by_id.usage = 0;
  hidemu::AddDevice(by_id);
  hidemu::AddOtherDevice("emu:keyboard", 0x046d, 0xc31c, 0x0001, 0x0006, "Keyboard");
  const auto found = FindHidCandidates();
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(found[0].path, "emu:usage");
  EXPECT_EQ(found[1].path, "emu:id");
  EXPECT_EQ(found[0].product, "HaptiCAD emulated 3-DOF device");
}

TEST_F(HidFinder, TheUsagePageAloneOrTheUsageAloneIsNotTheProtocol) {
  // an unknown VID:PID with our vendor page but another usage, or usage 1 of another page
  FirmwareConfig other_usage;
  other_usage.path = "emu:other_usage";
  other_usage.vendor_id = 0x1234;
  other_usage.product_id = 0x5678;
  other_usage.usage = 0x02;
  hidemu::AddDevice(other_usage);
  hidemu::AddOtherDevice("emu:other_page", 0x1234, 0x5679, 0xFF00, 0x01, "Vendor gadget");
  EXPECT_TRUE(FindHidCandidates().empty());
}

TEST_F(HidFinder, NoDeviceIsAnEmptyListNotAnError) {
  // hidapi answers NULL, and says "No HID devices found in the system.", when it finds
  // nothing: that is no HaptiCAD device, not a failure
  std::vector<HidCandidate> found;
  EXPECT_NO_THROW(found = FindHidCandidates());
  EXPECT_TRUE(found.empty());
  hidemu::AddOtherDevice("emu:keyboard", 0x046d, 0xc31c, 0x0001, 0x0006, "Keyboard");
  EXPECT_NO_THROW(found = FindHidCandidates());
  EXPECT_TRUE(found.empty());
}

TEST_F(HidFinder, ListsAnInterfaceOnceThoughHidrawListsItPerCollection) {
  // hidraw enumerates one entry per top-level collection, all with the interface's path:
  // a device of the known VID:PID with our collection and a consumer-control one
  hidemu::AddDevice(FirmwareConfig{});
  hidemu::AddOtherDevice("emu:0", 0x1209, 0x0001, 0x000C, 0x0001, "HaptiCAD emulated 3-DOF device");
  const auto found = FindHidCandidates();
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].path, "emu:0");
}

TEST_F(HidFinder, SaysWhatEachDeviceIsWithItsProductNameInUtf8) {
  FirmwareConfig c;
  c.path = "emu:arm";
  c.vendor_id = 0x1234;
  c.product_id = 0x5678;
  c.product = "Haptik-Ger\xE4t";  // hidapi's wide string holds U+00E4 (the emulator widens bytes)
  hidemu::AddDevice(c);
  FirmwareConfig unnamed;
  unnamed.path = "emu:unnamed";
  unnamed.product = "";
  hidemu::AddDevice(unnamed);
  const auto found = FindHidCandidates();
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(found[0].path, "emu:arm");
  EXPECT_EQ(found[0].vendor_id, 0x1234);
  EXPECT_EQ(found[0].product_id, 0x5678);
  EXPECT_EQ(found[0].usage_page, 0xFF48);
  EXPECT_EQ(found[0].usage, 0x01);
  EXPECT_EQ(found[0].product, "Haptik-Ger\xC3\xA4t");
  EXPECT_EQ(found[1].vendor_id, 0x1209);
  EXPECT_EQ(found[1].product_id, 0x0001);
  EXPECT_EQ(found[1].product, "");
}

}  // namespace
}  // namespace hapticad
