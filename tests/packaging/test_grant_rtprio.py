# SPDX-License-Identifier: GPL-3.0-or-later
"""packaging/grant-rtprio.sh, which setup.sh runs so that the shell that ran `sudo setup.sh`
has the servo loop's real-time priority limit before its next login (the live servo-loop
tests in run-tests.sh, started from that shell next, need it under load). Needs root to
raise another user's limit. Plain /usr/bin/python3."""
import os
import subprocess
import unittest

TOP = os.path.normpath(os.path.join(os.path.dirname(__file__), "..", ".."))
GRANT = os.path.join(TOP, "packaging", "grant-rtprio.sh")


def has_cap_sys_resource():
    """Whether this process may raise a hard limit (root without CAP_SYS_RESOURCE, as in
    some containers, may not)."""
    with open("/proc/self/status") as status:
        effective = next(int(line.split()[1], 16) for line in status if line.startswith("CapEff:"))
    return bool(effective & (1 << 24))  # CAP_SYS_RESOURCE


def user_shell(user):
    """A bash running as `user` that prints its pid, waits for a line, then prints its
    real-time priority limit (soft, hard)."""
    shell = subprocess.Popen(["runuser", "-u", user, "--", "bash", "-c",
                              'echo $$; read line; echo "$(ulimit -S -r) $(ulimit -H -r)"'],
                             stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    return shell, int(shell.stdout.readline())


@unittest.skipUnless(os.geteuid() == 0, "raising another process's limit needs root")
class GrantRtprioTest(unittest.TestCase):
    @unittest.skipUnless(has_cap_sys_resource(), "root here lacks CAP_SYS_RESOURCE: no hard limit can be raised")
    def test_the_users_shell_gets_the_limit_now(self):
        shell, pid = user_shell("nobody")
        # from a process of the user's (the shell's own child would do as well)
        done = subprocess.run([GRANT, "nobody", "70", str(pid)], capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stderr)
        out, _ = shell.communicate("\n", timeout=10)
        self.assertIn(f"real-time priority up to 70 for bash (pid {pid})", done.stdout)
        self.assertEqual(out.split(), ["70", "70"])

    @unittest.skipIf(has_cap_sys_resource(), "this root may raise limits")
    def test_without_the_capability_it_fails_saying_so(self):
        shell, pid = user_shell("nobody")
        done = subprocess.run([GRANT, "nobody", "70", str(pid)], capture_output=True, text=True)
        out, _ = shell.communicate("\n", timeout=10)
        self.assertEqual(done.returncode, 1)
        self.assertIn("RTPRIO", done.stderr)
        self.assertEqual(out.split(), ["0", "0"])

    def test_processes_of_other_users_are_passed_over(self):
        # this test's own ancestors are not nobody's: nothing is changed, and it says so
        shell, pid = user_shell("nobody")
        done = subprocess.run([GRANT, "nobody", "70", str(os.getpid())], capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("no process of nobody above this one", done.stdout)
        out, _ = shell.communicate("\n", timeout=10)
        self.assertEqual(out.split(), ["0", "0"])
        with open(f"/proc/{os.getpid()}/limits") as limits:
            mine = [line for line in limits if line.startswith("Max realtime priority")]
        self.assertNotIn(" 70 ", mine[0])

    def test_an_unknown_user_fails_and_changes_nothing(self):
        done = subprocess.run([GRANT, "no-such-user-hapticad", "70", str(os.getpid())],
                              capture_output=True, text=True)
        self.assertNotEqual(done.returncode, 0)
        self.assertIn("no-such-user-hapticad", done.stderr)


if __name__ == "__main__":
    unittest.main()
