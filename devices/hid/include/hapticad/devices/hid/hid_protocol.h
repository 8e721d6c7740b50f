// SPDX-License-Identifier: GPL-3.0-or-later
// The HaptiCAD HID protocol (devices/hid/PROTOCOL.md), host side: report layouts and
// their little-endian fixed-point encoding, as the host reads and writes them. Pure
// functions on byte buffers; the decoders check length, report ID and CRC. (The
// device side is written separately from PROTOCOL.md, in the test emulator, so the
// two check each other.)
//
// Servo-tick safe: no allocation (DescribeDeviceInfoProblem excepted, it is for Open).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "hapticad/devices/device.h"

namespace hapticad::hid {

constexpr std::uint16_t kUsagePage = 0xFF48;
constexpr std::uint16_t kUsage = 0x01;
constexpr std::uint16_t kMagic = 0x4348;        // 'H' 'C'
constexpr std::uint16_t kHostVersion = 0x0100;  // 1.0: this host speaks major 1
// The slowest input report rate the host accepts: the loop zeroes the force on data
// older than 5 ms (SafetyConfig::stale_after_s), and a report period must leave room
// for a late one (ServoLoop's own minimum rate is 2 / that limit too). A 100 Hz device
// had its data stale on 46 % of ticks and felt almost no force.
constexpr std::uint16_t kMinReportRateHz = 400;

constexpr std::uint8_t kInputReportId = 0x01;
constexpr std::uint8_t kOutputReportId = 0x02;
constexpr std::uint8_t kInfoReportId = 0x03;
constexpr std::uint8_t kSessionReportId = 0x04;
constexpr std::size_t kInputReportSize = 32;
constexpr std::size_t kOutputReportSize = 20;
constexpr std::size_t kInfoReportSize = 64;
constexpr std::size_t kSessionReportSize = 8;

// input status bits
constexpr std::uint8_t kStatusForceOn = 1u << 0;
constexpr std::uint8_t kStatusWatchdog = 1u << 1;
constexpr std::uint8_t kStatusFault = 1u << 2;
constexpr std::uint8_t kStatusNotHomed = 1u << 3;
constexpr std::uint8_t kStatusClamped = 1u << 4;
// output flags
constexpr std::uint8_t kOutputEnable = 1u << 0;
// session flags
constexpr std::uint8_t kSessionOpen = 1u << 0;

struct InputReport {
  std::uint8_t status = 0;
  std::uint16_t sequence = 0;
  std::uint32_t device_time_us = 0;
  std::int32_t position_nm[3] = {0, 0, 0};
  std::uint32_t buttons = 0;
  std::uint16_t round_trip_us = 0;
  std::uint16_t output_sequence_echo = 0;
};

struct OutputReport {
  std::uint8_t flags = 0;
  std::uint16_t sequence = 0;
  std::uint16_t input_sequence = 0;
  std::int32_t force_un[3] = {0, 0, 0};
};

struct InfoReport {
  std::uint8_t dof = 0;
  std::uint16_t magic = 0;
  std::uint16_t version_min = 0;
  std::uint16_t version_max = 0;
  std::uint16_t watchdog_ms = 0;
  std::uint16_t report_rate_hz = 0;
  std::uint32_t max_force_un = 0;
  std::uint32_t continuous_force_un = 0;
  std::uint32_t max_stiffness_n_per_m = 0;
  std::uint32_t max_damping_mn_s_per_m = 0;
  std::int32_t workspace_min_nm[3] = {0, 0, 0};
  std::int32_t workspace_max_nm[3] = {0, 0, 0};
  std::uint32_t position_resolution_nm = 0;
};

struct SessionReport {
  std::uint8_t flags = 0;
  std::uint16_t version = 0;
  std::uint16_t watchdog_ms = 0;
};

// CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF): "123456789" -> 0x29B1.
std::uint16_t Crc16(const std::uint8_t* data, std::size_t n);

// What the host reads. False for a wrong length, report ID or (input) CRC; the info
// and session reports may be longer than this version's (a later minor version).
bool DecodeInput(const std::uint8_t* data, std::size_t n, InputReport* out);
bool DecodeInfo(const std::uint8_t* data, std::size_t n, InfoReport* out);
bool DecodeSession(const std::uint8_t* data, std::size_t n, SessionReport* out);
// What the host writes: exactly the report's size.
void EncodeOutput(const OutputReport& r, std::uint8_t out[kOutputReportSize]);
void EncodeSession(const SessionReport& r, std::uint8_t out[kSessionReportSize]);

// Newtons to the wire (µN), rounded and saturated; non-finite is zero.
std::int32_t ForceToWire(double force_n);
inline double PositionFromWire(std::int32_t nm) { return static_cast<double>(nm) * 1e-9; }

// "1.0" for 0x0100.
std::string VersionString(std::uint16_t version);

// Empty when the device information is usable by this host (PROTOCOL.md §6), else a
// sentence saying what is wrong, for the user.
std::string DescribeInfoProblem(const InfoReport& info);

// The device's limits in SI units (the info must be usable).
DeviceLimits LimitsFromInfo(const InfoReport& info);

}  // namespace hapticad::hid
