#!/usr/bin/env bash
# Installs what the ParaView plugin needs: ParaView 5.11 with its headers and
# pvpython, the Qt development packages its CMake config looks for, and the
# core's own dependencies.
# Trap: Debian's python3-paraview conflicts with python3-vtk9, which
# libvtk9-dev depends on, so this removes those two (apt does it); the main
# build's scripts/install-deps.sh puts them back. The two builds therefore
# take turns on one machine (scripts/test.sh runs them one after the other);
# each swap takes about 10 s once the packages are downloaded.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bash "$root/scripts/apt-install.sh" \
  build-essential cmake ninja-build pkg-config \
  paraview paraview-dev python3-paraview \
  qtbase5-dev qttools5-dev libqt5svg5-dev qtxmlpatterns5-dev-tools libqt5opengl5-dev \
  libeigen3-dev libtbb-dev nlohmann-json3-dev \
  libopenvdb-dev libboost-iostreams-dev \
  xvfb xauth
