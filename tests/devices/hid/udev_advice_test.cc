// SPDX-License-Identifier: GPL-3.0-or-later
// The advice a permission error carries: HaptiCAD's rule for the IDs it lists, and for a
// device with a VID:PID of its own, the rule line with that VID:PID filled in.
#include "hapticad/devices/hid/udev_advice.h"

#include <string>

#include <gtest/gtest.h>

#include "hid_emulator.h"

namespace hapticad::hid {
namespace {

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(UdevAdvice, TheDevelopmentIdIsCoveredByHaptiCADsRule) {
  const std::string advice = UdevAdvice(true, 0x1209, 0x0001);
  EXPECT_EQ(advice,
            ". Install HaptiCAD's udev rule (sudo ./packaging/setup.sh, or copy "
            "packaging/70-hapticad.rules to /etc/udev/rules.d/) and plug the device in again");
}

TEST(UdevAdvice, ADeviceWithItsOwnIdsGetsTheRuleLineWithThem) {
  const std::string advice = UdevAdvice(true, 0x04D8, 0x0A2b);
  EXPECT_TRUE(Contains(advice, "this device is 04d8:0a2b")) << advice;
  // the line as packaging/70-hapticad.rules writes its own, lower-case IDs as sysfs does
  EXPECT_TRUE(Contains(advice,
                       "'SUBSYSTEM==\"hidraw\", ATTRS{idVendor}==\"04d8\", "
                       "ATTRS{idProduct}==\"0a2b\", MODE=\"0660\", GROUP=\"hapticad\", "
                       "TAG+=\"uaccess\"'"))
      << advice;
  EXPECT_TRUE(Contains(advice, "/etc/udev/rules.d/70-hapticad-local.rules")) << advice;
  EXPECT_TRUE(Contains(advice, "udevadm control --reload")) << advice;
  EXPECT_FALSE(Contains(advice, "1209")) << advice;
}

TEST(UdevAdvice, UnknownIdsGetBothTheRuleAndHowToWriteALineForOtherIds) {
  const std::string advice = UdevAdvice(false, 0, 0);
  EXPECT_TRUE(Contains(advice, "Install HaptiCAD's udev rule")) << advice;
  EXPECT_TRUE(Contains(advice, "1209:0001 only")) << advice;
  EXPECT_TRUE(Contains(advice, "ATTRS{idVendor}==\"vvvv\", ATTRS{idProduct}==\"pppp\"")) << advice;
}

TEST(UdevAdvice, FindsTheIdsOfAPathWithoutOpeningIt) {
  hidemu::Reset();
  hidemu::FirmwareConfig c;
  c.path = "emu:own";
  c.vendor_id = 0x04d8;
  c.product_id = 0xeb5a;
  c.deny_open = true;
  hidemu::AddDevice(c);
  std::uint16_t vid = 0, pid = 0;
  EXPECT_TRUE(FindUsbIds("emu:own", &vid, &pid));
  EXPECT_EQ(vid, 0x04d8);
  EXPECT_EQ(pid, 0xeb5a);
  EXPECT_FALSE(FindUsbIds("emu:nowhere", &vid, &pid));
  EXPECT_EQ(hidemu::OpenHandles("emu:own"), 0);
  hidemu::Reset();
}

}  // namespace
}  // namespace hapticad::hid
