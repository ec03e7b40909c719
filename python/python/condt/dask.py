"""The reconstruction tiled across a Dask cluster, with the one-machine result.

``condt.dask.reconstruct(points, client=None, tiles=16, **params)`` cuts the plane into
``tiles`` rectangles holding about as many points each, sends each rectangle's points with a
margin around them (the *halo*) to the cluster's workers, and joins the edges each tile owns.
The result equals ``condt.reconstruct(points, **params).edges``, as a set of edges, always:

- every tile proves that the part of the Delaunay triangulation its stages read is the whole
  set's (the certificate in ``python/src/tiles.rs``); a tile that cannot, because its halo is
  too narrow, is sent again with a halo twice as wide (near the convex hull a tile also gets
  the points within its halo of the hull's boundary, where the circles of triangles on long
  hull edges reach);
- its vertices follow the whole set's insertion order, so the stages break ties as one machine
  does;
- the one global step, Algorithm 3's threshold, runs once on the joined edges, in the library;
- where the triangulation is not unique (four cocircular points, as on integer grids), where all
  points are collinear, or where the coordinates span more than 200 binary orders of magnitude,
  the whole set runs in one piece on one worker instead.

Tiled today: the proximity graph with a fixed or adaptive ``u``, the repair and Algorithm 3,
which is the paper's pipeline (``paper=True``, with any of its ``u``, ``adaptive``, ``iqr``,
``repair`` and ``iqr_floor``). Any other step (the default's local outlier removal, gap closing,
junctions, tips, smoothing passes) raises ``NotImplementedError`` naming it:
``docs/distributed.md`` says what each needs. The points themselves stay on the machine that calls this (the driver), which
computes their insertion order and hull once; the workers triangulate and run the stages.

>>> import numpy as np, condt, condt.dask
>>> from dask.distributed import Client, LocalCluster
>>> t = np.linspace(0, 2 * np.pi, 2000, endpoint=False)
>>> points = np.column_stack([np.cos(t), np.sin(3 * t) / 3])
>>> with LocalCluster(n_workers=2, threads_per_worker=1, processes=False) as cluster:
...     with Client(cluster) as client:
...         tiled = condt.dask.reconstruct(points, client, tiles=4, paper=True)
>>> np.array_equal(tiled.edges, condt.reconstruct(points, paper=True).edges)
True
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from . import _condt

__all__ = ["TiledReconstruction", "reconstruct"]

# Delaunay hops around an owned point whose stars a tile must certify: the proximity graph reads
# one ring and the repair two more hops of it (python/src/tiles.rs); twice that, for margin.
REACH = 6


@dataclasses.dataclass(frozen=True)
class TiledReconstruction:
    """What ``condt.dask.reconstruct`` gives: the edges and how the tiles ran.

    ``edges`` is an ``(m, 2)`` int64 array of input positions, ``i < j``, sorted by rows: the
    same as ``condt.reconstruct(points, **params).edges``. ``tiles`` is the number of tiles,
    ``rounds`` how many times the widest-halo tile was sent (1 when every first halo sufficed),
    ``workers`` the addresses of the workers that ran a tile, ``sent`` how many points went to
    workers in all (every tile and round, halos included: its ratio to the set's size is the
    cost of tiling), and ``whole`` why the set ran in one piece instead (``None`` when it was
    tiled).
    """

    edges: np.ndarray
    tiles: int
    rounds: int
    workers: frozenset
    sent: int
    whole: str | None


def reconstruct(
    points: Any,
    client: Any = None,
    tiles: int = 16,
    *,
    halo: float | None = None,
    **params: Any,
) -> TiledReconstruction:
    """The reconstruction of ``points`` by tiles on ``client``'s cluster.

    ``points`` is an ``(n, 2)`` array-like or a Dask array (computed on the driver); ``client``
    a ``dask.distributed.Client`` (``None``: the current one, ``distributed.get_client()``);
    ``tiles`` how many rectangles to cut the plane into (at least 1); ``halo`` the margin
    each tile's points are first sent with (``None``: a quarter of the tile's shorter side),
    doubled for a tile whose certificate needs more. ``params`` are
    ``condt.reconstruct``'s keywords; see the module's text for those that can be tiled.

    Raises ``NotImplementedError`` for a step that is not tiled yet, ``ValueError`` for a NaN or
    infinite point (named) or a refused parameter, as ``condt.reconstruct`` does.
    """
    if isinstance(tiles, bool) or not isinstance(tiles, int) or tiles < 1:
        raise ValueError(f"tiles must be a positive integer, not {tiles!r}")
    number = isinstance(halo, (int, float)) and not isinstance(halo, bool)
    if halo is not None and not (number and 0 < halo < math.inf):
        raise ValueError(f"halo must be a positive finite number or None, not {halo!r}")
    if client is None:
        from distributed import get_client

        client = get_client()
    if hasattr(points, "dask") and hasattr(points, "compute"):
        points = points.compute()
    if isinstance(points, np.ndarray) and points.dtype == np.float64:
        points = np.ascontiguousarray(points)
    plan = _condt._tile_plan(points, **params)
    points = np.ascontiguousarray(np.asarray(points, dtype=np.float64)).reshape(-1, 2)
    n = len(points)
    whole = "no points" if n == 0 else plan["whole"]
    if whole is not None:
        return _in_one_piece(points, client, params, whole)

    bbox = np.concatenate([points.min(axis=0), points.max(axis=0)])
    rects = _cut(points, tiles, bbox)
    halo_of = [float(halo) if halo is not None else _first_halo(r, bbox) for r in rects]
    ranks, boundary, depth = plan["ranks"], plan["boundary"], plan["depth"]
    gathered: list[np.ndarray | None] = [None] * len(rects)
    workers: set = set()
    rounds = sent = 0
    # A tile that owns no point has nothing to send back.
    pending = [k for k in range(len(rects)) if _inside(points, rects[k], closed=False).any()]
    while pending:
        rounds += 1
        futures = {}
        for k in pending:
            # Each tile gets only its points (the driver cuts them out): a worker never holds
            # the whole set.
            known = _known(rects[k], halo_of[k], bbox)
            inside = _inside(points, known, closed=True)
            # Near the hull, the band along its boundary too (python/src/tiles.rs says why).
            band = 0.0
            if depth is not None and inside.any() and depth[inside].min() <= halo_of[k]:
                band = halo_of[k]
                inside |= depth <= band
            positions = np.flatnonzero(inside)
            sent += len(positions)
            # Scattered, not put into the task graph: the arrays go to a worker directly.
            payload = client.scatter(
                (
                    np.ascontiguousarray(points[positions]),
                    positions.astype(np.int64),
                    np.ascontiguousarray(ranks[positions]),
                    np.ascontiguousarray(boundary[positions]),
                ),
                hash=False,
            )
            futures[k] = client.submit(
                _tile,
                payload,
                plan["boundary_len"],
                plan["hull"],
                band,
                rects[k],
                known,
                tuple(float(b) for b in bbox),
                params,
                pure=False,
            )
        results = client.gather(list(futures.values()))
        pending = []
        for k, (status, edges, worker) in zip(futures, results):
            workers.add(worker)
            if status == "ok":
                gathered[k] = edges
            elif status == "cocircular":
                why = "cocircular points"
                return _in_one_piece(points, client, params, why, rounds, sent, workers)
            elif all(math.isinf(side) for side in _known(rects[k], halo_of[k], bbox)):
                # The tile held every point: no wider halo can certify more.
                why = "a tile held every point"
                return _in_one_piece(points, client, params, why, rounds, sent, workers)
            else:
                halo_of[k] *= 2.0
                pending.append(k)
    parts = [e for e in gathered if e is not None]
    joined = np.concatenate(parts) if parts else np.empty((0, 2), np.int64)
    edges = _condt._gathered_outliers(points, np.ascontiguousarray(joined), **params)
    return TiledReconstruction(edges, len(rects), rounds, frozenset(workers), sent, None)


def _inside(points, rect, closed):
    """Which points lie in ``rect``: closed on every side, or half-open ``[x0, x1) x [y0, y1)``."""
    x, y = points[:, 0], points[:, 1]
    if closed:
        return (x >= rect[0]) & (y >= rect[1]) & (x <= rect[2]) & (y <= rect[3])
    return (x >= rect[0]) & (y >= rect[1]) & (x < rect[2]) & (y < rect[3])


def _tile(payload, boundary_len, hull, band, rect, known, bbox, params):
    """On a worker: one tile's owned edges after the repair, or why it could not certify."""
    from distributed import get_worker

    # Arrays that crossed processes may arrive misaligned: the native module reads them in place.
    points, positions, ranks, boundary = (np.require(a, requirements="CA") for a in payload)
    status, edges = _condt._run_tile(
        points,
        positions,
        ranks,
        _inside(points, rect, closed=False),
        boundary,
        boundary_len,
        hull,
        band,
        known,
        bbox,
        REACH,
        **params,
    )
    return status, edges, get_worker().address


def _in_one_piece(points, client, params, why, rounds=0, sent=0, workers=frozenset()):
    """The whole set on one worker, when tiles cannot give the one-machine result (after
    ``rounds`` of tiles that sent ``sent`` points to ``workers``)."""
    edges, worker = client.submit(_whole, points, params, pure=False).result()
    workers = frozenset(workers) | {worker}
    return TiledReconstruction(edges, 1, rounds + 1, workers, sent + len(points), why)


def _whole(points, params):
    """On a worker: ``condt.reconstruct`` of the whole set."""
    from distributed import get_worker

    from condt import reconstruct as one_machine

    return np.array(one_machine(points, **params).edges), get_worker().address


def _cut(points, tiles, bbox):
    """``tiles`` rectangles ``[x0, y0, x1, y1)`` covering the bounding box, about as many points
    in each: columns at x quantiles, each cut into rows at its own y quantiles. The last column
    and row are closed by an upper bound just above the box."""
    columns = max(1, int(round(math.sqrt(tiles))))
    while tiles % columns:
        columns -= 1
    rows = tiles // columns
    top = (np.nextafter(bbox[2], np.inf), np.nextafter(bbox[3], np.inf))
    xs = np.quantile(points[:, 0], np.linspace(0, 1, columns + 1)[1:-1])
    x_cuts = np.concatenate([[bbox[0]], xs, [top[0]]])
    rects = []
    for c in range(columns):
        x0, x1 = x_cuts[c], x_cuts[c + 1]
        inside = (points[:, 0] >= x0) & (points[:, 0] < x1)
        column = points[inside, 1]
        if len(column):
            ys = np.quantile(column, np.linspace(0, 1, rows + 1)[1:-1])
        else:
            ys = np.linspace(bbox[1], bbox[3], rows + 1)[1:-1]
        y_cuts = np.concatenate([[bbox[1]], ys, [top[1]]])
        for r in range(rows):
            rects.append((float(x0), float(y_cuts[r]), float(x1), float(y_cuts[r + 1])))
    return rects


def _first_halo(rect, bbox):
    """A quarter of the tile's shorter side (within the bounding box): each tile is first sent
    with about twice its own points, whatever the set's scale."""
    width = min(rect[2], bbox[2]) - max(rect[0], bbox[0])
    height = min(rect[3], bbox[3]) - max(rect[1], bbox[1])
    side = min(width, height) if min(width, height) > 0 else max(width, height)
    return 0.25 * side if side > 0 else 1.0


def _known(rect, halo, bbox):
    """The rectangle whose points a tile holds: its own widened by ``halo``, a side that reaches
    the bounding box made infinite (nothing lies beyond it)."""
    x0, y0, x1, y1 = rect[0] - halo, rect[1] - halo, rect[2] + halo, rect[3] + halo
    return (
        -math.inf if x0 <= bbox[0] else x0,
        -math.inf if y0 <= bbox[1] else y0,
        math.inf if x1 >= bbox[2] else x1,
        math.inf if y1 >= bbox[3] else y1,
    )
