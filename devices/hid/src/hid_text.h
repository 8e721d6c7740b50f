// SPDX-License-Identifier: GPL-3.0-or-later
// Small hidapi helpers of the HID backend (private): one-time initialisation, and
// hidapi's wide strings as UTF-8 for messages and names. Not for the servo tick.
#pragma once

#include <string>

struct hid_device_;

namespace hapticad::hid {

// Calls hid_init() once per process; throws DeviceError if it fails.
void EnsureHidInit();

// hid_error(handle) (handle may be null) as UTF-8; "unknown error" when hidapi has none.
std::string ErrorText(hid_device_* handle);

// The USB product string, or "HaptiCAD protocol device" when there is none.
std::string ProductName(hid_device_* handle);

// UTF-32 (Linux wchar_t) to UTF-8.
std::string ToUtf8(const wchar_t* text);

}  // namespace hapticad::hid
