#!/usr/bin/env bash
# Installs the Debian 12 packages VolRad needs to build, run and test.
# Idempotent: packages already present are skipped, so re-runs are quick.
# Debian's python3-vtk9 (needed by libvtk9-dev) and python3-paraview
# conflict: after scripts/install-deps-paraview.sh this swaps them back.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bash "$root/scripts/apt-install.sh" \
  build-essential cmake ninja-build pkg-config \
  libvtk9-dev vtk9 python3-vtk9 python3-dev \
  libeigen3-dev libtbb-dev nlohmann-json3-dev \
  libopenvdb-dev libboost-iostreams-dev \
  libgtest-dev libgmock-dev libbenchmark-dev \
  xvfb xauth
