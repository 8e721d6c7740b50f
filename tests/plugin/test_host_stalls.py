# SPDX-License-Identifier: GPL-3.0-or-later
"""host_stalls: which traces count as the host's stall (and so earn a new attempt), and
that the attempts run setUp and tearDown again and end in a failure when every one
stalls. Synthetic traces; no FreeCAD or _core needed."""
import unittest

import numpy as np

import host_stalls

WATCHDOG = 1 << 14
CONTACT = 1


def trace(tick_us, flags, period_us=1000.0):
    t = np.zeros(len(tick_us), dtype=[("time_s", "f8"), ("flags", "u4"), ("tick_us", "f8"),
                                      ("period_us", "f8")])
    t["time_s"] = np.arange(len(tick_us)) * 1e-3
    t["tick_us"] = tick_us
    t["flags"] = flags
    t["period_us"] = period_us
    return t


class CheckHostStallTest(unittest.TestCase):
    def test_a_watchdog_fault_between_quick_ticks_is_the_hosts(self):
        stalled = trace([3.0, 2.5, 4.0], [CONTACT, CONTACT | WATCHDOG, CONTACT], [1000.0, 25000.0, 1000.0])
        with self.assertRaisesRegex(host_stalls.HostStall, r"t = 0\.001 s after a 25\.0 ms gap"):
            host_stalls.check_host_stall(stalled, WATCHDOG)

    def test_a_trace_without_a_watchdog_fault_is_no_stall(self):
        host_stalls.check_host_stall(trace([3.0, 2000.0], [CONTACT, 0]), WATCHDOG)
        host_stalls.check_host_stall(trace([], []), WATCHDOG)

    def test_a_watchdog_fault_after_a_slow_tick_of_its_own_is_left_to_the_test(self):
        host_stalls.check_host_stall(trace([3.0, 1500.0, 4.0], [0, 0, WATCHDOG]), WATCHDOG)


class RerunTest(unittest.TestCase):
    def setUp(self):
        self.runs = getattr(self, "runs", [])
        self.runs.append("setUp")

    def tearDown(self):
        self.runs.append("tearDown")

    def test_a_stall_runs_the_scene_again_from_a_fresh_set_up(self):
        stalls = iter([True, False])

        @host_stalls.rerun_after_host_stall
        def body(case):
            case.runs.append("body")
            if next(stalls):
                raise host_stalls.HostStall("stalled")
            return "felt"

        self.assertEqual(body(self), "felt")
        self.assertEqual(self.runs, ["setUp", "body", "tearDown", "setUp", "body"])

    def test_stalls_in_every_attempt_fail(self):
        @host_stalls.rerun_after_host_stall
        def body(case):
            case.runs.append("body")
            raise host_stalls.HostStall("stalled")

        with self.assertRaisesRegex(AssertionError, "all 3 attempts"):
            body(self)
        self.assertEqual(self.runs.count("body"), host_stalls.ATTEMPTS)

    def test_any_other_failure_is_not_run_again(self):
        @host_stalls.rerun_after_host_stall
        def body(case):
            case.runs.append("body")
            raise AssertionError("no contact")

        with self.assertRaisesRegex(AssertionError, "no contact"):
            body(self)
        self.assertEqual(self.runs.count("body"), 1)


if __name__ == "__main__":
    unittest.main()
