#!/usr/bin/env bash
# Runs one libFuzzer target for a bounded time on a copy of its seed corpus (ctest label
# `fuzz`, scripts/fuzz.sh). Usage: run_fuzzer.sh FUZZER SEED_DIR RUN_DIR
# Time per target: BCOT_FUZZ_SECONDS (default 20). Prints the number of executions; a crash
# leaves its input in RUN_DIR/crash-* and fails.
set -euo pipefail
fuzzer=$1 seeds=$2 run_dir=$3
seconds=${BCOT_FUZZ_SECONDS:-20}
mkdir -p "$run_dir/corpus"
cp -n "$seeds"/* "$run_dir/corpus/" 2>/dev/null || true
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# Leaks inside Debian's libraries (documented in the file) are not bcot's findings.
export LSAN_OPTIONS="suppressions=$(dirname "$0")/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
"$fuzzer" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=20 -print_final_stats=1 \
  -artifact_prefix="$run_dir/" "$run_dir/corpus" 2>"$run_dir/log.txt" || { tail -60 "$run_dir/log.txt"; exit 1; }
runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$run_dir/log.txt" | grep -o '[0-9]*$')
echo "$(basename "$fuzzer"): ${runs:-?} executions in ${seconds} s, no crash"
