# SPDX-License-Identifier: GPL-3.0-or-later
"""Running a command as the unprivileged user `nobody`, for tests of what a user may not
write: root may write anything, and CI runs as root. Needs root and runuser; a test
without them is skipped (unittest.SkipTest) and says why."""
import os
import pwd
import shutil
import subprocess
import tempfile
import unittest


def shared_folder(test):
    """A folder every user may read (0755, removed after ``test``), with a home for
    `nobody` in it: where a test puts what the command reads. Skips ``test`` when it cannot
    run a command as another user."""
    if os.geteuid() != 0 or not shutil.which("runuser"):
        raise unittest.SkipTest("needs root (CI runs as root) to run the command as another user")
    place = tempfile.mkdtemp()
    test.addCleanup(shutil.rmtree, place, True)
    os.chmod(place, 0o755)
    home = os.path.join(place, "home")
    os.mkdir(home)
    nobody = pwd.getpwnam("nobody")
    os.chown(home, nobody.pw_uid, nobody.pw_gid)
    return place


def run_as_nobody(place, argv, timeout=120):
    """Runs ``argv`` as `nobody`, its home and FreeCAD's user folders in ``place``'s home
    (shared_folder's); returns the CompletedProcess (text)."""
    home = os.path.join(place, "home")
    return subprocess.run(["runuser", "-u", "nobody", "--", "env", f"HOME={home}", f"XDG_CONFIG_HOME={home}/config",
                           f"XDG_DATA_HOME={home}/data", *argv], capture_output=True, text=True, timeout=timeout)
