#!/usr/bin/env python3
"""End-to-end scale benchmark of the `condt` command line.

Generates point sets (uniform in the unit square, and along closed curves) of the sizes asked
for, as NumPy `.npy` (float64, shape (n, 2)) and as text, runs `condt triangulate` and
`condt reconstruct` on them with `--timings` under `/usr/bin/time -v`, and prints two markdown
tables: wall time, processor time (user + system: the figure to compare on a busy machine),
peak resident memory and bytes per point (peak RSS over the number of points) of every run;
then the growth table, every step's time (the `--timings` lines, wall clock) per point at each
size, and its growth from the smallest size to the largest beside that of log n.

    python3 scripts/scale.py                       # 1M, 10M, 30M, 100M, both inputs, .npy
    python3 scripts/scale.py --sizes 1M 10M --formats npy txt
    python3 scripts/scale.py --generate-only --sizes 1M --dir /tmp/pts

The data go to --dir (default: a directory under the system's temporary directory) and are
kept, so that a second run reuses them; 100M points take 1.6 GB as .npy and about 4 GB as text.
Generating is deterministic (a fixed seed per input). With NumPy installed it is vectorised
(about 1 s per 10M points as .npy); without it the standard library's generator runs (about a
minute per 10M points) and its files carry `-py` in their names, since the two draw different
points. The binary is `target/release/condt` unless --condt names another; build it first with
`cargo build --release`. `--limit-gib G` caps each run's address space (a run that needs more
fails with an allocation error instead of pushing the machine into swap or the OOM killer).
"""

import argparse
import math
import os
import random
import re
import resource
import struct
import subprocess
import sys
import tempfile
import time
from array import array

try:
    import numpy
except ImportError:  # the standard library's generator below
    numpy = None

CHUNK = 1 << 20  # points generated and written at a time


def parse_size(text):
    """`1M`, `30M`, `250k` or `1000` as a number of points."""
    match = re.fullmatch(r"(\d+(?:\.\d+)?)([kKmM]?)", text)
    if not match:
        raise argparse.ArgumentTypeError(f"not a size: {text}")
    factor = {"": 1, "k": 1_000, "K": 1_000, "m": 1_000_000, "M": 1_000_000}[match.group(2)]
    return int(float(match.group(1)) * factor)


def size_name(n):
    if n % 1_000_000 == 0:
        return f"{n // 1_000_000}M"
    if n % 1_000 == 0:
        return f"{n // 1_000}k"
    return str(n)


def uniform_chunks(n, seed):
    """n points uniform in the unit square, as flat x, y arrays of at most CHUNK points."""
    rng = random.Random(seed)
    done = 0
    while done < n:
        m = min(CHUNK, n - done)
        flat = array("d", [rng.random() for _ in range(2 * m)])
        yield flat
        done += m


def curve_chunks(n, seed):
    """n points on closed curves (ellipses of about 5,000 points each, with a little noise,
    scattered over a square that grows with n so that the density stays that of 1M points in
    the unit square), curve by curve."""
    rng = random.Random(seed)
    per_curve = 5_000
    side = math.sqrt(n / 1_000_000)
    done = 0
    flat = array("d")
    while done < n:
        m = min(per_curve, n - done)
        cx, cy = rng.random() * side, rng.random() * side
        a = 0.02 + 0.03 * rng.random()
        b = a * (0.4 + 0.6 * rng.random())
        turn = rng.random() * math.pi
        c, s = math.cos(turn), math.sin(turn)
        step = 2 * math.pi / m
        for k in range(m):
            t = k * step + rng.random() * step * 0.1
            ex, ey = a * math.cos(t), b * math.sin(t)
            flat.append(cx + c * ex - s * ey + rng.gauss(0, a * 1e-4))
            flat.append(cy + s * ex + c * ey + rng.gauss(0, a * 1e-4))
        done += m
        if len(flat) >= 2 * CHUNK:
            yield flat
            flat = array("d")
    if flat:
        yield flat


PER_CURVE = 5_000  # points per ellipse


def numpy_uniform_chunks(n, seed):
    """As `uniform_chunks`, vectorised (other points: NumPy's generator)."""
    rng = numpy.random.default_rng(seed)
    done = 0
    while done < n:
        m = min(CHUNK, n - done)
        yield rng.random((m, 2))
        done += m


def numpy_curve_chunks(n, seed):
    """As `curve_chunks`, vectorised: the same shapes, density and noise (other points: NumPy's
    generator), 200 ellipses at a time; the last one is cut short when n is not a multiple of
    5,000."""
    rng = numpy.random.default_rng(seed)
    side = math.sqrt(n / 1_000_000)
    done = 0
    while done < n:
        m = min(CHUNK // PER_CURVE * PER_CURVE, n - done)
        k = -(-m // PER_CURVE)  # ellipses in this chunk, the last maybe short
        cx, cy = rng.random(k) * side, rng.random(k) * side
        a = 0.02 + 0.03 * rng.random(k)
        b = a * (0.4 + 0.6 * rng.random(k))
        turn = rng.random(k) * math.pi
        c, s = numpy.cos(turn)[:, None], numpy.sin(turn)[:, None]
        step = 2 * math.pi / PER_CURVE
        t = numpy.arange(PER_CURVE) * step + rng.random((k, PER_CURVE)) * step * 0.1
        ex, ey = a[:, None] * numpy.cos(t), b[:, None] * numpy.sin(t)
        noise = rng.normal(0.0, 1.0, (2, k, PER_CURVE)) * (a[:, None] * 1e-4)
        xy = numpy.empty((k, PER_CURVE, 2))
        xy[:, :, 0] = cx[:, None] + c * ex - s * ey + noise[0]
        xy[:, :, 1] = cy[:, None] + s * ex + c * ey + noise[1]
        yield xy.reshape(-1, 2)[:m]
        done += m


def npy_header(n):
    """The NPY version 1.0 header for a little-endian float64 array of shape (n, 2)."""
    text = "{'descr': '<f8', 'fortran_order': False, 'shape': (%d, 2), }" % n
    # magic (6) + version (2) + length (2) + text + '\n' padded to a multiple of 64
    total = 10 + len(text) + 1
    text += " " * ((64 - total % 64) % 64) + "\n"
    return b"\x93NUMPY\x01\x00" + struct.pack("<H", len(text)) + text.encode("latin1")


def generate(kind, n, fmt, path):
    if numpy is not None:
        if kind == "uniform":
            chunks = numpy_uniform_chunks(n, 1)
        else:
            chunks = numpy_curve_chunks(n, 2)
    else:
        chunks = uniform_chunks(n, 1) if kind == "uniform" else curve_chunks(n, 2)
    temp = path + ".partial"
    with open(temp, "wb") as out:
        if fmt == "npy":
            out.write(npy_header(n))
        for flat in chunks:
            if numpy is not None:
                if fmt == "npy":
                    out.write(flat.astype("<f8").tobytes())
                else:
                    out.write("".join("%r %r\n" % (x, y) for x, y in flat.tolist()).encode())
                continue
            if fmt == "npy":
                if sys.byteorder != "little":
                    flat.byteswap()
                out.write(flat.tobytes())
            else:
                it = iter(flat)
                out.write("".join("%r %r\n" % (x, y) for x, y in zip(it, it)).encode())
    os.replace(temp, path)


TIMING = re.compile(r"^condt: time ([a-z-]+) ([0-9.]+) s", re.MULTILINE)


def measure(command, limit_gib=None):
    """Runs `command` under /usr/bin/time -v: (exit code, wall seconds, user + system seconds,
    peak RSS in bytes, {step: seconds} from its `--timings` lines). The processor time is the
    figure to compare on a busy machine. `limit_gib` caps the run's address space."""

    def cap():
        size = int(limit_gib * 2**30)
        resource.setrlimit(resource.RLIMIT_AS, (size, size))

    start = time.monotonic()
    done = subprocess.run(["/usr/bin/time", "-v"] + command, stdout=subprocess.DEVNULL,
                          stderr=subprocess.PIPE, text=True,
                          preexec_fn=cap if limit_gib else None)
    wall = time.monotonic() - start
    steps = {step: float(seconds) for step, seconds in TIMING.findall(done.stderr)}

    def field(name):
        found = re.search(name + r": ([0-9.]+)", done.stderr)
        return float(found.group(1)) if found else 0.0

    rss = int(field(r"Maximum resident set size \(kbytes\)")) * 1024
    cpu = field(r"User time \(seconds\)") + field(r"System time \(seconds\)")
    if done.returncode != 0:
        sys.stderr.write(done.stderr)
    return done.returncode, wall, cpu, rss, steps


def growth_table(runs):
    """The markdown growth table of `runs` ({(command, kind, fmt): {n: steps}}): every step's
    time per point (ns) at each size, and the ratio of the largest size's to the smallest's
    beside the ratio of log n over the same sizes (what an n log n step would show)."""
    sizes = sorted({n for by_size in runs.values() for n in by_size})
    lines = ["| command | input | step | " + " | ".join(size_name(n) for n in sizes)
             + " | growth | log n growth |",
             "|---|---|---|" + "---|" * len(sizes) + "---|---|"]
    for (command, kind, fmt), by_size in runs.items():
        order = []
        for steps in by_size.values():
            order += [step for step in steps if step not in order]
        for step in order:
            cells, per_point = [], {}
            for n in sizes:
                seconds = by_size.get(n, {}).get(step)
                if seconds is None:
                    cells.append("")
                else:
                    per_point[n] = seconds / n * 1e9
                    cells.append(f"{per_point[n]:.1f}")
            measured = sorted(per_point)
            if len(measured) >= 2 and per_point[measured[0]] > 0:
                first, last = measured[0], measured[-1]
                growth = f"{per_point[last] / per_point[first]:.2f}"
                log_growth = f"{math.log(last) / math.log(first):.2f}"
            else:
                growth = log_growth = ""
            name = kind if fmt == "npy" else f"{kind} (.{fmt})"
            lines.append(f"| {command} | {name} | {step} | " + " | ".join(cells)
                         + f" | {growth} | {log_growth} |")
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", nargs="+", type=parse_size,
                        default=[parse_size(s) for s in ["1M", "10M", "30M", "100M"]])
    parser.add_argument("--inputs", nargs="+", choices=["uniform", "curves"],
                        default=["uniform", "curves"])
    parser.add_argument("--formats", nargs="+", choices=["npy", "txt"], default=["npy"])
    parser.add_argument("--commands", nargs="+", choices=["triangulate", "reconstruct"],
                        default=["triangulate", "reconstruct"])
    parser.add_argument("--dir", default=os.path.join(tempfile.gettempdir(), "condt-scale"))
    parser.add_argument("--condt", default="target/release/condt")
    parser.add_argument("--generate-only", action="store_true")
    parser.add_argument("--limit-gib", type=float, default=None,
                        help="cap each run's address space at this many GiB")
    args = parser.parse_args()
    os.makedirs(args.dir, exist_ok=True)
    if not args.generate_only and not os.access(args.condt, os.X_OK):
        sys.exit(f"{args.condt} is not an executable: run `cargo build --release` first")

    rows = []
    runs = {}
    for n in args.sizes:
        for kind in args.inputs:
            for fmt in args.formats:
                suffix = "" if numpy is not None else "-py"
                path = os.path.join(args.dir, f"{kind}-{size_name(n)}{suffix}.{fmt}")
                if not os.path.exists(path):
                    start = time.monotonic()
                    generate(kind, n, fmt, path)
                    print(f"generated {path} in {time.monotonic() - start:.1f} s",
                          file=sys.stderr)
                if args.generate_only:
                    continue
                for command in args.commands:
                    # Output as .npy (binary, what a user at scale wants) to a file that is
                    # removed afterwards; text output is measured with --formats txt input.
                    out = os.path.join(args.dir, f"out-{command}-{kind}-{size_name(n)}.{fmt}")
                    code, wall, cpu, rss, steps = measure(
                        [args.condt, command, path, "-o", out, "--timings"], args.limit_gib)
                    if code == 0:
                        runs.setdefault((command, kind, fmt), {})[n] = steps
                    if os.path.exists(out):
                        os.remove(out)
                    per_point = rss / n
                    row = (f"| {command} | {kind} | .{fmt} | {size_name(n)} | {wall:.2f} s | "
                           f"{cpu:.2f} s | {rss / 2**20:,.0f} MiB | {per_point:.0f} |"
                           + ("" if code == 0 else f" exit {code}"))
                    print(row, file=sys.stderr)
                    rows.append(row)
    if rows:
        print("| command | input | format (in and out) | points | wall | user + system | "
              "peak RSS | bytes/point |")
        print("|---|---|---|---|---|---|---|---|")
        for row in rows:
            print(row)
    if runs:
        print()
        print("Time per point (ns, wall clock of each `--timings` step):")
        print()
        for line in growth_table(runs):
            print(line)


if __name__ == "__main__":
    main()
