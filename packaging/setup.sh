#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Sets HaptiCAD up on Debian 12, from a checkout, as root or as a user with sudo (it runs
# itself through sudo then), for that user (setup-user.sh: the user who ran sudo, else root):
#   1. installs the dependencies (install-deps.sh),
#   2. builds everything in build/ (as that user, so the checkout stays theirs),
#   3. installs the workbench into that user's FreeCAD Mod folder
#      (~/.local/share/FreeCAD/Mod/HaptiCAD) and the `hapticad` command into /usr/local/bin,
#   4. lets that user open HaptiCAD HID devices without root (udev rule, group hapticad)
#      and give the servo loop real-time priority (rtprio limit for the group).
# Safe to run again: it rebuilds and reinstalls.
set -euo pipefail

top=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="$top/build"

if [ "$(id -u)" -ne 0 ]; then
  if ! command -v sudo > /dev/null; then
    echo "setup.sh: installing the Debian packages needs root, and this system has no sudo:" \
         "install sudo, or set HaptiCAD up for root by running this as root; nothing was changed." >&2
    exit 2
  fi
  exec sudo "$0" "$@"
fi
# root through a plain `su` keeps the user's PATH, without the sbin folders that runuser,
# groupadd, usermod and dpkg's helpers live in
export PATH="/usr/local/sbin:/usr/sbin:/sbin:$PATH"

# the user who ran sudo, else root (setup-user.sh)
read -r user home < <("$top/packaging/setup-user.sh" "$top")
mod_dir="$home/.local/share/FreeCAD/Mod/HaptiCAD"
as_user=()
[ "$user" = root ] || as_user=(runuser -u "$user" -- env HOME="$home")
# before anything is installed: a checkout in the Mod folder would be replaced below
"$top/packaging/check-install-folder.sh" "$top" "$mod_dir"

"$top/packaging/install-deps.sh"
# a build/ left by an earlier set-up for root is handed over: the user builds in it
if [ "$user" != root ] && [ -d "$build" ]; then
  chown -R "$user:" "$build"
fi

"${as_user[@]}" cmake -S "$top" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DHAPTICAD_MOD_DIR="$mod_dir" -DCMAKE_INSTALL_PREFIX=/usr/local -DHAPTICAD_BUILD_TESTS=ON
"${as_user[@]}" cmake --build "$build" -j "$(nproc)"

# the Mod folder's parents made as the user (a root install would leave ~/.local root's)
"${as_user[@]}" mkdir -p "$(dirname "$mod_dir")"
rm -rf "$mod_dir"
cmake --install "$build"
if [ "$user" != root ]; then
  chown -R "$user:" "$home/.local/share/FreeCAD" "$build"
fi
# haptic devices without root, and a real-time servo loop (takes effect at next login)
install -D -m 0644 "$top/packaging/70-hapticad.rules" /etc/udev/rules.d/70-hapticad.rules
groupadd --force hapticad
[ "$user" = root ] || usermod -a -G hapticad "$user"
install -d /etc/security/limits.d
printf '# HaptiCAD servo loop (packaging/setup.sh)\n@hapticad - rtprio 70\n' \
  > /etc/security/limits.d/hapticad.conf
# the limit above starts at the next login; the shell that ran sudo (and the run-tests.sh
# or hapticad it starts next) gets it now
if [ "$user" != root ]; then
  "$top/packaging/grant-rtprio.sh" "$user" 70 "$PPID" ||
    echo "setup.sh: real-time priority for $user from the next login only" >&2
fi
if command -v udevadm > /dev/null && [ -d /run/udev ]; then
  udevadm control --reload-rules && udevadm trigger --subsystem-match=hidraw || true
fi

echo "HaptiCAD is set up: workbench in $mod_dir, command $(command -v hapticad)"
