# Shared by the Google Benchmark scripts (source it from the repository root).
# run_google_benchmark NAME [benchmark flags]: configures build-bench/ (Release, benchmarks on),
# builds tests/bench/NAME and runs it with Google Benchmark's console table on stdout and the
# JSON report into build-bench/NAME.json (read it with scripts/bench_json.py).
# bench_summary NAME: runs the Python program on stdin with scripts/ on its import path (so it
# can `import bench_json`) and build-bench/NAME.json as its argument.
run_google_benchmark() {
  local name=$1
  shift
  local dir=build-bench
  cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DBCOT_BUILD_BENCHMARKS=ON >/dev/null
  cmake --build "$dir" --target "$name"
  "$dir/tests/bench/$name" --benchmark_format=console \
    --benchmark_out="$dir/$name.json" --benchmark_out_format=json "$@"
}

bench_summary() {
  PYTHONPATH=scripts python3 - "build-bench/$1.json"
}

# bench_build TARGET...: builds the targets (quietly) in BENCH_DIR, which it sets: an existing
# Release build given by BCOT_BENCH_BUILD (configured with -DBCOT_BUILD_BENCHMARKS=ON; used as it
# is), else build-bench/, configured here (Release, benchmarks on, no tests).
bench_build() {
  BENCH_DIR=${BCOT_BENCH_BUILD:-build-bench}
  if [ -z "${BCOT_BENCH_BUILD:-}" ]; then
    cmake -S . -B "$BENCH_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release -DBCOT_BUILD_TESTS=OFF \
      -DBCOT_BUILD_BENCHMARKS=ON >/dev/null
  fi
  cmake --build "$BENCH_DIR" --target "$@" >/dev/null
}
