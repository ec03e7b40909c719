#!/usr/bin/env python3
"""End-to-end scale benchmark of the `condt` command line (Python standard library only).

Generates point sets (uniform in the unit square, and along closed curves) of the sizes asked
for, as NumPy `.npy` (float64, shape (n, 2)) and as text, runs `condt triangulate` and
`condt reconstruct` on them under `/usr/bin/time -v`, and prints a markdown table of wall time,
processor time (user + system: the figure to compare on a busy machine), peak resident memory
and bytes per point (peak RSS over the number of points).

    python3 scripts/scale.py                       # 1M, 10M, 30M, 100M, both inputs, .npy
    python3 scripts/scale.py --sizes 1M 10M --formats npy txt
    python3 scripts/scale.py --generate-only --sizes 1M --dir /tmp/pts

The data go to --dir (default: a directory under the system's temporary directory) and are
kept, so that a second run reuses them; 100M points take 1.6 GB as .npy and about 4 GB as text.
Generating is deterministic (a fixed seed per input) and takes about a minute per 10M points.
The binary is `target/release/condt` unless --condt names another; build it first with
`cargo build --release`.
"""

import argparse
import math
import os
import random
import re
import struct
import subprocess
import sys
import tempfile
import time
from array import array

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


def npy_header(n):
    """The NPY version 1.0 header for a little-endian float64 array of shape (n, 2)."""
    text = "{'descr': '<f8', 'fortran_order': False, 'shape': (%d, 2), }" % n
    # magic (6) + version (2) + length (2) + text + '\n' padded to a multiple of 64
    total = 10 + len(text) + 1
    text += " " * ((64 - total % 64) % 64) + "\n"
    return b"\x93NUMPY\x01\x00" + struct.pack("<H", len(text)) + text.encode("latin1")


def generate(kind, n, fmt, path):
    chunks = uniform_chunks(n, 1) if kind == "uniform" else curve_chunks(n, 2)
    temp = path + ".partial"
    with open(temp, "wb") as out:
        if fmt == "npy":
            out.write(npy_header(n))
        for flat in chunks:
            if fmt == "npy":
                if sys.byteorder != "little":
                    flat.byteswap()
                out.write(flat.tobytes())
            else:
                it = iter(flat)
                out.write("".join("%r %r\n" % (x, y) for x, y in zip(it, it)).encode())
    os.replace(temp, path)


def measure(command):
    """Runs `command` under /usr/bin/time -v: (exit code, wall seconds, user + system seconds,
    peak RSS in bytes). The processor time is the figure to compare on a busy machine."""
    start = time.monotonic()
    done = subprocess.run(["/usr/bin/time", "-v"] + command, stdout=subprocess.DEVNULL,
                          stderr=subprocess.PIPE, text=True)
    wall = time.monotonic() - start

    def field(name):
        found = re.search(name + r": ([0-9.]+)", done.stderr)
        return float(found.group(1)) if found else 0.0

    rss = int(field(r"Maximum resident set size \(kbytes\)")) * 1024
    cpu = field(r"User time \(seconds\)") + field(r"System time \(seconds\)")
    if done.returncode != 0:
        sys.stderr.write(done.stderr)
    return done.returncode, wall, cpu, rss


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
    args = parser.parse_args()
    os.makedirs(args.dir, exist_ok=True)
    if not args.generate_only and not os.access(args.condt, os.X_OK):
        sys.exit(f"{args.condt} is not an executable: run `cargo build --release` first")

    rows = []
    for n in args.sizes:
        for kind in args.inputs:
            for fmt in args.formats:
                path = os.path.join(args.dir, f"{kind}-{size_name(n)}.{fmt}")
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
                    code, wall, cpu, rss = measure([args.condt, command, path, "-o", out])
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


if __name__ == "__main__":
    main()
