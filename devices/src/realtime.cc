// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/devices/realtime.h"

#include <sched.h>

#include <cstring>

namespace hapticad {

RealtimeReport RequestRealtime(pthread_t thread, int priority) {
  RealtimeReport report;
  if (priority <= 0) {
    report.message = "normal scheduling: real-time scheduling was not requested";
    return report;
  }
  if (priority > 99) priority = 99;
  sched_param param{};
  param.sched_priority = priority;
  const int error = pthread_setschedparam(thread, SCHED_FIFO, &param);
  if (error == 0) {
    report.realtime = true;
    report.priority = priority;
    report.message = "real-time scheduling: SCHED_FIFO priority " + std::to_string(priority);
    return report;
  }
  report.message = "normal scheduling: SCHED_FIFO priority " + std::to_string(priority) +
                   " was refused (" + std::strerror(error) + ")";
  if (error == EPERM) {
    report.message +=
        "; the servo loop may miss ticks under load. To allow it, add the line "
        "'@hapticad - rtprio " +
        std::to_string(priority) +
        "' to /etc/security/limits.d/hapticad.conf, add yourself to the group hapticad "
        "and log in again (packaging/setup.sh does the first two)";
  }
  return report;
}

}  // namespace hapticad
