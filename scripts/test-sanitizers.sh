#!/usr/bin/env bash
# The test suite built with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer in ./build-sanitize: the core and its tests, the
# VTK filter, volrad and their tests, the C++ rendering test, and the
# libFuzzer targets, each fuzzer run for VOLRAD_FUZZ_SECONDS (default 60) from
# its committed seed corpus. Any sanitizer report fails its test.
# Not in this run: the Python tests (Debian's python3 is not instrumented; the
# main build runs them), and the slowest tests, whose code the faster ones
# run too on smaller inputs: the six 12^3-16^3 hierarchical-vs-dense
# accuracy tests, the 16^3 closed-form wall flux, the cluster-exchange
# distance sweep, the link-refinement error sweep and volrad on the bundled
# 16^3 volume (about 6 of the suite's 8 minutes, 15 under the sanitizers).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
# The main build's packages (VTK) and clang's.
bash "$root/scripts/install-deps.sh"
bash "$root/scripts/apt-install.sh" clang libclang-rt-14-dev llvm
build="${VOLRAD_SANITIZE_BUILD_DIR:-$root/build-sanitize}"
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -g"
flags="$flags -fsanitize-ignorelist=$root/Testing/sanitizer-ignorelist.txt"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DVOLRAD_BUILD_VTK=ON -DVOLRAD_WRAP_PYTHON=OFF -DVOLRAD_BUILD_BENCHMARKS=OFF -DVOLRAD_FUZZ=ON \
  -DVOLRAD_FUZZ_SECONDS="${VOLRAD_FUZZ_SECONDS:-60}" >/dev/null
cmake --build "$build" --parallel "$(nproc)"
cd "$build"
# detect_leaks: TBB's worker threads keep their arenas to the end.
export ASAN_OPTIONS="detect_leaks=0:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
slow='HierarchicalSolver[.]MatchesDense|HierarchicalSolver[.]ErrorFalls|AbsorbingCube[.]WallFlux'
slow="$slow|ClusterExchange[.]ApproachesTheDenseSums|VolradCommand[.]SolvesTheBundledScene"
ctest --output-on-failure --parallel "$(nproc)" --timeout 1800 -E "$slow"
