// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/devices/hid/udev_advice.h"

#include <hidapi/hidapi.h>

#include <cstdio>
#include <mutex>

#include "hapticad/devices/hid/hid_device_finder.h"
#include "hid_text.h"

namespace hapticad::hid {
namespace {

constexpr const char* kInstall =
    ". Install HaptiCAD's udev rule (sudo ./packaging/setup.sh, or copy "
    "packaging/70-hapticad.rules to /etc/udev/rules.d/) and plug the device in again";

// A rule line as packaging/70-hapticad.rules writes them, for `vid`:`pid` (sysfs spells
// the IDs as four lower-case hex digits).
std::string RuleLine(const char* vid, const char* pid) {
  return std::string("SUBSYSTEM==\"hidraw\", ATTRS{idVendor}==\"") + vid +
         "\", ATTRS{idProduct}==\"" + pid +
         "\", MODE=\"0660\", GROUP=\"hapticad\", TAG+=\"uaccess\"";
}

}  // namespace

bool FindUsbIds(const std::string& path, std::uint16_t* vendor_id, std::uint16_t* product_id) {
  std::lock_guard<std::mutex> lock(GlobalStateMutex());  // hidapi's global error text
  hid_device_info* all = hid_enumerate(0, 0);
  bool found = false;
  for (const hid_device_info* d = all; d && !found; d = d->next) {
    if (d->path && path == d->path) {
      *vendor_id = d->vendor_id;
      *product_id = d->product_id;
      found = true;
    }
  }
  hid_free_enumeration(all);
  return found;
}

std::string UdevAdvice(bool known, std::uint16_t vendor_id, std::uint16_t product_id) {
  if (!known) {
    return std::string(kInstall) +
           ". That rule lets in HaptiCAD's development ID 1209:0001 only: a device with a USB "
           "ID of its own (lsusb shows it as vvvv:pppp) needs the line '" +
           RuleLine("vvvv", "pppp") + "' with its IDs in /etc/udev/rules.d/70-hapticad-local.rules";
  }
  for (const KnownHidDevice& k : kKnownHidDevices) {
    if (k.vendor_id == vendor_id && k.product_id == product_id) return kInstall;
  }
  char vid[8], pid[8], ids[16];
  std::snprintf(vid, sizeof vid, "%04x", vendor_id);
  std::snprintf(pid, sizeof pid, "%04x", product_id);
  std::snprintf(ids, sizeof ids, "%s:%s", vid, pid);
  return std::string(
             ". HaptiCAD's udev rule (packaging/70-hapticad.rules) lets in only the USB "
             "IDs HaptiCAD lists, and this device is ") +
         ids + ": give it a rule of its own. As root, put the line '" + RuleLine(vid, pid) +
         "' into /etc/udev/rules.d/70-hapticad-local.rules (sudo ./packaging/setup.sh makes the "
         "group hapticad), run 'sudo udevadm control --reload' and plug the device in again";
}

}  // namespace hapticad::hid
