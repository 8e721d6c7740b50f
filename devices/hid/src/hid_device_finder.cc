// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/devices/hid/hid_device_finder.h"

#include <hidapi/hidapi.h>

#include <algorithm>
#include <mutex>

#include "hapticad/devices/hid/hid_protocol.h"
#include "hid_text.h"

namespace hapticad {

std::vector<HidCandidate> FindHidCandidates() {
  hid::EnsureHidInit();
  std::vector<HidCandidate> found;
  std::lock_guard<std::mutex> lock(hid::GlobalStateMutex());  // hidapi's global error text
  hid_device_info* list = hid_enumerate(0, 0);
  for (const hid_device_info* d = list; d != nullptr; d = d->next) {
    const bool by_usage = d->usage_page == hid::kUsagePage && d->usage == hid::kUsage;
    const bool by_id = std::any_of(
        std::begin(kKnownHidDevices), std::end(kKnownHidDevices), [&](const KnownHidDevice& k) {
          return k.vendor_id == d->vendor_id && k.product_id == d->product_id;
        });
    if (!(by_usage || by_id) || d->path == nullptr) continue;
    const std::string path = d->path;
    if (std::any_of(found.begin(), found.end(),
                    [&](const HidCandidate& c) { return c.path == path; })) {
      continue;  // hidraw lists an interface once per top-level collection
    }
    HidCandidate c;
    c.path = path;
    c.vendor_id = d->vendor_id;
    c.product_id = d->product_id;
    c.usage_page = d->usage_page;
    c.usage = d->usage;
    c.product = hid::ToUtf8(d->product_string);
    found.push_back(std::move(c));
  }
  hid_free_enumeration(list);
  return found;
}

}  // namespace hapticad
