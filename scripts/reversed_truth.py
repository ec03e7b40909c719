#!/usr/bin/env python3
"""Counts ground-truth edges that run backwards along their curve in noisy evaluation cases.

Noise can move two consecutive samples past each other along the curve. The ground truth still
joins them in their original order, so it doubles back (a -> c -> b -> d where the points lie
in the order a, b, c, d), which no reconstruction that follows the points' order reproduces:
such a case cannot come out exact. An edge (a, b) of a chain p, a, b, q counts as reversed when
b - a points against q - p. docs/condt.md ("Exactness under noise has a ceiling") quotes the
figures.

    python3 scripts/reversed_truth.py DIR...

DIR holds `NAME.pts` and `NAME.gt` files, as `../shared/eval`'s generators write them
(`python3 gen_real.py DIR --seed 1`, or the case directories `run.py` keeps in the system's
temporary directory). Prints, per noise level (the name's last `_` field), the cases, those
without a reversed edge, and the mean number of reversed edges per case. Standard library only.
"""

import glob
import os
import sys
from collections import defaultdict


def numbers(path, count, kind):
    rows = []
    for line in open(path):
        fields = line.split()
        if fields and not line.startswith("#"):
            rows.append(tuple(kind(f) for f in fields[:count]))
    return rows


def reversed_edges(points, edges):
    neighbours = defaultdict(list)
    for a, b in edges:
        neighbours[a].append(b)
        neighbours[b].append(a)
    count = 0
    for a, b in edges:
        if len(neighbours[a]) != 2 or len(neighbours[b]) != 2:
            continue
        (p,) = [w for w in neighbours[a] if w != b] or [None]
        (q,) = [w for w in neighbours[b] if w != a] or [None]
        if p is None or q is None:
            continue
        along = (points[q][0] - points[p][0], points[q][1] - points[p][1])
        step = (points[b][0] - points[a][0], points[b][1] - points[a][1])
        count += along[0] * step[0] + along[1] * step[1] < 0
    return count


def main(dirs):
    levels = defaultdict(list)
    for d in dirs:
        for pts in sorted(glob.glob(os.path.join(d, "*.pts"))):
            name = os.path.basename(pts)[:-4]
            if "noise" not in name and not name.endswith(("_n15", "_n30")):
                continue
            points = numbers(pts, 2, float)
            edges = numbers(pts[:-4] + ".gt", 2, int)
            levels[name.rsplit("_", 1)[-1]].append(reversed_edges(points, edges))
    for level, counts in sorted(levels.items()):
        clean = sum(1 for c in counts if c == 0)
        print(f"{level}: {len(counts)} cases, {clean} without a reversed edge, "
              f"{sum(counts) / len(counts):.2f} reversed edges per case")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
