# SPDX-License-Identifier: GPL-3.0-or-later
"""packaging/setup-user.sh, which tells setup.sh whom to set HaptiCAD up for: the user
who ran sudo, else the checkout's owner (a user who ran it as root through `su`, having
no sudo), else root. Needs root to give a folder to another user. Plain /usr/bin/python3."""
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
        self.assertEqual(setup_user(self.checkout, sudo_user="nobody")[:2], (0, ["nobody", "/nonexistent"]))
        # sudo from root itself: as without sudo
        self.assertEqual(setup_user(self.checkout, sudo_user="root")[1], ["bin", "/bin"])

    def test_without_sudo_the_checkouts_owner_is_set_up_and_told(self):
        self.give("bin")  # Debian's base-passwd: home /bin, which every system has
        code, out, err = setup_user(self.checkout)
        self.assertEqual((code, out), (0, ["bin", "/bin"]))
        self.assertIn("setting up for bin, who owns this checkout", err)

    def test_an_owner_without_a_home_folder_leaves_it_to_root_and_says_so(self):
        self.give("nobody")  # home /nonexistent
        code, out, err = setup_user(self.checkout)
        self.assertEqual((code, out[0]), (0, "root"))
        self.assertIn("owner (nobody) has no home folder here: setting up for root", err)
        os.chown(self.checkout, 54321, 54321)  # a user id with no name (a folder from another system)
        code, out, err = setup_user(self.checkout)
        self.assertEqual((code, out[0]), (0, "root"))
        self.assertIn("has no home folder here", err)


    def test_a_user_on_a_system_without_sudo_is_told_to_run_it_as_root(self):
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
        self.assertIn("this system has no sudo: run it as root (su -c ./packaging/setup.sh); nothing was changed",
                      done.stderr)


if __name__ == "__main__":
    unittest.main()
