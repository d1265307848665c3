#!/usr/bin/env bash
# The main job: build, then light the bundled volume (Data/neghip16.vti) with
# the volrad command and write the result to out/neghip16-lit.vti.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bash "$root/scripts/build.sh"
build="${VOLRAD_BUILD_DIR:-$root/build}"
mkdir -p "$root/out"
"$build/bin/volrad" "$root/Data/neghip16.vti" --scene "$root/Data/neghip16.scene.json" -o "$root/out/neghip16-lit.vti"
echo "Output: $root/out/neghip16-lit.vti (open it in ParaView, or read it with vtkXMLImageDataReader)."
echo "Core-only example (prints a slice of G and checks it against Monte Carlo):"
"$build/bin/LitCloudCore"
