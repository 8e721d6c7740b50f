// SPDX-License-Identifier: GPL-3.0-or-later
// Stalls the threads of this process named `name` (pthread_setname_np; "hid-writer" is the
// HID writer's) for `seconds` of real time, as a loaded machine does by not scheduling
// them: each is sent SIGUSR2, whose handler sleeps, outside any hidapi call. Returns how
// many were sent it. Tests only; the handler stays installed (it is harmless unsent).
#pragma once

#include <dirent.h>
#include <signal.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>

namespace hapticad::testing_stall {

inline std::atomic<double>& StallSeconds() {
  static std::atomic<double> seconds{0.0};
  return seconds;
}

inline void SleepInHandler(int) {
  const double s = StallSeconds().load();
  timespec ts{static_cast<time_t>(s), static_cast<long>((s - std::floor(s)) * 1e9)};
  while (nanosleep(&ts, &ts) != 0) {  // async-signal-safe; a signal of its own resumes it
  }
}

inline int SignalThreads(const std::string& name) {
  int sent = 0;
  DIR* tasks = opendir("/proc/self/task");
  if (tasks == nullptr) return 0;
  while (dirent* entry = readdir(tasks)) {
    if (entry->d_name[0] == '.') continue;
    std::ifstream comm(std::string("/proc/self/task/") + entry->d_name + "/comm");
    std::string thread_name;
    std::getline(comm, thread_name);
    if (thread_name != name) continue;
    if (syscall(SYS_tgkill, getpid(), std::atoi(entry->d_name), SIGUSR2) == 0) ++sent;
  }
  closedir(tasks);
  return sent;
}

// Waits (at most 2 s) for a thread of that name: a thread just started names itself.
inline int StallThreads(const std::string& name, double seconds) {
  StallSeconds() = seconds;
  struct sigaction action {};
  action.sa_handler = SleepInHandler;
  action.sa_flags = SA_RESTART;
  sigemptyset(&action.sa_mask);
  sigaction(SIGUSR2, &action, nullptr);
  for (int tries = 0; tries < 2000; ++tries) {
    if (const int sent = SignalThreads(name)) return sent;
    const timespec ms{0, 1000000};
    nanosleep(&ms, nullptr);
  }
  return 0;
}

}  // namespace hapticad::testing_stall
