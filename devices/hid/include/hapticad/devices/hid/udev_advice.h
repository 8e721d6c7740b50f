// SPDX-License-Identifier: GPL-3.0-or-later
// What to tell a user whom Linux does not let open a HID device (permission denied): the
// udev rule that lets them. HaptiCAD's rule, packaging/70-hapticad.rules, lists the USB
// VID:PIDs of kKnownHidDevices (hid_device_finder.h); a product with a VID:PID of its own,
// found by its usage page (PROTOCOL.md §1), needs a rule line of its own, which the advice
// spells out with its IDs. HidDevice::Open() and Probe() add it to a permission error. Not
// for the servo tick.
#pragma once

#include <cstdint>
#include <string>

namespace hapticad::hid {

// The device's USB vendor and product IDs from hidapi's enumeration, looked up by path
// (nothing is opened). False when no HID device has that path. Takes the lock on hidapi's
// global state (hid_text.h): never call it holding that lock.
bool FindUsbIds(const std::string& path, std::uint16_t* vendor_id, std::uint16_t* product_id);

// The advice, to follow "cannot open the HID device <path>: <reason>" (it starts with ". ").
// `known`: whether the IDs were found at all.
std::string UdevAdvice(bool known, std::uint16_t vendor_id, std::uint16_t product_id);

}  // namespace hapticad::hid
