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
#include <vector>

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

// One device's probe, started on a thread of its own (slot set), or not started (error
// says why). Dropped unfinished, its thread is left to finish the request, and close the
// device, on its own.
struct StartedProbe {
  std::string path;
  std::shared_ptr<ProbeSlot> slot;
  std::thread worker;
  std::string error;

  StartedProbe() = default;
  StartedProbe(StartedProbe&&) = default;
  StartedProbe& operator=(StartedProbe&&) = delete;
  ~StartedProbe() {
    if (worker.joinable()) worker.detach();
  }
};

// Starts probing `path` on a thread of its own; not when an earlier listing's probe still
// waits on it, nor when no thread can be started (the process's limit).
StartedProbe StartProbe(const std::string& path) {
  StartedProbe started;
  started.path = path;
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
        started.error = NotAnswered(path) + " (an earlier request is still waiting)";
        return started;
      }
      unanswered.erase(it);
    }
  }
  auto slot = std::make_shared<ProbeSlot>();
  try {
    // nothing may escape the thread's body (std::terminate): what Probe throws is kept,
    // and the rest (a move, a mutex) does not throw
    started.worker = std::thread([slot, path] {
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
  } catch (const std::system_error& e) {  // no thread left (EAGAIN)
    started.error = "cannot probe the HID device " + path +
                    ": no thread could be started for it (" + e.what() +
                    "); close some programs and list the devices again";
    return started;
  }
  started.slot = std::move(slot);
  return started;
}

// Waits for a started probe until `deadline`: true with `*probe` read, false with `*error`
// (the device's, that it did not answer in time, or why it was not started).
bool FinishProbe(StartedProbe& started, std::chrono::steady_clock::time_point deadline,
                 HidProbe* probe, std::string* error) {
  if (!started.slot) {
    *error = started.error;
    return false;
  }
  ProbeSlot& slot = *started.slot;
  std::unique_lock<std::mutex> lock(slot.mutex);
  if (!slot.done_changed.wait_until(lock, deadline, [&] { return slot.done; })) {
    lock.unlock();
    started.worker.detach();
    {
      std::lock_guard<std::mutex> unanswered_lock(UnansweredMutex());
      Unanswered()[started.path] = started.slot;
    }
    *error = NotAnswered(started.path);
    return false;
  }
  *probe = std::move(slot.probe);
  const std::exception_ptr failed = slot.failed;
  lock.unlock();
  started.worker.join();
  if (!failed) return true;
  try {
    std::rethrow_exception(failed);
  } catch (const std::exception& e) {
    *error = e.what();
  } catch (...) {
    *error = "probing the HID device " + started.path + " failed";
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
  // all probed at once, then waited for until one deadline: devices that do not answer
  // hold the listing up kProbeWaitS in all, not each
  std::vector<StartedProbe> probes;
  probes.reserve(candidates.size());
  for (const HidCandidate& c : candidates) probes.push_back(StartProbe(c.path));
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(kProbeWaitS));
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const HidCandidate& c = candidates[i];
    DeviceListing listing;
    listing.info.kind = "hid";
    listing.info.path = c.path;
    listing.info.name = c.product.empty() ? "HaptiCAD protocol device" : c.product;
    HidProbe probe;
    if (FinishProbe(probes[i], deadline, &probe, &listing.error)) {
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
