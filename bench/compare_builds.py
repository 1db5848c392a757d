#!/usr/bin/env python3
"""Before/after speed of two texproc builds, interleaved on one machine.

  bench/compare_builds.py OLD_BUILD NEW_BUILD [--rounds 3] [BENCH:FILTER ...]

Runs each Google Benchmark program of both builds in turn (old, new, old,
new, ...), so drift of a noisy machine hits both alike, and prints the median
time of every benchmark in each build and new / old. Default benchmarks: the
encoders a restructuring must keep at speed (bench_bc1, bench_bc4,
bench_etc).
"""
import json
import statistics
import subprocess
import sys

DEFAULT = ["bench_bc1:^run/texproc_", "bench_bc4:^run/texproc_", "bench_etc:^color/etc"]


def run(build, bench, flt):
    out = subprocess.run([f"{build}/bench/{bench}", f"--benchmark_filter={flt}", "--benchmark_format=json"],
                         stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, check=True).stdout
    data = json.loads(out[out.index("{"):])
    return {b["name"]: b["real_time"] * {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b["time_unit"]]
            for b in data["benchmarks"] if b.get("run_type", "iteration") == "iteration"}


def main(argv):
    rounds, specs, dirs = 3, [], []
    i = 0
    while i < len(argv):
        if argv[i] == "--rounds":
            rounds = int(argv[i + 1])
            i += 2
            continue
        (specs if ":" in argv[i] else dirs).append(argv[i])
        i += 1
    if len(dirs) != 2:
        print(__doc__)
        return 2
    old, new = dirs
    times = {}
    for r in range(rounds):
        for spec in specs or DEFAULT:
            bench, flt = spec.split(":", 1)
            for label, build in (("old", old), ("new", new)):
                for name, ms in run(build, bench, flt).items():
                    times.setdefault((bench, name), {}).setdefault(label, []).append(ms)
    print(f"{'benchmark':60s} {'old ms':>10s} {'new ms':>10s} {'new/old':>8s}   (medians of {rounds}, interleaved)")
    for (bench, name), t in times.items():
        if "old" not in t or "new" not in t:
            continue
        o, n = statistics.median(t["old"]), statistics.median(t["new"])
        print(f"{bench + ' ' + name:60s} {o:10.2f} {n:10.2f} {n / o:8.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
