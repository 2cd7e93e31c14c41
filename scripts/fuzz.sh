#!/usr/bin/env bash
# Builds the libFuzzer harnesses (tests/fuzz/: rig.yaml, object.yaml, pose files, K.txt, the
# annotate config, OBJ meshes, cached viewpoint models) with clang, AddressSanitizer and UBSan
# into build-fuzz/, and runs each for SECONDS (default 20) on a copy of its seed corpus
# (tests/fuzz/corpus/<target>/).
#   scripts/fuzz.sh [SECONDS] [ctest args instead of the default -L '^fuzz$', e.g. -R mesh]
# Prints the executions per target; a crash fails and leaves its input in
# build-fuzz/tests/fuzz/runs/<target>/crash-*, which then belongs in the corpus and a
# regression test. Needs clang and libclang-rt-14-dev (scripts/setup.sh installs them).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=20
if [[ $# -gt 0 && $1 =~ ^[0-9]+$ ]]; then seconds=$1; shift; fi
command -v clang++ >/dev/null || { echo "fuzz: clang++ not found (scripts/setup.sh)" >&2; exit 1; }
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DBCOT_SANITIZE=ON -DBCOT_BUILD_TESTS=OFF -DBCOT_BUILD_BENCHMARKS=OFF -DBCOT_BUILD_FUZZERS=ON \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link" >/dev/null
targets=$(sed -n 's/^ *\([a-z_]*\):bcot_[a-z_]*:fuzz[a-z_]*)*$/fuzz_\1/p' tests/fuzz/CMakeLists.txt)
# shellcheck disable=SC2086
cmake --build build-fuzz -j "$(nproc 2>/dev/null || echo 2)" --target $targets
set +e
label=(-L '^fuzz$')
[ $# -gt 0 ] && label=()
BCOT_FUZZ_SECONDS=$seconds ctest --test-dir build-fuzz "${label[@]}" --output-on-failure -V "$@" \
  >build-fuzz/fuzz.log 2>&1
status=$?
set -e
grep -E "executions in|tests passed|tests failed|crash-|ERROR" build-fuzz/fuzz.log || true
exit $status
