// SPDX-License-Identifier: GPL-3.0-or-later
// hidapi's C API over emulated devices (hid_emulator.h). The prototypes come from
// hidapi's own header, so the compiler holds this file to the real API.
#include <hidapi/hidapi.h>
#include <time.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <cwchar>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "firmware.h"
#include "hid_emulator.h"

using hapticad::hidemu::Firmware;
using hapticad::hidemu::FirmwareConfig;

// what a hid_device* points to
struct hid_device_ {
  int device = -1;           // index into the registry
  std::uint64_t resets = 0;  // the registry's Reset() count at the open: older ones are dead
  std::string path;
  bool nonblocking = false;
  wchar_t error[256] = L"Success";
  hid_device_info* info = nullptr;  // for hid_get_device_info
};

namespace hapticad::hidemu {
namespace {

struct Other {
  std::string path, product;
  std::uint16_t vendor_id, product_id, usage_page, usage;
};

struct Registry {
  std::mutex mutex;
  std::condition_variable clock_changed;  // a blocked write waits on it (kSlowWrite)
  std::uint64_t resets = 0;
  std::map<std::string, int> open_handles;  // by path
  // the times the host writes blocked now are due (kSlowWrite, kLateWrite); fixed size:
  // hid_write allocates nothing
  static constexpr int kMaxBlocked = 16;
  double blocked_until[kMaxBlocked] = {};
  int blocked = 0;
  std::vector<std::unique_ptr<Firmware>> devices;
  std::vector<Other> others;
  bool manual_clock = false;
  double manual_time_s = 0.0;
  timespec epoch{};
  wchar_t global_error[256] = L"Success";
  bool configured_from_env = false;
};

Registry& R() {
  static Registry* registry = new Registry;  // never destroyed: hidapi may be called at exit
  return *registry;
}

double RealSeconds() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<double>(ts.tv_sec) + ts.tv_nsec * 1e-9;
}

double NowLocked() {
  Registry& r = R();
  return r.manual_clock ? r.manual_time_s : RealSeconds();
}

void SetError(wchar_t* where, const wchar_t* text) {
  std::wcsncpy(where, text, 255);
  where[255] = 0;
}

wchar_t* Dup(const std::string& s) {
  auto* out = static_cast<wchar_t*>(std::malloc((s.size() + 1) * sizeof(wchar_t)));
  for (std::size_t i = 0; i < s.size(); ++i) out[i] = static_cast<unsigned char>(s[i]);
  out[s.size()] = 0;
  return out;
}

hid_device_info* MakeInfo(const std::string& path, std::uint16_t vid, std::uint16_t pid,
                          std::uint16_t usage_page, std::uint16_t usage,
                          const std::string& product) {
  auto* info = static_cast<hid_device_info*>(std::calloc(1, sizeof(hid_device_info)));
  info->path = strdup(path.c_str());
  info->vendor_id = vid;
  info->product_id = pid;
  info->serial_number = Dup(path);
  info->release_number = 0x0100;
  info->manufacturer_string = Dup("HaptiCAD emulator");
  info->product_string = Dup(product);
  info->usage_page = usage_page;
  info->usage = usage;
  info->interface_number = 0;
  info->bus_type = HID_API_BUS_USB;
  return info;
}

void ConfigureFromEnvLocked() {
  Registry& r = R();
  if (r.configured_from_env) return;
  r.configured_from_env = true;
  if (const char* spec = std::getenv("HAPTICAD_HIDEMU")) {
    r.mutex.unlock();  // ConfigureFromSpec takes the lock per device
    try {
      ConfigureFromSpec(spec);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "hidapi emulator: %s\n", e.what());  // hidapi is C: no throwing
    }
    r.mutex.lock();
  }
}

Firmware* DeviceOf(hid_device* dev) {
  if (!dev || dev->device < 0 || dev->device >= static_cast<int>(R().devices.size()) ||
      dev->resets != R().resets) {
    return nullptr;  // (a handle from before a Reset() never reaches a later test's device)
  }
  return R().devices[dev->device].get();
}

// the calls into hidapi's global state (hid_emulator.h: SetGlobalCallDelay)
std::atomic<double> global_call_delay_s{0.0};
std::atomic<int> global_calls_inside{0};
std::atomic<int> global_calls_max{0};
thread_local int global_call_depth = 0;  // hid_open calls hid_open_path: one call

// A call into hidapi's global state, for its duration: counted, and first delayed (without
// the registry's lock, which would serialise the calls being watched).
class GlobalCall {
 public:
  GlobalCall() {
    if (global_call_depth++ > 0) return;
    const int inside = global_calls_inside.fetch_add(1) + 1;
    int max = global_calls_max.load();
    while (inside > max && !global_calls_max.compare_exchange_weak(max, inside)) {
    }
    const double delay_s = global_call_delay_s.load();
    if (delay_s > 0.0) std::this_thread::sleep_for(std::chrono::duration<double>(delay_s));
  }
  ~GlobalCall() {
    if (--global_call_depth == 0) global_calls_inside.fetch_sub(1);
  }
  GlobalCall(const GlobalCall&) = delete;
  GlobalCall& operator=(const GlobalCall&) = delete;
};

constexpr const wchar_t* kGone = L"hid_read_timeout: unexpected poll error (device disconnected)";

}  // namespace

void Reset() {
  std::lock_guard<std::mutex> lock(R().mutex);
  ++R().resets;  // a write blocked on a device about to go fails at once
  R().clock_changed.notify_all();
  R().devices.clear();
  R().others.clear();
  R().manual_clock = false;
  R().configured_from_env = true;  // an explicit set-up replaces the environment's
  global_call_delay_s = 0.0;
  global_calls_max = 0;
}

void SetGlobalCallDelay(double seconds) { global_call_delay_s = seconds; }

int MaxConcurrentGlobalCalls() { return global_calls_max.load(); }

int AddDevice(const FirmwareConfig& config) {
  std::lock_guard<std::mutex> lock(R().mutex);
  R().devices.push_back(std::make_unique<Firmware>(config, NowLocked()));
  return static_cast<int>(R().devices.size()) - 1;
}

void AddOtherDevice(const std::string& path, std::uint16_t vendor_id, std::uint16_t product_id,
                    std::uint16_t usage_page, std::uint16_t usage, const std::string& product) {
  std::lock_guard<std::mutex> lock(R().mutex);
  R().others.push_back(Other{path, product, vendor_id, product_id, usage_page, usage});
}

void Unplug(int id) {
  std::lock_guard<std::mutex> lock(R().mutex);
  R().devices.at(id)->AdvanceTo(NowLocked());
  R().devices.at(id)->Unplug();
}

void SetHandTarget(int id, const Vec3& target_m) {
  std::lock_guard<std::mutex> lock(R().mutex);
  R().devices.at(id)->AdvanceTo(NowLocked());
  R().devices.at(id)->SetHandTarget(target_m);
}

Snapshot GetSnapshot(int id) {
  std::lock_guard<std::mutex> lock(R().mutex);
  R().devices.at(id)->AdvanceTo(NowLocked());
  return R().devices.at(id)->snapshot();
}

void UseManualClock(double t_s) {
  std::lock_guard<std::mutex> lock(R().mutex);
  R().manual_clock = true;
  R().manual_time_s = t_s;
}

void SetTime(double t_s) {
  std::lock_guard<std::mutex> lock(R().mutex);
  R().manual_time_s = t_s;
  R().clock_changed.notify_all();
}

void UseRealClock() {
  std::lock_guard<std::mutex> lock(R().mutex);
  R().manual_clock = false;
  R().clock_changed.notify_all();
}

double Now() {
  std::lock_guard<std::mutex> lock(R().mutex);
  return NowLocked();
}

std::atomic<std::uint64_t> error_calls{0};

std::uint64_t HidErrorCalls() { return error_calls.load(std::memory_order_relaxed); }

int OpenHandles(const std::string& path) {
  std::lock_guard<std::mutex> lock(R().mutex);
  const auto it = R().open_handles.find(path);
  return it == R().open_handles.end() ? 0 : it->second;
}

int BlockedWrites() {
  std::lock_guard<std::mutex> lock(R().mutex);
  int n = 0;
  for (int i = 0; i < R().blocked; ++i) n += NowLocked() < R().blocked_until[i] ? 1 : 0;
  return n;
}

void ConfigureFromSpec(const std::string& spec) {
  std::stringstream devices(spec);
  std::string one;
  int index = 0;
  while (std::getline(devices, one, ';')) {
    if (one.empty()) continue;
    FirmwareConfig config;
    config.path = "emu:" + std::to_string(index++);
    bool other = false;
    std::stringstream fields(one);
    std::string field;
    while (std::getline(fields, field, ',')) {
      const auto eq = field.find('=');
      if (eq == std::string::npos)
        throw std::invalid_argument("HAPTICAD_HIDEMU: '" + field + "' is not key=value");
      const std::string key = field.substr(0, eq), value = field.substr(eq + 1);
      auto range = [&](double* a, double* b) {
        const auto dash = value.find('-');
        *a = std::stod(value.substr(0, dash));
        *b = dash == std::string::npos ? *a : std::stod(value.substr(dash + 1));
      };
      auto version = [](double v) {
        const int major = static_cast<int>(v);
        return static_cast<std::uint16_t>(major << 8 |
                                          static_cast<int>(std::lround((v - major) * 10)));
      };
      if (key == "path") {
        config.path = value;
      } else if (key == "product") {
        config.product = value;
      } else if (key == "version") {
        double a, b;
        range(&a, &b);
        config.version_min = version(a);
        config.version_max = version(b);
      } else if (key == "max_force") {
        config.max_force_n = std::stod(value);
        config.continuous_force_n = config.max_force_n / 2;
      } else if (key == "rate") {
        config.report_rate_hz = static_cast<std::uint16_t>(std::stoi(value));
      } else if (key == "unplug_at") {
        config.faults.push_back(FaultWindow{Fault::kUnplug, std::stod(value)});
      } else if (key == "stall") {
        double a, b;
        range(&a, &b);
        config.faults.push_back(FaultWindow{Fault::kStall, a, b});
      } else if (key == "slow_feature" || key == "slow_session") {
        const Fault fault = key == "slow_feature" ? Fault::kSlowFeature : Fault::kSlowSession;
        config.faults.push_back(
            FaultWindow{fault, 0.0, std::numeric_limits<double>::infinity(), std::stod(value)});
      } else if (key == "kind" && value == "other") {
        other = true;
      } else {
        throw std::invalid_argument("HAPTICAD_HIDEMU: unknown key '" + key + "'");
      }
    }
    if (other) {
      AddOtherDevice(config.path, 0x046d, 0xc31c, 0x0001, 0x0006, config.product);
    } else {
      AddDevice(config);
    }
  }
}

}  // namespace hapticad::hidemu

using hapticad::hidemu::DeviceOf;
using hapticad::hidemu::GlobalCall;
using hapticad::hidemu::kGone;
using hapticad::hidemu::NowLocked;
using hapticad::hidemu::R;
using hapticad::hidemu::SetError;

extern "C" {

int HID_API_EXPORT HID_API_CALL hid_init(void) {
  const GlobalCall global;
  std::lock_guard<std::mutex> lock(R().mutex);
  hapticad::hidemu::ConfigureFromEnvLocked();
  return 0;
}

int HID_API_EXPORT HID_API_CALL hid_exit(void) {
  const GlobalCall global;
  return 0;
}

struct hid_device_info HID_API_EXPORT* HID_API_CALL hid_enumerate(unsigned short vendor_id,
                                                                  unsigned short product_id) {
  const GlobalCall global;  // before the lock: released after it
  std::lock_guard<std::mutex> lock(R().mutex);
  hapticad::hidemu::ConfigureFromEnvLocked();
  hid_device_info* head = nullptr;
  hid_device_info** tail = &head;
  auto add = [&](hid_device_info* info) {
    if ((vendor_id && info->vendor_id != vendor_id) ||
        (product_id && info->product_id != product_id)) {
      hid_free_enumeration(info);
      return;
    }
    *tail = info;
    tail = &info->next;
  };
  for (const auto& o : R().others) {
    add(hapticad::hidemu::MakeInfo(o.path, o.vendor_id, o.product_id, o.usage_page, o.usage,
                                   o.product));
  }
  const double now = NowLocked();
  for (const auto& d : R().devices) {
    d->AdvanceTo(now);
    if (!d->plugged()) continue;
    const FirmwareConfig& c = d->config();
    add(hapticad::hidemu::MakeInfo(c.path, c.vendor_id, c.product_id, c.usage_page, c.usage,
                                   c.product));
  }
  if (!head) SetError(R().global_error, L"No HID devices found in the system.");
  return head;
}

void HID_API_EXPORT HID_API_CALL hid_free_enumeration(struct hid_device_info* devs) {
  while (devs) {
    hid_device_info* next = devs->next;
    std::free(devs->path);
    std::free(devs->serial_number);
    std::free(devs->manufacturer_string);
    std::free(devs->product_string);
    std::free(devs);
    devs = next;
  }
}

HID_API_EXPORT hid_device* HID_API_CALL hid_open_path(const char* path) {
  const GlobalCall global;  // before the lock: released after it
  std::lock_guard<std::mutex> lock(R().mutex);
  hapticad::hidemu::ConfigureFromEnvLocked();
  const double now = NowLocked();
  for (std::size_t i = 0; i < R().devices.size(); ++i) {
    Firmware& d = *R().devices[i];
    d.AdvanceTo(now);
    if (d.config().path == path && d.plugged()) {
      if (d.config().deny_open) {  // no udev rule: open() fails, enumeration still lists it
        std::swprintf(R().global_error, 256,
                      L"Failed to open a device with path '%s': Permission denied", path);
        errno = EACCES;
        return nullptr;
      }
      auto* dev = new hid_device_;
      dev->device = static_cast<int>(i);
      dev->resets = R().resets;
      dev->path = path;
      SetError(R().global_error, L"Success");
      ++R().open_handles[path];
      return dev;
    }
  }
  for (const auto& o : R().others) {
    if (o.path == path) {  // a keyboard: opens, but speaks no HaptiCAD
      auto* dev = new hid_device_;
      dev->device = -1;
      dev->path = path;
      ++R().open_handles[path];
      return dev;
    }
  }
  SetError(R().global_error,
           L"hid_open_path: failed to open device, error: No such file or directory");
  return nullptr;
}

HID_API_EXPORT hid_device* HID_API_CALL hid_open(unsigned short vendor_id,
                                                 unsigned short product_id,
                                                 const wchar_t* /*serial_number*/) {
  const GlobalCall global;
  std::string path;
  {
    std::lock_guard<std::mutex> lock(R().mutex);
    for (const auto& d : R().devices) {
      if (d->plugged() && d->config().vendor_id == vendor_id &&
          d->config().product_id == product_id) {
        path = d->config().path;
        break;
      }
    }
  }
  if (path.empty()) {
    std::lock_guard<std::mutex> lock(R().mutex);
    SetError(R().global_error, L"hid_open: no such device");
    return nullptr;
  }
  return hid_open_path(path.c_str());
}

// Blocked in the kernel until `until` (emulator clock), the lock free meanwhile; the
// device afterwards, or null if the emulator was reset.
static Firmware* BlockLocked(std::unique_lock<std::mutex>& lock, hid_device* dev, double until) {
  const std::uint64_t resets = R().resets;
  auto& r = R();
  const int slot = r.blocked < r.kMaxBlocked ? r.blocked++ : r.kMaxBlocked - 1;
  r.blocked_until[slot] = until;
  while (NowLocked() < until && R().resets == resets) {
    if (R().manual_clock) {
      R().clock_changed.wait(lock);
    } else {
      R().clock_changed.wait_for(lock, std::chrono::duration<double>(until - NowLocked()));
    }
  }
  for (int i = 0; i < r.blocked; ++i) {  // forget one entry of `until`
    if (r.blocked_until[i] == until) {
      r.blocked_until[i] = r.blocked_until[--r.blocked];
      break;
    }
  }
  return R().resets == resets ? DeviceOf(dev) : nullptr;
}

// A feature-report request the device does not answer (kSlowFeature): true, with the
// error set, after blocking as usbhid would.
static bool FeatureTimedOut(std::unique_lock<std::mutex>& lock, hid_device* dev, Firmware* d,
                            double now, std::uint8_t report_id) {
  const double block_s = d->FeatureBlockS(now, report_id);
  if (block_s <= 0.0) return false;
  BlockLocked(lock, dev, now + block_s);
  SetError(dev->error, L"Connection timed out");
  errno = ETIMEDOUT;
  return true;
}

int HID_API_EXPORT HID_API_CALL hid_write(hid_device* dev, const unsigned char* data,
                                          size_t length) {
  std::unique_lock<std::mutex> lock(R().mutex);
  Firmware* d = DeviceOf(dev);
  if (!d) {
    SetError(dev->error, L"hid_write: the device has no output endpoint");
    return -1;
  }
  double now = NowLocked();
  d->AdvanceTo(now);
  bool fails = false;
  if (const double block_s = d->WriteBlockS(now, &fails); block_s > 0.0) {
    d = BlockLocked(lock, dev, now + block_s);
    if (!d || fails) {  // timed out (usbhid: ETIMEDOUT), the report lost
      if (d) d->CountTimedOut();
      SetError(dev->error, L"Connection timed out");
      errno = ETIMEDOUT;
      return -1;
    }
    now = NowLocked();
    d->AdvanceTo(now);
  }
  const int n = d->WriteReport(now, data, length);
  if (n < 0) SetError(dev->error, L"hid_write: No such device");
  return n;
}

int HID_API_EXPORT HID_API_CALL hid_read_timeout(hid_device* dev, unsigned char* data,
                                                 size_t length, int milliseconds) {
  const double deadline = milliseconds < 0 ? 1e300 : hapticad::hidemu::Now() + milliseconds * 1e-3;
  while (true) {
    {
      std::lock_guard<std::mutex> lock(R().mutex);
      Firmware* d = DeviceOf(dev);
      if (!d) return 0;  // a keyboard that says nothing
      const double now = NowLocked();
      d->AdvanceTo(now);
      if (d->ReadInterrupted(now)) {  // hidapi: poll() returned -1, errno EINTR
        SetError(dev->error, L"Interrupted system call");
        errno = EINTR;
        return -1;
      }
      const int n = d->ReadReport(now, data, length);
      if (n < 0) SetError(dev->error, kGone);
      if (n != 0 || now >= deadline || R().manual_clock) return n;
    }
    std::this_thread::sleep_for(std::chrono::microseconds(100));
  }
}

int HID_API_EXPORT HID_API_CALL hid_read(hid_device* dev, unsigned char* data, size_t length) {
  return hid_read_timeout(dev, data, length, dev->nonblocking ? 0 : -1);
}

int HID_API_EXPORT HID_API_CALL hid_set_nonblocking(hid_device* dev, int nonblock) {
  dev->nonblocking = nonblock != 0;
  return 0;
}

int HID_API_EXPORT HID_API_CALL hid_send_feature_report(hid_device* dev, const unsigned char* data,
                                                        size_t length) {
  std::unique_lock<std::mutex> lock(R().mutex);
  Firmware* d = DeviceOf(dev);
  if (!d || !d->plugged()) {
    SetError(dev->error,
             d ? L"ioctl (SFEATURE): No such device" : L"ioctl (SFEATURE): Broken pipe");
    return -1;
  }
  d->AdvanceTo(NowLocked());
  if (FeatureTimedOut(lock, dev, d, NowLocked(), data[0])) return -1;
  const int n = d->SendFeature(data, length);
  if (n < 0) SetError(dev->error, L"ioctl (SFEATURE): Broken pipe");
  return n;
}

int HID_API_EXPORT HID_API_CALL hid_get_feature_report(hid_device* dev, unsigned char* data,
                                                       size_t length) {
  std::unique_lock<std::mutex> lock(R().mutex);
  Firmware* d = DeviceOf(dev);
  if (!d || !d->plugged()) {
    SetError(dev->error,
             d ? L"ioctl (GFEATURE): No such device" : L"ioctl (GFEATURE): Broken pipe");
    return -1;
  }
  d->AdvanceTo(NowLocked());
  if (FeatureTimedOut(lock, dev, d, NowLocked(), data[0])) return -1;
  const int n = d->GetFeature(data, length);
  if (n < 0) SetError(dev->error, L"ioctl (GFEATURE): Broken pipe");
  return n;
}

int HID_API_EXPORT HID_API_CALL hid_get_input_report(hid_device* dev, unsigned char*, size_t) {
  std::lock_guard<std::mutex> lock(R().mutex);
  SetError(dev->error, L"hid_get_input_report: not supported by the emulator");
  return -1;
}

void HID_API_EXPORT HID_API_CALL hid_close(hid_device* dev) {
  if (!dev) return;
  {
    std::lock_guard<std::mutex> lock(R().mutex);
    --R().open_handles[dev->path];
  }
  if (dev->info) hid_free_enumeration(dev->info);
  delete dev;
}

static int CopyString(hid_device* dev, const std::string& text, wchar_t* out, size_t maxlen) {
  if (maxlen == 0) return -1;
  std::size_t i = 0;
  for (; i < text.size() && i + 1 < maxlen; ++i) out[i] = static_cast<unsigned char>(text[i]);
  out[i] = 0;
  (void)dev;
  return 0;
}

int HID_API_EXPORT_CALL hid_get_manufacturer_string(hid_device* dev, wchar_t* string,
                                                    size_t maxlen) {
  return CopyString(dev, "HaptiCAD emulator", string, maxlen);
}

int HID_API_EXPORT_CALL hid_get_product_string(hid_device* dev, wchar_t* string, size_t maxlen) {
  std::lock_guard<std::mutex> lock(R().mutex);
  Firmware* d = DeviceOf(dev);
  return CopyString(dev, d ? d->config().product : "Keyboard", string, maxlen);
}

int HID_API_EXPORT_CALL hid_get_serial_number_string(hid_device* dev, wchar_t* string,
                                                     size_t maxlen) {
  std::lock_guard<std::mutex> lock(R().mutex);
  Firmware* d = DeviceOf(dev);
  return CopyString(dev, d ? d->config().path : "", string, maxlen);
}

int HID_API_EXPORT_CALL hid_get_indexed_string(hid_device* dev, int, wchar_t*, size_t) {
  std::lock_guard<std::mutex> lock(R().mutex);
  SetError(dev->error, L"hid_get_indexed_string: not supported by the emulator");
  return -1;
}

struct hid_device_info HID_API_EXPORT* HID_API_CALL hid_get_device_info(hid_device* dev) {
  std::lock_guard<std::mutex> lock(R().mutex);
  Firmware* d = DeviceOf(dev);
  if (!d) return nullptr;
  if (!dev->info) {
    const FirmwareConfig& c = d->config();
    dev->info = hapticad::hidemu::MakeInfo(c.path, c.vendor_id, c.product_id, c.usage_page, c.usage,
                                           c.product);
  }
  return dev->info;
}

HID_API_EXPORT const wchar_t* HID_API_CALL hid_error(hid_device* dev) {
  hapticad::hidemu::error_calls.fetch_add(1, std::memory_order_relaxed);
  if (!dev) {
    const GlobalCall global;
    return R().global_error;
  }
  return dev->error;
}

HID_API_EXPORT const struct hid_api_version* HID_API_CALL hid_version(void) {
  static const hid_api_version version{HID_API_VERSION_MAJOR, HID_API_VERSION_MINOR,
                                       HID_API_VERSION_PATCH};
  return &version;
}

HID_API_EXPORT const char* HID_API_CALL hid_version_str(void) {
  return HID_API_VERSION_STR "-hapticad-emulator";
}

}  // extern "C"
