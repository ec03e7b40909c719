//! The native module of the `condt` Python package, `condt._condt` (PyO3, the `numpy` crate,
//! built by maturin; `python/pyproject.toml`). The package `python/python/condt` re-exports it.
//!
//! Owns: the Python functions and classes, their arguments and their errors. It may not compute
//! geometry (but `tiles`' certificate, which tests circles against a tile and the hull) nor
//! decide a parameter's range: `condt`, `condt-io` and `condt-eval` do, so the
//! package gives what the command line gives. Modules: `convert` (NumPy in and out, errors),
//! `params` (the keywords), `reconstruction` and `triangulation` (the result classes), `tiles`
//! (`condt.dask`'s native half: the plan, a tile's certificate and its rounds).

// The command line's allocator, which recycles the pipeline's large blocks instead of faulting
// fresh pages in for each (a third of the page faults, a tenth of the time at 1M points along
// curves: python/README.md has the figures), in its scoped form: it keeps freed pages only
// while a call runs, so the Python process holds none between calls.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
#[global_allocator]
static ALLOCATOR: condt_alloc::Recycling = condt_alloc::Recycling::scoped();

/// Runs `work` as one call of the allocator (see above): the large blocks it frees are reused by
/// its later ones, and unmapped when it ends.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
pub(crate) fn within_call<T>(work: impl FnOnce() -> T) -> T {
    ALLOCATOR.within_call(work)
}

/// Elsewhere the system allocator serves everything: `work` runs as it is.
#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
pub(crate) fn within_call<T>(work: impl FnOnce() -> T) -> T {
    work()
}

/// `work` without the GIL, on threads that exist ([`on_live_threads`]): every call that may
/// reach the library's parallel code runs so.
///
/// # Errors
/// `RuntimeError` in a forked child that cannot start threads of its own.
pub(crate) fn detached<T: Send>(py: Python<'_>, work: impl FnOnce() -> T + Send) -> PyResult<T> {
    py.detach(|| on_live_threads(work))
}

/// The process that imported the module, whose rayon threads the calls use.
static LOADED_IN: OnceLock<u32> = OnceLock::new();

/// Runs `work` where rayon's threads run. `fork` copies only the calling thread, so a child
/// forked after its parent started rayon's global pool (on Linux, `multiprocessing`'s default
/// before Python 3.14) holds that pool without its threads, and its first parallel step would
/// wait forever: a user review found `multiprocessing.Pool` workers hanging in `triangulate`.
/// In such a child, `work` runs in a pool of the child's own, started at its first call (the
/// result is the same: the parallel paths give the sequential results). Where the child cannot
/// start a thread, an error instead of the wait.
pub(crate) fn on_live_threads<T: Send>(work: impl FnOnce() -> T + Send) -> PyResult<T> {
    let pid = std::process::id();
    if *LOADED_IN.get_or_init(|| pid) == pid {
        return Ok(work());
    }
    match childs_pool(pid) {
        Some(pool) => Ok(pool.install(work)),
        None => Err(PyRuntimeError::new_err(
            "this process was forked from one that had started condt's threads, and cannot \
             start threads of its own: use the spawn start method of multiprocessing",
        )),
    }
}

/// The pool of the forked child `pid`, started at its first call. It is built outside the lock,
/// so that a fork from another thread meanwhile leaves its child no lock held; a pool inherited
/// from the parent (a child that forks again) is forgotten, not dropped: its threads are not in
/// this process, and dropping it would wait on their state as the fork copied it.
fn childs_pool(pid: u32) -> Option<Arc<rayon::ThreadPool>> {
    static CHILDS_POOL: Mutex<Option<(u32, Arc<rayon::ThreadPool>)>> = Mutex::new(None);
    let kept = |lock: &Mutex<Option<(u32, Arc<rayon::ThreadPool>)>>| {
        let held = lock.lock().unwrap_or_else(PoisonError::into_inner);
        match &*held {
            Some((owner, pool)) if *owner == pid => Some(Arc::clone(pool)),
            _ => None,
        }
    };
    if let Some(pool) = kept(&CHILDS_POOL) {
        return Some(pool);
    }
    let built = Arc::new(rayon::ThreadPoolBuilder::new().build().ok()?);
    let mut held = CHILDS_POOL.lock().unwrap_or_else(PoisonError::into_inner);
    match &*held {
        // Another thread of this child built one first: that one serves (this one is dropped,
        // its threads being this process's own).
        Some((owner, pool)) if *owner == pid => Some(Arc::clone(pool)),
        _ => {
            if let Some(inherited) = held.replace((pid, Arc::clone(&built))) {
                core::mem::forget(inherited);
            }
            Some(built)
        }
    }
}

mod convert;
mod params;
mod reconstruction;
mod tiles;
mod triangulation;

use condt::Pipeline;
use condt_eval::score::{EdgeProblem, ScoreError};
use condt_io::{Column, Columns, InputFormat, IoErrorKind, ReadOptions};
use convert::{as_points, io_error, library_error, points_array, shape_text};
use numpy::ndarray::Array2;
use numpy::{PyArray2, PyArrayMethods, PyUntypedArray};
use params::type_name;
use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyUserWarning, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyByteArray, PyBytes, PyDict, PyInt, PyList, PyString, PyTuple};
use reconstruction::{Curve, EdgeStory, Reconstruction};
use std::ffi::CString;
use std::path::PathBuf;
use std::sync::{Arc, Mutex, OnceLock, PoisonError};
use std::time::{Duration, Instant};
use triangulation::Triangulation;

/// The curves through the points: ConDT's reconstruction, as ``condt reconstruct`` runs it.
///
/// ``points`` is any ``(n, 2)`` array-like of numbers, integers or floats (an empty sequence is
/// no points). A C-contiguous float64 ndarray is copied once, without the GIL, as the work
/// starts (16 bytes a point, which the result keeps); anything else is converted first. The work
/// runs on that copy without the GIL, so other Python threads run meanwhile, and changing the
/// array, during the call or afterwards, changes nothing in the result; Ctrl-C
/// (``KeyboardInterrupt``, or an exception from another signal handler) stops it at the end of
/// the stage it is in, or after the first stage when it comes during the triangulation (about
/// 0.3 s on a million scattered points). Python runs signal handlers on its main thread only:
/// a call made on another thread runs to its end (a ``ThreadPoolExecutor``'s shutdown waits for
/// it after the main thread's ``KeyboardInterrupt``), and so does one in a forked child.
///
/// An array whose dtype is not an integer or a float (complex, bool, str, bytes, datetime64,
/// timedelta64) is refused: numpy would convert it quietly into other numbers. What numpy makes
/// of a list decides (``numpy.asarray``): a list of Python numbers is fine, of bools it is not,
/// and a bool among a list's numbers is refused too (numpy would read it as a number).
/// An object array (``Decimal`` or ``Fraction`` values, which numpy leaves as objects) is
/// converted by each value's ``float()``, unless it holds a value of one of the refused kinds.
/// A float array wider than float64 (``numpy.longdouble``) is taken when float64 holds all its
/// values exactly (an array made from doubles), and refused when it would round one, since two
/// points might become one (``points.astype(float)`` accepts the rounding), as integers beyond
/// 2^53 are.
///
/// The parameters are the command line's options, ``-`` written ``_``: ``paper=True`` starts
/// from the paper's pipeline instead of the default, and the keywords adjust it: ``u`` (a
/// number) or ``adaptive=True``; ``iqr`` (a number, or ``None`` to skip the outlier removal,
/// as ``outlier_filter=False`` does); ``outliers_first``; ``iqr_floor``, ``repair_again``, ``local_outliers``, ``clumps``,
/// ``confirm_given_back``, ``close_gaps``, ``junctions``, ``crossings``, ``tips``, ``spikes``, ``hooks``, ``tails``, ``detours``, ``smooth`` (True or False); ``repair`` (``"needs"``,
/// ``"paper"``, ``"mutual"``, ``"crossing"`` or ``"off"``; ``manifold_fix=False`` is ``"off"``);
/// ``method`` (``"condt"``, ``"nn-crust"`` or ``"crust"``, a baseline taking none of the
/// others); ``sequential=True`` runs on one thread (same result).
///
/// Raises ``ValueError`` for a point with a NaN or infinite coordinate (named by its index and
/// row), a finite one beyond float64's range (an int, a long double or a ``Decimal``; named by
/// its index), an integer coordinate beyond 2^53 (where float64 holds only some integers; any
/// is refused, even one it holds) or a long-double one that is no float64 (float64 would round
/// it; both named by their row), two
/// points nearer than 2^-450 times the largest coordinate (too close for the stages to measure;
/// named by their positions), a value the library refuses (an int too large for a float is
/// infinite, and refused as such) or two keywords that contradict each other (``u=2, adaptive=True``; ``iqr=1.5`` or
/// ``iqr=None`` against ``outlier_filter=False`` or ``True``; a ``repair`` mode or ``"off"``
/// against ``manifold_fix=False`` or ``True``), and ``TypeError`` for points that are not
/// numbers, an unknown keyword or a value of the wrong type. Warns (``UserWarning``) of pairs
/// of points that look like points given twice a little apart
/// (``Reconstruction.twin_pairs``), which ``condt.snap`` would merge (``condt.dask`` does
/// not: its result has edges only).
///
/// >>> import condt, numpy as np
/// >>> t = np.linspace(0, 2 * np.pi, 40, endpoint=False)
/// >>> circle = np.column_stack([np.cos(t), np.sin(t)])
/// >>> r = condt.reconstruct(circle)
/// >>> len(r.curves), r.curves[0].closed, len(r.edges)
/// (1, True, 40)
/// >>> condt.reconstruct(circle, paper=True, u=2.0, iqr=None).edges.shape
/// (40, 2)
/// >>> condt.reconstruct([(0, 0), (1, float("nan"))])
/// Traceback (most recent call last):
///     ...
/// ValueError: point 1 has a NaN or infinite coordinate: row 1 of the points is [1.0, nan]
/// >>> condt.reconstruct([(0, 0), (1, 1j)])
/// Traceback (most recent call last):
///     ...
/// TypeError: points must hold numbers (integers or floats), not dtype complex128
// `paper` is read with the other keywords (`params::params`), so that a value of the wrong type
// is refused with its name as theirs are ("paper must be True or False, not int"), not by
// PyO3's own message naming no parameter.
#[pyfunction]
#[pyo3(signature = (points, **params))]
fn reconstruct(
    py: Python<'_>,
    points: &Bound<'_, PyAny>,
    params: Option<&Bound<'_, PyDict>>,
) -> PyResult<Reconstruction> {
    let params = params::params(params)?;
    let array = points_array(py, points)?;
    let borrowed = array.try_readonly()?;
    let points = as_points(borrowed.as_slice()?);
    // The work runs on a copy of the points, made first, which the result then keeps (GeoJSON,
    // shapely and `Curve.coords` read it later). Reading the caller's array during the work
    // instead let another thread's write meanwhile change the points under the triangulation: a
    // NaN written and put back made the point location walk forever, where Ctrl-C is not checked
    // (a Python user's review: a call on 300,000 points still running after a SIGINT at 40 s).
    // The result kept a copy anyway, made after the work: copied first, the call copies no more
    // than it did. The copy is made holding the GIL, so that no write from Python code (which
    // needs the GIL) overlaps it: made without it, such a write was a data race on `points`
    // (undefined behaviour, not only a torn point; a memory-safety review's find). NumPy's own
    // loops release the GIL, so `as_points` says what is left.
    let owned = points.to_vec();
    let (result, owned) = crate::detached(py, || {
        within_call(|| {
            let result = interruptible(&owned, &params)?;
            Ok::<_, PyErr>((result, owned))
        })
    })??;
    // Points given twice a little apart (`Reconstruction.twin_pairs`): a result that reads as
    // success, with a curve of two points or unused points in place of each sample (GIS users'
    // reviews).
    let twins = result.twin_pairs();
    if let Some([a, b]) = twins.first() {
        let message = format!(
            "{} pairs of points that lie 16 times nearer each other than any other point (the \
             first: points {a} and {b}): points given twice, a little apart (a shared border \
             exported from both sides, a grey image's contour)? condt.snap(points, d) merges \
             points within d",
            twins.len()
        );
        user_warning(py, message)?;
    }
    Ok(Reconstruction::new(result, owned))
}

/// The pipeline run to its end, as `condt::reconstruct` runs it, with Python's signal handlers
/// run between its steps once [`SIGNALS_EVERY`] has passed since the last time: Ctrl-C
/// (`KeyboardInterrupt`) stops a long call at the next step, not after the whole run (a user
/// review's find: on 1M scattered points, a SIGINT sent 1 s in was honoured at 7.1 s, when the
/// call ended). The triangulation, the pipeline's first
/// step, runs to its end; the clock starts before it, so a signal during it is acted on at the
/// end of the first stage. Handlers run on the main thread only: in a forked child whose work
/// runs on its own pool's thread ([`on_live_threads`]) the checks find none, and the call runs
/// to its end as before.
fn interruptible(
    points: &[condt::Point],
    params: &condt::Params,
) -> PyResult<condt::Reconstruction> {
    let mut checked = Instant::now();
    let mut pipeline = Pipeline::new(points, params).map_err(|err| library_error(err, points))?;
    while pipeline
        .step()
        .map_err(|err| library_error(err, points))?
        .is_some()
    {
        if checked.elapsed() >= SIGNALS_EVERY {
            Python::attach(|py| py.check_signals())?;
            checked = Instant::now();
        }
    }
    pipeline.finish().map_err(|err| library_error(err, points))
}

/// How often a long call takes the GIL back to run signal handlers: rarely enough that calls on
/// several Python threads at once do not wait on each other for it at every step, often enough
/// that Ctrl-C answers at once to a person.
const SIGNALS_EVERY: Duration = Duration::from_millis(50);

/// The Delaunay triangulation of the points, as ``condt triangulate`` computes it.
///
/// ``points`` as for ``reconstruct`` (copied as the work starts; the GIL is released while it
/// runs; the result holds input positions only, so it does not depend on the array afterwards).
/// Raises ``ValueError`` for a NaN or infinite coordinate,
/// a finite one beyond float64's range, an integer one beyond 2^53 or a long-double one that is
/// no float64 (as ``reconstruct`` does), ``TypeError`` for points that are not numbers.
///
/// >>> import condt
/// >>> t = condt.triangulate([(0, 0), (1, 0), (0, 1), (1, 1)])
/// >>> t.triangles.shape, t.edges.tolist()
/// ((2, 3), [[0, 1], [0, 2], [1, 2], [1, 3], [2, 3]])
#[pyfunction]
fn triangulate(py: Python<'_>, points: &Bound<'_, PyAny>) -> PyResult<Triangulation> {
    let array = points_array(py, points)?;
    let borrowed = array.try_readonly()?;
    let points = as_points(borrowed.as_slice()?);
    // On a copy, made holding the GIL, as `reconstruct` runs: a write to the caller's array from
    // another thread during the work could make the point location walk forever (16 bytes a
    // point while it runs), and one during the copy would race with it.
    let owned = points.to_vec();
    let (tri, owned) = crate::detached(py, || within_call(|| (condt::triangulate(&owned), owned)))?;
    let tri = tri.map_err(|err| library_error(err, &owned))?;
    Ok(Triangulation::new(tri))
}

/// The points with each one within ``distance`` of an earlier point that stays moved onto the
/// nearest such point (the earliest of equally near ones), but for an exact duplicate of an
/// earlier point, which goes where its first copy went even when a point that stays is nearer,
/// as ``condt reconstruct --snap`` does before it runs: a new ``(n, 2)``
/// float64 array (the points given are not changed). The points moved become exact duplicates,
/// which ``reconstruct`` and ``triangulate`` merge into the first of them: use it on data
/// exported piece by piece (parcels ring by ring, a font's contours), whose shared borders
/// repeat with rounding differences, before ``reconstruct`` or ``condt.dask.reconstruct``. A
/// point moves at most ``distance``; NaN and infinite points are left as they are.
///
/// ``points`` as for ``reconstruct``. Raises ``ValueError`` for a NaN, negative or infinite
/// ``distance``, ``TypeError`` for one that is not a number (a bool included).
///
/// >>> import condt
/// >>> condt.snap([(0, 0), (1, 0), (1 + 1e-9, 0)], 1e-6).tolist()
/// [[0.0, 0.0], [1.0, 0.0], [1.0, 0.0]]
/// >>> # Point 3 repeats point 1, which moved onto point 0: it does too, though 2 is nearer.
/// >>> condt.snap([(0, 0), (0.2, 0), (0.3, 0), (0.2, 0)], 0.25).tolist()
/// [[0.0, 0.0], [0.0, 0.0], [0.3, 0.0], [0.0, 0.0]]
#[pyfunction]
fn snap<'py>(
    py: Python<'py>,
    points: &Bound<'py, PyAny>,
    distance: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    // As the keywords' numbers are read: a bool is no distance, and a message names it.
    let distance = params::number("distance", distance)?;
    let array = points_array(py, points)?;
    let mut snapped = as_points(array.try_readonly()?.as_slice()?).to_vec();
    crate::detached(py, || within_call(|| condt::snap(&mut snapped, distance)))?
        .map_err(|err| library_error(err, &[]))?;
    let n = snapped.len();
    let flat: Vec<f64> = snapped.iter().flat_map(|p| [p.x, p.y]).collect();
    let array = Array2::from_shape_vec((n, 2), flat)
        .map_err(|err| PyRuntimeError::new_err(err.to_string()))?;
    Ok(PyArray2::from_owned_array(py, array))
}

/// The points of a file, as an ``(n, 2)`` float64 array: every format ``condt`` reads, told
/// apart by the name's ending (any case): ``.npy`` (float64, float32 or integers up to 2^53),
/// ``.csv`` or ``.tsv``, ``.geojson`` or ``.json``, ``.node`` (Triangle); any other name by its
/// content, a NumPy array or GeoJSON, else plain text (one ``x y`` per line). Row ``i`` is point
/// ``i``, as the command line numbers them.
///
/// ``path`` is a ``str``, ``bytes`` or ``os.PathLike`` (``pathlib.Path``), as ``open`` takes
/// it. A path is always a file: ``"-"`` is the file named ``-`` (the command line reads its
/// standard input for ``-``; this function never does).
///
/// ``input_format`` reads the file in that format whatever its name, as the command line's
/// ``--input-format``: ``"txt"``, ``"node"``, ``"csv"``, ``"tsv"``, ``"npy"``, ``"geojson"`` or
/// ``"geojsonl"``. ``columns`` chooses the x and y columns of a CSV, TSV or plain text file, as
/// ``--columns``: a pair of header names, ``("POINT_X", "POINT_Y")``, or the command line's
/// text, ``"POINT_X,POINT_Y"`` or ``"2,3"`` (numbers count from 1 there, as every message
/// about a column counts; a pair of ints is refused, as its count would be a guess). Without
/// it, the columns the header names ``x`` and ``y`` (or ``lon`` and ``lat``, ...) are read.
///
/// Raises ``OSError`` (``FileNotFoundError``, ``PermissionError``, ...) when the file cannot be
/// read, ``ValueError`` naming the file and line when its content is not a point file (or the
/// columns are not in it, or the file is read in another format than CSV, TSV or plain text), and
/// ``TypeError`` when ``path`` is not a path or ``columns`` not columns. A GeoJSON sequence
/// (``.geojsonl``) whose later record carries another ``crs`` than the first warns
/// (``UserWarning``, naming the file and the record's line; ``read_points_with_crs`` gives the
/// first), its points read as given. GeoJSON features whose geometry is ``null``, and empty
/// Points or MultiPoints, give no row, and a ``UserWarning`` says how many: row ``i`` is then
/// not the ``i``-th feature. A file in longitudes and latitudes (a CSV's ``lon`` and ``lat``
/// columns, GeoJSON without a projected ``crs``) beyond 18 degrees of latitude warns
/// (``UserWarning``), as ``condt reconstruct`` notes it: its points are plane coordinates to
/// ``reconstruct``, where an east-west gap counts 1/cos(latitude) times as long as a
/// north-south one of the same metres; project them first (python/README.md, *GeoPandas*).
///
/// >>> import condt, tempfile, os
/// >>> path = os.path.join(tempfile.mkdtemp(), "pts.txt")
/// >>> with open(path, "w") as f:
/// ...     _ = f.write("# x y\n0 0\n1.5 2\n")
/// >>> condt.read_points(path).tolist()
/// [[0.0, 0.0], [1.5, 2.0]]
/// >>> path = os.path.join(tempfile.mkdtemp(), "survey.txt")
/// >>> with open(path, "w") as f:
/// ...     _ = f.write("FID,POINT_X,POINT_Y\n1,2600000.5,1200000\n")
/// >>> condt.read_points(path, input_format="csv", columns=("POINT_X", "POINT_Y")).tolist()
/// [[2600000.5, 1200000.0]]
#[pyfunction]
#[pyo3(signature = (path, *, columns = None, input_format = None))]
fn read_points<'py>(
    py: Python<'py>,
    path: &Bound<'py, PyAny>,
    columns: Option<&Bound<'py, PyAny>>,
    input_format: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let options = read_options(columns, input_format)?;
    read_point_file(py, path, &options).map(|(points, _, _)| points)
}

/// The reading options of ``read_points``' keywords, checked: a known format name, and columns
/// as a pair of names or the command line's ``X,Y`` text.
fn read_options(
    columns: Option<&Bound<'_, PyAny>>,
    input_format: Option<&Bound<'_, PyAny>>,
) -> PyResult<ReadOptions> {
    let mut options = ReadOptions::new();
    if let Some(given) = input_format {
        let names = InputFormat::ALL.map(InputFormat::name).join(", ");
        let name: String = given.extract().map_err(|_| {
            PyTypeError::new_err(format!(
                "input_format must be a str, one of {names}, not {}",
                type_name(given)
            ))
        })?;
        let format = InputFormat::named(&name).ok_or_else(|| {
            PyValueError::new_err(format!(
                "input_format {name:?}: unknown input format; the formats are {names}"
            ))
        })?;
        options = options.with_format(format);
    }
    if let Some(given) = columns {
        let chosen = if let Ok(text) = given.extract::<String>() {
            Columns::parse(&text).map_err(|why| PyValueError::new_err(format!("columns {why}")))?
        } else {
            // A dict's keys, or bytes' numbers, are no pair of columns (a user review: b"x,y"
            // was read as seven numbers).
            let not_a_pair = given.is_instance_of::<PyDict>()
                || given.is_instance_of::<PyBytes>()
                || given.is_instance_of::<PyByteArray>();
            let pair: Vec<Bound<'_, PyAny>> = match given.extract() {
                Ok(items) if !not_a_pair => items,
                _ => {
                    return Err(PyTypeError::new_err(format!(
                        "columns must be a pair of header names, (\"POINT_X\", \"POINT_Y\"), or \
                         the command line's text, \"POINT_X,POINT_Y\" or \"2,3\", not {}",
                        type_name(given)
                    )))
                }
            };
            let name = |item: &Bound<'_, PyAny>| -> PyResult<Column> {
                // An int, a numpy integer: anything with `__index__` that is not a name.
                if !item.is_instance_of::<PyString>() && item.hasattr("__index__")? {
                    return Err(PyTypeError::new_err(format!(
                        "columns: {item} is a number, and whether it counts from 0 or from 1 \
                         would be a guess; give the command line's text, \"2,3\" for the \
                         second and third columns (counted from 1), or header names"
                    )));
                }
                let text: String = item.extract().map_err(|_| {
                    PyTypeError::new_err(format!(
                        "columns: a column is a header name (str), not {}",
                        type_name(item)
                    ))
                })?;
                if text.trim().is_empty() {
                    return Err(PyValueError::new_err("columns: an empty column name"));
                }
                Ok(Column::Named(text))
            };
            let [x, y] = &pair[..] else {
                return Err(PyValueError::new_err(format!(
                    "columns must be two, x and y, not {}",
                    pair.len()
                )));
            };
            Columns {
                x: name(x)?,
                y: name(y)?,
            }
        };
        options = options.with_columns(chosen);
    }
    Ok(options)
}

/// ``read_points(path)``, and the file's coordinate reference system: a tuple ``(points,
/// crs)``, ``crs`` the top-level ``"crs"`` member of a GeoJSON input as written (or, where it
/// has none, its first feature's; JSON text, as
/// GDAL and QGIS read it to place projected coordinates) and ``None`` for every other file.
/// ``Reconstruction.to_geojson(crs=crs)`` carries it on, as ``condt reconstruct`` does from a
/// GeoJSON input to a GeoJSON output. A member that no GeoJSON output can carry (``4326``,
/// ``[1, 2]``: neither an object, a name nor ``null``) gives ``None`` and a ``UserWarning``
/// saying why, as the command line notes it and writes its output without one.
///
/// Takes ``read_points``' keywords, raises what it raises, and warns as it warns.
///
/// >>> import condt, json, tempfile, os
/// >>> path = os.path.join(tempfile.mkdtemp(), "utm.geojson")
/// >>> with open(path, "w") as f:
/// ...     _ = f.write('{"type": "FeatureCollection", "crs": {"type": "name", '
/// ...                 '"properties": {"name": "EPSG:32632"}}, "features": ['
/// ...                 '{"type": "Feature", "properties": {}, "geometry": '
/// ...                 '{"type": "MultiPoint", "coordinates": [[500000, 4e6], [500010, 4e6]]}}]}')
/// >>> points, crs = condt.read_points_with_crs(path)
/// >>> points.tolist(), json.loads(crs)["properties"]["name"]
/// ([[500000.0, 4000000.0], [500010.0, 4000000.0]], 'EPSG:32632')
#[pyfunction]
#[pyo3(signature = (path, *, columns = None, input_format = None))]
fn read_points_with_crs<'py>(
    py: Python<'py>,
    path: &Bound<'py, PyAny>,
    columns: Option<&Bound<'py, PyAny>>,
    input_format: Option<&Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, PyArray2<f64>>, Option<String>)> {
    let options = read_options(columns, input_format)?;
    let (points, crs, shown) = read_point_file(py, path, &options)?;
    // As the command line takes it to a GeoJSON output: what `to_geojson` would refuse is left
    // out with a warning here, not handed on to fail there (a GIS user's review).
    let Some(raw) = crs else {
        return Ok((points, None));
    };
    if let Err(why) = condt_io::crs_member(&raw) {
        let message = format!("{shown}: its crs member {why}; None is returned for it");
        user_warning(py, message)?;
        return Ok((points, None));
    }
    Ok((points, Some(raw)))
}

/// The points of the file at `path` (as `open` takes it) read with `options`, its GeoJSON crs
/// as written, and the file's name as messages show it; a `UserWarning` naming the file and line of a GeoJSON sequence's later record whose
/// different crs was left out, and one for the features that gave no point (the command line's
/// notes).
fn read_point_file<'py>(
    py: Python<'py>,
    path: &Bound<'py, PyAny>,
    options: &ReadOptions,
) -> PyResult<(Bound<'py, PyArray2<f64>>, Option<String>, String)> {
    // `os.fsdecode` takes what `open` takes (str, bytes, os.PathLike of either) and gives a str
    // whose undecodable bytes are escaped, which becomes the same bytes again as an `OsString`.
    let decoded = py
        .import("os")?
        .call_method1("fsdecode", (path,))
        .map_err(|err| {
            if err.is_instance_of::<PyTypeError>(py) {
                PyTypeError::new_err(format!(
                    "path must be a str, bytes or os.PathLike, not {}",
                    type_name(path)
                ))
            } else {
                err
            }
        })?;
    let given: PathBuf = decoded.extract()?;
    // `condt_io::read_points` reads standard input for `-`, the command line's convention; from
    // Python that would block a notebook on a terminal it does not show. `./-` is the file.
    let stdin_name = given.as_os_str() == "-";
    let path = if stdin_name {
        PathBuf::from("./-")
    } else {
        given
    };
    let file = crate::detached(py, || {
        within_call(|| condt_io::read_points_with(&path, options))
    })?
    .map_err(|mut err| {
        // Named as given, in the message and in `OSError.filename`.
        if stdin_name {
            err.file = "-".into();
        }
        if let IoErrorKind::Content(message) = &mut err.kind {
            *message = keyword_advice(message);
        }
        io_error(err)
    })?;
    let condt_io::PointFile {
        points,
        crs,
        crs_dropped_at,
        null_geometries,
        empty_geometries,
        degrees,
        ..
    } = file;
    let shown = if stdin_name {
        "-".into()
    } else {
        path.display().to_string()
    };
    if let Some(skipped) = skipped_geometries(null_geometries, empty_geometries) {
        let message = format!(
            "{shown}: skipped {skipped}: they hold no point, so row i is not the i-th feature"
        );
        user_warning(py, message)?;
    }
    if let Some(line) = crs_dropped_at {
        let message = format!(
            "{shown}:{line}: this crs differs from the one kept (the document's own, else \
             the first one read), and every point is read as given, without conversion"
        );
        user_warning(py, message)?;
    }
    let degrees = degrees.then(|| condt_io::Degrees::of(&points)).flatten();
    let see = "GeoPandas: gdf.to_crs(gdf.estimate_utm_crs()); python/README.md, *GeoPandas*";
    for said in degrees
        .map(|degrees| degrees.notes(see))
        .unwrap_or_default()
    {
        let message = format!("{shown}: {said}");
        user_warning(py, message)?;
    }
    let n = points.len();
    // Into the points' own memory (same size and alignment: the collect reuses it), not a
    // second list beside them.
    let flat: Vec<f64> = points
        .into_iter()
        .map(|p| [p.x, p.y])
        .collect::<Vec<[f64; 2]>>()
        .into_flattened();
    let array = Array2::from_shape_vec((n, 2), flat)
        .map_err(|err| PyRuntimeError::new_err(err.to_string()))?;
    Ok((PyArray2::from_owned_array(py, array), crs, shown))
}

/// A `UserWarning` saying `message`, shown at the caller's line (stack level 1).
pub(crate) fn user_warning(py: Python<'_>, message: String) -> PyResult<()> {
    PyErr::warn(
        py,
        &py.get_type::<PyUserWarning>(),
        &CString::new(message)?,
        1,
    )
}

/// A reader's message with its advice in this function's keywords: the readers advise the
/// command line's options (`condt's --columns X,Y`, `condt's --input-format csv`).
fn keyword_advice(message: &str) -> String {
    let message = message.replace(
        "condt's --columns X,Y",
        "columns=(\"X\", \"Y\") (or \"2,3\", counted from 1)",
    );
    let option = "condt's --input-format ";
    let mut advised = String::with_capacity(message.len());
    let mut rest = message.as_str();
    while let Some(at) = rest.find(option) {
        advised.push_str(&rest[..at]);
        let after = &rest[at + option.len()..];
        let name_len = after
            .find(|c: char| !c.is_ascii_alphanumeric())
            .unwrap_or(after.len());
        advised.push_str(&format!("input_format=\"{}\"", &after[..name_len]));
        rest = &after[name_len..];
    }
    advised.push_str(rest);
    advised
}

/// The GeoJSON features that gave no point, in words (the command line's note), or `None`.
fn skipped_geometries(null: usize, empty: usize) -> Option<String> {
    let mut skipped = Vec::new();
    match null {
        0 => {}
        1 => skipped.push("1 feature with a null geometry".to_string()),
        n => skipped.push(format!("{n} features with a null geometry")),
    }
    match empty {
        0 => {}
        1 => skipped.push("1 empty Point or MultiPoint".to_string()),
        n => skipped.push(format!("{n} empty Points or MultiPoints")),
    }
    (!skipped.is_empty()).then(|| skipped.join(" and "))
}

/// An edge list as given: each end as `i64`, and the text of each end no `i64` holds (a uint64
/// or a Python int of `2**63` or more, or below `-2**63`), which is kept as `i64::MAX` (or
/// `i64::MIN`): out of range as any index no point has, and named as given in messages.
struct EdgeRows {
    rows: Vec<[i64; 2]>,
    /// `(row, end, value as given)`, in row order.
    beyond: Vec<(usize, usize, String)>,
}

impl EdgeRows {
    /// End `end` of row `row` as given, for messages.
    fn text(&self, row: usize, end: usize) -> String {
        self.beyond
            .iter()
            .find(|&&(r, e, _)| r == row && e == end)
            .map_or_else(|| self.rows[row][end].to_string(), |(_, _, t)| t.clone())
    }
}

/// Whether `value` is an integer: a Python int (not a bool) or a numpy integer
/// (`numpy_integer`, `numpy.integer`, looked up once by the caller).
fn is_integer(numpy_integer: &Bound<'_, PyAny>, value: &Bound<'_, PyAny>) -> PyResult<bool> {
    Ok(
        (value.is_instance_of::<PyInt>() && !value.is_instance_of::<PyBool>())
            || value.is_instance(numpy_integer)?,
    )
}

/// An edge list as given (`name` for messages): an `(m, 2)` array-like of integers.
///
/// A value no `i64` holds is kept (`EdgeRows`), not wrapped: numpy's cast of a uint64 above
/// `2**63 - 1` to int64 wraps it to a negative number, which would be reported as another index.
/// A list holding such a value is one numpy makes float64 (`[0, 2**63]`) or object (`2**64`):
/// it is read again as Python ints.
fn edge_rows(py: Python<'_>, name: &str, edges: &Bound<'_, PyAny>) -> PyResult<EdgeRows> {
    let numpy = py.import("numpy")?;
    let mut array = numpy.call_method1("asarray", (edges,))?;
    // None and scalars are the wrong type, not a wrong shape, as for the points.
    if edges.is_none() || array.getattr("ndim")?.extract::<usize>()? == 0 {
        return Err(PyTypeError::new_err(format!(
            "{name} must be an array-like of shape (m, 2), not {}",
            edges.get_type().name()?
        )));
    }
    let size: usize = array.getattr("size")?.extract()?;
    let mut read = EdgeRows {
        rows: Vec::new(),
        beyond: Vec::new(),
    };
    if size == 0 {
        // No edges: an empty sequence (shape (0,)) or an empty (0, 2) array; any other empty
        // shape, such as (0, 3) or (5, 0), is the wrong shape as it would be with rows.
        let shape: Vec<usize> = array.getattr("shape")?.extract()?;
        if !matches!(shape.as_slice(), [0] | [0, 2]) {
            return Err(PyValueError::new_err(format!(
                "{name} must be an array of shape (m, 2); got one of shape {}",
                shape_text(&shape)
            )));
        }
        return Ok(read);
    }
    let dtype = array.getattr("dtype")?.str()?.to_string();
    let not_integers = || {
        PyTypeError::new_err(format!(
            "{name} must be an (m, 2) array of integers (point indices); got dtype {dtype}"
        ))
    };
    let mut kind: String = array.getattr("dtype")?.getattr("kind")?.extract()?;
    // A list or tuple is read element by element, as Python objects: numpy would turn a bool
    // among ints into 0 or 1 (`[(True, 2)]` is an int64 array), which is a mistake, not a
    // position. Other array-likes (pandas, torch) keep numpy's dtype: a bool array is refused
    // by its dtype.
    let sequence = edges.is_instance_of::<PyList>() || edges.is_instance_of::<PyTuple>();
    if kind != "O"
        && (sequence || (kind != "i" && kind != "u"))
        && edges.cast::<PyUntypedArray>().is_err()
    {
        let kwargs = PyDict::new(py);
        kwargs.set_item("dtype", "object")?;
        array = numpy.getattr("asarray")?.call((edges,), Some(&kwargs))?;
        kind = "O".into();
    }
    let shape: Vec<usize> = array.getattr("shape")?.extract()?;
    if !matches!(shape.as_slice(), [_, 2]) {
        return Err(PyValueError::new_err(format!(
            "{name} must be an array of shape (m, 2); got one of shape {}",
            shape_text(&shape)
        )));
    }
    let mut put = |k: usize, value: Result<i64, String>| {
        let (row, end) = (k / 2, k % 2);
        if end == 0 {
            read.rows.push([0; 2]);
        }
        read.rows[row][end] = value.unwrap_or_else(|text| {
            let clamped = if text.starts_with('-') {
                i64::MIN
            } else {
                i64::MAX
            };
            read.beyond.push((row, end, text));
            clamped
        });
    };
    match kind.as_str() {
        "i" => {
            // Every integer dtype numpy has fits int64. `require` copies what is not C-contiguous,
            // aligned and native (`ascontiguousarray` passes an unaligned contiguous array as is).
            let array = numpy.call_method1("require", (array, "int64", ("C", "A")))?;
            let array = array.cast_into::<PyArray2<i64>>()?;
            let readonly = array.try_readonly()?;
            for (k, &value) in readonly.as_slice()?.iter().enumerate() {
                put(k, Ok(value));
            }
        }
        "u" => {
            let array = numpy.call_method1("require", (array, "uint64", ("C", "A")))?;
            let array = array.cast_into::<PyArray2<u64>>()?;
            let readonly = array.try_readonly()?;
            for (k, &value) in readonly.as_slice()?.iter().enumerate() {
                put(k, i64::try_from(value).map_err(|_| value.to_string()));
            }
        }
        "O" => {
            let numpy_integer = numpy.getattr("integer")?;
            for (k, value) in array.getattr("flat")?.try_iter()?.enumerate() {
                let value = value?;
                if !is_integer(&numpy_integer, &value)? {
                    // The first value that is no integer, by its row (the dtype numpy chose
                    // first, int64 for a bool among ints, would say nothing).
                    return Err(PyTypeError::new_err(format!(
                        "{name} must be an (m, 2) array of integers (point indices); row {} holds {}",
                        k / 2,
                        value.repr()?
                    )));
                }
                put(
                    k,
                    value
                        .extract::<i64>()
                        .map_err(|_| value.str().map_or_else(|_| "?".into(), |t| t.to_string())),
                );
            }
        }
        _ => return Err(not_integers()),
    }
    Ok(read)
}

/// Edges for `condt_eval::score`: a negative end, which no point has, becomes `usize::MAX`,
/// which the library reports as out of range like any other.
fn as_positions(edges: &EdgeRows) -> Vec<[usize; 2]> {
    edges
        .rows
        .iter()
        .map(|e| e.map(|i| usize::try_from(i).unwrap_or(usize::MAX)))
        .collect()
}

/// An edge list's problem, with the edge's row and the end as given (a negative one, or one
/// beyond any integer type, included).
fn problem_text(problem: EdgeProblem, given: &EdgeRows) -> String {
    let row = problem.position();
    match problem {
        EdgeProblem::OutOfRange { index, .. } => {
            // The library names the first end out of range (as `as_positions` maps them: a
            // negative end to `usize::MAX`); that end as given, as `condt score` names it.
            let [a, _] = given.rows[row];
            let first = usize::try_from(a).unwrap_or(usize::MAX) == index;
            format!(
                "row {row}: point {} does not exist",
                given.text(row, usize::from(!first))
            )
        }
        other => format!("row {row}: {other}"),
    }
}

/// How an output edge list compares with a ground truth: the metrics of ``condt score`` (and of
/// ``condt_eval::score``), as the dict ``condt score --json`` prints.
///
/// ``points`` as for ``reconstruct``; ``output`` and ``truth`` are ``(m, 2)`` integer
/// array-likes of point indices, edges in either direction. The keys: ``exact``,
/// ``precision``, ``recall``, ``f1``, ``tp``, ``fp``, ``fn``, ``outlier_edges`` (output edges
/// touching a point the truth leaves without an edge), ``max_dist`` and ``rms_dist`` (of the
/// output to the truth, over the bounding-box diagonal; ``None`` without output edges, or when
/// not finite), ``malformed`` (``None``, or the output's first problem: ``"row K: ..."``, as
/// ``condt score --json`` names it for the same array saved as ``.npy``), ``n_points``, ``n_gt``,
/// ``n_out`` (the output's valid edges, each once: ``tp + fp``). A malformed output (an index
/// out of range or negative, a self-loop, a repeated edge) scores precision, recall and F1 0;
/// its valid edges are counted once each. An index beyond int64 (a uint64 from ``2**63``, a
/// Python int) is out of range as any other and named as given, never wrapped. Edges are
/// compared by point index: where ``points`` repeats a point exactly, ``reconstruct`` gives the
/// duplicate's edges to its first copy, so a truth edge at a later copy is never matched; a
/// ``UserWarning`` names such points of the truth.
///
/// Raises ``ValueError`` for a malformed truth, an edge list of another shape or a NaN or
/// infinite point, ``TypeError`` for edges that are not integers or not an array (``None``, a
/// scalar) or points that are not numbers (as ``reconstruct`` refuses them).
///
/// >>> import condt
/// >>> square = [(0, 0), (1, 0), (1, 1), (0, 1)]
/// >>> s = condt.score(square, [(0, 1), (1, 2), (2, 3), (0, 2)], [(0, 1), (1, 2), (2, 3), (3, 0)])
/// >>> s["exact"], s["tp"], s["fp"], s["fn"], s["f1"]
/// (False, 3, 1, 1, 0.75)
/// >>> condt.score(square, [(0, 1), (1, 0)], [(0, 1)])["malformed"]
/// 'row 1: edge 0 1 repeated'
#[pyfunction]
fn score<'py>(
    py: Python<'py>,
    points: &Bound<'py, PyAny>,
    output: &Bound<'py, PyAny>,
    truth: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let array = points_array(py, points)?;
    let borrowed = array.try_readonly()?;
    // A copy, made holding the GIL, which the score then reads without it (as `reconstruct`'s).
    let points = &as_points(borrowed.as_slice()?).to_vec()[..];
    let output = edge_rows(py, "output", output)?;
    let truth = edge_rows(py, "truth", truth)?;
    let (output_positions, truth_positions) = (as_positions(&output), as_positions(&truth));
    // As `condt score` notes them: a truth edge at a later copy of a point is never matched.
    let later = condt_eval::score::later_copies(points, &truth_positions);
    if let Some(words) = condt_eval::score::later_copies_named(&later) {
        let message = format!(
            "the truth names {words}; edges are compared by point number, and \
             condt.reconstruct gives a duplicate's edges to its first copy"
        );
        user_warning(py, message)?;
    }
    let result = crate::detached(py, || {
        condt_eval::score::score(points, &output_positions, &truth_positions)
    })?
    .map_err(|err| match err {
        ScoreError::NonFinite { index } => library_error(condt::Error::NonFinite { index }, points),
        ScoreError::Truth(problem) => {
            PyValueError::new_err(format!("ground truth: {}", problem_text(problem, &truth)))
        }
    })?;
    // JSON has no infinity: `condt score --json` writes null, and so does this.
    let finite = |x: Option<f64>| x.filter(|x| x.is_finite());
    let dict = PyDict::new(py);
    dict.set_item("exact", result.exact)?;
    dict.set_item("f1", result.f1)?;
    dict.set_item("fn", result.false_negatives)?;
    dict.set_item("fp", result.false_positives)?;
    dict.set_item(
        "malformed",
        result.malformed.map(|p| problem_text(p, &output)),
    )?;
    dict.set_item("max_dist", finite(result.max_distance))?;
    dict.set_item("n_gt", truth.rows.len())?;
    // Valid edges, each once, as `condt score` and the evaluation's `score.py` count them.
    dict.set_item("n_out", result.true_positives + result.false_positives)?;
    dict.set_item("n_points", points.len())?;
    dict.set_item("outlier_edges", result.outlier_edges)?;
    dict.set_item("precision", result.precision)?;
    dict.set_item("recall", result.recall)?;
    dict.set_item("rms_dist", finite(result.rms_distance))?;
    dict.set_item("tp", result.true_positives)?;
    Ok(dict)
}

/// Curves through unorganized planar points (ConDT) and their exact Delaunay triangulation.
#[pymodule]
fn _condt(m: &Bound<'_, PyModule>) -> PyResult<()> {
    LOADED_IN.get_or_init(std::process::id);
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    ALLOCATOR.guard_forks();
    m.add_function(wrap_pyfunction!(reconstruct, m)?)?;
    m.add_function(wrap_pyfunction!(triangulate, m)?)?;
    m.add_function(wrap_pyfunction!(read_points, m)?)?;
    m.add_function(wrap_pyfunction!(read_points_with_crs, m)?)?;
    m.add_function(wrap_pyfunction!(score, m)?)?;
    m.add_function(wrap_pyfunction!(snap, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_tile_params, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_tile_plan, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_run_tile, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_gathered_outliers, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_gathered_repair_again, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_gathered_smoothing_pass, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_tile_state, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_step_kept, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_tests_kept, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_component_labels, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_gathered_clumps, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_gathered_clumps_found, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_gathered_tips, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_choices_kept, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_gathered_gaps, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_local_rules_kept, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_gathered_local_outliers, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_last_edges_kept, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_gathered_last_edges, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_given_back_standing, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_gathered_given_back, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_tile_index, m)?)?;
    m.add_function(wrap_pyfunction!(tiles::_split_edges, m)?)?;
    m.add_class::<tiles::TileState>()?;
    m.add_class::<tiles::TileIndex>()?;
    m.add_class::<Reconstruction>()?;
    m.add_class::<Curve>()?;
    m.add_class::<EdgeStory>()?;
    m.add_class::<Triangulation>()?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
