# SPDX-License-Identifier: GPL-3.0-or-later
"""`hapticad devices --json` end to end: the simulated hand always; HID devices from
the real hidapi (none on a machine without one) and, with the hidapi emulator
preloaded in front of libhidapi, emulated ones: usable devices with their limits,
unusable ones with the reason, other HID devices (a keyboard) never.

Environment: HAPTICAD_CLI (the launcher), HAPTICAD_HIDEMU_PRELOAD (the emulator as a
shared library). Runs under /usr/bin/python3."""
import json
import os
import subprocess
import unittest

CLI = os.environ["HAPTICAD_CLI"]
PRELOAD = os.environ["HAPTICAD_HIDEMU_PRELOAD"]

LIMIT_KEYS = {"max_force_n", "continuous_force_n", "max_stiffness_n_per_m", "max_damping_n_s_per_m",
              "workspace_min_d", "workspace_max_d", "position_resolution_m"}


def run_cli(*args, emulate=None):
    env = dict(os.environ)
    env.pop("LD_PRELOAD", None)
    if emulate is not None:
        # LD_PRELOAD splits on spaces: the library by name, found in its folder (a checkout path may have spaces)
        env["LD_PRELOAD"] = os.path.basename(PRELOAD)
        env["LD_LIBRARY_PATH"] = os.pathsep.join(p for p in (os.path.dirname(PRELOAD), env.get("LD_LIBRARY_PATH"))
                                                 if p)
        env["HAPTICAD_HIDEMU"] = emulate
    return subprocess.run([CLI, *args], capture_output=True, text=True, timeout=60, env=env)


class DevicesCommandTest(unittest.TestCase):
    def check_row(self, row):
        self.assertEqual(set(row), {"kind", "name", "path", "limits", "protocol", "error"})
        self.assertIn(row["kind"], ("sim", "hid"))
        self.assertTrue(row["name"])
        self.assertTrue(row["path"])
        if row["limits"] is not None:
            self.assertEqual(set(row["limits"]), LIMIT_KEYS)
            self.assertGreater(row["limits"]["max_force_n"], 0)
            for lo, hi in zip(row["limits"]["workspace_min_d"], row["limits"]["workspace_max_d"]):
                self.assertLess(lo, hi)
        else:
            self.assertTrue(row["error"])

    def test_the_simulated_hand_is_always_there(self):
        proc = run_cli("devices", "--json")
        self.assertEqual(proc.returncode, 0, proc.stderr)
        rows = json.loads(proc.stdout)
        for row in rows:
            self.check_row(row)
        self.assertEqual(rows[0]["kind"], "sim")
        self.assertEqual(rows[0]["path"], "sim:hand")
        self.assertEqual(rows[0]["limits"]["max_force_n"], 8.9)
        # this machine's real HID devices, if any, are HaptiCAD ones only
        for row in rows[1:]:
            self.assertEqual(row["kind"], "hid")

    def test_lists_emulated_hid_devices_with_limits_or_the_reason(self):
        proc = run_cli("devices", "--json", emulate=(
            "product=Desk arm,max_force=3.3;"
            "version=2.0-2.1;"
            "kind=other,product=Keyboard"))
        self.assertEqual(proc.returncode, 0, proc.stderr)
        rows = json.loads(proc.stdout)
        for row in rows:
            self.check_row(row)
        self.assertEqual([r["kind"] for r in rows], ["sim", "hid", "hid"])
        arm = rows[1]
        self.assertEqual(arm["name"], "Desk arm")
        self.assertEqual(arm["path"], "emu:0")
        self.assertEqual(arm["limits"]["max_force_n"], 3.3)
        self.assertEqual(arm["limits"]["workspace_max_d"], [0.08, 0.08, 0.08])
        self.assertEqual(arm["protocol"], "1.0-1.0")
        self.assertIsNone(arm["error"])
        newer = rows[2]
        self.assertIsNone(newer["limits"])
        self.assertIn("speaks HaptiCAD HID protocol 2.0-2.1", newer["error"])
        self.assertIn("update HaptiCAD", newer["error"])
        self.assertNotIn("Keyboard", proc.stdout)

    def test_prints_a_table_without_json(self):
        proc = run_cli("devices", emulate="product=Desk arm")
        self.assertEqual(proc.returncode, 0, proc.stderr)
        lines = proc.stdout.splitlines()
        self.assertEqual(len(lines), 2)
        self.assertIn("sim:hand", lines[0])
        self.assertIn("Desk arm", lines[1])
        self.assertIn("8 N, 2.5 N/mm, workspace 160 x 160 x 160 mm", lines[1])


if __name__ == "__main__":
    unittest.main()
