#!/usr/bin/env bash
# The main job: build, then light the bundled CT head (Data/headsq) with the
# volrad command (ct material, one directional light, the hierarchical
# solver on the head shrunk 4x) into out/headsq-lit.vti, and render the
# pictures of the Python example (Examples/Python/ct_head.py) into out/.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bash "$root/scripts/build.sh"
build="${VOLRAD_BUILD_DIR:-$root/build}"
mkdir -p "$root/out"
"$build/bin/volrad" "$root/Data/headsq/quarter.nhdr" --shrink 4 \
  --scene "$root/Data/headsq.scene.json" -o "$root/out/headsq-lit.vti"
echo "Output: $root/out/headsq-lit.vti (open it in ParaView, or read it with vtkXMLImageDataReader)."
echo "Pictures (the same head, rendered off-screen by Examples/Python/ct_head.py):"
PYTHONPATH="$build/lib/python3/dist-packages" xvfb-run -a /usr/bin/python3 \
  "$root/Examples/Python/ct_head.py" "$root/out"
echo "Pictures: $root/out/ct_head_volume.png, ct_head_bone.png, ct_head_slice.png"
