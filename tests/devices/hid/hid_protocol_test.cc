// SPDX-License-Identifier: GPL-3.0-or-later
// The host's codec against bytes written out by hand from PROTOCOL.md.
#include "hapticad/devices/hid/hid_protocol.h"

#include <cmath>
#include <cstring>
#include <limits>

#include <gtest/gtest.h>

namespace hapticad::hid {
namespace {

TEST(HidProtocol, CrcMatchesTheDocumentedCheckValue) {
  const char* text = "123456789";
  EXPECT_EQ(Crc16(reinterpret_cast<const std::uint8_t*>(text), 9), 0x29B1);
}

// PROTOCOL.md §3.1: status FORCE_ON|CLAMPED, sequence 0x0102, time 0x0A0B0C0D us,
// x = +1 mm, y = -2 mm, z = 0.5 um, buttons 0b101, round trip 1234 us, echo 7
std::array<std::uint8_t, 32> HandWrittenInput() {
  std::array<std::uint8_t, 32> d = {0x01, 0x11, 0x02, 0x01,
                                    0x0D, 0x0C, 0x0B, 0x0A,   // id, status, seq, time
                                    0x40, 0x42, 0x0F, 0x00,   // 1,000,000 nm
                                    0x80, 0x7B, 0xE1, 0xFF,   // -2,000,000 nm
                                    0xF4, 0x01, 0x00, 0x00,   // 500 nm
                                    0x05, 0x00, 0x00, 0x00,   // buttons
                                    0xD2, 0x04, 0x07, 0x00,   // 1234 us, echo 7
                                    0x00, 0x00, 0x00, 0x00};  // reserved, CRC below
  const std::uint16_t crc = Crc16(d.data(), 30);
  d[30] = crc & 0xFF;
  d[31] = crc >> 8;
  return d;
}

TEST(HidProtocol, DecodesAnInputReportFieldByField) {
  const auto d = HandWrittenInput();
  InputReport r;
  ASSERT_TRUE(DecodeInput(d.data(), d.size(), &r));
  EXPECT_EQ(r.status, kStatusForceOn | kStatusClamped);
  EXPECT_EQ(r.sequence, 0x0102);
  EXPECT_EQ(r.device_time_us, 0x0A0B0C0Du);
  EXPECT_EQ(r.position_nm[0], 1000000);
  EXPECT_EQ(r.position_nm[1], -2000000);
  EXPECT_EQ(r.position_nm[2], 500);
  EXPECT_DOUBLE_EQ(PositionFromWire(r.position_nm[1]), -0.002);
  EXPECT_EQ(r.buttons, 5u);
  EXPECT_EQ(r.round_trip_us, 1234);
  EXPECT_EQ(r.output_sequence_echo, 7);
}

TEST(HidProtocol, RejectsWrongLengthIdOrCrc) {
  auto d = HandWrittenInput();
  InputReport r;
  EXPECT_FALSE(DecodeInput(d.data(), 31, &r));  // truncated
  auto bad_id = d;
  bad_id[0] = 0x02;
  EXPECT_FALSE(DecodeInput(bad_id.data(), 32, &r));
  for (std::size_t i = 1; i < 32; ++i) {  // any single flipped bit is caught
    auto flipped = d;
    flipped[i] ^= 0x10;
    EXPECT_FALSE(DecodeInput(flipped.data(), 32, &r)) << i;
  }
}

TEST(HidProtocol, EncodesAnOutputReportByteForByte) {
  OutputReport r;
  r.flags = kOutputEnable;
  r.sequence = 0xBEEF;
  r.input_sequence = 0x0102;
  r.force_un[0] = ForceToWire(1.5);
  r.force_un[1] = ForceToWire(-0.25);
  r.force_un[2] = ForceToWire(0.0);
  std::uint8_t out[kOutputReportSize];
  EncodeOutput(r, out);
  const std::uint8_t expected[18] = {0x02, 0x01, 0xEF, 0xBE, 0x02, 0x01,  //
                                     0x60, 0xE3, 0x16, 0x00,              // 1,500,000 uN
                                     0x70, 0x2F, 0xFC, 0xFF,              // -250,000 uN
                                     0x00, 0x00, 0x00, 0x00};
  EXPECT_EQ(std::memcmp(out, expected, 18), 0);
  EXPECT_EQ(out[18] | out[19] << 8, Crc16(out, 18));
}

TEST(HidProtocol, ForceToTheWireRoundsSaturatesAndRefusesNaN) {
  EXPECT_EQ(ForceToWire(1e-6), 1);
  EXPECT_EQ(ForceToWire(1e6), std::numeric_limits<std::int32_t>::max());
  EXPECT_EQ(ForceToWire(-1e6), std::numeric_limits<std::int32_t>::min());
  EXPECT_EQ(ForceToWire(std::nan("")), 0);
  EXPECT_EQ(ForceToWire(std::numeric_limits<double>::infinity()), 0);
}

InfoReport GoodInfo() {
  InfoReport i;
  i.dof = 3;
  i.magic = kMagic;
  i.version_min = 0x0100;
  i.version_max = 0x0102;
  i.watchdog_ms = 20;
  i.report_rate_hz = 1000;
  i.max_force_un = 3300000;
  i.max_stiffness_n_per_m = 400;
  for (int a = 0; a < 3; ++a) {
    i.workspace_min_nm[a] = -80000000;
    i.workspace_max_nm[a] = 80000000;
  }
  i.position_resolution_nm = 55000;
  return i;
}

TEST(HidProtocol, AcceptsAGoodDeviceAndConvertsItsLimits) {
  EXPECT_EQ(DescribeInfoProblem(GoodInfo()), "");
  const DeviceLimits l = LimitsFromInfo(GoodInfo());
  EXPECT_DOUBLE_EQ(l.max_force_n, 3.3);
  EXPECT_DOUBLE_EQ(l.max_stiffness_n_per_m, 400.0);
  EXPECT_DOUBLE_EQ(l.workspace_max_d.x(), 0.08);
  EXPECT_DOUBLE_EQ(l.position_resolution_m, 55e-6);
  ValidateDeviceLimits(l);
}

TEST(HidProtocol, SaysWhatIsWrongWithADevice) {
  InfoReport i = GoodInfo();
  i.magic = 0x1234;
  EXPECT_NE(DescribeInfoProblem(i).find("does not identify itself"), std::string::npos);
  i = GoodInfo();
  i.dof = 6;
  EXPECT_NE(DescribeInfoProblem(i).find("6 degrees of freedom"), std::string::npos);
  i = GoodInfo();
  i.version_min = 0x0200;
  i.version_max = 0x0201;
  EXPECT_EQ(DescribeInfoProblem(i),
            "it speaks HaptiCAD HID protocol 2.0-2.1 and this HaptiCAD speaks 1.0; update "
            "HaptiCAD");
  i.version_min = 0x0009;
  i.version_max = 0x0009;
  EXPECT_NE(DescribeInfoProblem(i).find("update the device's firmware"), std::string::npos);
  i = GoodInfo();
  i.max_force_un = 2000000000u;  // 2000 N
  EXPECT_NE(DescribeInfoProblem(i).find("impossible maximum force"), std::string::npos);
  i = GoodInfo();
  i.workspace_max_nm[2] = i.workspace_min_nm[2];
  EXPECT_NE(DescribeInfoProblem(i).find("workspace"), std::string::npos);
  i = GoodInfo();
  i.report_rate_hz = 50;
  EXPECT_NE(DescribeInfoProblem(i).find("reports at 50 Hz, too slowly"), std::string::npos);
  i.report_rate_hz = 399;  // the data would be stale on many ticks: almost no force
  EXPECT_NE(DescribeInfoProblem(i).find("needs at least 400 Hz"), std::string::npos);
  i.report_rate_hz = 400;
  EXPECT_EQ(DescribeInfoProblem(i), "");
  i.report_rate_hz = 20001;
  EXPECT_NE(DescribeInfoProblem(i).find("report rate"), std::string::npos);
  i = GoodInfo();
  i.watchdog_ms = 0;
  EXPECT_NE(DescribeInfoProblem(i).find("watchdog"), std::string::npos);
  i = GoodInfo();
  i.max_stiffness_n_per_m = 0;
  EXPECT_NE(DescribeInfoProblem(i).find("stiffness"), std::string::npos);
}

}  // namespace
}  // namespace hapticad::hid
