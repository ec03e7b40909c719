"""condt.dask: the tiled reconstruction equals the one-machine one, edge for edge.

The cluster tests need `dask[distributed]` (`pip install ./python[dask]`; CI installs it).
"""

import numpy as np
import pytest

distributed = pytest.importorskip("distributed")
hypothesis = pytest.importorskip("hypothesis")

import condt  # noqa: E402
import condt.dask  # noqa: E402
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402


@pytest.fixture(scope="module")
def client():
    """Two workers in this process: quick to start, enough for the equality properties."""
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        yield client


def curves(n, rng, outliers=0.01, noisy_every=4):
    """About `n` points on ellipses of random size and place, every `noisy_every`-th with
    Gaussian noise of a fifth of its spacing, and `outliers` of `n` uniform random points."""
    parts = []
    k = 0
    while sum(len(p) for p in parts) < n:
        centre = rng.uniform(0, 100, 2)
        radius = rng.uniform(0.5, 3.0)
        m = int(rng.integers(30, 300))
        t = np.sort(rng.uniform(0, 2 * np.pi, m))
        p = np.column_stack(
            [centre[0] + radius * np.cos(t), centre[1] + radius * rng.uniform(0.3, 1) * np.sin(t)]
        )
        if k % noisy_every == 0:
            p += rng.normal(0, 0.2 * 2 * np.pi * radius / m, p.shape)
        parts.append(p)
        k += 1
    points = np.concatenate(parts)[:n]
    return np.concatenate([points, rng.uniform(0, 100, (int(n * outliers), 2))])


def stage_switches():
    """The keywords that switch a stage beyond the paper, as the module lists them in its refusal
    of an unknown keyword (so that a new stage is switched here too: a new contributor's review),
    but those the tests set otherwise (the presets, the parameters, the flows)."""
    with pytest.raises(TypeError, match="the parameters are ") as refused:
        condt.reconstruct([(0.0, 0.0)], no_such_keyword=True)
    accepted = str(refused.value).split("the parameters are ")[1].split(", ")
    others = {"paper", "u", "adaptive", "iqr", "outlier_filter", "outliers_first", "iqr_floor"}
    others |= {"smooth", "repair", "manifold_fix", "method", "sequential", "repair_again"}
    switches = [keyword for keyword in accepted if keyword not in others]
    assert {"clumps", "close_gaps", "detours"} <= set(switches), switches
    return switches


def one_machine(points, **params):
    return condt.reconstruct(points, **params).edges


@pytest.mark.first
def test_a_million_points_on_two_worker_processes_give_the_one_machine_edges():
    # The default pipeline, smoothing passes and all: every stage a tiled round. Eight tiles,
    # four a worker: 59 s here against 92 s at sixteen (a third of CI's Python tests); the
    # small sets' tests cover other tile counts and halos that grow.
    points = curves(1_000_000, np.random.default_rng(7))
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        tiled = condt.dask.reconstruct(points, client, tiles=8)
        workers = set(client.scheduler_info()["workers"])
    assert tiled.whole is None
    assert tiled.tiles == 8 and tiled.passes > 0
    assert tiled.workers == workers and len(workers) == 2
    expected = one_machine(points)
    assert len(expected) > 500_000  # most points keep edges: a real result, not an empty one
    np.testing.assert_array_equal(tiled.edges, expected)


@settings(max_examples=12, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(3, 3000),
    tiles=st.integers(1, 12),
    kind=st.sampled_from(["curves", "uniform", "clustered", "columns"]),
    repeats=st.booleans(),
    narrow=st.booleans(),
    adaptive=st.booleans(),
    flow=st.sampled_from([{}, {"outliers_first": True}, {"repair_again": True}]),
    smooth=st.booleans(),
    later=st.fixed_dictionaries({keyword: st.booleans() for keyword in stage_switches()}),
)
def test_any_tiling_gives_the_one_machine_edges(
    client, seed, n, tiles, kind, repeats, narrow, adaptive, flow, smooth, later
):
    rng = np.random.default_rng(seed)
    if kind == "curves":
        points = curves(n, rng, outliers=0.02)
    elif kind == "uniform":
        points = rng.uniform(-5, 5, (n, 2))
    elif kind == "clustered":
        centres = rng.uniform(0, 1000, (max(1, n // 200), 2))
        points = centres[rng.integers(0, len(centres), n)] + rng.normal(0, 1, (n, 2))
    else:
        # Three vertical lines: the x quantiles repeat, so some tiles own no point.
        points = np.column_stack([rng.integers(0, 3, n) * 1.5, rng.uniform(0, 7, n)])
        points[0] = [0.7, 3.3]  # not all on lines: one point between them
    if repeats:
        points = np.concatenate([points, points[rng.integers(0, len(points), len(points) // 10)]])
        points = points[rng.permutation(len(points))]
    # A narrow first halo makes most tiles prove too little at first and grow.
    halo = 1e-3 * np.ptp(points, axis=0).max() if narrow else None
    params = {"paper": True, "adaptive": adaptive, "smooth": smooth, **flow}
    params.update(later)
    # The given-back check reads what the local outlier removal gave back: only with it.
    params["confirm_given_back"] &= params["local_outliers"]
    tiled = condt.dask.reconstruct(points, client, tiles=tiles, halo=halo, **params)
    # Random floats are never cocircular (on the lines, almost never) nor all on one line.
    assert tiled.whole is None or (kind == "columns" and tiled.whole == "cocircular points")
    np.testing.assert_array_equal(tiled.edges, one_machine(points, **params))


def test_a_halo_given_far_too_narrow_grows_to_the_planned_one_at_once(client):
    # 1e-300 doubled would take a thousand rounds to reach the tiles' scale: the first resend
    # uses at least the halo the plan gives (a quarter of the tile's shorter side).
    rng = np.random.default_rng(5)
    t = rng.uniform(0, 2 * np.pi, 600)
    points = np.column_stack([np.cos(t), np.sin(t)]) * 10
    tiled = condt.dask.reconstruct(points, client, tiles=4, halo=1e-300, paper=True)
    planned = condt.dask.reconstruct(points, client, tiles=4, paper=True)
    assert tiled.whole is None and tiled.rounds <= planned.rounds + 1
    np.testing.assert_array_equal(tiled.edges, one_machine(points, paper=True))


def five_blobs():
    """Five small blobs far apart: the triangles between them have circles as wide as the set."""
    rng = np.random.default_rng(11)
    centres = rng.uniform(0, 1000, (5, 2))
    return centres[rng.integers(0, 5, 20_000)] + rng.normal(0, 1, (20_000, 2))


def test_tiles_whose_circles_reach_far_grow_their_halo(client):
    # A first halo of a blob's size: with the plan's (a quarter of a tile) a tile's band along
    # the hull already holds every point, and that tile runs for all (the test below).
    points = five_blobs()
    tiled = condt.dask.reconstruct(points, client, tiles=16, halo=1.0, paper=True)
    assert tiled.whole is None and tiled.rounds > 1
    np.testing.assert_array_equal(tiled.edges, one_machine(points, paper=True))


def test_a_tile_of_every_point_certifies_beside_slivers_of_a_straight_side(client):
    # A dask user's review: points on a line up to rounding make Delaunay slivers whose rounded
    # circumcircle is none (a zero determinant); a tile holding every point was then refused as
    # uncertain, and the set sent whole to one worker ("a tile held every point").
    x = np.sort(np.random.default_rng(0).uniform(0, 10, 200))
    points = np.column_stack([x, 2 * x + 1])
    for tiles in (1, 2):
        tiled = condt.dask.reconstruct(points, client, tiles=tiles, paper=True)
        assert tiled.whole is None, tiled.whole
        np.testing.assert_array_equal(tiled.edges, one_machine(points, paper=True))


def test_a_tile_whose_halo_reaches_every_point_runs_for_every_tile(client):
    # Each of the 16 tiles was sent again and again until each held every point: 13 rounds and
    # 102 points sent per point, where one tile holding every point certifies every tile's.
    points = five_blobs()
    tiled = condt.dask.reconstruct(points, client, tiles=16, paper=True)
    assert tiled.whole is None and tiled.tiles == 16
    assert tiled.rounds == 1 and tiled.sent == len(points)
    np.testing.assert_array_equal(tiled.edges, one_machine(points, paper=True))


def test_the_default_runs_each_pass_from_the_halos_the_run_before_reached(client):
    # The default keeps the whole tile's triangulation for its later stages, and each smoothing
    # pass starts from the halos the run before grew to. From a narrow first halo the first run
    # grows them until one tile holds every point; every pass then sends each point once (a
    # pass that started from the first halo again grew it again: 125,512 points for 60,000).
    points = five_blobs()
    first = condt.dask.reconstruct(points, client, tiles=16, halo=0.05, smooth=False)
    tiled = condt.dask.reconstruct(points, client, tiles=16, halo=0.05)
    assert tiled.whole is None and tiled.passes >= 1
    assert tiled.sent - first.sent == tiled.passes * len(points)
    np.testing.assert_array_equal(tiled.edges, one_machine(points))


@pytest.mark.parametrize(
    "params",
    [
        {"paper": True, "u": 2.0},
        {"paper": True, "iqr": 0.5, "iqr_floor": True},
        {"paper": True, "repair": "needs"},
        {"paper": True, "repair": "mutual", "iqr": None},
        {"paper": True, "repair": "off"},
        {"paper": True, "adaptive": True},
        {"paper": True, "outliers_first": True},
        {"paper": True, "repair_again": True},
        {"paper": True, "repair_again": True, "iqr": 0.5, "repair": "mutual"},
    ],
)
def test_the_paper_pipelines_variants_are_tiled_exactly(client, params):
    points = curves(40_000, np.random.default_rng(3), outliers=0.03)
    tiled = condt.dask.reconstruct(points, client, tiles=9, **params)
    assert tiled.whole is None
    expected = one_machine(points, **params)
    np.testing.assert_array_equal(tiled.edges, expected)
    if params.get("outliers_first") or params.get("repair_again"):
        # The tiles' second phase ran and mattered: the result is not the plain pipeline's.
        assert not np.array_equal(expected, one_machine(points, paper=True))


@pytest.mark.parametrize("flow", [{}, {"outliers_first": True}, {"repair_again": True}])
def test_the_smoothing_passes_are_tiled_runs_with_the_one_machine_edges(client, flow):
    # Every other ellipse noisy: loose ends show noise, so the passes run, each a tiled run of
    # the moved points; the library decides on the driver whether another follows.
    points = curves(20_000, np.random.default_rng(4), outliers=0.02, noisy_every=2)
    params = {"paper": True, "smooth": True, **flow}
    tiled = condt.dask.reconstruct(points, client, tiles=9, **params)
    assert tiled.whole is None and tiled.passes == 3
    assert condt.reconstruct(points, **params).passes == tiled.passes
    expected = one_machine(points, **params)
    np.testing.assert_array_equal(tiled.edges, expected)
    # The passes mattered: without them the edges differ.
    assert not np.array_equal(expected, one_machine(points, paper=True, **flow))
    # Evenly sampled circles show no noise: no pass, one tiled run (moved by a hair, so that
    # their samples are not cocircular).
    t = np.linspace(0, 2 * np.pi, 400, endpoint=False)
    clean = np.concatenate([np.column_stack([5 * k + np.cos(t), np.sin(t)]) for k in range(8)])
    clean += np.random.default_rng(4).uniform(-1e-9, 1e-9, clean.shape)
    tiled = condt.dask.reconstruct(clean, client, tiles=4, **params)
    assert tiled.passes == 0
    np.testing.assert_array_equal(tiled.edges, one_machine(clean, **params))


def test_a_second_phase_sends_no_point_again(client):
    # Both flows repair on the triangulations their tiles kept: the points sent are the first
    # phase's, the same as the one-phase pipeline's on the same tiles (twice that before).
    points = curves(40_000, np.random.default_rng(5), outliers=0.03)
    plain = condt.dask.reconstruct(points, client, tiles=9, paper=True)
    for flow in ({"outliers_first": True}, {"repair_again": True}):
        tiled = condt.dask.reconstruct(points, client, tiles=9, paper=True, **flow)
        np.testing.assert_array_equal(tiled.edges, one_machine(points, paper=True, **flow))
        assert tiled.sent == plain.sent and tiled.rounds == plain.rounds + 1


def test_a_kept_tile_pickles_to_the_same_repair():
    # Dask may move a kept triangulation to another worker: it is rebuilt from its points and
    # insertion order, and repairs as the original does.
    import pickle

    from condt import _condt
    from condt.dask import REACH

    points = curves(3_000, np.random.default_rng(9))
    plan = _condt._tile_plan(points, paper=True)
    n = len(points)
    bbox = [float(v) for v in np.concatenate([points.min(axis=0), points.max(axis=0)])]
    status, (proximity,), state = _condt._run_tile(
        points, np.arange(n), plan["ranks"], np.ones(n, bool), plan["boundary"],
        plan["boundary_len"], plan["hull"], 0.0, [-np.inf, -np.inf, np.inf, np.inf], bbox,
        REACH, "proximity", keep=True, paper=True,
    )
    assert status == "ok"
    again = pickle.loads(pickle.dumps(state))
    repaired = _condt._step_kept(state, proximity, "repair", paper=True)
    np.testing.assert_array_equal(_condt._step_kept(again, proximity, "repair", paper=True), repaired)
    # The tile holds every point: its repair of the proximity graph is the whole set's.
    expected = one_machine(points, paper=True, iqr=None)
    np.testing.assert_array_equal(np.unique(repaired, axis=0), expected)
    # Dask weighs a move by the state's size (``sys.getsizeof``): its arrays, not a few bytes.
    import sys

    from dask.sizeof import sizeof

    assert sizeof(state) == sys.getsizeof(state) >= 50 * n


@pytest.mark.parametrize("scale", [1e-300, 1e299])
def test_huge_and_tiny_coordinates_are_tiled(client, scale):
    # Squared, such coordinates overflow or underflow: the certificate works in a scaled frame.
    points = scale * curves(3_000, np.random.default_rng(2), outliers=0.03)
    tiled = condt.dask.reconstruct(points, client, tiles=9, paper=True)
    assert tiled.whole is None
    np.testing.assert_array_equal(tiled.edges, one_machine(points, paper=True))


@pytest.mark.parametrize("tiles", [9, 16])
def test_coordinates_of_both_signs_near_the_largest_double_are_tiled_exactly(client, tiles):
    # Curves at -1e308 and 1e308: a cut interpolated between a point on each side overflowed
    # (``b - a`` beyond the largest double), and the rectangles missed points or overlapped.
    rng = np.random.default_rng(1)
    t = np.linspace(0, 2 * np.pi, 100, endpoint=False) + 1e-7 * rng.standard_normal(100)
    circle = np.column_stack([1.7e308 * np.cos(t), 1.7e308 * np.sin(t)])
    ring = np.column_stack([np.cos(t[:60]), np.sin(t[:60])]) * 1e306
    rings = np.concatenate([ring + [0, -1e308], ring + [0, 1e308]])
    for points in (circle, rings):
        with np.errstate(all="raise"):  # no overflow on the driver either
            tiled = condt.dask.reconstruct(points, client, tiles=tiles)
        assert tiled.whole is None
        np.testing.assert_array_equal(tiled.edges, one_machine(points))
    # Two lines at x = -1e308 and 1e308: a column between them holds no point, and its rows were
    # cut evenly from -1e308 to 1e308, which overflowed. Every point is owned once.
    lines = np.column_stack([np.repeat([-1e308, 1e308], 50), np.tile(t[:50] - 1.5, 2) * 1e308])
    bbox = np.concatenate([lines.min(axis=0), lines.max(axis=0)])
    with np.errstate(all="raise"):
        rects = condt.dask._cut(lines, tiles, bbox)
        owned = sum(condt.dask._inside(lines, rect, False).astype(int) for rect in rects)
    assert np.isfinite(rects).all() and (owned == 1).all()


def test_cocircular_points_run_in_one_piece_with_the_same_edges(client):
    grid = np.array([(x, y) for x in range(60) for y in range(40)], dtype=float)
    tiled = condt.dask.reconstruct(grid, client, tiles=4, paper=True)
    assert tiled.whole == "cocircular points"
    np.testing.assert_array_equal(tiled.edges, one_machine(grid, paper=True))


@pytest.mark.parametrize(
    "points, why",
    [
        (np.column_stack([np.arange(50.0), 2 * np.arange(50.0)]), "all points lie on one line"),
        (np.empty((0, 2)), "no points"),
        (np.array([[0.0, 0.0], [1.0, 1.0]]), "all points lie on one line"),
        (np.array([[1e-250, 5e239], [1e250, 0.0], [0.0, 1e240]]), "the coordinates span"),
    ],
)
def test_sets_that_cannot_be_tiled_run_in_one_piece(client, points, why):
    tiled = condt.dask.reconstruct(points, client, tiles=4, paper=True)
    assert tiled.whole.startswith(why)
    np.testing.assert_array_equal(
        tiled.edges.reshape(-1, 2), one_machine(points, paper=True).reshape(-1, 2)
    )


def test_a_set_run_in_one_piece_says_how_many_passes_ran(client):
    # A user review: `passes` was None there, though the one-piece run made its passes. The
    # shipped shapes hold cocircular points, which run in one piece.
    from conftest import DATA

    points = condt.read_points(DATA / "shapes.txt")
    tiled = condt.dask.reconstruct(points, client, tiles=4)
    assert tiled.whole == "cocircular points"
    expected = condt.reconstruct(points)
    assert expected.passes > 0
    assert tiled.passes == expected.passes
    np.testing.assert_array_equal(tiled.edges, expected.edges)


def test_a_dask_array_is_computed_first(client):
    da = pytest.importorskip("dask.array")
    points = curves(5_000, np.random.default_rng(5))
    tiled = condt.dask.reconstruct(da.from_array(points, chunks=1000), client, tiles=4, paper=True)
    np.testing.assert_array_equal(tiled.edges, one_machine(points, paper=True))


# The default without its first later stage: the others' rounds alone.
LATER = {"local_outliers": False}


@pytest.mark.parametrize(
    "params, stages",
    [
        ({"paper": True, "junctions": True, "crossings": True}, ["junctions", "crossings"]),
        ({**LATER, "smooth": False}, ["junctions", "crossings"]),
        (LATER, ["junctions", "crossings"]),
        ({**LATER, "junctions": False}, ["crossings"]),
        ({"paper": True, "tips": True}, ["tips"]),
        (LATER, ["tips"]),
        ({}, ["hooks"]),
        ({}, ["tails"]),
        ({"paper": True, "close_gaps": True}, ["close_gaps"]),
        (LATER, ["close_gaps"]),
        ({}, ["local_outliers"]),
        ({"smooth": False}, ["local_outliers"]),
        ({"paper": True, "repair_again": True, "local_outliers": True}, ["local_outliers"]),
        ({"outliers_first": True}, ["local_outliers"]),
        ({}, ["confirm_given_back"]),
    ],
)
def test_the_later_stages_are_tiled_rounds_with_the_one_machine_edges(client, params, stages):
    # Ellipses overlapping at random: crossings, curves meeting where a noisy one ends, chords
    # across sharp tips.
    points = curves(20_000, np.random.default_rng(1))
    tiled = condt.dask.reconstruct(points, client, tiles=9, **params)
    assert tiled.whole is None
    expected = one_machine(points, **params)
    np.testing.assert_array_equal(tiled.edges, expected)
    # The rounds mattered: without those stages the edges differ.
    without = {**params, **{stage: False for stage in stages}}
    assert not np.array_equal(expected, one_machine(points, **without))


def resampled_triangles(rng, count=120):
    """Right triangles with integer legs, each side split at step 1 (a CAD tool's resampling),
    on a grid 60 apart, jittered by 1e-4 so that no four points are cocircular: sharp corners
    whose two or three samples the tips' apex form leaves to the spikes step where it runs."""
    parts = []
    for k in range(count):
        a = int(rng.integers(6, 25))
        b = int(rng.integers(3, a + 1))
        corners = [(0.0, 0.0), (float(a), 0.0), (float(a), float(b))]
        for i in range(3):
            p, q = np.array(corners[i]), np.array(corners[(i + 1) % 3])
            pieces = int(round(np.hypot(*(q - p))))
            t = (np.arange(pieces) / pieces)[:, None]
            parts.append(p + (q - p) * t + ((k % 12) * 60.0, (k // 12) * 60.0))
    points = np.vstack(parts)
    return points + rng.normal(0, 1e-4, points.shape)


@pytest.mark.parametrize("params", [{}, {"spikes": False}], ids=["spikes", "no-spikes"])
def test_the_tips_apex_form_tiled_follows_whether_the_spikes_step_runs(client, params):
    # The diff review of 2026-12-07: with spikes=False the tiles still left these tips to the
    # spikes step (4891 edges tiled, 4905 on one machine).
    points = resampled_triangles(np.random.default_rng(3))
    expected = one_machine(points, **params)
    for tiles in (4, 16):
        tiled = condt.dask.reconstruct(points, client, tiles=tiles, **params)
        assert tiled.whole is None
        np.testing.assert_array_equal(tiled.edges, expected)


def noisy_stars(rng, rows=25, per_side=3, noise=0.02):
    """Four-pointed stars (tips at 1, the corners between them at 0.3, times a size of 1.5 to 3)
    on a grid of ``rows`` by ``rows`` cells 8 apart, each side sampled ``per_side`` times, with
    uniform noise of ``noise`` times the size: thin tips whose samples the earlier stages leave
    without edges, a chord across their base."""
    parts = []
    for cx in range(rows):
        for cy in range(rows):
            size, turn = rng.uniform(1.5, 3.0), rng.uniform(0, np.pi)
            angles = turn + np.pi * np.arange(8) / 4
            radii = np.where(np.arange(8) % 2 == 0, 1.0, 0.3)
            corners = np.column_stack([np.cos(angles), np.sin(angles)]) * (radii * size)[:, None]
            corners += (8.0 * cx, 8.0 * cy)
            t = (np.arange(per_side) / per_side)[:, None]
            sides = [corners[i] + (corners[(i + 1) % 8] - corners[i]) * t for i in range(8)]
            outline = np.concatenate(sides)
            parts.append(outline + rng.uniform(-noise, noise, outline.shape) * size)
    return np.concatenate(parts)


def test_spikes_are_a_tiled_round_with_the_one_machine_edges(client):
    # 625 noisy stars, 15,000 points: the spikes step puts tips back on many of them.
    points = noisy_stars(np.random.default_rng(2))
    tiled = condt.dask.reconstruct(points, client, tiles=9)
    assert tiled.whole is None
    expected = one_machine(points)
    np.testing.assert_array_equal(tiled.edges, expected)
    assert not np.array_equal(expected, one_machine(points, spikes=False))


def stranded_junctions(rng, count=400):
    """``count`` evenly spaced junctions, each of three curves of eight samples leaving the
    junction's sample at 180°, 124° and 231° from a random direction: the first curve's first
    sample lies nearer the other two curves' first samples than the junction's own, so Algorithm 1
    joins it to them and the repair strands it. Returns the points and the junctions' positions."""
    points, junctions = [], []
    for k in range(count):
        centre = np.array([(k % 20) * 25.0, (k // 20) * 25.0]) + rng.uniform(-3, 3, 2)
        turn = rng.uniform(0, 2 * np.pi)
        junctions.append(len(points))
        points.append(centre)
        for angle in (180.0, 180.0 + 55.7, 180.0 - 51.0):
            direction = turn + np.radians(angle)
            step = np.array([np.cos(direction), np.sin(direction)])
            points.extend(centre + j * step for j in range(1, 9))
    return np.array(points), np.array(junctions)


def test_junctions_through_a_stranded_sample_are_a_tiled_round_with_the_one_machine_edges(client):
    points, junctions = stranded_junctions(np.random.default_rng(1))
    # Without the spikes step (eighteen hops) the junctions' sixteen are the widest reach.
    for params in ({}, {"spikes": False}):
        tiled = condt.dask.reconstruct(points, client, tiles=9, **params)
        assert tiled.whole is None
        np.testing.assert_array_equal(tiled.edges, one_machine(points, **params))
    expected = one_machine(points)
    # Every junction keeps its three edges: most through the branch's stranded last sample, the
    # rest where the junction's sample took the place of the chord that ran past it.
    degree = np.bincount(expected.ravel(), minlength=len(points))
    assert (degree[junctions] == 3).all()


def test_clumps_are_a_round_of_tests_and_the_rule_on_the_driver(client):
    # Clean ellipses (one noisy, so that the smoothing passes run) and 40 blobs of 6 to 15 random
    # points apart from them: the blobs are clumps.
    rng = np.random.default_rng(6)
    blobs = [c + rng.normal(0, 0.3, (int(rng.integers(6, 16)), 2)) for c in rng.uniform(0, 100, (40, 2))]
    points = np.concatenate([curves(20_000, rng, outliers=0.0, noisy_every=10**6)] + blobs)
    params = {**LATER, "close_gaps": False, "tips": False}
    tiled = condt.dask.reconstruct(points, client, tiles=9, **params)
    assert tiled.whole is None
    expected = one_machine(points, **params)
    np.testing.assert_array_equal(tiled.edges, expected)
    # The clumps went: without the stage the edges differ.
    assert not np.array_equal(expected, one_machine(points, **{**params, "clumps": False}))


def test_a_clump_that_gap_closing_joins_stays_on_the_driver_too(client):
    # Evenly spaced ellipses under Gaussian noise of 0.3 spacings: noise zig-zags stretches that
    # the earlier stages cut off, which the clump stage keeps where gap closing or the tips would
    # join them to a curve (on this set it keeps such pieces: the one-machine edges differ from
    # those of a build without that exemption). The driver asks the tiles for those joins.
    rng = np.random.default_rng(1)
    parts = []
    while sum(len(p) for p in parts) < 20_000:
        centre, radius, m = rng.uniform(0, 100, 2), rng.uniform(1.0, 4.0), int(rng.integers(100, 300))
        t = np.arange(m) * 2 * np.pi / m
        flat = rng.uniform(0.3, 1)
        ellipse = np.column_stack([centre[0] + radius * np.cos(t), centre[1] + radius * flat * np.sin(t)])
        parts.append(ellipse + rng.normal(0, 0.3 * 2 * np.pi * radius / m, ellipse.shape))
    points = np.concatenate(parts)
    tiled = condt.dask.reconstruct(points, client, tiles=9)
    assert tiled.whole is None
    np.testing.assert_array_equal(tiled.edges, one_machine(points))


def turned_copies(shape, rng, sizes, jitter=0.0):
    """36 copies of the points ``shape`` on a 6 x 6 grid of cells 10 apart, each jittered by
    Gaussian noise of ``jitter`` (if any), turned by a random angle and scaled by a random
    factor in ``sizes``: the points, and each copy's first position."""
    parts, firsts = [], []
    for k in range(36):
        angle, size = rng.uniform(0, 2 * np.pi), rng.uniform(*sizes)
        turn = np.array([[np.cos(angle), np.sin(angle)], [-np.sin(angle), np.cos(angle)]])
        firsts.append(sum(len(p) for p in parts))
        copy = shape + rng.normal(0, jitter, shape.shape) if jitter else shape
        parts.append(copy @ turn * size + [10.0 * (k % 6), 10.0 * (k // 6)])
    return np.concatenate(parts), firsts


@pytest.mark.parametrize(
    "params",
    [
        {"repair": "off", "smooth": False},
        # Alone after the proximity graph: the tiles certify the step's own six hops.
        {"paper": True, "repair": "off", "iqr": None, "detours": True},
    ],
)
def test_detours_are_a_tiled_round_with_the_one_machine_edges(client, params):
    # Circles of 40 unit-spaced samples, each with four outliers 1.2 spacings outside it between
    # two neighbouring samples, jittered, turned and scaled at random. Without the repair,
    # Algorithm 1 joins each outlier to its two samples: an ear the detours step cuts (tile borders
    # cut through many circles).
    rng = np.random.default_rng(5)
    t = 2 * np.pi * np.arange(40) / 40
    radius = 40 / (2 * np.pi)
    circle = np.column_stack([np.cos(t), np.sin(t)]) * radius
    mid = 2 * np.pi * (np.array([3, 13, 23, 33]) + 0.5) / 40
    ears = np.column_stack([np.cos(mid), np.sin(mid)]) * (radius + 1.2)
    points, _ = turned_copies(np.concatenate([circle, ears]), rng, (0.1, 0.12), jitter=0.01)
    tiled = condt.dask.reconstruct(points, client, tiles=9, **params)
    assert tiled.whole is None
    expected = one_machine(points, **params)
    np.testing.assert_array_equal(tiled.edges, expected)
    # The step mattered: every copy had its four ears, and each loses its two edges.
    kept = one_machine(points, **{**params, "detours": False})
    assert len(kept) - len(expected) == 36 * 4 * 2


def test_a_tooth_that_a_junction_joins_stays_on_the_driver_too(client):
    # Combs of evenly spaced samples, each a line with a short tooth between two long ones 1.8
    # spacings away, turned and scaled at random: no sample of a short tooth lies apart, and the
    # local outlier removal keeps it only for the junction its end makes with the line. The
    # tiles send those joins; tile borders cut through many combs. The long teeth are offset by
    # half a spacing: on a grid of whole spacings, turned, distances that tie exactly (two ends
    # side by side at 90°, a sample as near the next tooth's end as the line) are settled by
    # rounding, not by the rule under test.
    rng = np.random.default_rng(3)
    line = [(x, 0) for x in range(31)]
    shape = ((15, 1, 8), (13.2, 1.5, 20), (16.8, 1.5, 20))
    teeth = [[(x, y) for y in np.arange(low, low + length)] for x, low, length in shape]
    comb = np.array(line + [p for tooth in teeth for p in tooth], dtype=float)
    points, firsts = turned_copies(comb, rng, (0.05, 0.2))
    short = [first + 31 for first in firsts]
    expected = one_machine(points)
    # Every short tooth keeps its eight samples and its junction with the line.
    joined = {tuple(e) for e in expected.tolist()}
    assert all((end - 16, end) in joined for end in short)
    assert all((end + k, end + k + 1) in joined for end in short for k in range(7))
    tiled = condt.dask.reconstruct(points, client, tiles=9)
    assert tiled.whole is None
    np.testing.assert_array_equal(tiled.edges, expected)


def test_short_rungs_joined_at_both_ends_are_a_tiled_round_with_the_one_machine_edges(client):
    # Ladders of evenly spaced samples, turned and scaled at random: two lines seven spacings
    # apart and a rung of six samples between them, too short for a branch, joined to both lines
    # where both its ends meet them. Without the spikes step the junctions' sixteen hops are the
    # widest reach. A jitter of a thousandth of a spacing breaks the grid's exact ties and its
    # cocircular points (which send a split run whole to one worker).
    rng = np.random.default_rng(11)
    lines = [(x, y) for y in (0, 7) for x in range(13)]
    ladder = np.array(lines + [(6, y) for y in range(1, 7)], dtype=float)
    points, rungs = turned_copies(ladder, rng, (0.1, 0.5), jitter=1e-3)
    for params in ({}, {"spikes": False}):
        expected = one_machine(points, **params)
        kept = {tuple(e) for e in expected.tolist()}
        joined = sum((f + 6, f + 26) in kept and (f + 19, f + 31) in kept for f in rungs)
        assert joined >= 30, joined  # 35 of 36 at this seed; 1 without the rule
        tiled = condt.dask.reconstruct(points, client, tiles=9, **params)
        assert tiled.whole is None
        np.testing.assert_array_equal(tiled.edges, expected)


def test_a_convex_pupil_stays_on_the_driver_too(client):
    # Eyes sampled about one spacing apart: a pupil of eight samples, three pushed out to corners
    # of 100 degrees, in an iris 1.2 spacings away. Under three quarters of the pupil passes
    # smoothly, but it turns one way at every sample: rule 4 keeps it, reading each sample's turn
    # from the tile that owns it, whichever way the driver walks the cycle.
    rng = np.random.default_rng(5)
    t = 2 * np.pi * np.arange(8) / 8
    radii = np.array([1.95, 1.5, 1.5, 1.95, 1.5, 1.95, 1.5, 1.5])
    pupil = np.column_stack([radii * np.cos(t), radii * np.sin(t)])

    def circle(r, m):
        a = 2 * np.pi * np.arange(m) / m
        return np.column_stack([r * np.cos(a), r * np.sin(a)])

    eye = np.concatenate([circle(10.0, 50), circle(3.4, 18), pupil])
    points, firsts = turned_copies(eye, rng, (0.2, 0.4))
    pupils = [first + 68 for first in firsts]
    expected = one_machine(points)
    kept = {tuple(e) for e in expected.tolist()}
    assert all((p + k, p + k + 1) in kept for p in pupils for k in range(7))
    tiled = condt.dask.reconstruct(points, client, tiles=9)
    assert tiled.whole is None
    np.testing.assert_array_equal(tiled.edges, expected)


def last_edges_given_back_on_the_driver(client, seed, t):
    """Clean ellipses, and beside them 30 sparse open arcs sampled at the angles ``t``: the
    tiled run equals one machine's, and one machine gives every arc's last edge back."""
    rng = np.random.default_rng(seed)
    dense = curves(20_000, rng, outliers=0.0, noisy_every=10**6)
    arcs = [
        np.column_stack([105.0 + 10 * (k % 3) + 3 * np.cos(t), 5.0 + 10 * (k // 3) + 3 * np.sin(t)])
        for k in range(30)
    ]
    points = np.concatenate([dense] + arcs)
    tiled = condt.dask.reconstruct(points, client, tiles=9)
    assert tiled.whole is None
    expected = one_machine(points)
    np.testing.assert_array_equal(tiled.edges, expected)
    first, size = len(dense), len(t)
    last = [[first + size * k + size - 2, first + size * k + size - 1] for k in range(30)]
    assert all(edge in expected.tolist() for edge in last)


def test_a_curves_last_edge_is_given_back_on_the_driver(client):
    # The arcs' last sample lies 1.4 spacings beyond the one before: the IQR stage cuts the
    # arcs, rule 1 gives their passages back on the tiles and, where a curve stands behind,
    # their last edges on the driver.
    t = 0.5 / 3.0 * np.concatenate([np.arange(12), [12.4]])
    last_edges_given_back_on_the_driver(client, 8, t)


def test_a_last_edge_that_grows_as_its_curve_does_is_given_back_on_the_driver_too(client):
    # The arcs' spacing grows toward the end (a density change): the last two steps 1.7 times
    # the one before each, so the last edge is over 1.5 times the edge before it but grows as
    # that edge did.
    steps = np.concatenate([[0.0], np.full(8, 0.5), [0.85, 1.445]])
    last_edges_given_back_on_the_driver(client, 9, np.cumsum(steps) / 3.0)


def test_a_failure_on_a_worker_that_is_no_exception_reaches_the_driver_as_one(client):
    # A Rust panic reaches Python as a BaseException, which Dask does not report (the call
    # waited forever): the worker's calls raise it as a RuntimeError.
    class Panic(BaseException):
        pass

    def panics():
        raise Panic("index out of bounds")

    future = client.submit(condt.dask._on_worker, panics, pure=False)
    with pytest.raises(RuntimeError, match="condt failed on a worker: index out of bounds"):
        future.result(timeout=60)


def test_edges_are_split_among_the_tiles_holding_both_ends():
    from condt import _condt

    rng = np.random.default_rng(3)
    n = 500
    tiles = [np.flatnonzero(rng.random(n) < share) for share in (0.1, 0.5, 0.9, 0.0)]
    pairs = rng.integers(0, n, (2_000, 2))
    edges = np.sort(pairs[pairs[:, 0] != pairs[:, 1]], axis=1)
    split = _condt._split_edges(_condt._tile_index(n, tiles), edges)
    for positions, local in zip(tiles, split):
        # Each tile's rows, by hand: both ends among its points, in its own positions.
        place = np.full(n, -1)
        place[positions] = np.arange(len(positions))
        a, b = place[edges[:, 0]], place[edges[:, 1]]
        both = (a >= 0) & (b >= 0)
        np.testing.assert_array_equal(local, np.column_stack((a[both], b[both])))
    with pytest.raises(ValueError, match="not among the points"):
        _condt._tile_index(n, [np.array([n])])
    with pytest.raises(ValueError, match="not among the points"):
        _condt._split_edges(_condt._tile_index(n, tiles), np.array([[0, n]]))


def test_a_baseline_is_refused_by_name(client):
    points = curves(1_000, np.random.default_rng(1))
    with pytest.raises(NotImplementedError, match=r"not the baseline NN-Crust"):
        condt.dask.reconstruct(points, client, method="nn-crust")


def test_bad_input_is_refused_as_condt_reconstruct_refuses_it(client):
    points = curves(1_000, np.random.default_rng(1))
    points[5] = [np.nan, 1.0]
    with pytest.raises(ValueError, match="point 5 has a NaN"):
        condt.dask.reconstruct(points, client, paper=True)
    with pytest.raises(ValueError, match="iqr"):
        condt.dask.reconstruct(points[:4], client, paper=True, iqr=-1.0)
    for tiles in (0, -3, np.int64(0)):
        with pytest.raises(ValueError, match="tiles must be a positive integer"):
            condt.dask.reconstruct(points[:4], client, tiles=tiles, paper=True)


def test_a_masked_array_with_masked_entries_is_refused_as_condt_reconstruct_refuses_it(client):
    points = np.ma.masked_array(curves(400, np.random.default_rng(3)))
    points[7] = np.ma.masked
    with pytest.raises(ValueError) as one_machine_error:
        condt.reconstruct(points, paper=True)
    with pytest.raises(ValueError) as tiled_error:
        condt.dask.reconstruct(points, client, tiles=4, paper=True)
    assert str(tiled_error.value) == str(one_machine_error.value)
    assert "masked entries" in str(tiled_error.value)
    # Nothing masked: read as its data, as condt.reconstruct reads it.
    points[7] = points.data[7]
    tiled = condt.dask.reconstruct(points, client, tiles=4, paper=True)
    np.testing.assert_array_equal(tiled.edges, one_machine(points.data, paper=True))


def test_none_among_the_points_is_a_type_error(client):
    with pytest.raises(TypeError, match="not NoneType"):
        condt.dask.reconstruct([[0, None], [1, 1], [2, 3]], client, tiles=4)


def test_more_tiles_than_points_are_one_tile_per_point(client):
    points = curves(300, np.random.default_rng(4))
    points = points[:60]
    expected = one_machine(points, paper=True)
    # 2**63 tiles asked 16 GiB of cuts of numpy, 10**7 a minute of cutting: now one per point.
    for tiles in (len(points) + 1, 10**7, 2**63):
        tiled = condt.dask.reconstruct(points, client, tiles=tiles, paper=True)
        assert tiled.whole is None and tiled.tiles == len(points), tiles
        np.testing.assert_array_equal(tiled.edges, expected)
    # Each tile owns one point (the cuts once rounded down, leaving every other tile empty).
    bbox = np.concatenate([points.min(axis=0), points.max(axis=0)])
    rects = condt.dask._cut(points, len(points), bbox)
    owned = [int(condt.dask._inside(points, rect, False).sum()) for rect in rects]
    assert owned == [1] * len(points)


def test_tiles_and_halo_are_read_as_condt_reconstruct_reads_its_keywords(client):
    points = curves(1_000, np.random.default_rng(1))
    expected = one_machine(points, paper=True)
    # numpy's integers and floats are numbers too.
    for tiles, halo in [(np.int64(4), np.float32(0.5)), (np.uint8(4), np.int64(1)), (4, 0.5)]:
        tiled = condt.dask.reconstruct(points, client, tiles=tiles, halo=halo, paper=True)
        assert tiled.tiles == 4 and type(tiled.tiles) is int
        np.testing.assert_array_equal(tiled.edges, expected)
    # A wrong type is a TypeError, a wrong value a ValueError (as for u=True, u=-1).
    for tiles in ("4", 2.5, np.float64(4.0), True, np.True_, None):
        with pytest.raises(TypeError, match=f"^tiles must be an integer, not {type(tiles).__name__}$"):
            condt.dask.reconstruct(points, client, tiles=tiles, paper=True)
    for halo in ("1", True, np.True_, [1.0], 1j):
        with pytest.raises(TypeError, match=f"^halo must be a number or None, not {type(halo).__name__}$"):
            condt.dask.reconstruct(points, client, tiles=4, halo=halo, paper=True)
    for halo in (0, -1.0, np.float32(0.0), float("nan"), float("inf"), 2**2000, -(2**2000)):
        with pytest.raises(ValueError, match="^halo must be a positive finite number or None"):
            condt.dask.reconstruct(points, client, tiles=4, halo=halo, paper=True)
    with pytest.raises(TypeError, match="u must be a number, not bool"):
        condt.reconstruct(points, u=True)


def test_the_edges_are_read_only_as_condt_reconstructs_are(client):
    points = curves(1_000, np.random.default_rng(1))
    line = np.column_stack([np.arange(50.0), np.zeros(50)])
    for tiled in (
        condt.dask.reconstruct(points, client, tiles=4),
        condt.dask.reconstruct(line, client, tiles=4),  # in one piece
    ):
        assert not tiled.edges.flags.writeable
        with pytest.raises(ValueError, match="read-only"):
            tiled.edges[0, 0] = 5
        assert tiled.edges.copy().flags.writeable


def test_mypy_finds_no_error_in_the_package(tmp_path):
    pytest.importorskip("mypy")
    import pathlib
    import subprocess
    import sys

    package = pathlib.Path(__file__).resolve().parents[1] / "python" / "condt"
    done = subprocess.run(
        [sys.executable, "-m", "mypy", "--cache-dir", str(tmp_path), str(package)],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        check=False,
    )
    assert done.returncode == 0, done.stdout + done.stderr


def test_the_modules_examples_run():
    import doctest

    flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
    results = doctest.testmod(condt.dask, optionflags=flags)
    assert results.failed == 0
    assert results.attempted >= 4, results


def test_tiled_results_compare_and_hash_by_identity(client):
    # A dataclass's generated == compared the edge arrays and raised ("truth value of an
    # array is ambiguous"), and its hash raised on the array: identity, as other results.
    points = curves(400, np.random.default_rng(4))
    a = condt.dask.reconstruct(points, client, tiles=2)
    b = condt.dask.reconstruct(points, client, tiles=2)
    assert a == a and a != b and a in [a] and b not in [a]
    assert len({a, b, a}) == 2
    np.testing.assert_array_equal(a.edges, b.edges)


def test_a_closed_client_is_said_before_any_work():
    # A user review: a tiled set met the closed client as an AttributeError inside a scatter,
    # a collinear one (run in one piece) as Dask's own error.
    from distributed import Client, LocalCluster
    from distributed.client import ClosedClientError

    rng = np.random.default_rng(0)
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None) as cluster:
        closed = Client(cluster)
        closed.close()
        for points in (rng.uniform(0, 1, (500, 2)), np.c_[np.arange(10.0), np.arange(10.0)]):
            with pytest.raises(ClosedClientError, match="client given to condt.dask.reconstruct is closed"):
                condt.dask.reconstruct(points, closed, tiles=4)


def test_workers_of_another_version_are_refused_before_any_work(client, monkeypatch):
    # Workers importing another release would run other rules than the driver's: the result
    # would not be one machine's, and nothing said so.
    calls = []
    monkeypatch.setattr(condt.dask, "_worker_version", lambda: "0.0.0")
    monkeypatch.setattr(condt.dask, "_tile", lambda *args: calls.append(args))
    rng = np.random.default_rng(1)
    for points in (rng.uniform(0, 1, (500, 2)), np.c_[np.arange(10.0), np.arange(10.0)]):
        with pytest.raises(RuntimeError, match=r"must run the driver's condt .*: .* has 0\.0\.0"):
            condt.dask.reconstruct(points, client, tiles=4)
    assert calls == []


def test_the_module_examples_run():
    import doctest

    results = doctest.testmod(condt.dask, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert results.attempted > 0 and results.failed == 0, results


def test_a_client_of_the_wrong_type_is_said_at_once():
    # A user review: an address given as the client failed as an AttributeError in a scatter.
    points = np.random.default_rng(0).uniform(0, 1, (500, 2))
    for wrong in ("tcp://127.0.0.1:8786", 42):
        with pytest.raises(TypeError, match="client must be a dask.distributed.Client"):
            condt.dask.reconstruct(points, wrong, tiles=4)


def test_the_arguments_are_checked_before_the_client_is_looked_for(monkeypatch):
    # A review's find: with no client, a baseline, u=-1 or an unknown keyword met Dask's "No
    # global client found", not the error the docstring promises. No cluster: Dask's own lookup
    # is replaced by one that finds none (the module's fixture may hold a current client).
    def no_client(*args, **kwargs):
        raise ValueError("No global client found and no address provided")

    monkeypatch.setattr(distributed, "get_client", no_client)
    points = np.random.default_rng(0).uniform(0, 1, (50, 2))
    for method in ("crust", "nn-crust"):
        with pytest.raises(NotImplementedError, match="baseline"):
            condt.dask.reconstruct(points, method=method)
    with pytest.raises(ValueError, match="^u: parameter u = -1 is not accepted"):
        condt.dask.reconstruct(points, u=-1)
    with pytest.raises(TypeError, match="unexpected keyword argument 'bogus'"):
        condt.dask.reconstruct(points, bogus=1)
    # Points on the driver too: a NaN is named (it met the missing client first).
    bad = points.copy()
    bad[7, 1] = np.nan
    with pytest.raises(ValueError, match="point 7"):
        condt.dask.reconstruct(bad)
    # Arguments that are fine: the missing client is said.
    with pytest.raises(ValueError, match="No global client found"):
        condt.dask.reconstruct(points, paper=True)
