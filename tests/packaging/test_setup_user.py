# SPDX-License-Identifier: GPL-3.0-or-later
"""packaging/setup-user.sh, which tells setup.sh whom to set HaptiCAD up for: the user
who ran sudo, else root (root from `su` in another user's checkout is told that user's
FreeCAD will not see it: the README's next command runs as root too); and setup.sh run by
a user where there is no sudo. Needs root to give a folder to another user. Plain
/usr/bin/python3."""
import os
import pwd
import shutil
import subprocess
import tempfile
import unittest

TOP = os.path.normpath(os.path.join(os.path.dirname(__file__), "..", ".."))
SETUP_USER = os.path.join(TOP, "packaging", "setup-user.sh")
SETUP = os.path.join(TOP, "packaging", "setup.sh")


def setup_user(checkout, sudo_user=None):
    env = {k: v for k, v in os.environ.items() if k != "SUDO_USER"}
    if sudo_user is not None:
        env["SUDO_USER"] = sudo_user
    done = subprocess.run([SETUP_USER, checkout], capture_output=True, text=True, env=env)
    return done.returncode, done.stdout.split(), done.stderr


@unittest.skipUnless(os.geteuid() == 0, "giving a folder to another user needs root")
class SetupUserTest(unittest.TestCase):
    def setUp(self):
        self.checkout = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, self.checkout)

    def give(self, user):
        entry = pwd.getpwnam(user)
        os.chown(self.checkout, entry.pw_uid, entry.pw_gid)

    def test_a_checkout_of_roots_sets_up_for_root(self):
        self.assertEqual(setup_user(self.checkout), (0, ["root", pwd.getpwnam("root").pw_dir], ""))

    def test_the_user_who_ran_sudo_comes_first(self):
        self.give("bin")
        self.assertEqual(setup_user(self.checkout, sudo_user="nobody"), (0, ["nobody", "/nonexistent"], ""))

    def test_root_in_another_users_checkout_is_set_up_as_root_and_told(self):
        # root from `su`: the README's next command (run-tests.sh, hapticad demo) runs as root
        # too, so the set-up is root's; the owner is told how to have it for themselves
        self.give("bin")
        for sudo_user in (None, "root"):
            code, out, err = setup_user(self.checkout, sudo_user=sudo_user)
            self.assertEqual((code, out), (0, ["root", pwd.getpwnam("root").pw_dir]))
            self.assertIn("setting HaptiCAD up for root, who runs it; this checkout is bin's", err)
            self.assertIn("run ./packaging/setup.sh as bin", err)
        os.chown(self.checkout, 54321, 54321)  # a user id with no name (a folder from another system)
        self.assertEqual(setup_user(self.checkout), (0, ["root", pwd.getpwnam("root").pw_dir], ""))

    def test_a_user_on_a_system_without_sudo_is_told_what_to_do(self):
        # setup.sh copied where nobody may read it, run by nobody with a PATH that has no sudo
        os.chmod(self.checkout, 0o755)
        os.makedirs(os.path.join(self.checkout, "packaging"))
        shutil.copy(SETUP, os.path.join(self.checkout, "packaging"))
        tools = os.path.join(self.checkout, "bin")
        os.makedirs(tools)
        for tool in ("dirname", "id"):
            os.symlink(shutil.which(tool), os.path.join(tools, tool))
        done = subprocess.run(["runuser", "-u", "nobody", "--", "env", f"PATH={tools}", "/bin/bash",
                               os.path.join(self.checkout, "packaging", "setup.sh")],
                              capture_output=True, text=True, timeout=60)
        self.assertEqual(done.returncode, 2, done.stderr)
        self.assertIn("this system has no sudo: install sudo, or set HaptiCAD up for root by running this as root; "
                      "nothing was changed", done.stderr)

    def test_root_from_a_plain_su_finds_the_sbin_tools(self):
        # a plain `su` keeps the user's PATH: runuser, groupadd and usermod are in /usr/sbin.
        # setup.sh's PATH, read up to where it names the user (nothing installed by then)
        with open(SETUP) as handle:
            head = handle.read().split("# the user who ran sudo")[0]
        probe = os.path.join(self.checkout, "setup-head.sh")
        with open(probe, "w") as handle:
            handle.write(head + "\ncommand -v runuser groupadd usermod\n")
        done = subprocess.run(["env", "PATH=/usr/local/bin:/usr/bin:/bin", "/bin/bash", probe],
                              capture_output=True, text=True, timeout=60)
        self.assertEqual((done.returncode, done.stderr), (0, ""))
        self.assertEqual([os.path.basename(p) for p in done.stdout.split()], ["runuser", "groupadd", "usermod"])


if __name__ == "__main__":
    unittest.main()
