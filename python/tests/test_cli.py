"""The package gives exactly what the `condt` command line gives: on the shipped data, on every
input format, and (hypothesis) on any point set, with the default, the paper's and other
parameters; and the edge set does not depend on the order of the input."""

import json
import re

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import condt
from conftest import DATA, ROOT, shipped_point_files

# Parameters and the command line's options that ask for the same.
OPTIONS = [
    ({}, []),
    ({"paper": True}, ["--paper"]),
    ({"u": 2.0, "iqr": None}, ["--u", "2", "--no-outlier-filter"]),
    ({"adaptive": True, "repair": "mutual"}, ["--adaptive", "--repair", "mutual"]),
    (
        {"paper": True, "close_gaps": True, "outliers_first": True, "smooth": True},
        ["--paper", "--close-gaps", "--outliers-first", "--smooth"],
    ),
    (
        {"local_outliers": False, "manifold_fix": False, "sequential": True},
        ["--no-local-outliers", "--no-manifold-fix", "--sequential"],
    ),
    ({"confirm_given_back": False, "iqr": 1.2}, ["--no-confirm-given-back", "--iqr", "1.2"]),
    ({"iqr_floor": False}, ["--no-iqr-floor"]),
    ({"paper": True, "iqr_floor": True}, ["--paper", "--iqr-floor"]),
    ({"method": "nn-crust"}, ["--method", "nn-crust"]),
    ({"method": "crust"}, ["--method", "crust"]),
]

# Every shipped point file the command line reads (the malformed one is for the errors).
SHIPPED = [p for p in shipped_point_files()] + sorted(
    p
    for p in (ROOT / "crates" / "condt-cli" / "tests" / "data").iterdir()
    if not p.name.startswith("malformed")
)


def curves_text(result):
    """The curves as `condt reconstruct --format txt` writes them."""
    return "".join(
        ("closed" if c.closed else "open") + "".join(f" {i}" for i in c.points) + "\n"
        for c in result.curves
    )


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.name)
@pytest.mark.parametrize("params,options", OPTIONS, ids=lambda o: str(o))
def test_reconstruct_on_the_shipped_data_is_the_command_lines(cli, path, params, options):
    points = condt.read_points(path)
    result = condt.reconstruct(points, **params)
    out = cli.tmp / "shipped.npy"
    cli.run("reconstruct", path, "-o", out, "-q", *options)
    assert np.array_equal(result.edges, np.load(out).astype(np.int64).reshape(-1, 2))
    assert curves_text(result) == cli.reconstruct_text(points, "txt", *options)
    if params == {}:
        geojson = cli.tmp / "shipped.geojson"
        cli.run("reconstruct", path, "-o", geojson, "-q")
        assert result.to_geojson() == geojson.read_text()


def test_snap_is_the_command_lines(cli):
    from test_api import squares_exported_ring_by_ring

    points = squares_exported_ring_by_ring()
    result = condt.reconstruct(condt.snap(points, 1e-6))
    assert len(result.curves) == 3
    assert curves_text(result) == cli.reconstruct_text(points, "txt", "--snap", "1e-6")


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.name)
def test_triangulate_on_the_shipped_data_is_the_command_lines(cli, path):
    tri = condt.triangulate(condt.read_points(path))
    triangles, edges = cli.tmp / "t.npy", cli.tmp / "e.npy"
    cli.run("triangulate", path, "-o", triangles, "-q")
    cli.run("triangulate", path, "--edges", "-o", edges, "-q")
    # The same triangles in the same order, each with the same first corner.
    assert np.array_equal(tri.triangles, np.load(triangles).astype(np.int64).reshape(-1, 3))
    assert np.array_equal(tri.edges, np.load(edges).astype(np.int64).reshape(-1, 2))


def test_the_shipped_shapes_reconstruct_as_the_readme_says():
    result = condt.reconstruct(condt.read_points(DATA / "shapes.txt"))
    closed = sorted(c.closed for c in result.curves)
    assert len(result) == 235 and len(result.unused) > 0
    assert closed.count(True) >= 2 and closed.count(False) >= 1


def test_every_input_format_reads_the_points_the_text_gives(tmp_path):
    points = condt.read_points(DATA / "shapes.txt")
    np.save(tmp_path / "p.npy", points)
    with open(tmp_path / "f.NPY", "wb") as f:  # big-endian, Fortran order, any case
        np.save(f, np.asfortranarray(points.astype(">f8")))
    with open(tmp_path / "p.csv", "w") as f:  # lon and lat, in any position
        f.write("id,lat,name,lon\n")
        f.writelines(f'{k},{y!r},"p, {k}",{x!r}\n' for k, (x, y) in enumerate(points.tolist()))
    with open(tmp_path / "p.geojson", "w") as f:
        features = [
            {"type": "Feature", "geometry": {"type": "Point", "coordinates": [x, y]}}
            for x, y in points.tolist()
        ]
        json.dump({"type": "FeatureCollection", "features": features}, f)
    with open(tmp_path / "p.node", "w") as f:
        f.write(f"{len(points)} 2 0 0\n")
        f.writelines(f"{k + 1} {x!r} {y!r}\n" for k, (x, y) in enumerate(points.tolist()))
    for name in ["p.npy", "f.NPY", "p.csv", "p.geojson", "p.node"]:
        assert np.array_equal(condt.read_points(tmp_path / name), points), name
    assert condt.read_points(str(tmp_path / "p.npy")).dtype == np.float64


def test_score_is_the_command_lines(cli):
    points = condt.read_points(DATA / "shapes.txt")
    output = condt.reconstruct(points).edges
    for truth in [condt.reconstruct(points, paper=True).edges, output, output[::2]]:
        out, gt = cli.tmp / "out.edges", cli.tmp / "gt.edges"
        np.savetxt(out, output, fmt="%d")
        np.savetxt(gt, truth, fmt="%d")
        printed = cli.run("score", DATA / "shapes.txt", out, gt, "--json").stdout
        assert condt.score(points, output, truth) == json.loads(printed)


def test_a_malformed_output_scores_as_on_the_command_line(cli):
    # The same rows, given to Python or saved as .npy for the command line: the same metrics,
    # the same count of output edges and the same first problem (a negative point number is a
    # point that does not exist, in both).
    square = np.array([(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)])
    np.savetxt(cli.tmp / "sq.txt", square)
    truth = np.array([(0, 1), (1, 2), (2, 3), (0, 3)])
    np.save(cli.tmp / "gt.npy", truth)
    for output in [
        [(0, 1), (0, -1)],
        [(0, -1)],
        [(0, 1), (1, 2), (1, 2)],
        [(0, 1), (3, 3), (2, 9)],
        [(-5, 7), (0, 1)],
        # Two ends out of range: both name the first.
        [(7, 9)],
        [(-1, -5)],
        [(9, -1)],
        [(0, 1), (1, 2), (2, 3), (3, 0)],
    ]:
        output = np.array(output, dtype=np.int64)
        np.save(cli.tmp / "out.npy", output)
        printed = cli.run("score", cli.tmp / "sq.txt", cli.tmp / "out.npy", cli.tmp / "gt.npy",
                          "--json").stdout
        assert condt.score(square, output, truth) == json.loads(printed), output.tolist()


# Points drawn on a small grid (duplicates, collinear and cocircular sets) or anywhere.
coordinate = st.one_of(
    st.integers(-4, 4).map(float),
    st.floats(-1e3, 1e3, allow_nan=False, allow_infinity=False, width=64),
)
point_sets = st.lists(st.tuples(coordinate, coordinate), min_size=0, max_size=60)
# Near-curve samples: points on a few circles and segments, with noise and a few outliers.
@st.composite
def curve_samples(draw):
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    parts = []
    for _ in range(draw(st.integers(1, 3))):
        n = draw(st.integers(8, 60))
        t = np.sort(rng.uniform(0, 2 * np.pi, n))
        c, r = rng.uniform(-5, 5, 2), rng.uniform(0.5, 3)
        parts.append(np.column_stack([c[0] + r * np.cos(t), c[1] + r * np.sin(t)]))
    noise = draw(st.sampled_from([0.0, 0.01, 0.05]))
    points = np.concatenate(parts)
    points = points + rng.normal(0, noise, points.shape)
    outliers = rng.uniform(-8, 8, (draw(st.integers(0, 6)), 2))
    return np.concatenate([points, outliers])


SETTINGS = settings(
    max_examples=50,
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)


@SETTINGS
@given(points=st.one_of(point_sets, curve_samples()), which=st.sampled_from(range(len(OPTIONS))))
def test_any_points_reconstruct_and_triangulate_as_on_the_command_line(cli, points, which):
    params, options = OPTIONS[which]
    points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    try:
        result = condt.reconstruct(points, **params)
    except ValueError as refused:
        # Two points nearer than the stages measure beside the largest coordinate (a subnormal
        # next to 1e3): the command line refuses the same two.
        assert "closer than 2^-450 times the largest coordinate" in str(refused)
        with pytest.raises(AssertionError, match=re.escape(str(refused))):
            cli.reconstruct_edges(points, *options)
    else:
        assert np.array_equal(result.edges, cli.reconstruct_edges(points, *options))
    tri = condt.triangulate(points)
    assert np.array_equal(tri.triangles, cli.triangles(points))
    assert np.array_equal(tri.edges, cli.triangulation_edges(points))


def representatives(points):
    """For each point, the first input position holding the same coordinates: the one the
    library reports a group of exact duplicates under."""
    _, first, inverse = np.unique(points + 0.0, axis=0, return_index=True, return_inverse=True)
    return first[inverse.reshape(-1)]


def mapped_back(edges, order, rep):
    """The edges of the shuffled input (`points[order]`) as edges of the original, each end
    named by its group's representative: a set of pairs."""
    return {tuple(sorted((rep[order[a]], rep[order[b]]))) for a, b in edges.tolist()}


@SETTINGS
@given(points=st.one_of(point_sets, curve_samples()), seed=st.integers(0, 2**32 - 1))
def test_the_edge_set_does_not_depend_on_the_input_order(points, seed):
    points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    order = np.random.default_rng(seed).permutation(len(points))
    rep = representatives(points) if len(points) else np.zeros(0, dtype=np.int64)
    for params in [{}, {"paper": True}, {"method": "crust"}]:
        try:
            edges = condt.reconstruct(points, **params).edges
        except ValueError as refused:
            # Too close to measure: refused in every order too (which two it names depends on
            # the order when more than two points are too close).
            assert "closer than 2^-450" in str(refused)
            with pytest.raises(ValueError, match="closer than 2\\^-450"):
                condt.reconstruct(points[order], **params)
            continue
        shuffled = condt.reconstruct(points[order], **params).edges
        assert mapped_back(shuffled, order, rep) == {tuple(e) for e in edges.tolist()}, params
    edges = condt.triangulate(points).edges
    shuffled = condt.triangulate(points[order]).edges
    assert mapped_back(shuffled, order, rep) == {tuple(e) for e in edges.tolist()}
