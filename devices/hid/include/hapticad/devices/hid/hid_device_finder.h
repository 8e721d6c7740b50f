// SPDX-License-Identifier: GPL-3.0-or-later
// Finding HaptiCAD protocol devices among the HID devices hidapi enumerates: by the
// top-level collection's usage page and usage (PROTOCOL.md §1), or by a known VID:PID
// for firmware that does not report them. Does not open anything.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hapticad {

struct KnownHidDevice {
  std::uint16_t vendor_id;
  std::uint16_t product_id;
  const char* what;
};

// VID:PID pairs opened even without the usage page. packaging/70-hapticad.rules must
// list the same (tests/packaging checks it).
inline constexpr KnownHidDevice kKnownHidDevices[] = {
    {0x1209, 0x0001, "pid.codes test PID: HaptiCAD protocol prototypes"},
};

struct HidCandidate {
  std::string path;
  std::uint16_t vendor_id = 0;
  std::uint16_t product_id = 0;
  std::uint16_t usage_page = 0;
  std::uint16_t usage = 0;
  std::string product;  // USB product string, UTF-8
};

// Every HID interface that claims the protocol, once per path. Throws DeviceError if
// hidapi cannot be initialised. Takes the lock on hidapi's global state (hid_text.h).
std::vector<HidCandidate> FindHidCandidates();

}  // namespace hapticad
