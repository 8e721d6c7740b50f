// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: DecodeInput, EncodeOutput and ForceToWire run on the servo tick.
#include "hapticad/devices/hid/hid_protocol.h"

#include <cmath>
#include <cstring>
#include <limits>

namespace hapticad::hid {
namespace {

// little-endian fields, whatever the host's byte order
std::uint16_t U16(const std::uint8_t* p) { return static_cast<std::uint16_t>(p[0] | (p[1] << 8)); }
std::uint32_t U32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}
std::int32_t I32(const std::uint8_t* p) { return static_cast<std::int32_t>(U32(p)); }
void PutU16(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v);
  p[1] = static_cast<std::uint8_t>(v >> 8);
}
void PutU32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
void PutI32(std::uint8_t* p, std::int32_t v) { PutU32(p, static_cast<std::uint32_t>(v)); }

bool CrcOk(const std::uint8_t* data, std::size_t n) {
  return Crc16(data, n - 2) == U16(data + n - 2);
}

}  // namespace

std::uint16_t Crc16(const std::uint8_t* data, std::size_t n) {
  std::uint16_t crc = 0xFFFF;
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= static_cast<std::uint16_t>(data[i] << 8);
    for (int b = 0; b < 8; ++b) {
      crc = (crc & 0x8000) ? static_cast<std::uint16_t>((crc << 1) ^ 0x1021)
                           : static_cast<std::uint16_t>(crc << 1);
    }
  }
  return crc;
}

bool DecodeInput(const std::uint8_t* d, std::size_t n, InputReport* r) {
  if (n != kInputReportSize || d[0] != kInputReportId || !CrcOk(d, n)) return false;
  r->status = d[1];
  r->sequence = U16(d + 2);
  r->device_time_us = U32(d + 4);
  for (int a = 0; a < 3; ++a) r->position_nm[a] = I32(d + 8 + 4 * a);
  r->buttons = U32(d + 20);
  r->round_trip_us = U16(d + 24);
  r->output_sequence_echo = U16(d + 26);
  return true;
}

void EncodeOutput(const OutputReport& r, std::uint8_t d[kOutputReportSize]) {
  std::memset(d, 0, kOutputReportSize);
  d[0] = kOutputReportId;
  d[1] = r.flags;
  PutU16(d + 2, r.sequence);
  PutU16(d + 4, r.input_sequence);
  for (int a = 0; a < 3; ++a) PutI32(d + 6 + 4 * a, r.force_un[a]);
  PutU16(d + 18, Crc16(d, 18));
}

bool DecodeInfo(const std::uint8_t* d, std::size_t n, InfoReport* r) {
  if (n < kInfoReportSize || d[0] != kInfoReportId) return false;
  r->dof = d[1];
  r->magic = U16(d + 2);
  r->version_min = U16(d + 4);
  r->version_max = U16(d + 6);
  r->watchdog_ms = U16(d + 8);
  r->report_rate_hz = U16(d + 10);
  r->max_force_un = U32(d + 12);
  r->continuous_force_un = U32(d + 16);
  r->max_stiffness_n_per_m = U32(d + 20);
  r->max_damping_mn_s_per_m = U32(d + 24);
  for (int a = 0; a < 3; ++a) r->workspace_min_nm[a] = I32(d + 28 + 4 * a);
  for (int a = 0; a < 3; ++a) r->workspace_max_nm[a] = I32(d + 40 + 4 * a);
  r->position_resolution_nm = U32(d + 52);
  return true;
}

bool DecodeSession(const std::uint8_t* d, std::size_t n, SessionReport* r) {
  if (n < kSessionReportSize || d[0] != kSessionReportId) return false;
  r->flags = d[1];
  r->version = U16(d + 2);
  r->watchdog_ms = U16(d + 4);
  return true;
}

void EncodeSession(const SessionReport& r, std::uint8_t d[kSessionReportSize]) {
  std::memset(d, 0, kSessionReportSize);
  d[0] = kSessionReportId;
  d[1] = r.flags;
  PutU16(d + 2, r.version);
  PutU16(d + 4, r.watchdog_ms);
}

std::int32_t ForceToWire(double force_n) {
  if (!std::isfinite(force_n)) return 0;
  const double un = std::round(force_n * 1e6);
  constexpr double kMax = std::numeric_limits<std::int32_t>::max();
  constexpr double kMin = std::numeric_limits<std::int32_t>::min();
  return static_cast<std::int32_t>(un > kMax ? kMax : (un < kMin ? kMin : un));
}

std::string VersionString(std::uint16_t version) {
  return std::to_string(version >> 8) + "." + std::to_string(version & 0xFF);
}

std::string DescribeInfoProblem(const InfoReport& info) {
  if (info.magic != kMagic) {
    return "it does not identify itself as a HaptiCAD protocol device (magic " +
           std::to_string(info.magic) + ")";
  }
  if (info.dof != 3) {
    return "it renders force in " + std::to_string(info.dof) +
           " degrees of freedom; HaptiCAD drives 3";
  }
  const int host_major = kHostVersion >> 8;
  if (info.version_min > info.version_max || (info.version_min >> 8) > host_major ||
      (info.version_max >> 8) < host_major) {
    const std::string range =
        VersionString(info.version_min) + "-" + VersionString(info.version_max);
    const bool newer = (info.version_min >> 8) > host_major;
    return "it speaks HaptiCAD HID protocol " + range + " and this HaptiCAD speaks " +
           VersionString(kHostVersion) + "; " +
           (newer ? "update HaptiCAD" : "update the device's firmware");
  }
  auto bad = [](const std::string& what) { return "it states an impossible " + what; };
  if (info.max_force_un == 0 || info.max_force_un > 1000000000u) {
    return bad("maximum force (" + std::to_string(info.max_force_un * 1e-6) + " N)");
  }
  if (info.continuous_force_un > info.max_force_un) {
    return bad("continuous force (above its maximum force)");
  }
  if (info.max_stiffness_n_per_m == 0) return bad("maximum stiffness (0 N/m)");
  for (int a = 0; a < 3; ++a) {
    if (info.workspace_min_nm[a] >= info.workspace_max_nm[a]) return bad("workspace (empty)");
  }
  if (info.position_resolution_nm > 1000000u) {
    return bad("position resolution (" + std::to_string(info.position_resolution_nm * 1e-6) +
               " mm)");
  }
  if (info.report_rate_hz > 20000) {
    return bad("report rate (" + std::to_string(info.report_rate_hz) + " Hz)");
  }
  if (info.report_rate_hz < kMinReportRateHz) {
    return "it reports at " + std::to_string(info.report_rate_hz) +
           " Hz, too slowly: HaptiCAD renders from positions no older than 5 ms and needs at "
           "least " +
           std::to_string(kMinReportRateHz) + " Hz; raise the device's report rate";
  }
  if (info.watchdog_ms < 1 || info.watchdog_ms > 1000) {
    return bad("watchdog (" + std::to_string(info.watchdog_ms) + " ms)");
  }
  return {};
}

DeviceLimits LimitsFromInfo(const InfoReport& info) {
  DeviceLimits l;
  l.max_force_n = info.max_force_un * 1e-6;
  l.continuous_force_n = info.continuous_force_un * 1e-6;
  l.max_stiffness_n_per_m = info.max_stiffness_n_per_m;
  l.max_damping_n_s_per_m = info.max_damping_mn_s_per_m * 1e-3;
  for (int a = 0; a < 3; ++a) {
    l.workspace_min_d[a] = PositionFromWire(info.workspace_min_nm[a]);
    l.workspace_max_d[a] = PositionFromWire(info.workspace_max_nm[a]);
  }
  l.position_resolution_m = info.position_resolution_nm * 1e-9;
  return l;
}

}  // namespace hapticad::hid
