"""The Python interface: inputs it takes, errors it raises, what the result classes hold, the
GIL released, the input read without a conversion, and the stubs matching the module."""

import ast
import inspect
import json
import os
import pathlib
import re
import signal
import sys
import threading
import time
import tracemalloc
import types
import warnings
from decimal import Decimal
from fractions import Fraction

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


@pytest.mark.filterwarnings("ignore::PendingDeprecationWarning")  # np.matrix
def test_integers_beyond_two_to_the_53_are_refused_not_rounded():
    # 2**53 + 1 and 2**53 are one double: rounded, two points would become one.
    edge = 2**53
    for dtype, big, row in ((np.int64, edge + 1, 2), (np.int64, -edge - 1, 1), (np.uint64, 2**64 - 1, 3)):
        points = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=dtype)
        points[row, 1] = big
        for call in (condt.reconstruct, condt.triangulate):
            with pytest.raises(ValueError, match=rf"^points row {row} has the integer coordinate {big}, beyond 2\^53"):
                call(points)
    # A list of Python ints is an int64 array to numpy, refused alike; so are ints numpy keeps as
    # objects or makes floats of (beyond int64, beside others), and an np.matrix (a review).
    for big in (edge + 1, 2**63 + 1, 2**64 + 1, -(2**63) - 1):
        listed = [[0, 0], [big, 1], [1, 1]]
        for points in (listed, np.array(listed, dtype=object)):
            with pytest.raises(ValueError, match=rf"^points row 1 has the integer coordinate {big},"):
                condt.reconstruct(points)
    matrix = np.matrix([[0, 0], [1, edge + 1], [1, 1]], dtype=np.int64)
    with pytest.raises(ValueError, match=rf"^points row 1 has the integer coordinate {edge + 1},"):
        condt.reconstruct(matrix)
    # Floats as large are taken: the rounding was the caller's, before.
    assert condt.triangulate([[0.0, 0.0], [1e300, 1.0], [1.0, 1e300]]).triangles.shape == (1, 3)
    # 2**53 itself, and its negative, are doubles: taken, and exactly.
    exact = np.array([[edge, 0], [0, -edge], [-edge, 0]], dtype=np.int64)
    assert condt.triangulate(exact).triangles.shape == (1, 3)
    assert np.array_equal(
        condt.reconstruct(exact).edges, condt.reconstruct(exact.astype(np.float64)).edges
    )


LONG_DOUBLE_IS_WIDER = np.finfo(np.longdouble).nmant > np.finfo(np.float64).nmant


@pytest.mark.skipif(not LONG_DOUBLE_IS_WIDER, reason="numpy's longdouble is float64 here")
@pytest.mark.parametrize("function", [condt.reconstruct, condt.triangulate, condt.snap])
def test_long_doubles_float64_would_round_are_refused_not_rounded(function):
    # A review's find: rounded silently to float64, 1 + 4 eps became 1 (points 2 and 1 merged),
    # and a triangle 1e-4000 wide one point, where ints beyond 2^53 are refused for that reason.
    eps = np.finfo(np.longdouble).eps
    near = np.array([[0, 0], [1, 0], [1 + 4 * eps, 0], [0, 1]], dtype=np.longdouble)
    tiny = np.array([[0, 0], [np.longdouble("1e-4000"), 0], [0, 1]], dtype=np.longdouble)
    args = (1e-9,) if function is condt.snap else ()
    for points, row, value, rounded in ((near, 2, r"1\.00000000000000000\d+", r"1\.0"), (tiny, 1, "1e-4000", r"0\.0")):
        with pytest.raises(ValueError) as refused:
            function(points, *args)
        message = str(refused.value)
        assert re.match(
            rf"^points row {row} has the coordinate {value} \(dtype float\d+\), which float64 "
            rf"\(condt's coordinates\) cannot hold exactly: it would become {rounded},",
            message,
        ), message
        assert message.endswith("convert the points to float64 first (points.astype(float)) to accept the rounding")
        # As the message says: converted, the rounding is accepted.
        function(points.astype(float), *args)


@pytest.mark.parametrize("function", [condt.reconstruct, condt.triangulate])
def test_long_doubles_float64_holds_are_taken_as_float64(function):
    points = circle(40)
    wide = points.astype(np.longdouble)
    expected = function(points)
    got = function(wide)
    np.testing.assert_array_equal(got.edges, expected.edges)
    # NaN and the infinities are float64s too: named as non-finite points, as in float64.
    for bad in (np.nan, np.inf, -np.inf):
        wide[3, 0] = bad
        with pytest.raises(ValueError, match="^point 3 has a NaN or infinite coordinate"):
            function(wide)


@pytest.mark.parametrize("function", [condt.reconstruct, condt.triangulate])
def test_a_finite_value_beyond_float64_is_named_too_large_not_infinite(function):
    # A review's find: long double 1e400 and Decimal("1e400") were named as a NaN or infinite
    # coordinate, "[inf, 0.0]", where an int beyond float64 was named too large.
    wide = [np.array([[0, 0], [0, 1], [sign * np.longdouble("1e400"), 0]]) for sign in (1, -1)]
    if not np.finfo(np.longdouble).max > np.finfo(np.float64).max:
        wide = []
    decimals = [
        np.array([[0, 0], [0, 1], [Decimal(text), 0]], dtype=object) for text in ("1e400", "-1e400")
    ]
    for points in wide + decimals + [[[0, 0], [0, 1], [Decimal("1e400"), 0]]]:
        with pytest.raises(ValueError, match="^point 2 has a coordinate too large for a float64: ") as refused:
            function(points)
        assert "e+400" in str(refused.value) or "E+400" in str(refused.value), str(refused.value)
    # An infinite Decimal is an infinite point, named as one.
    with pytest.raises(ValueError, match="^point 2 has a NaN or infinite coordinate"):
        function(np.array([[0, 0], [0, 1], [Decimal("-Infinity"), 0]], dtype=object))


def test_a_float64_c_array_is_read_without_a_copy_during_the_call():
    # numpy's allocations are traced by tracemalloc, the Rust side's are not: a conversion of
    # the points would show as an allocation of their size.
    points = circle(100_000)
    # Made before tracing starts: only a conversion inside the call is to show.
    fortran = np.asfortranarray(points)
    tracemalloc.start()
    try:
        condt.reconstruct(points)
        _, in_place = tracemalloc.get_traced_memory()
        tracemalloc.reset_peak()
        condt.reconstruct(fortran)
        _, converted = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert in_place < points.nbytes / 10 and converted >= points.nbytes, (in_place, converted)


def test_a_call_does_not_import_numpy_ma():
    """NumPy 2 imports ``numpy.ma`` on first use only (about 1 MB of Python objects). The check
    for a masked array imported it at a process's first call, which the tracemalloc test above
    counted as a copy of the points when it ran first (``pytest -k without_a_copy`` failed)."""
    import subprocess

    code = (
        "import sys, numpy, condt\n"
        "before = 'numpy.ma' in sys.modules\n"
        "condt.reconstruct([(0, 0), (1, 0), (0, 1)])\n"
        "condt.triangulate([(0, 0), (1, 0), (0, 1)])\n"
        "condt.score([(0, 0), (1, 0)], [(0, 1)], [(0, 1)])\n"
        "print(before, 'numpy.ma' in sys.modules)\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    )
    before, after = done.stdout.split()
    if before == "True":
        pytest.skip("this numpy imports numpy.ma with numpy (numpy 1)")
    assert after == "False", done.stdout


def test_the_result_does_not_change_with_the_callers_array_afterwards():
    # The work runs on a copy of the array, which the result keeps: changing the array
    # afterwards (even to NaN) changes nothing in it.
    points = np.array([(0, 0), (1, 0), (1, 1), (0, 1)], float)
    r = condt.reconstruct(points)
    tri = condt.triangulate(points)

    try:
        import shapely  # noqa: F401

        drawn = lambda: [list(line.coords) for line in r.to_shapely().geoms]  # noqa: E731
    except ImportError:  # the other checks need no shapely
        drawn = lambda: None  # noqa: E731

    def seen():
        strict = json.loads(r.to_geojson(), parse_constant=lambda c: pytest.fail(f"{c} in JSON"))
        return (
            [c.coords.tolist() for c in r.curves],
            strict,
            drawn(),
            r.edges.tolist(),
            tri.triangles.tolist(),
            tri.edges.tolist(),
            tri.hull.tolist(),
            [tri.neighbors(i).tolist() for i in range(4)],
        )

    before = seen()
    points[0] = (100.0, 100.0)
    points[1] = np.nan
    assert seen() == before
    assert before[0] == [[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]]


def test_a_write_to_the_array_during_the_call_changes_nothing_in_the_result():
    """A Python user's review: another thread writing to the array during a call (a NaN written
    and put back) made the triangulation walk forever, past Ctrl-C, as the work read the array in
    place. The work now runs on a copy made as it starts. The write here comes from a signal
    handler, which the call runs between its steps on the calling thread (so it lands inside the
    call, after the triangulation): every point moved by 1 in x. The result is the unmoved
    points', coordinates included (read in place, the stages after the write saw moved points
    and the result kept the moved coordinates)."""
    points = np.random.default_rng(5).random((200_000, 2))
    expected = condt.reconstruct(points.copy())
    inside = False
    moved = []
    done = threading.Event()

    def move(signum, frame):
        if inside and not moved:
            points[:, 0] += 1.0
            moved.append(signum)

    def send():
        while not done.wait(0.005):
            os.kill(os.getpid(), signal.SIGUSR1)

    previous = signal.signal(signal.SIGUSR1, move)
    sender = threading.Thread(target=send)
    try:
        sender.start()
        inside = True
        r = condt.reconstruct(points)
        inside = False
    finally:
        done.set()
        sender.join()
        signal.signal(signal.SIGUSR1, previous)
    assert moved, "the handler never ran during the call"
    assert np.array_equal(r.edges, expected.edges)
    assert [c.coords.tolist() for c in r.curves[:20]] == [
        c.coords.tolist() for c in expected.curves[:20]
    ]


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


@pytest.mark.parametrize("function", [condt.reconstruct, condt.triangulate])
def test_an_int_beyond_float64_is_a_value_error_naming_its_point(function):
    # Found by a fuzzer: numpy's OverflowError came through, naming no point.
    points = [[0, 0], [1, 0], [0, -(10**400)], [1, 1]]
    with pytest.raises(ValueError, match="^point 2 has a coordinate too large for a float64") as e:
        function(points)
    # The 402 characters are cut with a mark: no shorter number is shown as if it were the value.
    assert str(e.value).endswith("... (402 characters)"), str(e.value)


@pytest.mark.parametrize(
    "shape", [(3,), (4, 3), (2, 2, 2), (5, 1)], ids=lambda s: "x".join(map(str, s))
)
def test_a_wrong_shape_is_a_value_error(shape):
    with pytest.raises(ValueError, match=r"shape \(n, 2\)"):
        condt.reconstruct(np.zeros(shape))
    with pytest.raises(ValueError, match=r"shape \(n, 2\)"):
        condt.triangulate(np.zeros(shape))


def test_shapes_other_tools_hand_over_are_named_with_the_fix():
    """An image user's review: np.nonzero's (2, n), OpenCV's (n, 1, 2) contours and (n, 3)
    points got the bare shape; the message now says how to pass them."""
    for shape, hint in (
        ((2, 64), "points.T"),
        ((64, 1, 2), "points.reshape(-1, 2)"),
        ((64, 3), "points[:, :2]"),
    ):
        with pytest.raises(ValueError, match=re.escape(hint)):
            condt.reconstruct(np.zeros(shape))
    # skimage's find_contours gives a list of arrays of different lengths, which numpy calls
    # "inhomogeneous" and nothing more (another image user's review).
    contours = [np.zeros((3, 2)), np.ones((4, 2))]
    with pytest.raises(ValueError, match=re.escape("numpy.vstack(contours)")):
        condt.reconstruct(contours)
    with pytest.raises(ValueError, match=re.escape("numpy.vstack(contours)")):
        condt.triangulate(contours)


def test_lists_of_contours_are_named_with_the_fix_that_makes_them_n_by_2():
    """An image user's review: OpenCV's contours are (n, 1, 2) each, so the fix given for a list
    of them, numpy.vstack(contours), gave (n, 1, 2) and a second refusal; and contours of one
    length (findContours of one blob gives a tuple of one) stack into a 3-d or 4-d array that
    got the bare shape."""
    opencv = [np.zeros((3, 1, 2), np.int32), np.ones((4, 1, 2), np.int32)]
    fix = "numpy.vstack(contours).reshape(-1, 2)"
    for contours in (opencv, tuple(opencv), (opencv[1],), [opencv[0], opencv[0] + 1]):
        with pytest.raises(ValueError, match=re.escape(fix)):
            condt.reconstruct(contours)
        # The fix named works.
        stacked = np.vstack(contours).reshape(-1, 2)
        assert condt.triangulate(stacked).edges.shape[1] == 2
    # skimage's find_contours: (n, 2) each; a list of one, or of equal lengths, is (k, n, 2).
    skimage = [np.array([[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]])]
    for contours in (skimage, skimage * 2):
        with pytest.raises(ValueError, match=re.escape("list of contours? pass numpy.vstack")):
            condt.reconstruct(contours)
        condt.reconstruct(np.vstack(contours))


def test_a_label_image_passed_whole_is_named_with_the_borders_between_its_regions():
    """A label-image user's review: a segmentation (regions numbered) passed as points was told
    the fixes of an edge image and a mask, which give every labelled pixel or the outline of
    all regions together, not the borders between them."""
    labels = np.ones((40, 40), np.int32)
    labels[:20, 20:] = 2
    labels[20:, 20:] = 3
    said = (
        "a label image (regions numbered)? b = skimage.segmentation.find_boundaries(labels, "
        "mode='subpixel'), then numpy.argwhere(b)[:, ::-1] / 2 gives the borders between "
        "regions, junctions included"
    )
    for function in (condt.reconstruct, condt.triangulate):
        with pytest.raises(ValueError, match=re.escape(said)):
            function(labels)
    # The fix named works: the three borders of a T meet at the pixel corner (19.5, 19.5),
    # a point of its own with an edge along each border.
    segmentation = pytest.importorskip("skimage.segmentation")
    b = segmentation.find_boundaries(labels, mode="subpixel")
    xy = np.argwhere(b)[:, ::-1] / 2
    r = condt.reconstruct(xy)
    corner = int(np.nonzero((xy == (19.5, 19.5)).all(axis=1))[0][0])
    ends = sorted(tuple(xy[j]) for i, j in r.edges.tolist() + [e[::-1] for e in r.edges.tolist()]
                  if i == corner)
    assert ends == [(19.5, 19.0), (19.5, 20.0), (20.0, 19.5)]
    assert [c.closed for c in r.curves] == [False, False, False] and len(r.unused) == 0


def test_an_image_or_a_mask_passed_whole_is_named_with_its_pixels_places():
    """An image user's review: a mask or an edge image passed as points got the bare shape (or,
    as bools, the dtype alone), where the places of its edge or boundary pixels are meant."""
    mask = np.zeros((40, 60), bool)
    mask[10:30, 20:40] = True
    fix = "numpy.argwhere(edges)[:, ::-1] gives an edge image's pixels as (x, y), and mask & "
    fix += "~scipy.ndimage.binary_erosion(mask) a filled mask's boundary"
    for image in (mask.astype(np.uint8) * 255, mask.astype(float)):
        for function in (condt.reconstruct, condt.triangulate):
            said = "an image or a mask? condt takes points: " + fix
            with pytest.raises(ValueError, match=re.escape(said)):
                function(image)
    with pytest.raises(TypeError, match=re.escape("a mask? condt takes points: " + fix)):
        condt.reconstruct(mask)
    # A colour image (a diff review: told its shape alone): an edge image or a mask first.
    colour = "a colour image? make an edge image or a mask of it first (skimage.color.rgb2gray, "
    colour += "then a threshold or skimage.feature.canny), then pass points: "
    colour += "numpy.argwhere(edges)[:, ::-1] gives its pixels as (x, y)"
    for channels in (3, 4):
        with pytest.raises(ValueError, match=re.escape(colour)):
            condt.reconstruct(np.zeros((40, 60, channels), np.uint8))
    # The fix named works: the square's boundary (erosion by a cross, written out in numpy),
    # (x, y), comes back as one closed curve through its 76 pixels.
    eroded = np.zeros_like(mask)
    eroded[1:-1, 1:-1] = (
        mask[1:-1, 1:-1] & mask[:-2, 1:-1] & mask[2:, 1:-1] & mask[1:-1, :-2] & mask[1:-1, 2:]
    )
    points = np.argwhere(mask & ~eroded)[:, ::-1]
    r = condt.reconstruct(points)
    assert points[:, 0].max() == 39 and len(points) == 76
    assert [(c.closed, len(c.points)) for c in r.curves] == [(True, 76)]
    # Points, or a short table, get no image hint: bools of shape (n, 2) keep the bare message.
    with pytest.raises(TypeError) as refused:
        condt.reconstruct(np.zeros((10, 2), bool))
    assert "argwhere" not in str(refused.value)
    with pytest.raises(ValueError) as refused:
        condt.reconstruct(np.zeros((3, 7)))
    assert "argwhere" not in str(refused.value)


def test_rows_held_as_objects_are_named_with_the_shape_they_need():
    # A user review: numpy's "setting an array element with a sequence" named neither.
    for row in ([0, 0], np.zeros(2)):
        rows = np.empty(3, dtype=object)
        for i in range(3):
            rows[i] = row
        for function in (condt.reconstruct, condt.triangulate):
            with pytest.raises(ValueError, match=r"shape \(n, 2\); got a 1-d array of 3 objects"):
                function(rows)
    # Rows of three are no pairs: numpy.stack would not make them (n, 2), and it is not said.
    rows = np.empty(2, dtype=object)
    rows[0], rows[1] = [0, 0, 0], [1, 1, 1]
    with pytest.raises(ValueError) as refused:
        condt.reconstruct(rows)
    assert "numpy.stack" not in str(refused.value)


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
    with pytest.raises((ValueError, TypeError)):
        condt.reconstruct([(0, 0), (1,)])
    with pytest.raises(TypeError):
        condt.reconstruct([(0, 0), (1, 1j)])
    with pytest.raises(TypeError):
        condt.reconstruct(np.array([(0, 0), (1, object())], dtype=object))


SQUARE = [(0, 0), (1, 0), (1, 1), (0, 1)]


@pytest.mark.parametrize(
    "dtype", [complex, bool, "U8", "S8", "datetime64[s]", "timedelta64[s]"], ids=str
)
def test_points_that_are_not_numbers_are_a_type_error_naming_the_dtype(dtype):
    points = np.array(SQUARE).astype(dtype)
    functions = [condt.reconstruct, condt.triangulate, lambda p: condt.score(p, [], [])]
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # not converted with only numpy's ComplexWarning
        for function in functions:
            with pytest.raises(TypeError, match=f"not dtype {re.escape(str(points.dtype))}$"):
                function(points)
            # The same values in an object array, or in a list numpy makes that dtype of.
            with pytest.raises(TypeError):
                function(points.astype(object))
            with pytest.raises(TypeError):
                function(points.tolist())


@pytest.mark.parametrize(
    "function",
    [condt.reconstruct, condt.triangulate, lambda p: condt.score(p, [], [])],
    ids=["reconstruct", "triangulate", "score"],
)
def test_none_among_the_points_is_a_type_error_not_a_nan(function):
    # numpy converts None to NaN: a missing value would be told as a NaN point.
    for points in ([[0, None], [1, 1], [2, 3]], np.array([[0.0, 1.0], [None, 1.0]], dtype=object)):
        with pytest.raises(TypeError, match=r"^points must hold numbers \(integers or floats\), not NoneType"):
            function(points)


def test_numbers_of_any_kind_numpy_converts_to_float_are_read():
    expected = condt.reconstruct(SQUARE).edges.tolist()
    readable = [
        [[Decimal(x), Decimal(y)] for x, y in SQUARE],  # numpy: an object array
        np.array([[Fraction(x), Fraction(y)] for x, y in SQUARE], dtype=object),
        np.array(SQUARE, dtype=object),
        [[0, 0.0], [1, 0], [np.float32(1), 1], [np.int8(0), 1]],
        np.array(SQUARE, dtype=np.uint8),
        np.array(SQUARE, dtype=np.float16),
    ]
    for points in readable:
        assert condt.reconstruct(points).edges.tolist() == expected
    for refused in ([[True, False]], np.array([[0, "1"]], dtype=object)):
        with pytest.raises(TypeError, match="numbers"):
            condt.reconstruct(refused)


@pytest.mark.parametrize(
    "function",
    [condt.reconstruct, condt.triangulate, lambda p: condt.score(p, [], [])],
    ids=["reconstruct", "triangulate", "score"],
)
def test_a_bool_among_a_lists_numbers_is_a_type_error(function):
    # numpy makes an int64 or float64 array of these, reading True as 1: a mistake, not a
    # coordinate, as a bool among score's edge positions is.
    for points in (
        [[False, 0], [1, 0], [1, 1], [0, 1]],
        [(0.0, 0.0), (1.0, 0.0), [np.True_, 0.5]],
        ([1, 0], (0.5, True), [0, 1]),
        [np.array([0.0, 0.0]), np.array([True, False]), (0.5, 1.0)],
    ):
        with pytest.raises(TypeError, match=r"^points must hold numbers \(integers or floats\), not bool: row \d"):
            function(points)


@pytest.mark.parametrize(
    "params,error,words",
    [
        ({"u": -1}, ValueError, "u: parameter u = -1 is not accepted"),
        ({"u": 0}, ValueError, "u = 0 is not accepted (u is a finite number greater than 0)"),
        ({"iqr": -1}, ValueError, "iqr = -1 is not accepted (iqr is a finite number, 0 or more)"),
        ({"u": float("nan")}, ValueError, "u = NaN"),
        ({"u": float("inf")}, ValueError, "u = inf"),
        ({"iqr": -0.5}, ValueError, "iqr: parameter iqr = -0.5"),
        ({"iqr": float("nan")}, ValueError, "iqr"),
        ({"u": 2, "adaptive": True}, ValueError, "contradict"),
        ({"iqr": 2, "outlier_filter": False}, ValueError, "contradict"),
        ({"repair": "mutual", "manifold_fix": False}, ValueError, "contradict"),
        ({"repair": "sometimes"}, ValueError, "'needs', 'paper', 'mutual', 'crossing', 'off'"),
        ({"method": "delaunay"}, ValueError, "'condt', 'nn-crust', 'crust'"),
        ({"method": "crust", "u": 2}, ValueError, "baseline"),
        ({"method": "nn-crust", "paper": True}, ValueError, "paper=True sets a ConDT stage"),
        # Whatever the value, as smooth=True (the default) is refused too.
        ({"method": "nn-crust", "paper": False}, ValueError, "paper=False sets a ConDT stage"),
        ({"method": "crust", "smooth": True}, ValueError, "smooth=True sets a ConDT stage"),
        ({"method": "crust", "smooth": False}, ValueError, "baseline"),
        # A step the other keywords leave no way to run, as the command line refuses it.
        ({"confirm_given_back": True, "local_outliers": False}, ValueError, "confirm_given_back=True needs the local outlier removal"),
        ({"paper": True, "confirm_given_back": True}, ValueError, "needs the local outlier removal"),
        ({"repair_again": True, "iqr": None}, ValueError, "repair_again=True needs the repair"),
        ({"repair_again": True, "outliers_first": True}, ValueError, "needs the repair and then"),
        ({"iqr_floor": True, "outlier_filter": False}, ValueError, "spacing floor"),
        ({"outliers_first": True, "repair": "off"}, ValueError, "before the repair"),
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


def test_keyword_pairs_that_contradict_each_other_are_value_errors():
    points = condt.read_points(SHAPES)
    for contradicting in [
        {"iqr": None, "outlier_filter": True},
        {"outlier_filter": True, "iqr": None},
        {"iqr": 1.5, "outlier_filter": False},
        {"repair": "off", "manifold_fix": True},
        {"manifold_fix": True, "repair": "off"},
        {"repair": "needs", "manifold_fix": False},
        {"u": 2, "adaptive": True},
    ]:
        with pytest.raises(ValueError, match="contradict each other"):
            condt.reconstruct(points, **contradicting)
    # Pairs that agree run what they say.
    stages = lambda **params: list(condt.reconstruct(points, paper=True, **params).stages)
    assert stages(iqr=None, outlier_filter=False) == ["proximity", "repair"]
    assert stages(iqr=1.5, outlier_filter=True) == ["proximity", "repair", "iqr-outliers"]
    assert stages(outlier_filter=True) == ["proximity", "repair", "iqr-outliers"]
    assert stages(repair="off", manifold_fix=False) == ["proximity", "iqr-outliers"]
    assert stages(repair="mutual", manifold_fix=True) == ["proximity", "repair", "iqr-outliers"]
    assert np.array_equal(
        condt.reconstruct(points, u=2, adaptive=False).edges,
        condt.reconstruct(points, u=2).edges,
    )
    assert np.array_equal(
        condt.reconstruct(points, iqr=1.5, outlier_filter=True).edges,
        condt.reconstruct(points, iqr=1.5).edges,
    )


def test_numbers_out_of_range_are_the_documented_errors_naming_the_parameter():
    for huge in (2**2000, -(2**2000)):
        with pytest.raises(ValueError, match=r"^u: parameter u = -?inf is not accepted"):
            condt.reconstruct(SQUARE, u=huge)
        with pytest.raises(ValueError, match=r"^iqr: parameter iqr = -?inf is not accepted"):
            condt.reconstruct(SQUARE, iqr=huge)
    with pytest.raises(ValueError, match=r"^iqr: parameter iqr = -1 is not accepted"):
        condt.reconstruct(SQUARE, iqr=-1)
    for flag in (1, None, "yes"):
        with pytest.raises(TypeError, match=f"^paper must be True or False, not {type(flag).__name__}$"):
            condt.reconstruct(SQUARE, paper=flag)
    assert list(condt.reconstruct(SQUARE, paper=np.bool_(True)).stages) == [
        "proximity", "repair", "iqr-outliers",
    ]
    r = condt.reconstruct(SQUARE)
    tri = condt.triangulate(SQUARE)
    for position in (2**63, 2**70, -(2**63) - 1, np.uint64(2**64 - 1), 4, -1):
        with pytest.raises(IndexError, match=f"^{position} is not an input position \\(0 to 3\\)$"):
            r.explain(position, 0)
        with pytest.raises(IndexError, match="not an input position"):
            r.explain(0, position)
        with pytest.raises(IndexError, match=f"^{position} is not an input position"):
            tri.neighbors(position)
    with pytest.raises(TypeError, match="'i'"):
        tri.neighbors(1.0)
    assert tri.neighbors(np.int64(0)).tolist() == tri.neighbors(0).tolist()
    assert r.explain(np.uint8(1), np.int32(0)).edge == (0, 1)


def test_explain_reads_a_duplicate_as_its_first_point():
    points = [(0, 0), (1, 0), (0, 1), (1, 1), (0, 0)]  # 4 repeats 0
    r = condt.reconstruct(points)
    tri = condt.triangulate(points)
    assert 1 in tri.neighbors(4).tolist()
    for i, j in [(4, 1), (1, 4)]:
        story = r.explain(i, j)
        assert story.edge == (0, 1) and str(story) == str(r.explain(0, 1))
        assert story.kept == r.explain(0, 1).kept
    with pytest.raises(ValueError, match=r"explain\(2, 2\): an edge joins two points"):
        r.explain(2, 2)
    with pytest.raises(ValueError, match=r"4 and 0 are the same point \(duplicates: the first is 0\)"):
        r.explain(4, 0)


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


def test_read_points_reads_a_path_as_a_file_even_a_dash(tmp_path, monkeypatch):
    (tmp_path / "-").write_text("0 0\n1.5 2\n")
    expected = [[0.0, 0.0], [1.5, 2.0]]
    monkeypatch.chdir(tmp_path)
    # The file named `-`, never standard input (which pytest gives as empty).
    assert condt.read_points("-").tolist() == expected
    for path in (b"-", pathlib.Path("-"), tmp_path / "-", os.fsencode(tmp_path / "-")):
        assert condt.read_points(path).tolist() == expected
    (tmp_path / "pts.txt").write_text("3 4\n")
    assert condt.read_points(b"pts.txt").tolist() == [[3.0, 4.0]]
    (tmp_path / "-").unlink()
    with pytest.raises(FileNotFoundError) as err:
        condt.read_points("-")
    assert err.value.filename == "-"
    (tmp_path / "-").write_text("0 0\nnot a point\n")
    with pytest.raises(ValueError, match=r"^-:2: "):
        condt.read_points("-")
    for wrong in (3, None, ["pts.txt"]):
        with pytest.raises(TypeError, match=f"^path must be a str, bytes or os.PathLike, not {type(wrong).__name__}$"):
            condt.read_points(wrong)


def test_score_checks_its_edges():
    square = [(0, 0), (1, 0), (1, 1), (0, 1)]
    truth = [(0, 1), (1, 2), (2, 3), (3, 0)]
    s = condt.score(square, truth, truth)
    assert s["exact"] and s["f1"] == 1.0 and s["max_dist"] == 0.0 and s["malformed"] is None
    bad = condt.score(square, [(0, 1), (1, -1), (2, 2)], truth)
    assert bad["malformed"] == "row 1: point -1 does not exist"
    assert (bad["f1"], bad["exact"], bad["n_out"]) == (0.0, False, 1)
    # n_out counts valid edges once each, as the evaluation's score.py (a researcher's review).
    twice = condt.score(square, truth + [(1, 0)], truth)
    assert (twice["n_out"], twice["tp"] + twice["fp"]) == (4, 4)
    assert condt.score(square, [(0, 1), (1, 9)], truth)["malformed"] == "row 1: point 9 does not exist"
    assert condt.score(square, [(2, 2)], truth)["malformed"] == "row 0: self-loop at point 2"
    assert condt.score(square, [], truth)["max_dist"] is None
    assert condt.score(square, [(0, 1)], [])["max_dist"] is None  # infinite: null in JSON
    with pytest.raises(ValueError, match="ground truth: row 1: point 7 does not exist"):
        condt.score(square, [], [(0, 1), (7, 1)])
    with pytest.raises(ValueError, match="ground truth: row 0: point -2 does not exist"):
        condt.score(square, [], [(-2, 1)])
    with pytest.raises(TypeError, match="integers"):
        condt.score(square, [(0.5, 1)], truth)
    with pytest.raises(ValueError, match=r"shape \(m, 2\)"):
        condt.score(square, [(0, 1, 2)], truth)


def test_score_edges_that_are_no_array_are_a_type_error_and_shapes_are_written_as_python_does():
    square = [(0, 0), (1, 0), (1, 1), (0, 1)]
    truth = [(0, 1), (1, 2), (2, 3), (3, 0)]
    for wrong in (None, 3, np.int64(3), 2.5):
        name = type(wrong).__name__
        with pytest.raises(TypeError, match=rf"^output must be an array-like of shape \(m, 2\), not {name}$"):
            condt.score(square, wrong, truth)
        with pytest.raises(TypeError, match=rf"^truth must be an array-like of shape \(m, 2\), not {name}$"):
            condt.score(square, truth, wrong)
    for edges, shown in (([(0, 1, 2)], "(1, 3)"), ([0, 1, 2], "(3,)"), ([[[0, 1]]], "(1, 1, 2)")):
        with pytest.raises(ValueError, match=rf"got one of shape {re.escape(shown)}$"):
            condt.score(square, edges, truth)
    # No edges at all is an empty sequence or a (0, 2) array; an empty array of another shape
    # is refused as its rows would be (it was scored as no edges).
    assert condt.score(square, np.zeros((0, 2), int), truth)["n_out"] == 0
    for empty, shown in ((np.zeros((0, 3), int), "(0, 3)"), (np.zeros((5, 0), int), "(5, 0)")):
        with pytest.raises(ValueError, match=rf"^output must be an array of shape \(m, 2\); got one of shape {re.escape(shown)}$"):
            condt.score(square, empty, truth)
        with pytest.raises(ValueError, match=rf"^truth must be an array of shape \(m, 2\); got one of shape {re.escape(shown)}$"):
            condt.score(square, truth, empty)


def test_score_reads_unaligned_integer_edge_arrays():
    """A contiguous int64 or uint64 array at an odd address (np.frombuffer at an offset) is read
    as its aligned copy would be, output and truth alike."""
    square = [(0, 0), (1, 0), (1, 1), (0, 1)]
    truth = np.array([(0, 1), (1, 2), (2, 3), (0, 3)], np.int64)
    for dtype in (np.int64, np.uint64, np.dtype(">i8")):
        raw = bytearray(truth.nbytes + 1)
        shifted = np.frombuffer(raw, dtype, offset=1, count=8).reshape(-1, 2)
        shifted[:] = truth
        assert not shifted.flags.aligned
        assert condt.score(square, shifted, truth)["exact"]
        assert condt.score(square, truth, shifted)["exact"]
        shifted[0, 1] = 2
        assert not condt.score(square, shifted, truth)["exact"]


def test_score_names_an_index_beyond_int64_as_given_and_never_wraps_it():
    square = [(0, 0), (1, 0), (1, 1), (0, 1)]
    truth = [(0, 1), (1, 2), (2, 3), (3, 0)]
    beyond = [
        (np.array([[0, 2**63 + 1]], dtype=np.uint64), "9223372036854775809"),
        (np.array([[2**64 - 1, 0]], dtype=np.uint64), "18446744073709551615"),
        ([[0, 2**63]], "9223372036854775808"),  # numpy: float64
        ([[0, 2**70]], "1180591620717411303424"),  # numpy: object
        ([[1, -(2**70)]], "-1180591620717411303424"),
        (np.array([[0, 2**80]], dtype=object), "1208925819614629174706176"),
    ]
    for edges, value in beyond:
        s = condt.score(square, edges, truth)
        assert s["malformed"] == f"row 0: point {value} does not exist", edges
        assert (s["f1"], s["n_out"]) == (0.0, 0)
        with pytest.raises(ValueError, match=f"^ground truth: row 0: point {value} does not exist$"):
            condt.score(square, [], edges)
    # Unsigned and object arrays of indices in range are read as they are.
    for edges in (np.array(truth, dtype=np.uint64), np.array(truth, dtype=object), np.array(truth, np.uint8)):
        assert condt.score(square, edges, truth)["exact"]
        assert condt.score(square, truth, edges)["exact"]
    for not_indices in ([[0, 2**63 + 0.5]], np.array([[0, 1.0]], dtype=object), [[0.5, 1]]):
        with pytest.raises(TypeError, match="integers"):
            condt.score(square, not_indices, truth)


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
        "given-back", "gaps", "junctions", "crossings", "tips", "spikes", "hooks", "tails",
        "detours",
    ]
    assert np.array_equal(stages["detours"], r.edges)
    stages.clear()  # a copy: the result's stays
    assert len(r.stages) == 15
    assert "235 points" in repr(r)


def test_reading_the_curves_keeps_no_cycle_that_holds_the_result():
    # The result caches its curves; a curve that held the result back made a cycle the garbage
    # collector cannot see, which kept every result whose curves were read (about 21 MB a call
    # on 200,000 points). A curve holds the result's data alone, and outlives the result.
    r = condt.reconstruct(condt.read_points(SHAPES))
    before = sys.getrefcount(r)
    curves = r.curves
    assert len(curves) > 1 and sys.getrefcount(r) == before
    assert r.curves[0] is curves[0]
    coords = [c.coords.tolist() for c in curves]
    del r
    assert [c.coords.tolist() for c in curves] == coords


def test_score_refuses_a_bool_among_the_positions_of_a_list():
    square = [(0, 0), (1, 0), (1, 1), (0, 1)]
    truth = [(0, 1), (1, 2), (2, 3), (3, 0)]
    for output, row in (([(True, 2)], 0), ([(0, 1), (np.True_, 2)], 1), ([[1, False]], 0)):
        with pytest.raises(TypeError, match=rf"^output must be an \(m, 2\) array of integers \(point indices\); row {row} holds "):
            condt.score(square, output, truth)
    assert condt.score(square, [(0, 1), (np.int64(1), 2)], truth)["tp"] == 2


def test_a_bool_is_no_input_position():
    points = condt.read_points(SHAPES)
    r, tri = condt.reconstruct(points), condt.triangulate(points)
    a, b = r.edges[0].tolist()
    # numpy's bool as Python's, whatever numpy's version: NumPy 1 gives it an `__index__`
    # (deprecated), and `neighbors(np.True_)` was point 1's neighbors there.
    for call in (
        lambda: r.explain(True, b),
        lambda: r.explain(a, False),
        lambda: tri.neighbors(True),
        lambda: tri.neighbors(np.True_),
        lambda: r.explain(a, np.False_),
    ):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            with pytest.raises(TypeError, match=r"^argument '[ij]': an input position is an integer, not bool$"):
                call()
    with pytest.raises(TypeError, match=r"^argument 'j': 'str' object cannot be interpreted"):
        r.explain(a, "1")
    # numpy's integers are positions.
    assert r.explain(np.int64(a), np.uint8(b)).edge == (a, b)
    assert tri.neighbors(np.int32(1)).tolist() == tri.neighbors(1).tolist()


def test_a_detour_is_explained_with_its_ends():
    # A line of twelve samples and point 12 above samples 5 and 6: without the repair Algorithm
    # 1's ear through it stays until the detours step cuts it.
    points = np.array([(i, 0.0) for i in range(12)] + [(5.5, 1.2)])
    r = condt.reconstruct(points, repair="off", smooth=False)
    assert r.edges.tolist() == [[i, i + 1] for i in range(11)]
    for edge in [(5, 12), (6, 12)]:
        story = r.explain(*edge)
        assert not story.kept
        change = story.changes[-1]
        assert change == {
            "stage": "detours", "added": False, "reason": "detour", "from": 5, "to": 6, "points": 1,
        }
        assert "detour through 1 point between 5 and 6" in story.text
    kept = condt.reconstruct(points, repair="off", smooth=False, detours=False)
    assert [5, 12] in kept.edges.tolist() and [6, 12] in kept.edges.tolist()


def test_explain_tells_why_with_numbers():
    points = condt.read_points(SHAPES)
    r = condt.reconstruct(points)
    for a, b in r.edges[:20].tolist():
        story = r.explain(b, a)
        assert story.kept and story.edge == (a, b)
        # The verdict closes the story, before the word on the smoothing passes that ran.
        verdict = str(story).split(" (lengths where the stages saw the points")[0]
        assert str(story).startswith(f"{a}-{b}: ") and verdict.endswith("; kept")
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
    with pytest.raises(KeyError, match="is not .*, nor an edge a stage added: no stage saw it"):
        r.explain(*far)


def test_after_smoothing_passes_explain_speaks_of_the_moved_points():
    # A noisy circle: passes run, and some Delaunay edges of the input are no Delaunay edges
    # of the moved points the last run walked; the refusal says so instead of denying that
    # they are Delaunay edges.
    rng = np.random.default_rng(3)
    t = np.linspace(0, 2 * np.pi, 300, endpoint=False)
    points = np.column_stack([np.cos(t), np.sin(t)]) + rng.normal(0, 0.006, (300, 2))
    r = condt.reconstruct(points)
    refused = []
    for a, b in condt.triangulate(points).edges.tolist():
        try:
            r.explain(a, b)
        except KeyError as e:
            refused.append(str(e))
    assert refused, "the passes changed some Delaunay edges"
    assert all("smoothing pass" in message for message in refused), refused[:1]
    assert all("last run's Delaunay triangulation" in message for message in refused)
    assert not any("not a Delaunay edge" in message for message in refused)
    # And a story's text says its lengths are the moved points', as the viewer does (an image
    # user's review: pixels 1 apart read "|e2| = 1.250 |e1|" with no word of the passes).
    passes = r.passes
    said = f"(lengths where the stages saw the points, after {passes} smoothing pass"
    assert passes > 0 and r.explain(0, 1).text.endswith(said + ("es)" if passes > 1 else ")"))
    assert "smoothing" not in condt.reconstruct(points, smooth=False).explain(0, 1).text


def test_passes_say_how_many_smoothing_passes_ran():
    # The noisy circle above shows noise: passes run (three at most); the clean one and the
    # paper's pipeline (no smoothing) run none.
    rng = np.random.default_rng(3)
    t = np.linspace(0, 2 * np.pi, 300, endpoint=False)
    clean = np.column_stack([np.cos(t), np.sin(t)])
    noisy = clean + rng.normal(0, 0.006, (300, 2))
    assert 1 <= condt.reconstruct(noisy).passes <= 3
    assert condt.reconstruct(noisy, smooth=False).passes == 0
    assert condt.reconstruct(noisy, paper=True).passes == 0
    assert condt.reconstruct(clean).passes == 0


def test_timings_name_each_step_in_the_order_it_ran():
    rng = np.random.default_rng(3)
    t = np.linspace(0, 2 * np.pi, 300, endpoint=False)
    clean = np.column_stack([np.cos(t), np.sin(t)])
    for points, first in [(clean, []), (clean + rng.normal(0, 0.006, (300, 2)), ["earlier-passes"])]:
        r = condt.reconstruct(points)
        assert list(r.timings) == first + ["triangulation", *r.stages, "curves"]
        assert all(isinstance(s, float) and s >= 0 for s in r.timings.values())


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


def test_no_points_collinear_hulls_and_baselines_are_told_as_they_are():
    for empty in (condt.reconstruct([]), condt.triangulate([])):
        with pytest.raises(IndexError, match="^0 is not an input position: there are no points$"):
            empty.explain(0, 0) if isinstance(empty, condt.Reconstruction) else empty.neighbors(0)
    # The hull of collinear points goes out and back, as its docstring and stub say.
    line = condt.triangulate([(0, 0), (1, 0), (2, 0), (3, 0)])
    assert line.hull.tolist() == [0, 1, 2, 3, 2, 1]
    assert "out along the line and back" in condt.Triangulation.hull.__doc__
    assert "out and back" in STUB.read_text()
    # A baseline's story: its choice is the change with reason "baseline"; the ends are
    # Algorithm 1's view, as the docstring says (the text comes from condt-io's story_text).
    story = condt.reconstruct(SQUARE, method="crust").explain(0, 1)
    assert [c["reason"] for c in story.changes] == ["baseline"]
    assert "Algorithm 1 would have seen" in condt.Reconstruction.explain.__doc__


# --- snapping ----------------------------------------------------------------------------------


def squares_exported_ring_by_ring():
    """Two 30 by 30 squares sampled every unit, written ring by ring; the second's side on the
    shared border is 1e-9 off the first's (a reprojection's rounding)."""
    rows = []
    for x0, wobble in ((0.0, 0.0), (30.0, 1e-9)):
        corners = [(0, 0), (30, 0), (30, 30), (0, 30), (0, 0)]
        for (ax, ay), (bx, by) in zip(corners, corners[1:]):
            for i in range(30):
                t = i / 30
                x, y = x0 + ax + t * (bx - ax), ay + t * (by - ay)
                rows.append((x, y + wobble if x == 30 else y))
    return np.array(rows)


def test_snap_makes_a_shared_border_exported_twice_one():
    points = squares_exported_ring_by_ring()
    given = points.copy()
    # The twins are left unused, and warned of all the same (a GIS user's review: the warning
    # came only for twins the stages made curves of two points).
    with pytest.warns(UserWarning, match="31 pairs of points that lie 16 times nearer"):
        assert len(condt.reconstruct(points).unused) > 0, "the twins break the border"
    snapped = condt.snap(points, 1e-6)
    np.testing.assert_array_equal(points, given)  # a new array: the input is not changed
    moved = np.flatnonzero((snapped != points).any(axis=1))
    assert len(moved) == 31 and moved.min() >= 120, "only the second ring's twins move"
    assert np.abs(snapped - points).max() <= 1e-6
    r = condt.reconstruct(snapped)
    assert len(r.unused) == 0 and len(r.curves) == 3
    assert condt.snap(points, 0).tolist() == points.tolist()


def test_points_given_twice_a_little_apart_are_warned_of_and_listed():
    # A wavy ring given twice, the second copy a millionth off: each sample and its twin make a
    # curve of two points, a result that reads as success; the command line notes it, Python
    # warns (a contributor's review: only the command line told).
    t = np.linspace(0, 2 * np.pi, 60, endpoint=False)
    ring = np.column_stack([10 * np.cos(t) + 0.3 * np.sin(5 * t), 10 * np.sin(t)])
    twice = np.vstack([ring, ring + [1e-6, 0]])
    with pytest.warns(UserWarning, match="16 times nearer each other.*condt.snap"):
        r = condt.reconstruct(twice)
    twins = r.twin_pairs
    assert twins.dtype == np.int64 and twins.shape[1] == 2
    # Each sample k and its copy 60 + k: every pair, the lower position first.
    assert twins.tolist() == [[k, 60 + k] for k in range(60)]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert condt.reconstruct(ring).twin_pairs.shape == (0, 2)
        assert condt.reconstruct(condt.snap(twice, 1e-5)).twin_pairs.shape == (0, 2)


def test_snap_moves_an_exact_duplicate_where_its_first_copy_went_as_its_docs_say():
    # A review's find: the docs said every point moves "onto the nearest such point", but point
    # 3, an exact duplicate of point 1, follows it onto point 0 (0.2 away), not onto point 2,
    # which stays 0.1 away (crates/condt/src/snap.rs says so).
    points = [(0.0, 0.0), (0.2, 0.0), (0.3, 0.0), (0.2, 0.0)]
    assert condt.snap(points, 0.25).tolist() == [[0.0, 0.0], [0.0, 0.0], [0.3, 0.0], [0.0, 0.0]]
    said = "an exact duplicate of an earlier point, which goes where its first copy went"
    assert said in " ".join(condt.snap.__doc__.split())
    readme = pathlib.Path(__file__).resolve().parents[2] / "README.md"
    if readme.exists():
        text = " ".join(readme.read_text().split())
        assert "an exact duplicate of an earlier point goes where its first copy went" in text


def test_the_readmes_image_boundaries_run_as_written():
    """python/README.md's *Image boundaries* block (an image user's review: the Python docs
    said nothing of OpenCV's or scikit-image's layouts, rows and columns, or duplicates) runs,
    and its own asserts check the curves it promises."""
    for module in ("cv2", "scipy", "skimage"):
        pytest.importorskip(module)
    assert run_the_readmes_first_block_under("## Image boundaries")["xy"].shape[1] == 2


def run_the_readmes_first_block_under(heading):
    """Runs python/README.md's first Python block after `heading` and returns its names."""
    readme = pathlib.Path(__file__).resolve().parents[1] / "README.md"
    if not readme.exists():
        pytest.skip("no python/README.md beside the tests")
    section = readme.read_text().split(heading, 1)[1]
    block = section.split("```python\n", 1)[1].split("```", 1)[0]
    names = {}
    exec(compile(block, str(readme), "exec"), names)
    return names


def test_the_readmes_label_images_run_as_written():
    """python/README.md's *Label images* block (a label-image user's review: nothing said which
    of scikit-image's boundaries gives a segmentation's borders with their junctions) runs,
    and its asserts check the three borders and the junction's three edges."""
    pytest.importorskip("skimage")
    assert len(run_the_readmes_first_block_under("### Label images")["r"].curves) == 3


@pytest.mark.parametrize("distance", [float("nan"), -1.0, float("inf")])
def test_snap_refuses_a_distance_that_is_no_length(distance):
    with pytest.raises(ValueError, match="distance"):
        condt.snap([(0, 0), (1, 0)], distance)


@pytest.mark.parametrize("distance", ["1e-6", True, None])
def test_snap_refuses_a_distance_that_is_no_number(distance):
    with pytest.raises(TypeError, match="distance must be a number"):
        condt.snap([(0, 0), (1, 0)], distance)


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
        # The private functions (condt.dask's native half) are the native module's alone.
        module = condt._condt if name.startswith("_") else condt
        runtime = inspect.signature(getattr(module, name))
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
    # And every keyword the module accepts is in the stub (`reconstruct` takes **params at run
    # time, so stubtest cannot see a missing one: a new contributor's review). The module's own
    # refusal of an unknown keyword lists them.
    with pytest.raises(TypeError, match="the parameters are ") as refused:
        condt.reconstruct(circle(), no_such_keyword=True)
    accepted = str(refused.value).split("the parameters are ")[1].split(", ")
    missing, extra = set(accepted) - set(keywords), set(keywords) - set(accepted)
    assert not missing and not extra, f"add {missing} to / remove {extra} from _condt.pyi"
    assert sorted(accepted) == sorted(keywords)
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


def test_the_tiled_results_fields_are_typed_for_a_strict_checker(tmp_path):
    """A typed client's review: ``condt.dask.TiledReconstruction``'s ``workers`` was a bare
    ``frozenset`` (pyright's strict mode: "partially unknown" at every use) and ``edges`` an
    ndarray of any dtype, where ``condt.reconstruct``'s edges are int64."""
    pytest.importorskip("mypy")
    import subprocess

    client = tmp_path / "client.py"
    client.write_text(
        "import condt.dask\n"
        "def f(t: condt.dask.TiledReconstruction) -> None:\n"
        "    reveal_type(t.workers)\n"
        "    reveal_type(t.edges)\n"
    )
    done = subprocess.run(
        [sys.executable, "-m", "mypy", "--strict", "--no-incremental", str(client)],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        check=False,
    )
    revealed = re.findall(r'Revealed type is "(.*)"', done.stdout)
    assert len(revealed) == 2, done.stdout + done.stderr
    assert revealed[0].replace("builtins.", "") == "frozenset[str]", revealed
    assert "signedinteger" in revealed[1] and "_64Bit" in revealed[1], revealed


def test_points_too_close_to_measure_beside_the_largest_coordinate_are_a_value_error():
    # A circle of radius 1 beside a point at 1e230: its edges' squares underflow in the
    # stages' frame, and the curves came out in pieces; the set is refused, by name.
    t = np.linspace(0, 2 * np.pi, 40, endpoint=False)
    points = np.vstack([np.column_stack([np.cos(t), np.sin(t)]), [[1e230, 0.0]]])
    with pytest.raises(ValueError, match=r"points (\d+) and (\d+) are closer than 2\^-450") as refused:
        condt.reconstruct(points)
    first, second = (int(k) for k in re.findall(r"points (\d+) and (\d+)", str(refused.value))[0])
    assert first < second < 40
    assert np.hypot(*(points[first] - points[second])) < 2.0**-450 * 1e230
    assert len(condt.triangulate(points).edges) > 0
    # At 1e100 the stages measure the circle, which comes out whole.
    points[40] = (1e100, 0.0)
    result = condt.reconstruct(points)
    assert [c.closed for c in result.curves] == [True] and len(result.edges) == 40


def test_read_points_with_crs_carries_the_crs_to_geojson(tmp_path):
    # A GeoJSON input's crs, as the command line carries it from a GeoJSON input to a GeoJSON
    # output (Python read the points alone, and to_geojson wrote no crs).
    crs_text = '{"type": "name",\n  "properties": {"name": "EPSG:32632"}}'
    coords = [[500000.0 + 10 * x, 4000000.0 + 10 * y] for x, y in SQUARE]
    doc = (
        '{"type": "FeatureCollection", "crs": ' + crs_text + ', "features": ['
        '{"type": "Feature", "properties": {}, "geometry": null},'
        '{"type": "Feature", "properties": {}, "geometry": {"type": "MultiPoint", "coordinates": '
        + json.dumps(coords)
        + "}}]}"
    )
    path = tmp_path / "utm.geojson"
    path.write_text(doc)
    with pytest.warns(UserWarning, match="skipped 1 feature with a null geometry"):
        points, crs = condt.read_points_with_crs(path)
    assert points.tolist() == coords
    assert crs == crs_text
    with pytest.warns(UserWarning, match="skipped 1 feature with a null geometry"):
        assert condt.read_points(path).tolist() == coords
    r = condt.reconstruct(points)
    # The text as read, written on as it is; a dict is written by json.dumps.
    written = r.to_geojson(crs=crs)
    assert written.startswith('{"type":"FeatureCollection","crs":' + crs_text + ",")
    assert json.loads(written)["crs"] == json.loads(crs_text)
    as_dict = json.loads(r.to_geojson(crs=json.loads(crs_text)))
    assert as_dict["crs"] == json.loads(crs_text)
    assert as_dict["features"] == json.loads(written)["features"]
    # Without a crs such coordinates read as degrees: warned of, as the command line notes it
    # (a GIS user's review: Python said nothing).
    with pytest.warns(UserWarning, match=r"\(500000, 4000000\) are no longitude and latitude"):
        assert "crs" not in json.loads(r.to_geojson())
    with pytest.warns(UserWarning, match="crs= names the input's system"):
        assert r.to_geojson(crs=None) == r.to_geojson()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r.to_geojson(crs="null")
        condt.reconstruct(points / 1e5).to_geojson()
    # A name, as the command line's --crs takes it; text that starts as JSON must be JSON.
    named = json.loads(r.to_geojson(crs="EPSG:32632"))["crs"]
    assert named == {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32632"}}
    with pytest.raises(ValueError, match="not one JSON object"):
        r.to_geojson(crs='{"type": ')
    with pytest.raises(ValueError, match="not a name"):
        r.to_geojson(crs=" ")
    with pytest.raises(TypeError, match="crs must be JSON text"):
        r.to_geojson(crs=object())
    # A number JSON cannot write is named as such (it was "not one JSON object": a review).
    for number in (float("inf"), float("nan")):
        with pytest.raises(ValueError, match=r"crs holds a number JSON cannot write"):
            r.to_geojson(crs={"type": "name", "properties": {"scale": number}})
    # JSON that names no crs is refused rather than written; null is written (GeoJSON 2008: no
    # crs can be assumed).
    for text in ("[1, 2]", "4326", "true"):
        with pytest.raises(ValueError, match="is JSON but neither"):
            r.to_geojson(crs=text)
    assert json.loads(r.to_geojson(crs="null"))["crs"] is None
    # A crs member read from a file goes on as the command line carries it (a user review: a
    # string member became a name in Python but stayed a string on the command line).
    for member, expected in [
        ("null", None),
        ('"EPSG:3857"', {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::3857"}}),
        ("{}", {}),
    ]:
        path = tmp_path / "member.geojson"
        path.write_text('{"type": "MultiPoint", "crs": %s, "coordinates": [[0, 0], [1, 0], [0, 1]]}' % member)
        points, crs = condt.read_points_with_crs(path)
        assert json.loads(condt.reconstruct(points).to_geojson(crs=crs))["crs"] == expected
    # A member no output can carry is left out with a warning, as the command line notes it,
    # not handed on for to_geojson to refuse (a GIS user's review).
    for member in ("4326", "[1]"):
        path = tmp_path / "member.geojson"
        path.write_text('{"type": "MultiPoint", "crs": %s, "coordinates": [[0, 0], [1, 0], [0, 1]]}' % member)
        with pytest.warns(UserWarning, match=r"member\.geojson: its crs member .*is JSON but neither"):
            points, crs = condt.read_points_with_crs(path)
        assert crs is None and points.shape == (3, 2)
        assert "crs" not in json.loads(condt.reconstruct(points).to_geojson(crs=crs))
    # Any mapping is written as its dict.
    proxy = types.MappingProxyType(json.loads(crs_text))
    assert json.loads(r.to_geojson(crs=proxy))["crs"] == json.loads(crs_text)
    # GeoJSON's crs is an object: a number or a list is a mistake, not written.
    for wrong in (5, [1], 1.5):
        said = 'crs must be JSON text, a name ("EPSG:4326" for an EPSG code), a dict, a pyproj CRS'
        with pytest.raises(TypeError, match=f"^{re.escape(said)} or None, not {type(wrong).__name__}$"):
            r.to_geojson(crs=wrong)
    # Other formats, and GeoJSON without one, have no crs.
    (tmp_path / "pts.txt").write_text("0 0\n1 0\n")
    assert condt.read_points_with_crs(tmp_path / "pts.txt")[1] is None
    (tmp_path / "plain.geojson").write_text('{"type": "Point", "coordinates": [1, 2]}')
    assert condt.read_points_with_crs(tmp_path / "plain.geojson")[1] is None


def test_read_points_with_crs_warns_of_a_later_records_other_crs(tmp_path):
    # A GeoJSON sequence keeps its first record's crs; a later record's other crs is told, not
    # dropped without a word (as the command line's note tells it), and its points are read.
    def record(name, x):
        crs = {"type": "name", "properties": {"name": name}}
        point = {"type": "Point", "coordinates": [x, 0.0]}
        return json.dumps({"type": "Feature", "crs": crs, "properties": {}, "geometry": point})

    path = tmp_path / "two.geojsonl"
    path.write_text(record("EPSG:32632", 1.0) + "\n" + record("EPSG:4326", 2.0) + "\n")
    with pytest.warns(UserWarning, match="two.geojsonl:2: this crs differs"):
        points, crs = condt.read_points_with_crs(path)
    with pytest.warns(UserWarning, match="two.geojsonl:2: "):
        assert condt.read_points(path).tolist() == [[1.0, 0.0], [2.0, 0.0]]
    assert points.tolist() == [[1.0, 0.0], [2.0, 0.0]]
    assert json.loads(crs)["properties"]["name"] == "EPSG:32632"
    same = tmp_path / "same.geojsonl"
    same.write_text(record("EPSG:32632", 1.0) + "\n" + record("EPSG:32632", 2.0) + "\n")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        condt.read_points_with_crs(same)


def test_read_points_takes_the_command_lines_columns_and_input_format(tmp_path):
    # An ESRI or QGIS export names its columns POINT_X and POINT_Y; the command line's
    # --columns and --input-format choose them, and so do these keywords.
    path = tmp_path / "survey.txt"
    path.write_text("FID,POINT_X,POINT_Y\n1,2600000.5,1200000\n2,2600001,1200002.5\n")
    expected = [[2600000.5, 1200000.0], [2600001.0, 1200002.5]]
    for columns in [("POINT_X", "POINT_Y"), ["point_x", "Point_Y"], "POINT_X,POINT_Y", "2,3"]:
        got = condt.read_points(path, input_format="csv", columns=columns)
        assert got.tolist() == expected, columns
        points, crs = condt.read_points_with_crs(path, input_format="csv", columns=columns)
        assert points.tolist() == expected and crs is None
    # Swapped columns swap the coordinates: the pair is (x, y).
    swapped = condt.read_points(path, input_format="csv", columns=("POINT_Y", "POINT_X"))
    assert swapped.tolist() == [[y, x] for x, y in expected]
    # By its name the file is plain text, whose header does not name x and y first.
    with pytest.raises(ValueError, match="survey.txt:"):
        condt.read_points(path)
    # Columns apply to CSV, TSV and plain text, as on the command line: a .txt whose first
    # line has commas is read as CSV.
    got = condt.read_points(path, columns=("POINT_X", "POINT_Y"))
    assert got.tolist() == expected
    with pytest.raises(ValueError, match="no column named \"easting\""):
        condt.read_points(path, input_format="csv", columns=("easting", "northing"))
    with pytest.raises(ValueError, match="unknown input format; the formats are txt, node"):
        condt.read_points(path, input_format="xlsx")
    with pytest.raises(TypeError, match="input_format must be a str"):
        condt.read_points(path, input_format=1)


def test_read_points_refuses_columns_it_would_have_to_guess(tmp_path):
    path = tmp_path / "survey.csv"
    path.write_text("FID,Shape_X,Shape_Y\n1,2,3\n")
    # Ints: Python counts from 0, the command line and every message from 1.
    for columns in [(1, 2), ("Shape_X", 2), np.array([1, 2])]:
        with pytest.raises(TypeError, match="would be a guess"):
            condt.read_points(path, columns=columns)
    for columns, error in [
        (("Shape_X",), ValueError),
        (("Shape_X", "Shape_Y", "FID"), ValueError),
        (("Shape_X", " "), ValueError),
        (("Shape_X", "shape_x"), ValueError),
        ("Shape_X", ValueError),
        ("0,1", ValueError),
        (("Shape_X", 2.0), TypeError),
        ({"x": "Shape_X", "y": "Shape_Y"}, TypeError),
        (3, TypeError),
    ]:
        with pytest.raises(error):
            condt.read_points(path, columns=columns)
    # Bytes are no pair of names (they were read as numbers, one per byte).
    for columns in (b"Shape_X,Shape_Y", bytearray(b"xy")):
        with pytest.raises(TypeError, match=f"not {type(columns).__name__}$"):
            condt.read_points(path, columns=columns)
    # Without columns, the reader's advice names this function's keywords, not the command
    # line's options.
    with pytest.raises(ValueError, match=r"with columns=\(\"X\", \"Y\"\)") as raised:
        condt.read_points(path)
    assert "--columns" not in str(raised.value)
    assert condt.read_points(path, columns=("Shape_X", "Shape_Y")).tolist() == [[2, 3]]
    lines = tmp_path / "two.json"
    lines.write_text('{"type": "Point", "coordinates": [0, 0]}\n'
                     '{"type": "Point", "coordinates": [1, 0]}\n')
    with pytest.raises(ValueError, match='input_format="geojsonl"') as raised:
        condt.read_points(lines)
    assert "--input-format" not in str(raised.value)
    assert condt.read_points(lines, input_format="geojsonl").tolist() == [[0, 0], [1, 0]]


def test_read_points_warns_of_features_that_give_no_point(tmp_path):
    # Row i is no longer the i-th feature: as the command line's note, a warning says so.
    def feature(geometry):
        return {"type": "Feature", "properties": {}, "geometry": geometry}

    path = tmp_path / "holes.geojson"
    features = [
        feature(None),
        feature({"type": "Point", "coordinates": [0, 0]}),
        feature({"type": "Point", "coordinates": []}),
        feature({"type": "MultiPoint", "coordinates": []}),
        feature({"type": "Point", "coordinates": [1, 0]}),
        feature(None),
    ]
    path.write_text(json.dumps({"type": "FeatureCollection", "features": features}))
    with pytest.warns(UserWarning) as warned:
        points = condt.read_points(path)
    assert points.tolist() == [[0, 0], [1, 0]]
    assert [str(w.message) for w in warned] == [
        f"{path}: skipped 2 features with a null geometry and 2 empty Points or MultiPoints: "
        "they hold no point, so row i is not the i-th feature"
    ]
    whole = tmp_path / "whole.geojson"
    whole.write_text(json.dumps({"type": "FeatureCollection", "features": features[1:2]}))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert condt.read_points(whole).tolist() == [[0, 0]]


def test_curve_coordinates_are_read_only_as_every_result_array():
    square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
    curve = condt.reconstruct(square).curves[0]
    assert not curve.coords.flags.writeable and not curve.points.flags.writeable
    with pytest.raises(ValueError):
        curve.coords[0, 0] = 5.0
    # Each row the coordinates of the point at that place along the curve.
    assert curve.coords.tolist() == [square[i] for i in curve.points.tolist()]


def test_merged_duplicates_and_stage_points_account_for_every_point():
    # A researcher's review: duplicates were in no edge, curve or `unused`, and after smoothing
    # passes the stages' numbers were measured on positions no attribute gave.
    rng = np.random.default_rng(5)
    t = np.linspace(0, 2 * np.pi, 80, endpoint=False)
    circle = np.column_stack([np.cos(t), np.sin(t)]) + rng.normal(0, 0.03, (80, 2))
    points = np.concatenate([circle, circle[[3, 3, 40]], [[5.0, 5.0], [5.0, 5.0]]])
    r = condt.reconstruct(points)
    assert r.merged.tolist() == [[80, 3], [81, 3], [82, 40], [84, 83]]
    assert not r.merged.flags.writeable
    used = set(np.unique(r.edges).tolist())
    duplicates = dict(r.merged.tolist())
    # Every position is on an edge, unused, or a duplicate of one that is on an edge.
    for i in range(len(points)):
        first = duplicates.get(i, i)
        assert (first in used) != (i in set(r.unused.tolist())), i
    assert r.passes > 0
    moved = r.stage_points
    assert moved.shape == points.shape and not moved.flags.writeable
    assert not np.array_equal(moved, points), "the passes moved the noisy circle"
    assert np.array_equal(condt.reconstruct(points, smooth=False).stage_points, points)


def test_results_copy_as_themselves():
    import copy

    r = condt.reconstruct([(0, 0), (1, 0), (0, 1)])
    tri = condt.triangulate([(0, 0), (1, 0), (0, 1)])
    for value in (r, r.curves[0], r.explain(0, 1), tri):
        assert copy.copy(value) is value and copy.deepcopy(value) is value
    assert copy.deepcopy({"result": r})["result"] is r
    # A story's dicts and lists are the caller's (a user review changed a "deep copy" of one,
    # which was the story itself, and so the story): each read gives new ones.
    story = condt.reconstruct([(0, 0), (1, 0), (2, 0), (2, 9)]).explain(3, 0)
    told = (story.ends, story.changes, story.text)
    story.ends[0]["choice"] = "edited"
    story.changes.append("edited")
    assert (story.ends, story.changes, story.text) == told
    assert story.ends[0]["choice"] != "edited" and "edited" not in story.changes


@pytest.mark.skipif(not hasattr(os, "fork"), reason="no fork on this platform")
@pytest.mark.filterwarnings("ignore:.*fork")
def test_a_forked_child_and_its_own_child_run_the_parallel_paths():
    # A user review: after one parallel call in the parent, a child forked from it (as
    # `multiprocessing.Pool` forks on Linux) waited forever in `triangulate`, since fork copies
    # rayon's pool without its threads. Each child now starts threads of its own. The pool
    # starts at 65,536 points: with fewer (20,000, as this test had) the parent has none to pass
    # on, and a child that kept the copied pool passed (a tests audit).
    t = np.linspace(0, 2 * np.pi, 70_000, endpoint=False)
    points = np.column_stack([np.cos(t), np.sin(3 * t) / 3])
    triangles = condt.triangulate(points).triangles
    result = condt.reconstruct(points)
    geojson = result.to_geojson()

    def same_in_a_child(depth):
        pid = os.fork()
        if pid == 0:
            status = 3
            try:
                signal.alarm(120)  # a hang ends the child (status from the signal), not the test
                same = (
                    np.array_equal(condt.triangulate(points).triangles, triangles)
                    and np.array_equal(condt.reconstruct(points).edges, result.edges)
                    and condt.reconstruct(points).to_geojson() == geojson
                )
                status = 0 if same and (depth == 0 or same_in_a_child(depth - 1)) else 1
            finally:
                os._exit(status)
        _, status = os.waitpid(pid, 0)
        return os.WIFEXITED(status) and os.WEXITSTATUS(status) == 0

    assert same_in_a_child(1)



def test_signal_handlers_run_while_a_long_reconstruction_runs():
    """Ctrl-C's handler (and any other) runs between the steps of a long call, so that its
    KeyboardInterrupt ends the call from inside. Signals that arrive while no handler can run
    count as one: a call that ran handlers only while it read its arguments and once it had
    returned (as before: on 1M points a SIGINT sent 1 s in waited until 7.1 s) ran this one at
    most three times (before, after, and once more before the sender stops); at its steps it runs about
    every 50 ms of the run, which lasts well over a second here. The handler only counts: one
    that raised could raise again outside any `try` while the sender stops."""
    points = np.random.default_rng(5).random((400_000, 2))
    calls = []
    done = threading.Event()

    def send():
        while not done.wait(0.005):
            os.kill(os.getpid(), signal.SIGUSR1)

    previous = signal.signal(signal.SIGUSR1, lambda signum, frame: calls.append(signum))
    sender = threading.Thread(target=send)
    try:
        sender.start()
        condt.reconstruct(points)
    finally:
        done.set()
        sender.join()
        signal.signal(signal.SIGUSR1, previous)
    assert len(calls) >= 5, calls


def test_the_docs_say_a_call_off_the_main_thread_runs_to_its_end():
    """A Python user's review: Ctrl-C during a call made on a ``ThreadPoolExecutor``'s thread
    (2M scattered points) raised ``KeyboardInterrupt`` in the main thread, whose executor
    shutdown then waited 16 s for the call; the docs said only a forked child's call runs to its
    end. Python runs signal handlers on its main thread only, so no check in a call elsewhere
    finds Ctrl-C."""
    said = "a call made on another thread runs to its end"
    assert said in " ".join(condt.reconstruct.__doc__.split())
    readme = pathlib.Path(__file__).resolve().parents[1] / "README.md"
    if readme.exists():
        assert "a call made on another thread than the main one" in " ".join(
            readme.read_text().split()
        )


def test_score_warns_of_a_truth_at_a_later_copy_of_a_point():
    # A Python researcher's review: a ring exported with its first point again at its end,
    # scored against its truth as a polyline, lost an edge without a word.
    t = np.linspace(0, 2 * np.pi, 13)[:12]
    ring = np.vstack([np.c_[np.cos(t), np.sin(t)], [[1.0, 0.0]]])
    truth = np.c_[np.arange(12), np.arange(1, 13)]
    output = condt.reconstruct(ring).edges
    with pytest.warns(UserWarning, match=r"the truth names 1 point that repeats an earlier point exactly \(12 = 0\)"):
        s = condt.score(ring, output, truth)
    assert (s["fp"], s["fn"]) == (1, 1)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        condt.score(ring, output, output)



def test_a_dataframe_of_more_than_two_columns_is_told_to_pass_its_coordinates():
    # A name or a z column beside x and y said only "not str" or pointed at NumPy's
    # points[:, :2], which a DataFrame does not take.
    pd = pytest.importorskip("pandas")
    xy = {"x": [0.0, 1.0, 0.5], "y": [0.0, 0.0, 1.0]}
    for extra in ({"name": ["a", "b", "c"]}, {"z": [1.0, 2.0, 3.0]}):
        table = pd.DataFrame({**extra, **xy})
        with pytest.raises((TypeError, ValueError), match=re.escape('df[["x", "y"]]')):
            condt.reconstruct(table)
        # What the message advises works.
        assert condt.reconstruct(table[["x", "y"]]).edges.shape == (3, 2)
