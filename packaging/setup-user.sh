#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# setup-user.sh CHECKOUT (as root): prints "USER HOME", whom setup.sh sets HaptiCAD up for:
# the user who ran sudo (SUDO_USER); without sudo (root logged in, or `su` from a user who
# has no sudo), the checkout's owner when that is a user other than root whose home folder
# exists (who cloned it, and will run FreeCAD as themselves; a root set-up would leave the
# workbench in /root, out of their FreeCAD's reach, and build/ root's); else root. Says on
# stderr when it chose the owner, or passed over an owner it could not use.
set -euo pipefail
checkout=$1
home_of() { getent passwd "$1" | cut -d: -f6; }
if [ -n "${SUDO_USER:-}" ] && [ "$SUDO_USER" != root ]; then
  echo "$SUDO_USER $(home_of "$SUDO_USER")"
  exit 0
fi
owner=$(stat -c %U "$checkout")
if [ "$owner" != root ]; then
  home=$(home_of "$owner" || true)
  if [ -n "$home" ] && [ -d "$home" ]; then
    echo "setup.sh: setting up for $owner, who owns this checkout (run it as root from a checkout" \
         "of root's to set up for root)" >&2
    echo "$owner $home"
    exit 0
  fi
  echo "setup.sh: this checkout's owner ($owner) has no home folder here: setting up for root" >&2
fi
echo "root $(home_of root)"
