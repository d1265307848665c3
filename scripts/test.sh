#!/usr/bin/env bash
# Runs every test: the main build (system VTK) and its ctest; the core, its
# tests and the fuzzers under ASan and UBSan (scripts/test-sanitizers.sh);
# then the ParaView plugin's build and its ctest (pvpython). Debian's
# python3-vtk9 and python3-paraview conflict, so the main and the ParaView
# builds take turns (scripts/install-deps*.sh); at the end the main build's
# packages are put back. VOLRAD_SKIP_SANITIZERS=1 / VOLRAD_SKIP_PARAVIEW=1
# leave a part out.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
# Seconds per phase, so that CI's time (kept well under 30 minutes) can be
# read off its log.
phase() { echo "test.sh: $1 took $SECONDS s"; SECONDS=0; }
SECONDS=0
bash "$root/scripts/build.sh"
phase "the main build"
build="${VOLRAD_BUILD_DIR:-$root/build}"
status=0
(cd "$build" && ctest --output-on-failure --parallel "$(nproc)" --timeout 900) || status=1
phase "the main tests"

if [ "${VOLRAD_SKIP_SANITIZERS:-0}" != 1 ]; then
  bash "$root/scripts/test-sanitizers.sh" || status=1
  phase "the sanitizer build and tests"
fi

if [ "${VOLRAD_SKIP_PARAVIEW:-0}" != 1 ]; then
  bash "$root/scripts/build-paraview.sh"
  (cd "${VOLRAD_PARAVIEW_BUILD_DIR:-$root/build-paraview}" &&
     ctest --output-on-failure --timeout 900) || status=1
  bash "$root/scripts/install-deps.sh"
  phase "the ParaView build and tests"
fi
exit $status
