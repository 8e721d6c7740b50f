#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# check-install-folder.sh CHECKOUT MOD_DIR: exits 2, saying why, when setup.sh must not
# install into MOD_DIR because the checkout is MOD_DIR or lies inside it (cloned straight
# into FreeCAD's Mod folder, or put there by the Addon Manager): setup.sh replaces MOD_DIR
# with the built workbench, which would delete the checkout and its uncommitted work.
set -euo pipefail
checkout=$(realpath -m "$1")
mod_dir=$(realpath -m "$2")
case "$checkout/" in
  "$mod_dir"/*)
    echo "setup.sh: this checkout ($1) is in $2, the folder setup.sh replaces with the built" \
         "workbench: installing would delete it. Clone HaptiCAD elsewhere (e.g. ~/src/HaptiCAD)" \
         "and run packaging/setup.sh there; nothing was changed." >&2
    exit 2
    ;;
esac
