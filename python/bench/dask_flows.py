"""`condt.dask.reconstruct` of the paper's pipeline and its two-phase variants against
`condt.reconstruct`, on a LocalCluster of worker processes (docs/distributed.md, "Measured on
one machine").

    python3 python/bench/dask_flows.py [--points 1000000] [--tiles 16] [--workers 2]

The points are `curves()` of `python/tests/test_dask.py` (ellipses, every fourth noisy, 1 %
uniform outliers; seed 7). Prints, per flow, the one-machine and the tiled wall time, the
rounds, the points sent per point, and whether the edges are identical.
"""

import argparse
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))

from test_dask import curves  # noqa: E402

import condt  # noqa: E402
import condt.dask  # noqa: E402

FLOWS = [
    {"paper": True},
    {"paper": True, "outliers_first": True},
    {"paper": True, "repair_again": True},
]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", type=int, default=1_000_000)
    parser.add_argument("--tiles", type=int, default=16)
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    from dask.distributed import Client, LocalCluster

    points = curves(args.points, np.random.default_rng(7), outliers=0.01)
    with LocalCluster(
        n_workers=args.workers, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, Client(cluster) as client:
        for params in FLOWS:
            start = time.perf_counter()
            one = condt.reconstruct(points, **params).edges
            alone = time.perf_counter() - start
            start = time.perf_counter()
            tiled = condt.dask.reconstruct(points, client, tiles=args.tiles, **params)
            spread = time.perf_counter() - start
            print(
                f"{params}: one machine {alone:.2f} s, tiled {spread:.2f} s, "
                f"rounds {tiled.rounds}, sent per point {tiled.sent / len(points):.2f}, "
                f"identical {np.array_equal(one, tiled.edges)}",
                flush=True,
            )


if __name__ == "__main__":
    main()
