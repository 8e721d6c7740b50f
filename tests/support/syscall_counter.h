// SPDX-License-Identifier: GPL-3.0-or-later
// Counts the system calls a function makes: it runs in a forked child under a seccomp
// filter that traps every system call (SIGSYS, answered with ENOSYS and counted) but
// the child's report to the parent and its exit. The function must not need any other
// system call to work, which is the point: a servo tick that makes none runs the same.
// Linux x86-64.
#pragma once

#include <functional>

namespace hapticad::testing {

// The number of system calls `fn` made; -1 if the child could not report (it
// crashed), -2 if seccomp is unavailable.
long CountSystemCalls(const std::function<void()>& fn);

}  // namespace hapticad::testing
