# SPDX-License-Identifier: GPL-3.0-or-later
"""packaging/70-hapticad.rules: well-formed udev rules that open exactly the VID:PIDs
the HID backend knows to the seat's user and the group hapticad, installed by
setup.sh before 73-seat-late.rules; and the real-time limit setup.sh grants matches
the priority the servo loop asks for. Plain /usr/bin/python3."""
import os
import re
import subprocess
import unittest

TOP = os.path.normpath(os.path.join(os.path.dirname(__file__), "..", ".."))
RULES = os.path.join(TOP, "packaging", "70-hapticad.rules")
SETUP = os.path.join(TOP, "packaging", "setup.sh")
FINDER = os.path.join(TOP, "devices", "hid", "include", "hapticad", "devices", "hid", "hid_device_finder.h")
SERVO = os.path.join(TOP, "devices", "include", "hapticad", "devices", "servo_loop.h")

# udev syntax: KEY{attr}=="value" (match) or KEY="value" / KEY+="value" (assign)
PAIR = re.compile(r'\s*([A-Z_]+)(\{[^}]+\})?\s*(==|!=|=|\+=|:=)\s*"([^"]*)"\s*(,|$)')


def parse_rules(path):
    rules = []
    with open(path) as f:
        for line in f:
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            pairs, pos = {}, 0
            while pos < len(line):
                m = PAIR.match(line, pos)
                if not m:
                    raise ValueError(f"not udev syntax at {line[pos:]!r}")
                key = m.group(1) + (m.group(2) or "")
                pairs[(key, m.group(3))] = m.group(4)
                pos = m.end()
            rules.append(pairs)
    return rules


class UdevRuleTest(unittest.TestCase):
    def test_rules_open_exactly_the_known_devices_to_the_user(self):
        rules = parse_rules(RULES)
        self.assertTrue(rules)
        ids = set()
        for r in rules:
            self.assertEqual(r[("SUBSYSTEM", "==")], "hidraw")
            self.assertEqual(r[("MODE", "=")], "0660")
            self.assertEqual(r[("GROUP", "=")], "hapticad")
            self.assertEqual(r[("TAG", "+=")], "uaccess")
            ids.add((r[("ATTRS{idVendor}", "==")], r[("ATTRS{idProduct}", "==")]))
        with open(FINDER) as f:
            known = set(re.findall(r"\{0x([0-9A-Fa-f]{4}), 0x([0-9A-Fa-f]{4}),", f.read()))
        self.assertTrue(known)
        self.assertEqual(ids, {(v.lower(), p.lower()) for v, p in known})

    def test_setup_installs_the_rule_before_the_seat_rules_and_grants_the_rt_priority(self):
        with open(SETUP) as f:
            setup = f.read()
        m = re.search(r"packaging/70-hapticad.rules\" (/etc/udev/rules.d/(\d+)-hapticad.rules)", setup)
        self.assertIsNotNone(m)
        self.assertLess(int(m.group(2)), 73)
        granted = int(re.search(r"@hapticad - rtprio (\d+)", setup).group(1))
        with open(SERVO) as f:
            asked = int(re.search(r"int realtime_priority = (\d+);", f.read()).group(1))
        self.assertEqual(granted, asked)
        subprocess.run(["bash", "-n", SETUP], check=True)


if __name__ == "__main__":
    unittest.main()
