#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# setup-user.sh CHECKOUT (as root): prints "USER HOME", whom setup.sh sets HaptiCAD up for:
# the user who ran sudo (SUDO_USER), else root. Root from `su` in another user's checkout
# is set up as root, since the README's next command (run-tests.sh, hapticad demo) runs in
# that root shell too; it is told on stderr that the owner's FreeCAD will not see it.
set -euo pipefail
checkout=$1
home_of() { getent passwd "$1" | cut -d: -f6; }
if [ -n "${SUDO_USER:-}" ] && [ "$SUDO_USER" != root ]; then
  echo "$SUDO_USER $(home_of "$SUDO_USER")"
  exit 0
fi
owner=$(stat -c %U "$checkout")
if [ "$owner" != root ] && [ "$owner" != UNKNOWN ]; then
  echo "setup.sh: setting HaptiCAD up for root, who runs it; this checkout is $owner's, whose FreeCAD" \
       "will not see it: to set it up for $owner, run ./packaging/setup.sh as $owner (it asks sudo)" >&2
fi
echo "root $(home_of root)"
