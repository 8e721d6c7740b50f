// SPDX-License-Identifier: GPL-3.0-or-later
// Small hidapi helpers of the HID backend (private): one-time initialisation, the lock
// on hidapi's global state, and hidapi's wide strings as UTF-8 for messages and names. Not
// for the servo tick.
#pragma once

#include <mutex>
#include <string>

struct hid_device_;

namespace hapticad::hid {

// Calls hid_init() once per process (under GlobalStateMutex()); throws DeviceError if it
// fails. Never call it holding GlobalStateMutex().
void EnsureHidInit();

// The lock on hidapi's global state. hidapi (0.13, linux/hid.c) keeps one process-wide
// error string that hid_init, hid_enumerate and hid_open_path free and replace, and
// hid_error(NULL) reads, with no lock: two threads in them at once can double-free it or
// read it freed (ListDevices probes on threads of its own, and the workbench opens a device
// on a worker thread while its panel lists devices). hidapi's calls that touch that state
// (hid_init, hid_enumerate/hid_free_enumeration, hid_open_path and the hid_error(NULL) read
// right after a failed open, hid_exit if ever called) are made under it; nothing that can
// block on a device is (calls on a handle touch that handle's state only, and a feature
// report can block for seconds). Not recursive: FindUsbIds and EnsureHidInit take it.
std::mutex& GlobalStateMutex();

// hid_error(handle) (handle may be null) as UTF-8; "unknown error" when hidapi has none.
std::string ErrorText(hid_device_* handle);

// The USB product string, or "HaptiCAD protocol device" when there is none.
std::string ProductName(hid_device_* handle);

// UTF-32 (Linux wchar_t) to UTF-8.
std::string ToUtf8(const wchar_t* text);

}  // namespace hapticad::hid
