#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# grant-rtprio.sh USER PRIORITY START_PID (as root): raises the real-time priority limit
# (RLIMIT_RTPRIO, soft and hard) to PRIORITY for the nearest process, from START_PID up
# through its parents, that runs wholly as USER (real and effective uid), and says which.
# setup.sh writes the limit to /etc/security/limits.d, which takes effect at the user's
# next login; it calls this with its parent so the shell that ran setup.sh (and
# so the run-tests.sh it starts next) has the limit now. sudo itself runs with the
# user's real uid but root's effective one, and is passed over. Exits 0 when no such
# process is found (nothing to do), 1 when prlimit fails.
set -euo pipefail
user=$1
priority=$2
pid=$3
uid=$(id -u "$user")
while [ "$pid" -gt 1 ] && [ -d "/proc/$pid" ]; do
  # /proc/PID/status: "Uid: real effective saved filesystem"
  read -r real effective _ < <(awk '/^Uid:/ { print $2, $3, $4 }' "/proc/$pid/status")
  if [ "$real" = "$uid" ] && [ "$effective" = "$uid" ]; then
    prlimit --pid "$pid" --rtprio="$priority:$priority"
    echo "real-time priority up to $priority for $(cat "/proc/$pid/comm") (pid $pid) and what" \
         "it starts from now on; $user's other sessions get it at their next login"
    exit 0
  fi
  pid=$(awk '/^PPid:/ { print $2 }' "/proc/$pid/status")
done
echo "no process of $user above this one: real-time priority from $user's next login"
