// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/devices/device_catalog.h"

#include "hapticad/devices/hid/hid_device.h"
#include "hapticad/devices/hid/hid_device_finder.h"
#include "hapticad/devices/simulated_hand.h"

namespace hapticad {

std::vector<DeviceListing> ListDevices() {
  std::vector<DeviceListing> out;
  {
    SimulatedHand hand;
    DeviceListing sim;
    sim.info = hand.info();
    sim.has_limits = true;
    out.push_back(std::move(sim));
  }
  std::vector<HidCandidate> candidates;
  try {
    candidates = FindHidCandidates();
  } catch (const DeviceError& e) {
    DeviceListing failed;
    failed.info.kind = "hid";
    failed.info.name = "HID devices";
    failed.error = e.what();
    out.push_back(std::move(failed));
    return out;
  }
  for (const HidCandidate& c : candidates) {
    DeviceListing listing;
    listing.info.kind = "hid";
    listing.info.path = c.path;
    listing.info.name = c.product.empty() ? "HaptiCAD protocol device" : c.product;
    try {
      const HidProbe probe = HidDevice::Probe(c.path);
      listing.info = probe.info;
      listing.has_limits = true;
      listing.protocol = hid::VersionString(probe.report.version_min) + "-" +
                         hid::VersionString(probe.report.version_max);
    } catch (const DeviceError& e) {
      listing.error = e.what();
    }
    out.push_back(std::move(listing));
  }
  return out;
}

std::unique_ptr<Device> OpenDevice(const std::string& path) {
  if (path == "sim:hand") return std::make_unique<SimulatedHand>();
  if (path.rfind("sim:", 0) == 0) {
    throw DeviceError("unknown simulated device '" + path + "' (there is sim:hand)");
  }
  return HidDevice::Open(path);
}

}  // namespace hapticad
