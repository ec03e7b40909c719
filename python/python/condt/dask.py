"""The reconstruction tiled across a Dask cluster, with the one-machine result.

``condt.dask.reconstruct(points, client=None, tiles=16, **params)`` cuts the plane into
``tiles`` rectangles holding about as many points each, sends each rectangle's points with a
margin around them (the *halo*) to the cluster's workers, and joins the edges each tile owns.
The result equals ``condt.reconstruct(points, **params).edges``, as a set of edges, always:

- every tile proves that the part of the Delaunay triangulation its stages read is the whole
  set's (the certificate in ``python/src/tiles.rs``); a tile that cannot, because its halo is
  too narrow, is sent again with a wider halo (half as wide again, then twice; near the convex
  hull a tile also gets the points within its halo of the hull's boundary, where the circles of
  triangles on long hull edges reach); once a tile's halo reaches every point, that one tile
  runs for every tile still waiting;
- its vertices follow the whole set's insertion order, so the stages break ties as one machine
  does;
- every global decision runs once on the driver, on the joined edges, with the library's own
  code: Algorithm 3's threshold (exact quartiles), components and their tallies, the guards over
  every point, walks along curves, which joins and moves stand; the tiles send what only the
  triangulation shows (each point's tests, each loose end's choices), one round per stage on
  the triangulations they keep;
- where the triangulation is not unique (four cocircular points, as on integer grids), where all
  points are collinear, or where the coordinates span more than 200 binary orders of magnitude,
  the whole set runs in one piece on one worker instead.

Every ConDT pipeline is tiled: the default, the paper's (``paper=True``) and every variant their
keywords make, with the smoothing passes (each pass a tiled run of its own on the moved points;
whether a pass follows, and where it moves the points, the library decides on the driver from
the edges the tiles sent). A baseline (``method="nn-crust"`` or ``"crust"``) raises
``NotImplementedError``. ``docs/distributed.md`` says what each stage's round carries. The points
themselves stay on the machine that calls this (the driver), which computes their insertion
order and hull once; the workers triangulate and run the stages.

>>> import numpy as np, condt, condt.dask
>>> from dask.distributed import Client, LocalCluster
>>> # Irregular samples: an evenly sampled symmetric curve has cocircular points (by its
>>> # symmetry), and would run in one piece.
>>> t = np.sort(np.random.default_rng(1).uniform(0, 2 * np.pi, 2000))
>>> points = np.column_stack([np.cos(t), np.sin(3 * t) / 3])
>>> with LocalCluster(n_workers=2, threads_per_worker=1, processes=False) as cluster:
...     with Client(cluster) as client:
...         tiled = condt.dask.reconstruct(points, client, tiles=4)
>>> np.array_equal(tiled.edges, condt.reconstruct(points).edges), tiled.whole, tiled.tiles
(True, None, 4)
"""

from __future__ import annotations

import dataclasses
import math
import operator
from typing import Any, SupportsFloat, SupportsIndex

import numpy as np
import numpy.typing as npt

from . import _condt

__all__ = ["TiledReconstruction", "reconstruct"]

# Delaunay hops around an owned point whose stars a tile must certify for the paper's stages: the
# proximity graph reads one ring and the repair two more hops of it (python/src/tiles.rs); twice
# that, for margin. Later stages read farther: the plan says how far (``plan["reach"]``).
REACH = 6

# How much wider a tile's halo is sent again when its certificate needs more: by half the first
# time (a halo just short of what the tile needs: every later round pays for the tile's area, so
# the square of the overshoot, and a failed try only one triangulation), twice after that (a halo
# far short, as a tiny tile's: fewer round trips). docs/distributed.md, "Measured on one machine".
HALO_GROWTH = (1.5, 2.0)


# Compared and hashed by identity (`eq=False`): an ndarray field has no truth value for `==`.
@dataclasses.dataclass(frozen=True, eq=False)
class TiledReconstruction:
    """What ``condt.dask.reconstruct`` gives: the edges and how the tiles ran.

    ``edges`` is a read-only ``(m, 2)`` int64 array of input positions, ``i < j``, sorted by
    rows: the same as ``condt.reconstruct(points, **params).edges``. ``tiles`` is the number of
    tiles, ``rounds`` how many rounds of tasks went to the workers (the tiles' first sends and
    their resends with wider halos, then one round per later stage; summed over the runs of the
    smoothing passes), ``workers`` the addresses of the
    workers that ran a tile, ``sent`` how many points went to workers in all (every tile and
    round, halos included: its ratio to the set's size is the cost of tiling), ``whole`` why the
    set ran in one piece instead (``None`` when it was tiled), and ``passes`` how many smoothing
    passes ran (each a tiled run of its own after the first; those of the one-piece run when the
    set ran in one piece, as ``condt.reconstruct(...).passes`` says).
    """

    edges: npt.NDArray[np.int64]
    tiles: int
    rounds: int
    workers: frozenset[str]
    sent: int
    whole: str | None
    passes: int = 0


def reconstruct(
    points: Any,
    client: Any = None,
    tiles: SupportsIndex = 16,
    *,
    halo: SupportsFloat | SupportsIndex | None = None,
    **params: Any,
) -> TiledReconstruction:
    """The reconstruction of ``points`` by tiles on ``client``'s cluster.

    ``points`` is an ``(n, 2)`` array-like or a Dask array (computed on the driver); ``client``
    a ``dask.distributed.Client`` (``None``: the current one, ``distributed.get_client()``);
    ``tiles`` how many rectangles to cut the plane into: an integer (numpy's too), at least 1;
    more tiles than points are as many tiles as points (``.tiles`` says how many were cut), since
    a tile beyond one per point would own nothing and only cost the driver a pass over the
    points (each round sends a task per tile, and the default takes dozens of rounds: give
    each tile tens of thousands of points). The tiles are a grid of the count's two factors
    nearest its square root: a prime count is one column of strips, which sends more points
    (a dask user's review, 100,000 points: 17 tiles sent 37.2 points per point, 16 sent 25.7).
    ``halo`` is the margin each tile's points are first
    sent with, a positive finite number (numpy's too; ``None``: a quarter of the tile's shorter
    side), grown for a tile whose certificate needs more (by half, then doubled; a smoothing
    pass's run starts from the halos the run before grew to). ``params`` are
    ``condt.reconstruct``'s keywords (every ConDT pipeline is tiled). Unlike
    ``condt.reconstruct`` it does not warn of points given twice a little apart (its result has
    edges only): ``condt.snap`` them first where the data may hold such pairs.

    Raises ``RuntimeError`` when a worker imports another condt version than the driver;
    ``NotImplementedError`` for a baseline method; ``TypeError`` for a ``client`` that
    is no ``Client`` (an address: ``Client(address)``), a ``tiles`` or ``halo`` of the wrong
    type (a bool, a str, a float for ``tiles``) or points that are not numbers; ``ValueError``
    for a NaN or infinite point (named), a masked array with masked entries, ``tiles`` below 1,
    a ``halo`` not positive and finite or a refused parameter; as ``condt.reconstruct`` does
    for its own.
    """
    count = _tile_count(tiles)
    width = _halo_width(halo)
    # Before the client is looked for: without one, a baseline or a refused parameter met Dask's
    # "No global client found" instead of the error promised above (a review's find).
    _condt._tile_params(**params)
    # Points already on the driver are checked then too (a NaN named as condt.reconstruct names
    # it); a Dask array is computed only once a client is known to be open.
    lazy = hasattr(points, "dask") and hasattr(points, "compute")
    plan = None
    if not lazy:
        points, plan = _planned(points, params)
    from distributed import Client

    if client is None:
        from distributed import get_client

        client = get_client()
    if not isinstance(client, Client):
        # Said at once: an address or a cluster given here failed as an AttributeError deep in a
        # scatter (a Python user's review).
        raise TypeError(
            "client must be a dask.distributed.Client (None: the current one), "
            f"not {type(client).__name__}"
        )
    if client.status in ("closing", "closed"):
        # Said before any work, whatever the points: a tiled set would otherwise meet it as an
        # AttributeError deep in a scatter, a set run in one piece as Dask's own error.
        from distributed.client import ClosedClientError

        raise ClosedClientError("the Dask client given to condt.dask.reconstruct is closed")
    _same_version(client)
    if plan is None:
        points, plan = _planned(points.compute(), params)
    n = len(points)
    whole = "no points" if n == 0 else plan["whole"]
    if whole is not None:
        return _in_one_piece(points, client, params, whole)
    count = min(count, n)

    # One tiled run, or with the smoothing passes one per pass: the library says after each run
    # whether a pass follows and where it moves the points (``_gathered_smoothing_pass``).
    runs: list[_Run] = []
    original, previous, passes = points, None, 0
    while True:
        bbox = np.concatenate([points.min(axis=0), points.max(axis=0)])
        rects = _cut(points, count, bbox)
        # A pass moves the points by little and the rectangles are cut the same way: each tile
        # starts from the halo it certified with in the run before, not from the first halo
        # again (on 20,000 points and 16 tiles every run grew each tile four or five times).
        halos = runs[-1].halo_of if runs else width
        runs.append(_Run(points, client, plan, params, bbox, rects, halos))
        try:
            edges = _phases(runs[-1], plan, points, params)
        except _WholeSet as refused:
            return _in_one_piece(original, client, params, refused.why, runs)
        if not plan["smooth"]:
            break
        moved = _condt._gathered_smoothing_pass(points, edges, passes, previous)
        if moved is None:
            break
        if isinstance(moved, str):
            return _in_one_piece(original, client, params, moved, runs)
        previous, points, passes = edges, moved, passes + 1
        plan = _condt._tile_plan(points, **params)
        if plan["whole"] is not None:
            return _in_one_piece(original, client, params, plan["whole"], runs)
    rounds, sent, workers = _spent(runs)
    return TiledReconstruction(_read_only(edges), len(rects), rounds, workers, sent, None, passes)


def _same_version(client) -> None:
    """Refuses a cluster whose workers import another condt than the driver: the tiles' rules
    and the driver's must be the same code for the result to be one machine's, and a worker of
    another release would otherwise give other edges without a word, or fail deep in a task (a
    review's find). Workers that join after this check are not asked."""
    theirs = client.run(_worker_version)
    other = {worker: version for worker, version in theirs.items() if version != _condt.__version__}
    if other:
        listed = ", ".join(f"{worker} has {version}" for worker, version in sorted(other.items()))
        raise RuntimeError(
            f"the Dask workers must run the driver's condt {_condt.__version__}: {listed}"
        )


def _worker_version() -> str:
    """On a worker: the version of the condt it imports."""
    return _condt.__version__


def _planned(points: Any, params: dict) -> tuple[np.ndarray, dict]:
    """``points`` checked and planned by the library (``_tile_plan``), and as the ``(n, 2)``
    float64 array the tiles are cut from."""
    # A masked array goes to the library as it is, which refuses one with masked entries:
    # ``ascontiguousarray`` would drop its mask.
    if type(points) is np.ndarray and points.dtype == np.float64:
        points = np.ascontiguousarray(points)
    plan = _condt._tile_plan(points, **params)
    return np.ascontiguousarray(np.asarray(points, dtype=np.float64)).reshape(-1, 2), plan


def _tile_count(tiles: Any) -> int:
    """``tiles`` as an int: any integer (``operator.index``: numpy's too) but a bool, as
    ``condt.reconstruct`` refuses a bool where it wants a number."""
    if not isinstance(tiles, (bool, np.bool_)):
        try:
            count = operator.index(tiles)
        except TypeError:
            pass
        else:
            if count < 1:
                raise ValueError(f"tiles must be a positive integer, not {tiles!r}")
            return count
    raise TypeError(f"tiles must be an integer, not {type(tiles).__name__}")


def _halo_width(halo: Any) -> float | None:
    """``halo`` as a float, or ``None``: any number Python converts by its ``__float__`` or
    ``__index__`` (numpy's too), not a bool nor a str, as ``condt.reconstruct`` reads ``u``. An
    int too large for a float is infinite, with its sign, and refused as ``inf`` is."""
    if halo is None:
        return None
    kind = type(halo)
    if isinstance(halo, (bool, np.bool_)) or not (
        hasattr(kind, "__float__") or hasattr(kind, "__index__")
    ):
        raise TypeError(f"halo must be a number or None, not {kind.__name__}")
    try:
        width = float(halo)
    except OverflowError:
        width = -math.inf if halo < 0 else math.inf
    if not 0 < width < math.inf:
        raise ValueError(f"halo must be a positive finite number or None, not {width!r}")
    return width


def _read_only(edges):
    """``edges`` made read-only, as ``Reconstruction.edges`` is: a result shared by whoever
    holds it (``.copy()`` gives a writable one)."""
    edges.setflags(write=False)
    return edges


def _phases(run, plan, points, params):
    """The edges of a tiled run: the phases on the tiles, with the library's global steps
    between them on the driver (``plan["flow"]``: ``python/src/tiles.rs``'s ``Flow``), then one
    round on the kept tiles per later stage (``plan["later"]``)."""
    flow, later = plan["flow"], plan["later"]
    keep = bool(later)
    n = len(points)
    # Algorithm 3's input, which the local outlier removal's rule 1 reads.
    if flow == "outliers_first":
        (proximity,) = run.tiles("proximity", keep=True)
        before_outliers = proximity
        kept = _condt._gathered_outliers(points, proximity, **params)
        edges = _sorted(run.on_kept(kept, "repair"))
    elif flow == "repair_again":
        proximity, repaired = run.tiles("both", keep=True)
        before_outliers = _sorted(repaired)
        short = _condt._gathered_repair_again(points, repaired, proximity, **params)
        if short is None:
            edges = _condt._gathered_outliers(points, repaired, **params)
        else:
            edges = _sorted(run.on_kept(short, "repair"))
    else:
        (repaired,) = run.tiles("repaired", keep=keep)
        before_outliers = _sorted(repaired)
        edges = _condt._gathered_outliers(points, repaired, **params)
    if not plan["outliers"]:
        before_outliers = edges  # Algorithm 3 does not run: the stage reads its own input
    before_local = edges
    for step in later:
        if step == "local-outliers":
            # Rules 1 to 3 on the tiles (rule 1 only where the IQR stage cut more than the steps
            # since added: the driver counts); rule 4 on the driver, with the clump tests, the gap
            # choices, the tips' candidate moves and the hooks' and junctions' joins on their
            # result.
            before_local = edges
            give_back = len(before_outliers) > len(edges)
            if give_back:
                # Rule 1's candidates at curves' last edges, read off the cut before rules 1 to 3
                # run; the driver keeps those a curve stands behind once they have.
                last = run.on_kept(edges, "last-edges", before=before_outliers)
            edges = _sorted(run.on_kept(edges, step, before=before_outliers, give_back=give_back))
            if give_back and len(last):
                back = _condt._gathered_last_edges(n, edges, last)
                edges = edges if back is None else back
            labels = _condt._component_labels(n, edges)
            tests = run.tests_on_kept(edges, step, labels)
            # All three in one round (one scatter of the edges to each tile).
            choices, tips, joins = run.on_kept(edges, "joins", width=(10, 4, 2))
            kept = _condt._gathered_local_outliers(n, edges, tests, choices, tips, joins)
            edges = edges if kept is None else kept
        elif step == "given-back":
            standing = _condt._given_back_standing(n, edges, before_local)
            if standing is not None:
                labels, status = standing
                tests = run.tests_on_kept(edges, step, labels, status)
                kept = _condt._gathered_given_back(n, edges, before_local, tests)
                edges = edges if kept is None else kept
        elif step == "clumps":
            # The tests at each point on the tiles, the rule (a component's tally) on the driver;
            # where it finds clumps, the gap choices, the tips' candidate moves and the hooks' and
            # junctions' joins too (a clump they would join to a component that stays, stays).
            labels = _condt._component_labels(n, edges)
            tests = run.tests_on_kept(edges, step, labels)
            if _condt._gathered_clumps_found(n, edges, tests):
                choices, tips, joins = run.on_kept(edges, "joins", width=(10, 4, 2))
                kept = _condt._gathered_clumps(n, edges, tests, choices, tips, joins)
                edges = edges if kept is None else kept
        elif step == "gaps":
            # Each loose end's choice and straight walk on the tiles; agreement, the joins along
            # lone edges (a fixed point along chains) and the stranded runs on the driver.
            choices = run.on_kept(edges, step, width=10)
            after = _condt._gathered_gaps(len(points), edges, choices)
            edges = edges if after is None else after
        elif step == "tips":
            # The candidate moves on the tiles; the split test (a walk along a curve) and the
            # settling of moves that share a point on the driver.
            candidates = run.on_kept(edges, step, width=4)
            after = _condt._gathered_tips(len(points), edges, candidates)
            edges = edges if after is None else after
        else:
            edges = _sorted(run.on_kept(edges, step))
    run.release()
    return _sorted(edges)


def _sorted(edges):
    """The tiles' edges, each from the tile owning its smaller end (so once), sorted by rows as
    the library's answers are (a lexical sort; ``np.unique`` by rows took 1.3 s at 1M)."""
    edges = edges.reshape(-1, 2)
    return edges[np.lexsort((edges[:, 1], edges[:, 0]))]


class _WholeSet(Exception):
    """A tile cannot certify however wide its halo: the set runs in one piece (``why``)."""

    def __init__(self, why):
        super().__init__(why)
        self.why = why


class _Run:
    """The tiles of one call: their halos (grown where a certificate needs more, and kept for
    the next phase) and what they cost."""

    def __init__(self, points, client, plan, params, bbox, rects, halo):
        self.points, self.client, self.plan, self.params = points, client, plan, params
        self.bbox, self.rects = bbox, rects
        if isinstance(halo, list):
            self.halo_of = list(halo)  # the run before's, one per tile
        else:
            self.halo_of = [
                float(halo) if halo is not None else _first_halo(r, bbox) for r in rects
            ]
        self.grown = [0] * len(rects)
        self.workers: set = set()
        self.rounds = self.sent = 0
        # With ``keep``: per certified tile, the future holding its triangulation on its worker
        # (``python/src/tiles.rs``'s ``TileState``), the positions of its points and that worker.
        self.kept: dict = {}
        # Which kept tiles hold each point (``_split``), built once the tiles are kept.
        self._index = None
        # For each task holding every point, by its first tile, the tiles it runs for
        # (``_whole_tiles``).
        self.owners: dict = {}
        # The deepest point's distance from the hull's boundary (``_holds_every_point``).
        depth = plan["depth"]
        self.deepest = float(depth.max()) if depth is not None and len(depth) else None
        # A tile that owns no point has nothing to send back.
        self.owning = [
            k for k in range(len(rects)) if _inside(points, rects[k], closed=False).any()
        ]

    def release(self):
        """Lets the kept tiles' triangulations go (on their workers) and the index of them."""
        self.kept.clear()
        self._index = None

    def tiles(self, phase, keep=False):
        """Every owning tile's edges for ``phase`` (one joined ``(m, 2)`` array per graph it
        sends); ``keep``: each certified tile's triangulation stays on its worker for
        ``repair_kept``. Raises ``_WholeSet`` when the set must run in one piece instead."""
        points, bbox, plan = self.points, self.bbox, self.plan
        gathered = {}
        pending = list(self.owning)
        while pending:
            self.rounds += 1
            futures, sent_positions, batch = {}, {}, []
            if any(self._holds_every_point(k) for k in pending):
                # A tile of this round holds every point: it owns the points of every tile still
                # pending, in one task (``_whole_tiles``).
                k, arrays, band, known = self._whole_tiles(pending)
                sent_positions[k] = arrays[1]
                self.sent += len(points)
                batch.append((k, arrays, band, known))
                pending = []
            for k in pending:
                # Each tile gets only its points (the driver cuts them out): a worker holds the
                # whole set only once a tile's halo reaches every point (above).
                inside, band, known = self._held(k)
                positions = np.flatnonzero(inside)
                sent_positions[k] = positions
                self.sent += len(positions)
                arrays = (
                    np.ascontiguousarray(points[positions]),
                    positions.astype(np.int64),
                    np.ascontiguousarray(plan["ranks"][positions]),
                    np.ascontiguousarray(plan["boundary"][positions]),
                )
                batch.append((k, arrays, band, known))
                # A batch goes once it holds the points' own bytes: the driver holds at most about
                # one more copy of the points at a time.
                if sum(a.nbytes for _, tile, _, _ in batch for a in tile) >= points.nbytes:
                    futures.update(self._send(batch, phase, keep))
                    batch = []
            futures.update(self._send(batch, phase, keep))
            # Only the reports come back: a kept triangulation stays in its task's result.
            reports = [self.client.submit(_report, f, pure=False) for f in futures.values()]
            results = self.client.gather(reports)
            pending = []
            for k, (status, lists, worker) in zip(futures, results):
                self.workers.add(worker)
                if status == "ok":
                    gathered[k] = lists
                    if keep:
                        self.kept[k] = (futures[k], sent_positions[k], worker)
                        self._index = None
                elif status == "cocircular":
                    raise _WholeSet("cocircular points")
                elif k in self.owners or all(
                    math.isinf(side) for side in _known(self.rects[k], self.halo_of[k], bbox)
                ):
                    # The tile held every point: no wider halo can certify more.
                    raise _WholeSet("a tile held every point")
                else:
                    # Wider (``HALO_GROWTH``), and at least the first halo the plan would give: a
                    # halo the caller gave far too narrow (1e-300) would otherwise grow a thousand
                    # times.
                    growth = HALO_GROWTH[min(self.grown[k], 1)]
                    self.grown[k] += 1
                    first = _first_halo(self.rects[k], bbox)
                    self.halo_of[k] = max(growth * self.halo_of[k], first)
                    pending.append(k)
        graphs = len(next(iter(gathered.values()))) if gathered else 1
        return [
            np.concatenate([gathered[k][g] for k in sorted(gathered)] + [np.empty((0, 2), np.int64)])
            for g in range(graphs)
        ]

    def _held(self, k):
        """The points tile ``k`` is sent with its halo (a mask), its band and its known
        rectangle."""
        points, plan = self.points, self.plan
        known = _known(self.rects[k], self.halo_of[k], self.bbox)
        inside = _inside(points, known, closed=True)
        # Near the hull, the band along its boundary too (python/src/tiles.rs says why).
        band = 0.0
        depth = plan["depth"]
        if depth is not None and inside.any() and depth[inside].min() <= self.halo_of[k]:
            band = self.halo_of[k]
            inside |= depth <= band
        return inside, band, known

    def _holds_every_point(self, k):
        """Whether tile ``k`` is sent every point (``_held``), told without a pass over them:
        its known rectangle reaches the bounding box on every side, or near the hull its band
        (the points within its halo of the hull's boundary) reaches the deepest point; an
        owning tile holds a point of its own, so the band applies once it reaches. (A tile whose
        rectangle and band hold every point between them, neither alone, is sent as any other:
        it may still certify.)"""
        if all(math.isinf(side) for side in _known(self.rects[k], self.halo_of[k], self.bbox)):
            return True
        return self.deepest is not None and self.deepest <= self.halo_of[k]

    def _whole_tiles(self, tiles):
        """One task for ``tiles``, once the halo of one of them reaches every point, as a batch
        entry ``(tile, arrays, band, known)``: the first tile, holding every point and owning the
        points of all.

        A tile holding every point needs no certificate (no point lies outside it): its known
        region is the whole plane, so it certifies at once where a finite one around the same
        points could ask for another round. It certifies the others' points too, so they need
        no triangulation of their own, in this round or any later one: before, on 20,000 points
        and 16 tiles, every tile of a run was sent again and again until up to nine of them
        each held every point."""
        points, plan = self.points, self.plan
        self.owners[tiles[0]] = list(tiles)
        every = np.arange(len(points), dtype=np.int64)
        arrays = (points, every, plan["ranks"], plan["boundary"])
        return tiles[0], arrays, 0.0, (-math.inf, -math.inf, math.inf, math.inf)

    def _send(self, batch, phase, keep):
        """The ``_tile`` tasks of the tiles of ``batch`` (``(tile, arrays, band, known)`` each),
        by tile. Their arrays are scattered, not put into the task graph (they go to a worker
        directly), in one call: each call is a round trip, which small sets' tiles waited on one
        by one."""
        if not batch:
            return {}
        plan, bbox = self.plan, tuple(float(b) for b in self.bbox)
        payloads = self.client.scatter([arrays for _, arrays, _, _ in batch], hash=False)
        return {
            k: self.client.submit(
                _tile,
                payload,
                plan["boundary_len"],
                plan["hull"],
                band,
                [self.rects[j] for j in self.owners.get(k, [k])],
                known,
                bbox,
                plan["reach"],
                phase,
                keep,
                self.params,
                pure=False,
            )
            for (k, _, band, known), payload in zip(batch, payloads)
        }

    def tests_on_kept(self, given, step, labels, status=None):
        """The per-point tests of ``step`` on each kept tile, with the driver's edges ``given``
        and component ``labels`` (one per point), joined: one byte per point of the whole set,
        each from the tile owning it."""
        tasks = [
            (
                state,
                worker,
                (
                    local,
                    np.ascontiguousarray(labels[positions]),
                    None if status is None else np.ascontiguousarray(status[positions]),
                ),
            )
            for (state, positions, worker), local in zip(*self._split(given))
        ]
        results = self.client.gather(self._beside(_tile_tests, tasks, step, self.params))
        self.rounds += 1
        tests = np.zeros(len(self.points), np.uint8)
        for (owned, bits), worker in results:
            self.workers.add(worker)
            tests[owned] = bits
        return tests

    def _split(self, given):
        """The kept tiles (their state, positions and worker, by tile) and, for each, the rows
        of ``given`` with both ends among its points, in its own positions."""
        kept = [self.kept[k] for k in sorted(self.kept)]
        if self._index is None:
            # The kept tiles stay the same through the run's rounds: one index for all of them.
            self._index = _condt._tile_index(len(self.points), [p for _, p, _ in kept])
        given = np.ascontiguousarray(given, dtype=np.int64).reshape(-1, 2)
        return kept, _condt._split_edges(self._index, given)

    def _beside(self, call, tasks, *args):
        """``call(state, arrays, *args)`` for each ``(state, worker, arrays)`` of ``tasks``, on the
        worker that holds the kept tile ``state``: the futures, in the order of ``tasks``.

        The arrays are scattered to that worker and the task asks for it, so that the tile stays
        where it is: left to itself, the scheduler moved a state it took for a few bytes (before
        the state said its size, ``__sizeof__``) to wherever the scatter had put megabytes of
        arrays, and the tile was pickled and triangulated again there (on 1M points, 16 tiles and
        two worker processes, in most rounds). The request is loose (``allow_other_workers``): a
        lost worker fails the call as before. One scatter per worker, not per tile: each is a
        round trip, which small sets' rounds wait on.
        """
        payloads = [None] * len(tasks)
        for worker in {worker for _, worker, _ in tasks}:
            mine = [k for k, (_, w, _) in enumerate(tasks) if w == worker]
            # Scattered, not put into the task graph (as the tiles' points are).
            scattered = self.client.scatter(
                [tasks[k][2] for k in mine], workers=[worker], hash=False
            )
            for k, payload in zip(mine, scattered):
                payloads[k] = payload
        return [
            self.client.submit(
                call, state, payload, *args, workers=[worker], allow_other_workers=True, pure=False
            )
            for (state, worker, _), payload in zip(tasks, payloads)
        ]

    def on_kept(self, given, step, width=2, before=None, give_back=False):
        """``step`` run on the driver's edges ``given`` on each kept tile (the triangulation and
        halo that certified it, on its worker), joined: the second phase of a two-phase flow
        (``"repair"``) or a later stage's round, which sends each tile only its given edges. The
        tiles' rows (owned edges; for the tips, ``width`` 4, candidate moves; for gap closing,
        ``width`` 10, choices) in tile order; for ``"joins"`` (``width`` ``(10, 4, 2)``) the gap
        choices, the tip candidates and the hooks' and junctions' joins, three lists from one
        round."""
        kept, locals_ = self._split(given)
        earlier = [None] * len(kept) if before is None else self._split(before)[1]
        tasks = [
            (state, worker, (local, local_before))
            for (state, _, worker), local, local_before in zip(kept, locals_, earlier)
        ]
        results = self.client.gather(
            self._beside(_tile_given, tasks, step, give_back, self.params)
        )
        self.rounds += 1
        for _, worker in results:
            self.workers.add(worker)
        if isinstance(width, tuple):
            return tuple(
                np.concatenate([rows[k] for rows, _ in results] + [np.empty((0, w), np.int64)])
                for k, w in enumerate(width)
            )
        return np.concatenate([rows for rows, _ in results] + [np.empty((0, width), np.int64)])


def _inside(points, rect, closed):
    """Which points lie in ``rect``: closed on every side, or half-open ``[x0, x1) x [y0, y1)``."""
    x, y = points[:, 0], points[:, 1]
    if closed:
        return (x >= rect[0]) & (y >= rect[1]) & (x <= rect[2]) & (y <= rect[3])
    return (x >= rect[0]) & (y >= rect[1]) & (x < rect[2]) & (y < rect[3])


def _tile(payload, boundary_len, hull, band, rects, known, bbox, reach, phase, keep, params):
    """On a worker: the owned edges for ``phase`` of a tile (or of several holding every point:
    the points inside any of ``rects``), or why it could not certify; with ``keep``, its
    triangulation too (left on the worker, see ``_report``)."""
    from distributed import get_worker

    # Arrays that crossed processes may arrive misaligned: the native module reads them in place.
    points, positions, ranks, boundary = (np.require(a, requirements="CA") for a in payload)
    owned = _inside(points, rects[0], closed=False)
    for rect in rects[1:]:
        owned |= _inside(points, rect, closed=False)
    status, edges, state = _on_worker(
        _condt._run_tile,
        points,
        positions,
        ranks,
        owned,
        boundary,
        boundary_len,
        hull,
        band,
        known,
        bbox,
        reach,
        phase,
        keep,
        **params,
    )
    return status, edges, get_worker().address, state


def _on_worker(call, *args, **kwargs):
    """``call(*args, **kwargs)``, with a failure that is no ``Exception`` (a Rust panic reaches
    Python as pyo3's ``PanicException``, a ``BaseException``) raised as ``RuntimeError``: Dask
    reports an ``Exception`` to the driver, while the other kind left the call waiting for a
    task that never finished."""
    try:
        return call(*args, **kwargs)
    except Exception:
        raise
    except (KeyboardInterrupt, SystemExit, GeneratorExit):
        raise
    except BaseException as err:
        raise RuntimeError(f"condt failed on a worker: {err}") from err


def _report(result):
    """On a worker: what the driver reads of a tile's result (not its kept triangulation)."""
    return result[:3]


def _tile_tests(result, payload, step, params):
    """On a worker: ``step``'s per-point tests on a tile's kept triangulation, with the driver's
    edges among the tile's points, their component labels and (for the given-back check) their
    status."""
    from distributed import get_worker

    # Arrays that crossed processes may arrive misaligned: the native module reads them in place.
    given, labels = (np.require(a, requirements="CA") for a in payload[:2])
    status = None if payload[2] is None else np.require(payload[2], requirements="CA")
    state = result[3]
    tests = _on_worker(_condt._tests_kept, state, given, labels, step, status, **params)
    return tests, get_worker().address


def _tile_given(result, payload, step, give_back, params):
    """On a worker: ``step`` on the driver's edges among a tile's points, on its kept
    triangulation (``payload``: those edges, and the IQR stage's input among them, which the
    local outlier removal's rules 1 to 3 read with ``give_back``)."""
    from distributed import get_worker

    given, before = payload
    state, given = result[3], np.require(given, requirements="CA")
    if step == "local-outliers":
        before = np.require(before, requirements="CA")
        rows = _on_worker(_condt._local_rules_kept, state, given, before, give_back, **params)
    elif step == "last-edges":
        before = np.require(before, requirements="CA")
        rows = _on_worker(_condt._last_edges_kept, state, given, before, **params)
    elif step in ("tips", "gaps"):
        rows = _on_worker(_condt._choices_kept, state, given, step, **params)
    elif step == "joins":
        rows = tuple(
            _on_worker(_condt._choices_kept, state, given, one, **params)
            for one in ("gaps", "tip-joins", "end-joins")
        )
    else:
        rows = _on_worker(_condt._step_kept, state, given, step, **params)
    return rows, get_worker().address


def _spent(runs):
    """What tiled ``runs`` cost together: rounds, points sent, and the workers that ran them."""
    workers = frozenset().union(*(run.workers for run in runs))
    return sum(run.rounds for run in runs), sum(run.sent for run in runs), workers


def _in_one_piece(points, client, params, why, runs=()):
    """The whole set on one worker, when tiles cannot give the one-machine result (after the
    tiled ``runs`` that found it out)."""
    rounds, sent, workers = _spent(runs)
    edges, passes, worker = client.submit(_whole, points, params, pure=False).result()
    return TiledReconstruction(
        _read_only(edges), 1, rounds + 1, workers | {worker}, sent + len(points), why, passes
    )


def _whole(points, params):
    """On a worker: ``condt.reconstruct`` of the whole set: its edges and smoothing passes."""
    from distributed import get_worker

    from condt import reconstruct as one_machine

    result = _on_worker(one_machine, points, **params)
    return np.array(result.edges), result.passes, get_worker().address


def _cut(points, tiles, bbox):
    """``tiles`` rectangles ``[x0, y0, x1, y1)`` covering the bounding box, about as many points
    in each: columns at x quantiles, each cut into rows at its own y quantiles. The last column
    and row are closed by an upper bound just above the box."""
    columns = max(1, int(round(math.sqrt(tiles))))
    while tiles % columns:
        columns -= 1
    rows = tiles // columns
    # Python's `nextafter`: numpy's warns of an overflow above the largest double.
    top = (math.nextafter(float(bbox[2]), math.inf), math.nextafter(float(bbox[3]), math.inf))
    xs = _inner_cuts(points[:, 0], columns)
    x_cuts = np.concatenate([[bbox[0]], xs, [top[0]]])
    rects = []
    for c in range(columns):
        x0, x1 = x_cuts[c], x_cuts[c + 1]
        inside = (points[:, 0] >= x0) & (points[:, 0] < x1)
        column = points[inside, 1]
        if len(column):
            ys = _inner_cuts(column, rows)
        else:
            ys = np.full(rows - 1, bbox[1])  # no point to share: empty rows, no overflow
        y_cuts = np.concatenate([[bbox[1]], ys, [top[1]]])
        for r in range(rows):
            rects.append((float(x0), float(y_cuts[r]), float(x1), float(y_cuts[r + 1])))
    return rects


def _inner_cuts(values, parts):
    """The ``parts - 1`` cuts between ``parts`` runs of about as many of ``values`` each: values
    of the set itself, so always finite and in order. (``np.quantile`` interpolates, ``a + (b -
    a) * t``, which overflows to infinity or NaN for values of opposite signs near 1e308: the
    rectangles then overlapped or missed points, and edges came twice or not at all.)"""
    ordered = np.sort(values)
    # Run k begins at value k * len / parts: as many runs as values own one each.
    at = (np.arange(1, parts) * len(ordered)) // parts
    return ordered[at]


def _first_halo(rect, bbox):
    """A quarter of the tile's shorter side (within the bounding box): each tile is first sent
    with about twice its own points, whatever the set's scale."""
    # Quarters first: a side from -1e308 to 1e308 would overflow.
    box = [float(b) for b in bbox]
    width = 0.25 * min(rect[2], box[2]) - 0.25 * max(rect[0], box[0])
    height = 0.25 * min(rect[3], box[3]) - 0.25 * max(rect[1], box[1])
    side = min(width, height) if min(width, height) > 0 else max(width, height)
    return side if side > 0 else 1.0


def _known(rect, halo, bbox):
    """The rectangle whose points a tile holds: its own widened by ``halo``, a side that reaches
    the bounding box made infinite (nothing lies beyond it). In Python's floats, so that a side
    beyond the largest double is an infinite one without numpy's overflow warning."""
    halo = float(halo)
    x0, y0, x1, y1 = rect[0] - halo, rect[1] - halo, rect[2] + halo, rect[3] + halo
    return (
        -math.inf if x0 <= bbox[0] else x0,
        -math.inf if y0 <= bbox[1] else y0,
        math.inf if x1 >= bbox[2] else x1,
        math.inf if y1 >= bbox[3] else y1,
    )
