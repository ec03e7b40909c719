#!/usr/bin/env python3
"""The detours step on synthetic outlines in a scatter (docs/condt.md, *Detours*).

Each set is an ellipse of 60 unit-spaced samples (axes 1.3 r and r, r = 60 / 2 pi) with 45
outliers drawn uniformly in the square of side 3.2 r around it, each more than one spacing from
every sample: outliers near the curve take two of its samples as their nearest neighbours.
Prints the false and missed edges and the exact sets over `SEEDS` seeds, with and without the
step, with and without smoothing passes. With `--draw SEED DIR` it also writes the points, the
truth and both outputs of one seed, for `../shared/eval/viz.py`.

Needs the Python package (`pip install ./python`):
`python3 scripts/detours_synthetic.py [SEEDS] [--draw SEED DIR]` (default 200 seeds).
"""
import os
import sys

import numpy as np

import condt

SAMPLES, OUTLIERS = 60, 45


def outline_in_scatter(seed):
    rng = np.random.default_rng(seed)
    r = SAMPLES / (2 * np.pi)
    t = 2 * np.pi * np.arange(SAMPLES) / SAMPLES
    curve = np.column_stack([1.3 * r * np.cos(t), r * np.sin(t)])
    outliers = []
    while len(outliers) < OUTLIERS:
        p = rng.uniform(-1.6 * r, 1.6 * r, 2)
        if np.hypot(*(curve - p).T).min() > 1.0:
            outliers.append(p)
    return np.concatenate([curve, outliers])


TRUTH = {tuple(sorted((i, (i + 1) % SAMPLES))) for i in range(SAMPLES)}


def edges(points, **params):
    return {tuple(e) for e in condt.reconstruct(points, **params).edges.tolist()}


def main():
    args = sys.argv[1:]
    draw = None
    if "--draw" in args:
        k = args.index("--draw")
        draw = (int(args[k + 1]), args[k + 2])
        del args[k : k + 3]
    seeds = int(args[0]) if args else 200
    for smooth in (True, False):
        for detours in (False, True):
            false = missed = exact = 0
            for seed in range(seeds):
                got = edges(outline_in_scatter(seed), smooth=smooth, detours=detours)
                false += len(got - TRUTH)
                missed += len(TRUTH - got)
                exact += got == TRUTH
            print(f"smooth={smooth} detours={detours}: {false} false edges, {missed} missed, "
                  f"{exact} of {seeds} exact")
    if draw:
        seed, out = draw
        os.makedirs(out, exist_ok=True)
        points = outline_in_scatter(seed)
        np.savetxt(os.path.join(out, "points.pts"), points)
        write = lambda name, es: np.savetxt(os.path.join(out, name), sorted(es), fmt="%d")
        write("truth.gt", TRUTH)
        write("before.edges", edges(points, detours=False))
        write("after.edges", edges(points))


if __name__ == "__main__":
    main()
