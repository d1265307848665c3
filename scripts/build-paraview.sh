#!/usr/bin/env bash
# Configures and builds the ParaView plugin in ./build-paraview (the same
# source tree with -DVOLRAD_PARAVIEW=ON, against ParaView's own VTK):
# build-paraview/lib/paraview-plugins/VolRad/VolRad.so.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bash "$root/scripts/install-deps-paraview.sh"
build="${VOLRAD_PARAVIEW_BUILD_DIR:-$root/build-paraview}"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DVOLRAD_PARAVIEW=ON >/dev/null
cmake --build "$build" --parallel "$(nproc)"
