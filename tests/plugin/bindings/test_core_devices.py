# SPDX-License-Identifier: GPL-3.0-or-later
"""The device part of hapticad._core, as the FreeCAD GUI uses it (devices/README.md):
a SimulatedHand whose target another thread sets, a ServoLoop started and stopped
with its trace drained while it runs, its statistics, the end of a session and why,
the device list and HID devices (through the hidapi emulator preloaded in front of
libhidapi, configured by HAPTICAD_HIDEMU). No FreeCAD needed. The simulated hand waits for a late tick (it lives on
the loop's clock): no live trace here may show the watchdog's fault, whatever the host does.

Environment: HAPTICAD_MOD (the staged Mod folder). Runs under /usr/bin/python3."""
import os
import sys
import threading
import time
import unittest

import numpy as np

sys.path.insert(0, os.environ["HAPTICAD_MOD"])
from hapticad import _core  # noqa: E402

# a box [-50, 50] mm, top face at z = 50 mm, one CAD face per side
V = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
              [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], float) * 0.05
T = np.array([[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],
              [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]])
FACES = np.array([4, 4, 5, 5, 2, 2, 1, 1, 3, 3, 0, 0], np.int32)


def box_renderer(limits, top=0.05):
    """The box, its top face at `top` m."""
    v = V.copy()
    v[4:, 2] = top
    scene = _core.HapticScene.build(v, T, FACES, 1.0)
    surfaces = _core.SurfaceTable([_core.SurfaceProperties() for _ in range(6)])
    return _core.ForceRenderer(scene, surfaces, _core.render_limits_for(limits, _core.WorkspaceMapping()))


def hand_limits():
    limits = _core.simulated_hand_limits()
    limits.workspace_min_d = [-0.1, -0.1, -0.1]
    limits.workspace_max_d = [0.1, 0.1, 0.1]
    return limits


def wait_until(predicate, timeout=3.0):
    end = time.monotonic() + timeout
    while time.monotonic() < end and not predicate():
        time.sleep(0.005)
    return predicate()


class SimulatedHandSession(unittest.TestCase):
    def test_a_mouse_thread_presses_the_hand_onto_the_part(self):
        limits = hand_limits()
        hand = _core.SimulatedHand(limits=limits, model=_core.HandModel())
        hand.set_target((0.0, 0.0, 0.06))
        loop = _core.ServoLoop(hand, box_renderer(limits), rate_hz=1000.0)
        self.assertFalse(loop.running)
        self.assertEqual(loop.session_end, _core.SessionEnd.NOT_STARTED)
        loop.start()
        self.assertTrue(loop.running)
        self.assertTrue(loop.realtime_report.startswith(("real-time scheduling", "normal scheduling")))

        # the GUI's thread moves the target while the loop runs
        def mouse():
            for z in np.linspace(0.06, 0.045, 100):
                hand.set_target(np.array([0.0, 0.0, z]))
                time.sleep(0.002)
        t = threading.Thread(target=mouse)
        t.start()
        t.join()
        chunks = []
        deadline = time.monotonic() + 1.5
        while time.monotonic() < deadline:
            chunks.append(loop.drain_trace())  # never blocks
            time.sleep(0.05)
        loop.stop()
        stats = loop.calc_stats()  # after the stop: the trace below holds every tick it counted
        chunks.append(loop.drain_trace())
        trace = np.concatenate(chunks)
        self.assertFalse((trace["flags"] & _core.FLAG_FAULT_WATCHDOG).any())
        self.assertFalse(loop.running)
        self.assertEqual(loop.session_end, _core.SessionEnd.STOPPED)
        self.assertEqual(loop.fault_message, "")
        # a NumPy structured array of TraceSample
        for field in ("time_s", "device_m", "proxy_m", "force_n", "flags", "cad_face", "handle_d_m"):
            self.assertIn(field, trace.dtype.names)
        self.assertTrue(np.all(np.diff(trace["time_s"]) > 0))
        # pressed 5 mm into 400 N/m against a 400 N/m grip: 1 N, the hand 2.5 mm in
        last = trace[-1]
        self.assertTrue(last["flags"] & _core.FLAG_CONTACT)
        self.assertEqual(last["cad_face"], 5)
        self.assertAlmostEqual(last["force_n"][2], 1.0, delta=0.05)
        self.assertAlmostEqual(hand.true_state.position_d[2], 0.0475, delta=1e-4)
        self.assertGreater(stats.achieved_rate_hz, 0)
        self.assertLessEqual(stats.period_jitter_p50_us, stats.period_jitter_p99_us)
        f = stats.faults
        self.assertEqual(f.zero_force_ticks, 0,
                         f"no_data {f.no_data}, stale {f.stale}, out_of_range {f.out_of_range}, "
                         f"non_finite {f.non_finite}, reported {f.reported}, watchdog {f.watchdog}, "
                         f"unplugged {f.unplugged}")
        self.assertEqual(stats.ticks, len(trace))

    def test_the_servo_thread_runs_while_python_holds_the_gil(self):
        hand = _core.SimulatedHand(limits=hand_limits())
        loop = _core.ServoLoop(hand, box_renderer(hand_limits()))
        loop.start()
        before = loop.ticks
        # pure Python (loop.ticks keeps the GIL too): the GIL is never released here, until
        # the loop has counted 100 more ticks; the deadline only bounds a loop that stopped
        end = time.monotonic() + 10.0
        while loop.ticks - before <= 100 and time.monotonic() < end:
            pass
        after = loop.ticks
        loop.stop()
        self.assertGreater(after - before, 100)
        # the ticks ran on the loop's clock: each at its own period
        stats = loop.calc_stats()
        self.assertGreaterEqual(stats.ticks, after)
        self.assertGreaterEqual(stats.elapsed_s, (stats.ticks - 1) * 1e-3 - 1e-9)

    def test_follows_a_path_and_a_recorded_trajectory(self):
        hand = _core.SimulatedHand(limits=hand_limits())
        hand.follow_path([0.0, 0.2, 0.4], np.array([[0, 0, 0.07], [0.02, 0, 0.07], [0.02, 0.02, 0.07]]))
        loop = _core.ServoLoop(hand, box_renderer(hand_limits()))
        first = loop.run_for(0.6)
        self.assertFalse((first["flags"] & _core.FLAG_FAULT_WATCHDOG).any())
        self.assertTrue(hand.following_path)
        self.assertAlmostEqual(first[-1]["handle_d_m"][0], 0.02, delta=3e-4)
        # replay what the handle did as a recording
        hand.follow_path(first["time_s"], first["handle_d_m"])
        second = loop.run_for(0.6)
        self.assertFalse((second["flags"] & _core.FLAG_FAULT_WATCHDOG).any())
        self.assertAlmostEqual(second[-1]["handle_d_m"][1], first[-1]["handle_d_m"][1], delta=3e-4)
        hand.follow_target()
        self.assertFalse(hand.following_path)

    def test_bad_input_gets_a_clear_error(self):
        hand = _core.SimulatedHand()
        with self.assertRaisesRegex(ValueError, "three numbers"):
            hand.set_target((1.0, 2.0))
        with self.assertRaisesRegex(ValueError, "not finite"):
            hand.set_target((float("nan"), 0.0, 0.0))
        with self.assertRaisesRegex(ValueError, "rate"):
            _core.ServoLoop(hand, box_renderer(hand_limits()), rate_hz=50000.0)
        with self.assertRaises(_core.DeviceError):
            _core.open_device("sim:nothing")
        self.assertTrue(issubclass(_core.DeviceError, RuntimeError))
        scene = _core.HapticScene.build(V, T, FACES, 1.0)
        for far in ((float("nan"), 0.0, 0.0), (0.0, float("inf"), 0.0), (1e200, 0.0, 0.0)):
            with self.assertRaisesRegex(ValueError, "not finite, or more than a million"):
                scene.calc_closest_point(far)

    def test_mapping_clutch_and_scene_swap_reach_the_running_loop(self):
        limits = hand_limits()
        hand = _core.SimulatedHand(limits=limits)
        hand.set_target((0.0, 0.0, 0.08))
        loop = _core.ServoLoop(hand, box_renderer(limits))
        loop.start()
        mapping = _core.WorkspaceMapping()
        mapping.offset_w = [0.0, 0.0, 0.01]
        loop.set_mapping(mapping)
        self.assertTrue(wait_until(lambda: abs(loop.mapping.offset_w[2] - 0.01) < 1e-12))
        loop.set_clutch(True)
        self.assertTrue(wait_until(lambda: loop.latest()["flags"] & _core.FLAG_CLUTCHED))
        loop.set_clutch(False)
        self.assertTrue(wait_until(lambda: not loop.latest()["flags"] & _core.FLAG_CLUTCHED))
        world = loop.mapping.device_to_world(hand.true_state.position_d)
        self.assertFalse(loop.latest()["flags"] & _core.FLAG_CONTACT)  # free, 40 mm over the top
        # a box whose top, at 95 mm, is over the tool (90 mm): the proxy restarts on it
        loop.set_renderer(box_renderer(limits, top=0.095))
        self.assertTrue(wait_until(lambda: loop.latest()["flags"] & _core.FLAG_CONTACT),
                        "the new scene never reached the loop")
        after = loop.latest()
        loop.stop()
        self.assertFalse((loop.drain_trace()["flags"] & _core.FLAG_FAULT_WATCHDOG).any())
        self.assertAlmostEqual(world[2], 0.09, delta=2e-4)
        self.assertEqual(after["cad_face"], 5)
        self.assertAlmostEqual(after["proxy_m"][2], 0.095, delta=1e-6)  # on the new top


class HidSession(unittest.TestCase):
    """Needs the emulator preloaded (HAPTICAD_HIDEMU: emu:0 unplugged at 1 s)."""

    def test_an_unplugged_device_ends_the_session_with_a_message(self):
        devices = _core.list_devices()
        self.assertEqual([d["path"] for d in devices], ["sim:hand", "emu:0"])
        device = _core.open_device("emu:0")
        self.assertIsInstance(device, _core.HidDevice)
        loop = _core.ServoLoop(device, box_renderer(device.info.limits))
        loop.start()
        self.assertTrue(wait_until(lambda: not loop.running, timeout=5.0))
        self.assertEqual(loop.session_end, _core.SessionEnd.UNPLUGGED)
        self.assertIn("was unplugged at", loop.fault_message)
        self.assertIn("device disconnected", loop.fault_message)
        trace = loop.drain_trace()
        self.assertTrue(trace[-1]["flags"] & _core.FLAG_FAULT_UNPLUGGED)
        self.assertEqual(np.abs(trace[-1]["force_n"]).max(), 0.0)
        self.assertGreater(device.calc_link_stats().reports_used, 100)
        self.assertTrue(device.unplugged)
        with self.assertRaisesRegex(_core.DeviceError, "cannot open the HID device emu:0"):
            _core.HidDevice.open("emu:0")


if __name__ == "__main__":
    unittest.main()
