#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Sets HaptiCAD up on Debian 12, from a checkout, as root or with sudo:
#   1. installs the dependencies (install-deps.sh),
#   2. builds everything in build/ (as the user who ran sudo, so the checkout stays theirs),
#   3. installs the workbench into that user's FreeCAD Mod folder
#      (~/.local/share/FreeCAD/Mod/HaptiCAD) and the `hapticad` command into /usr/local/bin.
# Safe to run again: it rebuilds and reinstalls.
set -euo pipefail

top=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="$top/build"

if [ "$(id -u)" -ne 0 ]; then
  exec sudo "$0" "$@"
fi

"$top/packaging/install-deps.sh"

user=${SUDO_USER:-root}
home=$(getent passwd "$user" | cut -d: -f6)
mod_dir="$home/.local/share/FreeCAD/Mod/HaptiCAD"
as_user=()
[ "$user" = root ] || as_user=(sudo -u "$user" -H)

"${as_user[@]}" cmake -S "$top" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DHAPTICAD_MOD_DIR="$mod_dir" -DCMAKE_INSTALL_PREFIX=/usr/local
"${as_user[@]}" cmake --build "$build" -j "$(nproc)"

rm -rf "$mod_dir"
cmake --install "$build"
if [ "$user" != root ]; then
  chown -R "$user:" "$home/.local/share/FreeCAD" "$build"
fi
echo "HaptiCAD is set up: workbench in $mod_dir, command $(command -v hapticad)"
