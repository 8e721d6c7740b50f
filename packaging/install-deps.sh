#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs HaptiCAD's build, run and test dependencies from Debian 12's own packages.
# Idempotent: apt-get skips what is already installed. Needs root (or sudo).
set -euo pipefail

packages=(
  # build
  build-essential cmake ninja-build pkg-config
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev libeigen3-dev libopenmesh-dev
  libhidapi-dev pybind11-dev python3-dev
  # FreeCAD and the Python it embeds
  freecad python3-numpy python3-matplotlib python3-pivy
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev xvfb xauth
  # the .deb (CPack: dpkg-shlibdeps computes library dependencies, `file` finds the ELF files)
  dpkg-dev file
)

sudo=()
[ "$(id -u)" -eq 0 ] || sudo=(sudo)
"${sudo[@]}" apt-get update
DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y --no-install-recommends "${packages[@]}"
