// SPDX-License-Identifier: GPL-3.0-or-later
// Servo loop timing, as a CLI printing JSON (a timing is measured, never asserted).
//
//   servo_jitter_benchmark --device sim|emulator [--seconds 60] [--rate 1000]
//                          [--realtime-priority 70] [--transport-latency-us 0]
//                          [--load none|rebuild:TRIANGLES|scatter:MB|scatter-huge:MB]
//
// The real servo thread runs for the given time on the monotonic clock while a hand
// strokes a box's top face back and forth at 50 mm/s, pressing 3 mm in (so every tick
// renders contact and friction). `sim`: the SimulatedHand. `emulator`: the shipped HID
// backend over the hidapi emulator (tests/devices/hid/emulator), whose firmware
// measures the round trip: from sending an input report to receiving the force computed
// from it. Prints the loop's statistics (achieved rate, period jitter, wake-up latency,
// tick time, overruns, late ticks: those over the watchdog's gap, faults) and, for the
// emulator, the round trip.
//
// --load runs work on another thread of the same process for the whole time, as a
// designer's edits do in FreeCAD: `rebuild` builds a scene of an icosphere, repair
// included, over and over (what a property edit that retessellates costs); `scatter`
// adds one to random bytes of a block of MB megabytes, on 4 KiB pages or on huge pages:
// no system call, no page fault, only misses of the caches and the TLB.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "hapticad/core/geometry/icosphere.h"
#include "hapticad/core/huge_page_allocator.h"
#include "hapticad/devices/hid/hid_device.h"
#include "hapticad/devices/servo_loop.h"
#include "hapticad/devices/simulated_hand.h"
#include "hid_emulator.h"
#include "test_meshes.h"

namespace hapticad {
namespace {

struct Options {
  std::string device = "sim";
  double seconds = 60.0;
  double rate_hz = 1000.0;
  int realtime_priority = 70;
  double transport_latency_s = 0.0;
  std::string load = "none";  // none, rebuild, scatter or scatter-huge
  long long load_size = 0;    // triangles, or megabytes
};

[[noreturn]] void Usage(const char* why) {
  std::fprintf(stderr,
               "servo_jitter_benchmark: %s\nusage: servo_jitter_benchmark --device sim|emulator "
               "[--seconds S] [--rate HZ] [--realtime-priority P] [--transport-latency-us US]\n"
               "       [--load none|rebuild:TRIANGLES|scatter:MB|scatter-huge:MB]\n",
               why);
  std::exit(2);
}

Options Parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 >= argc) Usage(("missing value for " + arg).c_str());
    const char* value = argv[++i];
    if (arg == "--device") {
      o.device = value;
    } else if (arg == "--seconds") {
      o.seconds = std::atof(value);
    } else if (arg == "--rate") {
      o.rate_hz = std::atof(value);
    } else if (arg == "--realtime-priority") {
      o.realtime_priority = std::atoi(value);
    } else if (arg == "--transport-latency-us") {
      o.transport_latency_s = std::atof(value) * 1e-6;
    } else if (arg == "--load") {
      const std::string v = value;
      const std::size_t colon = v.find(':');
      o.load = v.substr(0, colon);
      if (colon != std::string::npos) o.load_size = std::atoll(v.c_str() + colon + 1);
      const bool sized = o.load == "rebuild" || o.load == "scatter" || o.load == "scatter-huge";
      if (o.load != "none" && !(sized && o.load_size > 0)) {
        Usage("--load is none, rebuild:TRIANGLES, scatter:MB or scatter-huge:MB");
      }
    } else {
      Usage(("unknown option " + arg).c_str());
    }
  }
  if (o.device != "sim" && o.device != "emulator") Usage("--device is sim or emulator");
  if (!(o.seconds > 0.0)) Usage("--seconds must be positive");
  return o;
}

// Adds one to random bytes of `block` until `stop`: returns how many millions it changed.
template <class Block>
long long Scatter(Block* block, const std::atomic<bool>& stop) {
  std::memset(block->data(), 1, block->size());  // every page in before the clock runs
  std::mt19937_64 rng(5);
  long long rounds = 0;
  unsigned long long sum = 0;
  while (!stop.load(std::memory_order_relaxed)) {
    for (int i = 0; i < 1000000; ++i) sum += ++(*block)[rng() % block->size()];
    ++rounds;
  }
  return sum == 0 ? -1 : rounds;  // the sum keeps the loop from being optimized away
}

// The work --load asks for, on its own thread until `stop`: returns how many rounds it
// made (scenes built, or millions of bytes changed).
long long RunLoad(const Options& o, const std::atomic<bool>& stop) {
  if (o.load == "rebuild") {
    const TriangleSoup soup = MakeIcosphere(IcosphereFrequencyFor(o.load_size), 50.0);
    long long builds = 0;
    while (!stop.load(std::memory_order_relaxed)) {
      HapticScene::Build(soup, 1e-3);
      ++builds;
    }
    return builds;
  }
  const auto bytes = static_cast<std::size_t>(o.load_size) << 20;
  if (o.load == "scatter") {
    std::vector<unsigned char> block(bytes);
    return Scatter(&block, stop);
  }
  HugePageVector<unsigned char> block(bytes);
  return Scatter(&block, stop);
}

// The hand: above the face (z = 0) for 0.2 s, down 3 mm into it, then strokes along x
// between -30 and +30 mm at 50 mm/s until the end.
void StrokePath(double seconds, std::vector<double>* times, std::vector<Vec3>* points) {
  times->assign({0.0, 0.2, 0.5});
  points->assign({Vec3(-0.03, 0, 0.01), Vec3(-0.03, 0, 0.01), Vec3(-0.03, 0, -0.003)});
  double t = 0.5;
  bool right = true;
  while (t < seconds + 2.0) {
    t += 1.2;  // 60 mm at 50 mm/s
    times->push_back(t);
    points->push_back(Vec3(right ? 0.03 : -0.03, 0, -0.003));
    right = !right;
  }
}

std::string LoadAverage() {
  std::ifstream f("/proc/loadavg");
  std::string one, five, fifteen;
  f >> one >> five >> fifteen;
  return "[" + one + ", " + five + ", " + fifteen + "]";
}

std::string Escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

int Main(int argc, char** argv) {
  const Options o = Parse(argc, argv);
  auto scene =
      HapticScene::Build(testing::MakeBoxSoup(Vec3(-50, -50, -100), Vec3(50, 50, 0)), 1e-3);
  auto renderer = std::make_shared<ForceRenderer>(scene, std::make_shared<SurfaceTable>(),
                                                  RenderLimits{8.0, 2500.0});
  std::vector<double> times;
  std::vector<Vec3> points;
  StrokePath(o.seconds, &times, &points);

  std::unique_ptr<Device> device;
  int emulated = -1;
  if (o.device == "sim") {
    DeviceLimits limits = SimulatedHandLimits();
    limits.workspace_min_d = Vec3::Constant(-0.08);
    limits.workspace_max_d = Vec3::Constant(0.08);
    auto hand = std::make_unique<SimulatedHand>(limits);
    ScriptedPath path;
    path.times_s = times;
    path.positions = points;
    hand->FollowPath(path);
    device = std::move(hand);
  } else {
    hidemu::FirmwareConfig c;
    c.hand_times_s = times;
    c.hand_positions_m = points;
    c.transport_latency_s = o.transport_latency_s;
    emulated = hidemu::AddDevice(c);
    device = HidDevice::Open(c.path);
  }

  ServoConfig config;
  config.rate_hz = o.rate_hz;
  config.realtime_priority = o.realtime_priority;
  ServoLoop loop(*device, renderer, config);
  const std::string load_before = LoadAverage();
  std::vector<TraceSample> trace;
  trace.reserve(static_cast<std::size_t>(o.seconds * o.rate_hz) + 1024);
  loop.Start();
  std::atomic<bool> stop_load{false};
  long long load_rounds = 0;
  std::thread load;
  if (o.load != "none") load = std::thread([&] { load_rounds = RunLoad(o, stop_load); });
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(o.seconds);
  while (std::chrono::steady_clock::now() < end && loop.running()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    loop.DrainTrace(&trace);
  }
  loop.Stop();
  loop.DrainTrace(&trace);
  stop_load.store(true);
  if (load.joinable()) load.join();  // a build under way finishes first
  const ServoStats s = loop.CalcStats();
  std::size_t contact = 0;
  // ticks that started over the watchdog after the one before: faults for a device in
  // real time; the simulated hand waits for them (Device::runs_on_loop_time)
  std::size_t late = 0;
  for (const TraceSample& t : trace) {
    contact += (t.flags & kContact) ? 1 : 0;
    late += t.period_us > config.safety.watchdog_s * 1e6 ? 1 : 0;
  }

  std::printf("{\n");
  std::printf("  \"device\": \"%s\",\n  \"rate_hz\": %g,\n  \"seconds\": %g,\n", o.device.c_str(),
              o.rate_hz, o.seconds);
  std::printf("  \"cpus\": %u,\n  \"load_average_before\": %s,\n  \"load_average_after\": %s,\n",
              std::thread::hardware_concurrency(), load_before.c_str(), LoadAverage().c_str());
  std::printf("  \"realtime\": %s,\n  \"realtime_report\": \"%s\",\n",
              s.realtime ? "true" : "false", Escape(loop.realtime_report()).c_str());
  std::printf("  \"load\": {\"kind\": \"%s\", \"size\": %lld, \"rounds\": %lld},\n", o.load.c_str(),
              o.load_size, load_rounds);
  std::printf("  \"session_end\": \"%s\",\n", SessionEndName(loop.session_end()));
  std::printf("  \"ticks\": %llu,\n  \"achieved_rate_hz\": %.3f,\n",
              static_cast<unsigned long long>(s.ticks), s.achieved_rate_hz);
  std::printf("  \"overruns\": %llu,\n  \"skipped_ticks\": %llu,\n  \"late_ticks\": %zu,\n",
              static_cast<unsigned long long>(s.overruns),
              static_cast<unsigned long long>(s.skipped_ticks), late);
  std::printf("  \"period_jitter_us\": {\"p50\": %.2f, \"p99\": %.2f, \"max\": %.1f},\n",
              s.period_jitter_p50_us, s.period_jitter_p99_us, s.period_jitter_max_us);
  std::printf("  \"wake_latency_us\": {\"p50\": %.2f, \"p99\": %.2f, \"max\": %.1f},\n",
              s.wake_latency_p50_us, s.wake_latency_p99_us, s.wake_latency_max_us);
  std::printf("  \"tick_us\": {\"p50\": %.2f, \"p99\": %.2f, \"max\": %.1f},\n", s.tick_p50_us,
              s.tick_p99_us, s.tick_max_us);
  std::printf("  \"contact_fraction\": %.4f,\n",
              trace.empty() ? 0.0 : static_cast<double>(contact) / trace.size());
  std::printf(
      "  \"faults\": {\"zero_force_ticks\": %llu, \"no_data\": %llu, \"stale\": %llu, "
      "\"watchdog\": %llu, \"out_of_range\": %llu, \"reported\": %llu, \"non_finite\": %llu}",
      static_cast<unsigned long long>(s.faults.zero_force_ticks),
      static_cast<unsigned long long>(s.faults.no_data),
      static_cast<unsigned long long>(s.faults.stale),
      static_cast<unsigned long long>(s.faults.watchdog),
      static_cast<unsigned long long>(s.faults.out_of_range),
      static_cast<unsigned long long>(s.faults.reported),
      static_cast<unsigned long long>(s.faults.non_finite));
  if (emulated >= 0) {
    const hidemu::Snapshot d = hidemu::GetSnapshot(emulated);
    const HidLinkStats link = static_cast<HidDevice&>(*device).CalcLinkStats();
    std::printf(",\n  \"transport_latency_us\": %g,\n", o.transport_latency_s * 1e6);
    std::printf(
        "  \"round_trip_us\": {\"p50\": %.1f, \"p99\": %.1f, \"max\": %.1f, \"count\": %llu},\n",
        d.round_trip_p50_s * 1e6, d.round_trip_p99_s * 1e6, d.round_trip_max_s * 1e6,
        static_cast<unsigned long long>(d.round_trips));
    std::printf(
        "  \"link\": {\"reports_read\": %llu, \"reports_used\": %llu, \"not_newer\": %llu, "
        "\"dropped\": %llu, \"malformed\": %llu, \"device_watchdog_trips\": %llu}",
        static_cast<unsigned long long>(link.reports_read),
        static_cast<unsigned long long>(link.reports_used),
        static_cast<unsigned long long>(link.not_newer),
        static_cast<unsigned long long>(link.dropped),
        static_cast<unsigned long long>(link.malformed),
        static_cast<unsigned long long>(d.watchdog_trips));
  }
  std::printf("\n}\n");
  return 0;
}

}  // namespace
}  // namespace hapticad

int main(int argc, char** argv) { return hapticad::Main(argc, argv); }
