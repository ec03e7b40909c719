"""`condt.dask.reconstruct` of the default pipeline (or any keywords) against
`condt.reconstruct`, at several tile counts, on a LocalCluster of worker processes
(docs/distributed.md, "Measured on one machine").

    python3 python/bench/dask_scale.py [--points 1000000] [--tiles 4,16,64] [--workers 2]
                                       [--paper]

The points are `curves()` of `python/tests/test_dask.py` (ellipses, every fourth noisy, 1 %
uniform outliers; seed 7). Prints the one-machine wall time, then per tile count the tiled wall
time, whether the edges are identical, the rounds, the points sent per point and the smoothing
passes. One run each: the machine's speed drifts, so compare only runs made together.
"""

import argparse
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", type=int, default=1_000_000)
    parser.add_argument("--tiles", default="4,16,64")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--paper", action="store_true")
    args = parser.parse_args()

    import condt
    import condt.dask
    import distributed
    from test_dask import curves

    params = {"paper": True} if args.paper else {}
    points = curves(args.points, np.random.default_rng(7))
    start = time.perf_counter()
    expected = condt.reconstruct(points, **params).edges
    print(f"{len(points)} points, one machine {time.perf_counter() - start:.2f} s", flush=True)
    with distributed.LocalCluster(
        n_workers=args.workers, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        for tiles in (int(t) for t in args.tiles.split(",")):
            start = time.perf_counter()
            tiled = condt.dask.reconstruct(points, client, tiles=tiles, **params)
            took = time.perf_counter() - start
            print(
                f"  {tiles} tiles: {took:.1f} s, identical {np.array_equal(tiled.edges, expected)}, "
                f"{tiled.rounds} rounds, {tiled.sent / len(points):.2f} sent per point, "
                f"{tiled.passes} passes, whole {tiled.whole}",
                flush=True,
            )


if __name__ == "__main__":
    main()
