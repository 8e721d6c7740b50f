// SPDX-License-Identifier: GPL-3.0-or-later
// The devices HaptiCAD can feel with: the simulated hand (always) and every HID
// device speaking the HaptiCAD protocol. What `hapticad devices --json` prints, and
// how a GUI opens the one the user picked. (It lives with the HID backend, the one
// backend that enumerates.)
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "hapticad/devices/device.h"

namespace hapticad {

struct DeviceListing {
  DeviceInfo info;          // kind "sim" or "hid", name, path, limits
  bool has_limits = false;  // false when the device could not be read (see error)
  std::string protocol;     // "1.0"-"1.2" for HID devices, empty for simulated ones
  std::string error;        // why it cannot be used (permissions, version), or empty
};

// How long ListDevices waits for a HID device to answer its information request. A
// device that does not answer blocks the request in the kernel for up to 5 s (usbhid's
// control timeout): a GUI listing devices as its panel opens would freeze that long.
inline constexpr double kProbeWaitS = 0.5;

// The simulated hand first ("sim:hand"), then HID devices in enumeration order. Each
// HID device is probed (its information read; no session is touched), on a thread of its
// own, all at once, waited for at most kProbeWaitS in all (not for each); one that cannot
// be read, or does not answer in time, is listed with its error (the probe's thread then finishes
// on its own and closes the device; until then a later listing does not ask it again, and lists it
// at once with that error). Never throws for a device's fault (nor for no thread to probe one on:
// that device is listed with that error); hidapi failing to initialise gives one "hid" listing with
// the error. May run while OpenDevice() runs on another thread, and while probes of an earlier
// listing still run: hidapi's global state (its enumeration, opens and error text) is touched under
// one process-wide lock, held by nothing that waits on a device.
std::vector<DeviceListing> ListDevices();

// Opens what a listing's `path` names: "sim:hand" is a new SimulatedHand with default
// limits; anything else a HID device path. Throws DeviceError with a sentence for the
// user.
std::unique_ptr<Device> OpenDevice(const std::string& path);

}  // namespace hapticad
