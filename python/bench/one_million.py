"""`condt.reconstruct` from Python against `condt reconstruct IN.npy -o OUT.npy`, on the same
points (issue 28: the Python call may take no longer than the command line).

    python3 python/bench/one_million.py DIR [--runs 7] [--condt target/release/condt]

DIR holds `curves-1M.npy` and `uniform-1M.npy` (`python3 scripts/scale.py --generate-only
--sizes 1M --formats npy --dir DIR`). Each run is a fresh process, as a command-line run is:
the Python side times `np.load` + `condt.reconstruct` + reading `.edges` (the result as an
array) inside the process, and the whole process from outside (interpreter start and imports
included); the command line is timed from outside (read, reconstruct, write). Prints the
median and every run, in seconds.
"""

import argparse
import os
import resource
import statistics
import subprocess
import sys
import time

INNER = r"""
import resource, sys, time
import numpy as np
t0 = time.perf_counter()
import condt
points = np.load(sys.argv[1])
t1 = time.perf_counter()
u1 = resource.getrusage(resource.RUSAGE_SELF)
r = condt.reconstruct(points)
t2 = time.perf_counter()
edges = r.edges
t3 = time.perf_counter()
u2 = resource.getrusage(resource.RUSAGE_SELF)
cpu = (u2.ru_utime - u1.ru_utime) + (u2.ru_stime - u1.ru_stime)
print(f"{t2 - t1:.4f} {t3 - t1:.4f} {t3 - t0:.4f} {len(edges)} {cpu:.4f} {u2.ru_stime - u1.ru_stime:.4f}")
"""


def wall(command):
    """Wall time, output, and processor time (user + system) and system time of `command`."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True, check=True)
    seconds = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    system = after.ru_stime - before.ru_stime
    return seconds, done.stdout, after.ru_utime - before.ru_utime + system, system


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("dir")
    parser.add_argument("--runs", type=int, default=7)
    parser.add_argument("--condt", default="target/release/condt")
    parser.add_argument("--inputs", nargs="+", default=["curves-1M", "uniform-1M"])
    args = parser.parse_args()
    for name in args.inputs:
        path = os.path.join(args.dir, name + ".npy")
        out = os.path.join(args.dir, name + "-out.npy")
        cli, call, call_edges, process, in_python = [], [], [], [], []
        cli_cpu, cli_sys, call_cpu, call_sys = [], [], [], []
        for _ in range(args.runs):
            seconds, _, cpu, system = wall([args.condt, "reconstruct", path, "-o", out, "-q"])
            cli.append(seconds)
            cli_cpu.append(cpu)
            cli_sys.append(system)
            seconds, printed, _, _ = wall([sys.executable, "-c", INNER, path])
            r, re_, total, edges, cpu, system = printed.split()
            call.append(float(r))
            call_edges.append(float(re_))
            in_python.append(float(total))
            process.append(seconds)
            call_cpu.append(float(cpu))
            call_sys.append(float(system))
        print(f"{name}: {edges} edges, medians of {args.runs} runs")
        for label, values in [
            ("condt reconstruct IN.npy -o OUT.npy (process)", cli),
            ("condt.reconstruct(points)", call),
            ("condt.reconstruct(points).edges", call_edges),
            ("import + np.load + reconstruct + .edges", in_python),
            ("python process, all of it", process),
            ("processor time: condt reconstruct (process)", cli_cpu),
            ("processor time: condt.reconstruct(points).edges", call_cpu),
            ("system time: condt reconstruct (process)", cli_sys),
            ("system time: condt.reconstruct(points).edges", call_sys),
        ]:
            runs = " ".join(f"{v:.3f}" for v in values)
            print(f"  {label:48s} {statistics.median(values):.3f} s   ({runs})")


if __name__ == "__main__":
    main()
