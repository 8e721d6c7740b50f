// SPDX-License-Identifier: GPL-3.0-or-later
// Real-time scheduling for the servo thread: ask Linux for SCHED_FIFO and say plainly
// what was granted and, when refused, how to allow it. Never fatal: a refused request
// leaves the thread at normal priority, which keeps 1 kHz on an idle desktop but not
// under load (BENCHMARKS.md).
#pragma once

#include <pthread.h>

#include <string>

namespace hapticad {

struct RealtimeReport {
  bool realtime = false;  // SCHED_FIFO granted
  int priority = 0;       // granted priority, 0 when not real-time
  std::string message;    // for the user, one sentence
};

// Asks SCHED_FIFO at `priority` (1..99) for `thread`; `priority` <= 0 asks nothing.
RealtimeReport RequestRealtime(pthread_t thread, int priority);

}  // namespace hapticad
