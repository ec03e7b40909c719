"""`condt.dask.reconstruct` on curves inside a straight outline sampled at float steps (a plot
frame, a parcel, a CAD border), against the same outline moved by up to 1e-9 at random and
against no outline (docs/distributed.md, *Limits*: slivers along a straight side of the hull).

    python3 python/bench/outline_tiles.py

The outline is 8,000 points along the four sides of a quadrilateral; inside it, 40,000 points
on random ellipses (seed 0); `paper=True`, 4 and 16 tiles, two workers in this process. Prints
per set and tile count the rounds, the points sent per point, whether any tile's known region
was the whole plane (a tile holding every point, watched through `condt.dask._known`), and
whether the edges equal `condt.reconstruct`'s.
"""

import math

import numpy as np

import condt
import condt.dask

SIDE_SAMPLES = 2000
INNER_POINTS = 40_000


def outline():
    corners = np.array([[0.1, 0.3], [97.3, 2.9], [101.7, 88.1], [3.3, 93.7]])
    t = np.arange(SIDE_SAMPLES) / SIDE_SAMPLES
    sides = zip(corners, np.roll(corners, -1, 0))
    return np.concatenate([a + np.outer(t, b - a) for a, b in sides])


def ellipses(rng, n):
    parts = []
    while sum(map(len, parts)) < n:
        centre = rng.uniform(15, 85, 2)
        radius = rng.uniform(1, 4)
        t = np.sort(rng.uniform(0, 2 * np.pi, int(rng.integers(50, 300))))
        parts.append(np.column_stack([centre[0] + radius * np.cos(t), centre[1] + 0.7 * radius * np.sin(t)]))
    return np.concatenate(parts)[:n]


def main():
    import distributed

    whole_plane = []
    known = condt.dask._known

    def watched(rect, halo, bbox):
        region = known(rect, halo, bbox)
        whole_plane.append(all(math.isinf(side) for side in region))
        return region

    condt.dask._known = watched
    rng = np.random.default_rng(0)
    inner = ellipses(rng, INNER_POINTS)
    frame = outline()
    sets = [
        ("outline", frame),
        ("outline moved by up to 1e-9", frame + rng.uniform(-1e-9, 1e-9, frame.shape)),
        ("no outline", np.empty((0, 2))),
    ]
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        for label, around in sets:
            points = np.vstack([around, inner])
            expected = condt.reconstruct(points, paper=True).edges
            for tiles in (4, 16):
                whole_plane.clear()
                tiled = condt.dask.reconstruct(points, client, tiles=tiles, paper=True)
                print(
                    f"{label}, {tiles} tiles: whole={tiled.whole!r}, rounds {tiled.rounds}, "
                    f"{tiled.sent / len(points):.1f} points sent per point, a tile of every "
                    f"point: {any(whole_plane)}, edges equal: "
                    f"{np.array_equal(tiled.edges, expected)}",
                    flush=True,
                )


if __name__ == "__main__":
    main()
