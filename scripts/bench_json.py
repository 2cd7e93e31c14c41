"""Reads a Google Benchmark JSON report for the scripts/bench_*.sh summaries."""
import json

_SCALE_TO_MS = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}


def load(path, notes, columns):
    """The report; prints its machine line (CPUs, MHz, load average), the `notes` lines and the
    head of a markdown table with `columns` (the first left-aligned, the others right)."""
    with open(path) as f:
        report = json.load(f)
    ctx = report["context"]
    print()
    print(f"bcot Release build, {ctx.get('num_cpus', '?')} CPUs @ {ctx.get('mhz_per_cpu', '?')} "
          f"MHz, load average {ctx.get('load_avg', '?')}")
    for line in notes:
        print(line)
    print()
    print("| " + " | ".join(columns) + " |")
    print("|---|" + "---:|" * (len(columns) - 1))
    return report


def runs(report, aggregate=None):
    """(benchmark, wall ms, CPU ms) of every plain run, or only of the named aggregate rows
    (e.g. "median") when the report has repetitions and `aggregate` is given."""
    for b in report["benchmarks"]:
        is_aggregate = b.get("run_type") == "aggregate"
        if is_aggregate and b.get("aggregate_name") != aggregate:
            continue
        scale = _SCALE_TO_MS[b["time_unit"]]
        yield b, b["real_time"] * scale, b["cpu_time"] * scale
