// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/devices/device_catalog.h"

#include <chrono>
#include <condition_variable>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>
#include <utility>

#include "hapticad/devices/hid/hid_device.h"
#include "hapticad/devices/hid/hid_device_finder.h"
#include "hapticad/devices/simulated_hand.h"

namespace hapticad {
namespace {

// One device's probe, shared by the lister and the thread that probes (which may
// outlive the lister when the device does not answer).
struct ProbeSlot {
  std::mutex mutex;
  std::condition_variable done_changed;
  bool done = false;
  HidProbe probe;
  std::exception_ptr failed;  // what Probe threw: its text is made on the lister's thread
};

// Probes `path` on a thread of its own and waits at most kProbeWaitS for it: true with
// `*probe` read, false with `*error` (the device's, that it did not answer in time, or that
// no thread could be started for it; the thread is then left to finish the request, and
// close the device, on its own).
// The probes left waiting on a device that did not answer, by path: a later listing does
// not ask that device again (another handle, another thread) until the request is over.
std::mutex& UnansweredMutex() {
  static std::mutex mutex;
  return mutex;
}
std::map<std::string, std::weak_ptr<ProbeSlot>>& Unanswered() {
  static auto* probes = new std::map<std::string, std::weak_ptr<ProbeSlot>>;  // kept to exit
  return *probes;
}

std::string NotAnswered(const std::string& path) {
  return "the HID device " + path + " did not answer its device information request within " +
         std::to_string(static_cast<int>(kProbeWaitS * 1000)) +
         " ms (a HaptiCAD device answers in milliseconds): it is busy or not a HaptiCAD "
         "protocol device; unplug it and plug it in again";
}

bool ProbeWithin(const std::string& path, HidProbe* probe, std::string* error) {
  {
    std::lock_guard<std::mutex> lock(UnansweredMutex());
    auto& unanswered = Unanswered();
    const auto it = unanswered.find(path);
    if (it != unanswered.end()) {
      const std::shared_ptr<ProbeSlot> earlier = it->second.lock();
      bool waiting = false;
      if (earlier) {
        std::lock_guard<std::mutex> slot_lock(earlier->mutex);
        waiting = !earlier->done;
      }
      if (waiting) {
        *error = NotAnswered(path) + " (an earlier request is still waiting)";
        return false;
      }
      unanswered.erase(it);
    }
  }
  auto slot = std::make_shared<ProbeSlot>();
  std::thread worker;
  try {
    // nothing may escape the thread's body (std::terminate): what Probe throws is kept,
    // and the rest (a move, a mutex) does not throw
    worker = std::thread([slot, path] {
      HidProbe read;
      std::exception_ptr failed;
      try {
        read = HidDevice::Probe(path);
      } catch (...) {  // DeviceError, or out of memory: said by the lister, not thrown
        failed = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(slot->mutex);
      slot->probe = std::move(read);
      slot->failed = std::move(failed);
      slot->done = true;
      slot->done_changed.notify_all();
    });
  } catch (const std::system_error& e) {  // no thread left (EAGAIN): the process's limit
    *error = "cannot probe the HID device " + path + ": no thread could be started for it (" +
             e.what() + "); close some programs and list the devices again";
    return false;
  }
  std::unique_lock<std::mutex> lock(slot->mutex);
  const bool done = slot->done_changed.wait_for(lock, std::chrono::duration<double>(kProbeWaitS),
                                                [&] { return slot->done; });
  if (!done) {
    lock.unlock();
    worker.detach();
    {
      std::lock_guard<std::mutex> unanswered_lock(UnansweredMutex());
      Unanswered()[path] = slot;
    }
    *error = NotAnswered(path);
    return false;
  }
  *probe = std::move(slot->probe);
  const std::exception_ptr failed = slot->failed;
  lock.unlock();
  worker.join();
  if (!failed) return true;
  try {
    std::rethrow_exception(failed);
  } catch (const std::exception& e) {
    *error = e.what();
  } catch (...) {
    *error = "probing the HID device " + path + " failed";
  }
  return false;
}

}  // namespace

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
    HidProbe probe;
    if (ProbeWithin(c.path, &probe, &listing.error)) {
      listing.info = probe.info;
      listing.has_limits = true;
      listing.protocol = hid::VersionString(probe.report.version_min) + "-" +
                         hid::VersionString(probe.report.version_max);
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
