#!/usr/bin/env bash
# The whole test suite: installs packages, builds with AddressSanitizer + UBSan, runs ctest,
# then (sanitized runs without extra ctest args) every libFuzzer harness for 20 s
# (scripts/fuzz.sh; BCOT_FUZZ_SECONDS changes the time, 0 skips them).
# Usage: scripts/test.sh [--no-sanitize] [extra ctest args, e.g. -L render]
set -euo pipefail
cd "$(dirname "$0")/.."
kind=asan
if [ "${1:-}" = "--no-sanitize" ]; then kind=release; shift; fi
scripts/setup.sh
scripts/build.sh "$kind"
dir=build; [ "$kind" = asan ] && dir=build-asan
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
ctest --test-dir "$dir" --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" "$@"
fuzz_seconds=${BCOT_FUZZ_SECONDS:-20}
if [ "$kind" = asan ] && [ $# -eq 0 ] && [ "$fuzz_seconds" != 0 ]; then
  scripts/fuzz.sh "$fuzz_seconds"
fi
