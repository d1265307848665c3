#!/usr/bin/env bash
# Installs the Debian 12 packages VolRad needs to build, run and test.
# Idempotent: packages already present are skipped, so re-runs are quick.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libvtk9-dev vtk9 python3-vtk9 python3-dev
  libeigen3-dev libtbb-dev nlohmann-json3-dev
  libopenvdb-dev libboost-iostreams-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  xvfb xauth
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
