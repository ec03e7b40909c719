"""The Python interface: inputs it takes, errors it raises, what the result classes hold, the
GIL released, the input read without a copy, and the stubs matching the module."""

import ast
import inspect
import json
import pathlib
import sys
import threading
import time

import numpy as np
import pytest

import condt
from conftest import DATA

SHAPES = DATA / "shapes.txt"


def circle(n=40, r=1.0):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return np.column_stack([r * np.cos(t), r * np.sin(t)])


# --- inputs ------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "convert",
    [
        lambda p: p,
        lambda p: p.tolist(),
        lambda p: [tuple(r) for r in p.tolist()],
        lambda p: np.asfortranarray(p),
        lambda p: p.astype(">f8"),
        lambda p: np.column_stack([p, p[:, :1]])[:, :2],  # a strided view
        lambda p: p[::-1][::-1],
    ],
)
def test_any_array_like_gives_the_same_result(convert):
    points = condt.read_points(SHAPES)
    expected = condt.reconstruct(points).edges
    assert np.array_equal(condt.reconstruct(convert(points)).edges, expected)
    assert np.array_equal(
        condt.triangulate(convert(points)).triangles, condt.triangulate(points).triangles
    )


def test_a_memory_mapped_read_only_array_is_read_in_place(tmp_path):
    points = condt.read_points(SHAPES)
    np.save(tmp_path / "p.npy", points)
    mapped = np.load(tmp_path / "p.npy", mmap_mode="r")
    assert not mapped.flags.writeable
    assert np.array_equal(condt.reconstruct(mapped).edges, condt.reconstruct(points).edges)
    assert np.array_equal(condt.triangulate(mapped).edges, condt.triangulate(points).edges)


def test_integer_and_empty_inputs():
    square = np.array([[0, 0], [2, 0], [2, 2], [0, 2]], dtype=np.int32)
    assert condt.reconstruct(square).edges.tolist() == [[0, 1], [0, 3], [1, 2], [2, 3]]
    for empty in ([], np.zeros((0, 2)), ()):
        r = condt.reconstruct(empty)
        assert r.edges.shape == (0, 2) and r.curves == [] and len(r) == 0
        t = condt.triangulate(empty)
        assert t.triangles.shape == (0, 3) and t.edges.shape == (0, 2)
    one = condt.reconstruct([(1.0, 2.0)])
    assert one.unused.tolist() == [0]


def test_a_float64_c_array_is_read_where_it_lies():
    points = circle()
    result = condt.reconstruct(points)
    # The result reads its coordinates from the caller's array (no copy was made): a change
    # made afterwards shows in them.
    points[0] = (7.0, 8.0)
    curve = result.curves[0]
    assert curve.coords[list(curve.points).index(0)].tolist() == [7.0, 8.0]
    # A list is converted: the result holds its own array.
    listed = circle().tolist()
    result = condt.reconstruct(listed)
    listed[0] = [7.0, 8.0]
    assert result.curves[0].coords[0].tolist() == [1.0, 0.0]


def test_the_gil_is_released_while_the_work_runs():
    rng = np.random.default_rng(1)
    points = rng.uniform(0, 1, (300_000, 2))
    done = threading.Event()
    ticks = 0

    def work():
        condt.reconstruct(points)
        condt.triangulate(points)
        done.set()

    worker = threading.Thread(target=work)
    worker.start()
    # While the worker is inside Rust, this thread keeps running Python code: with the GIL held
    # for the whole call it could not run at all until the call returned.
    while not done.is_set():
        ticks += 1
        time.sleep(0)
    worker.join()
    assert ticks > 100, ticks


# --- errors ------------------------------------------------------------------------------------


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
@pytest.mark.parametrize("function", [condt.reconstruct, condt.triangulate])
def test_a_non_finite_point_is_a_value_error_naming_it(function, bad):
    points = circle(10)
    points[6, 1] = bad
    with pytest.raises(ValueError) as err:
        function(points)
    message = str(err.value)
    assert message.startswith("point 6 has a NaN or infinite coordinate")
    assert "row 6" in message and repr(float(bad)) in message
    with pytest.raises(ValueError, match="^point 2 "):
        condt.score([(0, 0), (1, 0), (np.nan, 0)], [], [])


@pytest.mark.parametrize(
    "shape", [(3,), (4, 3), (2, 2, 2), (5, 1)], ids=lambda s: "x".join(map(str, s))
)
def test_a_wrong_shape_is_a_value_error(shape):
    with pytest.raises(ValueError, match=r"shape \(n, 2\)"):
        condt.reconstruct(np.zeros(shape))
    with pytest.raises(ValueError, match=r"shape \(n, 2\)"):
        condt.triangulate(np.zeros(shape))


@pytest.mark.parametrize("points", [None, 3.0, np.float64(2)], ids=["None", "float", "numpy"])
def test_none_or_a_scalar_is_a_type_error(points):
    name = type(points).__name__
    with pytest.raises(TypeError, match=f"array-like of shape \\(n, 2\\), not {name}"):
        condt.reconstruct(points)
    with pytest.raises(TypeError):
        condt.triangulate(points)


def test_a_masked_array_with_masked_rows_is_refused_and_one_without_is_read():
    points = np.ma.masked_array([[0.0, 0.0], [1.0, 0.0], [0.5, 1.0], [9.0, 9.0]])
    assert condt.reconstruct(points).edges.tolist() == condt.reconstruct(points.data).edges.tolist()
    points[3] = np.ma.masked
    with pytest.raises(ValueError, match="masked entries"):
        condt.reconstruct(points)
    rows = np.ma.compress_rows(points)
    assert condt.reconstruct(rows).edges.tolist() == [[0, 1], [0, 2], [1, 2]]


def test_what_numpy_cannot_convert_is_its_error():
    with pytest.raises(ValueError):
        condt.reconstruct([("a", "b")])
    with pytest.raises((ValueError, TypeError)):
        condt.reconstruct([(0, 0), (1,)])
    with pytest.raises(TypeError):
        condt.reconstruct([(0, 0), (1, 1j)])


@pytest.mark.parametrize(
    "params,error,words",
    [
        ({"u": -1}, ValueError, "u: parameter u = -1 is not accepted"),
        ({"u": 0}, ValueError, "u = 0"),
        ({"u": float("nan")}, ValueError, "u = NaN"),
        ({"u": float("inf")}, ValueError, "u = inf"),
        ({"iqr": -0.5}, ValueError, "iqr: parameter k = -0.5"),
        ({"iqr": float("nan")}, ValueError, "iqr"),
        ({"u": 2, "adaptive": True}, ValueError, "contradict"),
        ({"iqr": 2, "outlier_filter": False}, ValueError, "contradict"),
        ({"repair": "mutual", "manifold_fix": False}, ValueError, "contradict"),
        ({"repair": "sometimes"}, ValueError, "'needs', 'paper', 'mutual', 'crossing', 'off'"),
        ({"method": "delaunay"}, ValueError, "'condt', 'nn-crust', 'crust'"),
        ({"method": "crust", "u": 2}, ValueError, "baseline"),
        ({"method": "nn-crust", "paper": True}, ValueError, "paper=True sets a ConDT stage"),
        ({"method": "crust", "smooth": False}, ValueError, "baseline"),
        ({"u": "2"}, TypeError, "u must be a number, not str"),
        ({"u": True}, TypeError, "u must be a number, not bool"),
        ({"smooth": 1}, TypeError, "smooth must be True or False, not int"),
        ({"close_gaps": None}, TypeError, "close_gaps must be True or False"),
        ({"repair": 3}, TypeError, "repair must be a str"),
        ({"no_smooth": True}, TypeError, "unexpected keyword argument 'no_smooth'"),
        ({"parallel": False}, TypeError, "unexpected keyword argument 'parallel'"),
    ],
)
def test_parameters_are_checked_as_on_the_command_line(params, error, words):
    with pytest.raises(error) as err:
        condt.reconstruct(circle(), **params)
    assert words in str(err.value)


def test_accepted_parameters_change_what_runs():
    points = condt.read_points(SHAPES)
    paper = condt.reconstruct(points, paper=True)
    assert list(paper.stages) == ["proximity", "repair", "iqr-outliers"]
    assert list(condt.reconstruct(points, iqr=None, paper=True).stages) == ["proximity", "repair"]
    assert list(condt.reconstruct(points, outlier_filter=False, manifold_fix=False, paper=True).stages) == ["proximity"]
    assert list(condt.reconstruct(points, method="crust").stages) == ["crust"]
    numpy_values = condt.reconstruct(points, u=np.float64(2.75), smooth=np.bool_(True))
    assert np.array_equal(numpy_values.edges, condt.reconstruct(points).edges)
    assert np.array_equal(
        condt.reconstruct(points, u=np.int64(3)).edges, condt.reconstruct(points, u=3.0).edges
    )
    assert np.array_equal(
        condt.reconstruct(points, adaptive=False, outlier_filter=True, manifold_fix=True).edges,
        condt.reconstruct(points).edges,
    )


def test_file_errors_are_os_errors_and_bad_content_value_errors(tmp_path):
    with pytest.raises(FileNotFoundError) as err:
        condt.read_points(tmp_path / "missing.txt")
    assert err.value.filename == str(tmp_path / "missing.txt")
    assert "os error" not in str(err.value)
    with pytest.raises(IsADirectoryError):
        condt.read_points(tmp_path)
    malformed = DATA.parent / "crates" / "condt-cli" / "tests" / "data" / "malformed_line3.txt"
    with pytest.raises(ValueError, match=r"malformed_line3.txt:3: "):
        condt.read_points(malformed)
    (tmp_path / "bad.npy").write_bytes(b"\x93NUMPY nonsense")
    with pytest.raises(ValueError, match="bad.npy"):
        condt.read_points(tmp_path / "bad.npy")


def test_score_checks_its_edges():
    square = [(0, 0), (1, 0), (1, 1), (0, 1)]
    truth = [(0, 1), (1, 2), (2, 3), (3, 0)]
    s = condt.score(square, truth, truth)
    assert s["exact"] and s["f1"] == 1.0 and s["max_dist"] == 0.0 and s["malformed"] is None
    bad = condt.score(square, [(0, 1), (1, -1), (2, 2)], truth)
    assert bad["malformed"] == "edge 1: point -1 does not exist"
    assert (bad["f1"], bad["exact"], bad["n_out"]) == (0.0, False, 3)
    assert condt.score(square, [(0, 1), (1, 9)], truth)["malformed"] == "edge 1: point 9 does not exist"
    assert condt.score(square, [(2, 2)], truth)["malformed"] == "edge 0: self-loop at point 2"
    assert condt.score(square, [], truth)["max_dist"] is None
    assert condt.score(square, [(0, 1)], [])["max_dist"] is None  # infinite: null in JSON
    with pytest.raises(ValueError, match="ground truth: edge 1: point 7 does not exist"):
        condt.score(square, [], [(0, 1), (7, 1)])
    with pytest.raises(ValueError, match="ground truth: edge 0: point -2 does not exist"):
        condt.score(square, [], [(-2, 1)])
    with pytest.raises(TypeError, match="integers"):
        condt.score(square, [(0.5, 1)], truth)
    with pytest.raises(ValueError, match=r"shape \(m, 2\)"):
        condt.score(square, [(0, 1, 2)], truth)


# --- results -----------------------------------------------------------------------------------


def test_the_result_arrays():
    points = condt.read_points(SHAPES)
    r = condt.reconstruct(points)
    assert r.edges.dtype == np.int64 and r.edges.shape[1] == 2
    assert np.all(r.edges[:, 0] < r.edges[:, 1])
    assert [tuple(e) for e in r.edges.tolist()] == sorted(tuple(e) for e in r.edges.tolist())
    assert r.edges is not None and not r.edges.flags.writeable
    with pytest.raises(ValueError):
        r.edges[0, 0] = 5
    assert r.edges.copy().flags.writeable
    # Every edge lies on exactly one curve, and the unused points on none.
    on_curves = sorted(
        tuple(sorted(pair))
        for c in r.curves
        for pair in zip(c.points, np.roll(c.points, -1) if c.closed else c.points[1:])
    )
    assert on_curves == [tuple(e) for e in r.edges.tolist()]
    # A point is unused when it has no edge; an exact duplicate shares its point's edges.
    first = {}
    for i, p in enumerate(map(tuple, points.tolist())):
        first.setdefault(p, i)
    used = set(r.edges.ravel().tolist())
    representative = [first[tuple(p)] for p in points.tolist()]
    assert set(r.unused.tolist()) == {i for i in range(len(points)) if representative[i] not in used}
    for c in r.curves:
        assert c.coords.shape == (len(c), 2)
        assert np.array_equal(c.coords, points[c.points])
        assert repr(c).startswith("<condt.Curve: ")
    stages = r.stages
    assert list(stages) == [
        "proximity", "repair", "iqr-outliers", "repair-again", "local-outliers", "clumps",
        "given-back", "gaps", "junctions", "crossings",
    ]
    assert np.array_equal(stages["crossings"], r.edges)
    stages.clear()  # a copy: the result's stays
    assert len(r.stages) == 10
    assert "235 points" in repr(r)


def test_explain_tells_why_with_numbers():
    points = condt.read_points(SHAPES)
    r = condt.reconstruct(points)
    for a, b in r.edges[:20].tolist():
        story = r.explain(b, a)
        assert story.kept and story.edge == (a, b)
        assert str(story).startswith(f"{a}-{b}: ") and str(story).endswith("; kept")
        assert story.text == str(story)
    dropped = [
        r.explain(*e)
        for e in r.stages["proximity"].tolist()
        if not r.explain(*e).kept
    ]
    assert dropped, "the shipped data has outlier edges"
    reasons = {c["reason"] for s in dropped for c in s.changes}
    assert reasons <= {
        "repair", "longer-than-threshold", "given-back", "long-at", "component", "spur",
        "gap-closed", "junction", "clump", "baseline", "not-confirmed", "repaired-again",
        "crossing",
    }
    for story in dropped:
        for change in story.changes:
            assert change["stage"] in r.stages
            if change["reason"] == "longer-than-threshold":
                assert change["length"] > change["threshold"]
    with pytest.raises(IndexError):
        r.explain(0, len(points))
    with pytest.raises(IndexError):
        r.explain(-1, 0)
    tri = condt.triangulate(points)
    delaunay = {tuple(e) for e in tri.edges.tolist()}
    far = next((0, j) for j in range(1, len(points)) if (0, j) not in delaunay)
    with pytest.raises(KeyError, match="neither a Delaunay edge"):
        r.explain(*far)


def test_geojson_and_shapely_agree():
    points = condt.read_points(SHAPES)
    r = condt.reconstruct(points)
    doc = json.loads(r.to_geojson())
    assert len(doc["features"]) == len(r.curves)
    shapely = pytest.importorskip("shapely")
    geometry = r.to_shapely()
    assert isinstance(geometry, shapely.MultiLineString)
    assert len(geometry.geoms) == len(r.curves)
    for line, curve, feature in zip(geometry.geoms, r.curves, doc["features"]):
        assert line.is_closed == curve.closed == feature["properties"]["closed"]
        assert np.array_equal(np.asarray(line.coords), np.asarray(feature["geometry"]["coordinates"]))


def test_to_shapely_without_shapely_says_how_to_get_it(monkeypatch):
    monkeypatch.setitem(sys.modules, "shapely", None)
    with pytest.raises(ImportError, match=r"pip install shapely"):
        condt.reconstruct(circle()).to_shapely()


def test_the_triangulation():
    points = condt.read_points(SHAPES)
    tri = condt.triangulate(points)
    assert len(tri) == 235 and tri.num_vertices == 234  # one exact duplicate
    t = tri.triangles
    assert t.dtype == np.int64 and t.shape[1] == 3 and not t.flags.writeable
    # Counter-clockwise corners.
    a, b, c = points[t[:, 0]], points[t[:, 1]], points[t[:, 2]]
    cross = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    assert np.all(cross > 0)
    # The neighbours of each distinct point are the other ends of its edges, counter-clockwise
    # (a duplicate has its point's).
    ends = {}
    for a, b in tri.edges.tolist():
        ends.setdefault(a, set()).add(b)
        ends.setdefault(b, set()).add(a)
    for i in range(len(points)):
        around = tri.neighbors(i)
        if i in ends:
            assert set(around.tolist()) == ends[i] and len(around) == len(ends[i])
            if i not in set(tri.hull.tolist()):
                angles = np.arctan2(*(points[around] - points[i]).T[::-1])
                turns = np.diff(np.unwrap(angles))
                assert np.all(turns > 0)
        else:
            assert np.all(points[i] == points[:i]).any() or len(around) > 0
    # Euler on a triangulated disc: e = 3v - 3 - h, t = 2v - 2 - h.
    v, h = tri.num_vertices, len(tri.hull)
    assert len(tri.edges) == 3 * v - 3 - h and len(t) == 2 * v - 2 - h
    with pytest.raises(IndexError):
        tri.neighbors(len(points))
    with pytest.raises(IndexError):
        tri.neighbors(-1)
    line = condt.triangulate([(0, 0), (2, 0), (1, 0)])
    assert line.triangles.shape == (0, 3) and line.edges.tolist() == [[0, 2], [1, 2]]


# --- stubs and docs ----------------------------------------------------------------------------

STUB = pathlib.Path(condt.__file__).with_name("_condt.pyi")


def test_the_package_ships_its_stubs():
    assert STUB.exists() and STUB.with_name("py.typed").exists()


def test_the_stubs_name_what_the_module_has():
    tree = ast.parse(STUB.read_text())
    functions = {n.name: n for n in tree.body if isinstance(n, ast.FunctionDef)}
    classes = {n.name: n for n in tree.body if isinstance(n, ast.ClassDef)}
    for name in condt.__all__:
        assert name in functions or name in classes or name == "__version__", name
    for name, node in functions.items():
        runtime = inspect.signature(getattr(condt, name))
        stub_params = [a.arg for a in node.args.args] + [a.arg for a in node.args.kwonlyargs]
        fixed = [p for p in runtime.parameters.values() if p.kind != p.VAR_KEYWORD]
        assert stub_params[: len(fixed)] == [p.name for p in fixed], name
    for name, node in classes.items():
        if name.startswith("_"):
            continue
        members = {
            n.name for n in node.body if isinstance(n, ast.FunctionDef) and not n.name.startswith("_")
        }
        runtime = {m for m in dir(getattr(condt, name)) if not m.startswith("_")}
        assert members == runtime, name
    keywords = [a.arg for a in functions["reconstruct"].args.kwonlyargs]
    for params in keywords:
        # Every keyword the stub names is accepted (with a value of its type).
        value = {"u": 2.75, "iqr": 1.7, "repair": "needs", "method": "condt"}.get(params, False)
        if params in ("outlier_filter", "manifold_fix"):
            value = True
        condt.reconstruct(circle(), **{params: value})


def test_every_docstring_example_runs():
    import doctest

    finder = doctest.DocTestFinder(exclude_empty=True)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    objects = [condt] + [getattr(condt, name) for name in condt.__all__ if name != "__version__"]
    seen = 0
    for obj in objects:
        docs = [obj]
        if inspect.isclass(obj):
            docs += [getattr(obj, m) for m in vars(obj) if not m.startswith("__")]
        for item in docs:
            text = getattr(item, "__doc__", None)
            if not text or ">>>" not in text:
                continue
            name = getattr(item, "__qualname__", getattr(item, "__name__", repr(item)))
            test = doctest.DocTestParser().get_doctest(text, {}, name, None, 0)
            seen += len(test.examples)
            runner.run(test)
    results = runner.summarize(verbose=False)
    assert results.failed == 0
    assert seen > 30, seen


def test_mypy_stubtest_finds_no_difference_between_the_stubs_and_the_module(tmp_path):
    pytest.importorskip("mypy")
    import subprocess

    done = subprocess.run(
        [sys.executable, "-m", "mypy.stubtest", "condt._condt"],
        cwd=tmp_path,  # where it leaves its cache
        capture_output=True,
        text=True,
        check=False,
    )
    assert done.returncode == 0, done.stdout + done.stderr
