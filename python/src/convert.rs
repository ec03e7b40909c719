//! NumPy in and out, and the library's errors as Python exceptions.
//!
//! Owns: turning whatever the caller passed as points into a C-contiguous float64 `(n, 2)` array
//! (the caller's own array when it already is one: no copy), refusing what does not hold numbers,
//! viewing its rows as `&[Point]`, reading an index argument, building index arrays from the
//! library's results, and mapping every Rust error to the Python exception a Python user
//! expects. It may not compute anything.

use condt::{Error, Point};
use condt_io::{IoError, IoErrorKind};
use numpy::ndarray::Array2;
use numpy::{PyArray1, PyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::{
    PyIndexError, PyOSError, PyOverflowError, PyRuntimeError, PyTypeError, PyValueError,
};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyBool, PyDict, PyList, PyTuple, PyType};

/// `numpy.ascontiguousarray`, looked up once.
fn ascontiguousarray(py: Python<'_>) -> PyResult<&Bound<'_, PyAny>> {
    static FUNCTION: PyOnceLock<Py<PyAny>> = PyOnceLock::new();
    FUNCTION
        .get_or_try_init(py, || {
            Ok::<_, PyErr>(py.import("numpy")?.getattr("ascontiguousarray")?.unbind())
        })
        .map(|f| f.bind(py))
}

/// Whether `array` can be read as `&[Point]` as it is: C order, aligned, shape `(n, 2)` (its
/// dtype, native float64, is checked by the cast that made it a `PyArray2<f64>`).
fn readable_as_points(array: &Bound<'_, PyArray2<f64>>) -> bool {
    array.is_c_contiguous() && array.is_aligned() && array.shape()[1] == 2
}

/// Whether numpy's dtype kind `kind` is a number a coordinate can be: a signed or unsigned
/// integer, or a float. Every other kind numpy would convert to float64 without a word or with
/// only a warning, and the result would be silently wrong: a complex number's imaginary part
/// dropped, a bool as 0 or 1, a string parsed, a date or a duration as its raw count of units.
fn is_number_kind(kind: &str) -> bool {
    matches!(kind, "i" | "u" | "f")
}

/// Refuses an array that does not hold numbers (`is_number_kind`). An object array (Decimal or
/// Fraction values, a list mixing them with ints; numpy makes one of those) is judged by what
/// numpy makes of each element's type: `numpy.dtype(type)` is an integer or float kind (`int`,
/// `numpy.float32`), or object (`Decimal`, `Fraction`: converted by their `__float__`); a str,
/// bytes, bool, complex, date or duration among them is refused as its own array would be, and
/// so is `None`, which numpy would convert to NaN: a missing value is a wrong type, not a point
/// with a NaN coordinate.
fn check_numbers(numpy: &Bound<'_, PyModule>, array: &Bound<'_, PyAny>) -> PyResult<()> {
    let dtype = array.getattr("dtype")?;
    let kind: String = dtype.getattr("kind")?.extract()?;
    if is_number_kind(&kind) {
        return Ok(());
    }
    if kind != "O" {
        // A boolean mask passed whole (an image user's review): its pixels' places are wanted.
        let shape: Vec<usize> = array.getattr("shape")?.extract()?;
        let hint = if kind == "b" && is_image(&shape) {
            format!("; a mask? {IMAGE_FIX}")
        } else {
            String::new()
        };
        return Err(PyTypeError::new_err(format!(
            "points must hold numbers (integers or floats), not dtype {}{hint}",
            dtype.str()?
        )));
    }
    let numpy_dtype = numpy.getattr("dtype")?;
    // Few distinct types in practice: each is judged once.
    let mut judged: Vec<Bound<'_, PyType>> = Vec::new();
    for element in array.getattr("flat")?.try_iter()? {
        let element = element?;
        let element_type = element.get_type();
        if judged.iter().any(|t| t.is(&element_type)) {
            continue;
        }
        // A type numpy cannot make a dtype of is an object to it, as `Decimal` is.
        let kind = numpy_dtype
            .call1((&element_type,))
            .and_then(|d| d.getattr("kind")?.extract::<String>())
            .unwrap_or_else(|_| "O".into());
        // Shapely geometries (a GeoSeries, a GeoDataFrame, `.geometry.values`) are objects to
        // numpy, and `float()` of one said only "not 'Point'" (a GIS user's review).
        if is_shapely(&element_type)? {
            return Err(PyTypeError::new_err(format!(
                "points holds shapely geometries ({}), not numbers: {GEOMETRY_FIX}",
                element_type.name()?
            )));
        }
        if element.is_none() || (!is_number_kind(&kind) && kind != "O") {
            return Err(PyTypeError::new_err(format!(
                "points must hold numbers (integers or floats), not {} (in an array of dtype \
                 object)",
                element_type.name()?
            )));
        }
        judged.push(element_type);
    }
    Ok(())
}

/// Whether `t` is one of shapely's geometry types (`shapely.Point`, `shapely.MultiPoint`, ...).
fn is_shapely(t: &Bound<'_, PyType>) -> PyResult<bool> {
    let module: String = t.getattr("__module__")?.extract().unwrap_or_default();
    Ok(module == "shapely" || module.starts_with("shapely."))
}

/// What to pass instead of shapely geometries: their coordinates, with the GeoDataFrame's own
/// index kept beside them (python/README.md, *GeoPandas*, has the way back to a GeoDataFrame).
const GEOMETRY_FIX: &str = "pass their coordinates, gdf.get_coordinates() for a GeoDataFrame or \
                            GeoSeries (one row per point, the index kept: a MultiPoint's points \
                            share its label, None and empty geometries give none) or \
                            shapely.get_coordinates(geometries); python/README.md, *GeoPandas*";

/// What to pass instead of an image or a mask: the places of its edge pixels, of a filled
/// mask's boundary for a segmentation (its every pixel would be read as a point).
const IMAGE_FIX: &str = "condt takes points: numpy.argwhere(edges)[:, ::-1] gives an edge \
                         image's pixels as (x, y), and mask & ~scipy.ndimage.binary_erosion(mask) \
                         a filled mask's boundary";

/// What to pass instead of a label image (regions numbered): neither of a mask's fixes gives
/// the borders between its regions (a label-image user's review), the subpixel boundaries do,
/// with the pixel corners where three regions meet as points of their own.
const LABELS_FIX: &str = "a label image (regions numbered)? b = \
                          skimage.segmentation.find_boundaries(labels, mode='subpixel'), then \
                          numpy.argwhere(b)[:, ::-1] / 2 gives the borders between regions, \
                          junctions included";

/// What to pass instead of a colour image: an edge image's or a mask's pixels, as for a grey one.
const COLOUR_FIX: &str = "; a colour image? make an edge image or a mask of it first \
                          (skimage.color.rgb2gray, then a threshold or skimage.feature.canny), \
                          then pass points: numpy.argwhere(edges)[:, ::-1] gives its pixels as \
                          (x, y)";

/// Whether an array of this shape reads as an image rather than as points: two axes of 5 or
/// more (a table of 5 columns or more reads so too; the hints name both).
fn is_image(shape: &[usize]) -> bool {
    matches!(shape, [h, w] if *h >= 5 && *w >= 5)
}

/// Refuses a bool among the numbers of a list's (or tuple's) rows, and a row that is a numpy
/// array of bools: numpy makes `[[True, 0.5]]` or `[np.array([True, False]), (0.5, 1.0)]` a
/// float64 array, reading `True` as 1, where an array of bools alone is refused by its dtype
/// ([`check_numbers`]) and `score`'s edges refuse a bool among ints too.
fn check_no_bools_in_rows(numpy: &Bound<'_, PyModule>, obj: &Bound<'_, PyAny>) -> PyResult<()> {
    if !(obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>()) {
        return Ok(());
    }
    let numpy_bool = numpy.getattr("bool_")?;
    let ndarray = numpy.getattr("ndarray")?;
    for (k, row) in obj.try_iter()?.enumerate() {
        let row = row?;
        if row.is_instance(&ndarray)? {
            if row.getattr("dtype")?.getattr("kind")?.extract::<String>()? == "b" {
                return Err(PyTypeError::new_err(format!(
                    "points must hold numbers (integers or floats), not bool: row {k} is an \
                     array of bool (numpy would read it as numbers)"
                )));
            }
            continue;
        }
        if !(row.is_instance_of::<PyList>() || row.is_instance_of::<PyTuple>()) {
            continue;
        }
        for value in row.try_iter()? {
            let value = value?;
            if value.is_instance_of::<PyBool>() || value.is_instance(&numpy_bool)? {
                return Err(PyTypeError::new_err(format!(
                    "points must hold numbers (integers or floats), not bool: row {k} holds {} \
                     (numpy would read it as a number)",
                    value.repr()?
                )));
            }
        }
    }
    Ok(())
}

/// The `ValueError` naming point `point` for a coordinate no float64 holds, `shown` as Python
/// writes it.
fn too_large(point: usize, shown: String) -> PyErr {
    // Shortened with a mark, so that a cut integer is not read as a smaller one.
    let shown = match shown.char_indices().nth(40) {
        Some((cut, _)) => format!(
            "{}... ({} characters)",
            &shown[..cut],
            shown.chars().count()
        ),
        None => shown,
    };
    PyValueError::new_err(format!(
        "point {point} has a coordinate too large for a float64: {shown}"
    ))
}

/// The `ValueError` naming the first point of `given` (an array numpy made of the caller's
/// points) whose coordinate no float64 holds, if one is found: a value whose `float()` raises
/// `OverflowError` (an int), or gives an infinity while the value itself is finite (a
/// `Decimal`'s does, and numpy's conversion then reads it as an infinite point).
fn overflowing_point(py: Python<'_>, given: &Bound<'_, PyAny>) -> PyResult<Option<PyErr>> {
    let float = py.import("builtins")?.getattr("float")?;
    let shape: Vec<usize> = given.getattr("shape")?.extract()?;
    let columns = if shape.len() == 2 { shape[1].max(1) } else { 1 };
    for (k, item) in given.call_method0("ravel")?.try_iter()?.enumerate() {
        let item = item?;
        let overflows = match float.call1((&item,)) {
            Err(err) => err.is_instance_of::<PyOverflowError>(py),
            // An infinite value equals the infinity it converts to; a value that cannot be
            // compared is left to be named as the infinite point it became.
            Ok(converted) => {
                converted.extract::<f64>().is_ok_and(f64::is_infinite)
                    && !item.eq(&converted).unwrap_or(true)
            }
        };
        if overflows {
            let shown = item.repr().map_or_else(|_| "?".into(), |r| r.to_string());
            return Ok(Some(too_large(k / columns, shown)));
        }
    }
    Ok(None)
}

/// Refuses a float array of shape (n, 2) wider than float64 (numpy's `longdouble`: 80-bit on
/// x86, a quad on some other platforms) whose values float64 does not hold: numpy's conversion
/// would round them, and two points closer than a float64's step would become one, as integers
/// beyond 2^53 would ([`check_exact_integers`]). An array whose values are all float64s (one
/// made from doubles) loses nothing, and is taken. `given` is what numpy made of the caller's
/// points, before any conversion.
///
/// # Errors
/// `ValueError` naming the first point with a finite coordinate beyond float64's range, as an
/// int beyond it is named ([`overflowing_point`]); then the first row with a coordinate float64
/// would round, its value and what it would become.
fn check_long_doubles(numpy: &Bound<'_, PyModule>, given: &Bound<'_, PyAny>) -> PyResult<()> {
    // A plain array: an `np.matrix`'s ravel would be a matrix, its items rows.
    let given = numpy.getattr("asarray")?.call1((given,))?;
    let dtype = given.getattr("dtype")?;
    let kind: String = dtype.getattr("kind")?.extract()?;
    let itemsize: usize = dtype.getattr("itemsize")?.extract()?;
    let shape: Vec<usize> = given.getattr("shape")?.extract()?;
    // Another shape is refused by its shape, after the conversion.
    if kind != "f" || itemsize <= 8 || !matches!(shape.as_slice(), [_, 2]) {
        return Ok(());
    }
    let first = |mask: Bound<'_, PyAny>| -> PyResult<Option<usize>> {
        if mask.call_method0("any")?.is_truthy()? {
            Ok(Some(mask.call_method0("argmax")?.extract()?))
        } else {
            Ok(None)
        }
    };
    let flat = given.call_method0("ravel")?;
    let finite = numpy.getattr("isfinite")?.call1((&flat,))?;
    // Compared in the array's own precision (numpy casts a Python float to it exactly), before
    // any conversion: converting such a value to float64 gives an infinity, with a warning.
    let beyond = numpy
        .getattr("abs")?
        .call1((&flat,))?
        .call_method1("__gt__", (f64::MAX,))?;
    let beyond = numpy.getattr("logical_and")?.call1((&finite, beyond))?;
    if let Some(k) = first(beyond)? {
        return Err(too_large(k / 2, flat.get_item(k)?.str()?.to_string()));
    }
    let rounded = flat.call_method1("astype", ("float64",))?;
    // NaN and the infinities convert as themselves: only finite values can be rounded.
    let inexact = rounded
        .call_method1("astype", (&dtype,))?
        .call_method1("__ne__", (&flat,))?;
    let inexact = numpy.getattr("logical_and")?.call1((&finite, inexact))?;
    if let Some(k) = first(inexact)? {
        return Err(PyValueError::new_err(format!(
            "points row {} has the coordinate {} (dtype {}), which float64 (condt's \
             coordinates) cannot hold exactly: it would become {}, and two points might become \
             one; convert the points to float64 first (points.astype(float)) to accept the \
             rounding",
            k / 2,
            flat.get_item(k)?.str()?,
            dtype.str()?,
            float_text(rounded.get_item(k)?.extract()?)
        )));
    }
    Ok(())
}

/// Whether `given` is a 1-d array whose every element is a sequence of two (a row held as one
/// object), which `numpy.stack` makes an `(n, 2)` array.
fn rows_of_pairs(given: &Bound<'_, PyAny>) -> PyResult<bool> {
    if given.getattr("ndim")?.extract::<usize>()? != 1 {
        return Ok(false);
    }
    for element in given.try_iter()? {
        if !element?.len().is_ok_and(|length| length == 2) {
            return Ok(false);
        }
    }
    Ok(true)
}

/// The points `obj` holds, as a C-contiguous, aligned, native float64 array of shape `(n, 2)`:
/// `obj` itself when it is one (no copy), otherwise `numpy.ascontiguousarray(obj, "float64")`
/// of what `numpy.asarray(obj)` gives, when that holds numbers (`check_numbers`). An empty
/// sequence (`[]`, shape `(0,)`) is no points.
///
/// # Errors
/// `TypeError` for `None`, a scalar, or an array whose dtype is not an integer or a float (or an
/// object array holding something else, `None` among them); `ValueError` for a masked array
/// with masked entries, any other shape, a finite value beyond float64 (an int, a long double, a
/// `Decimal`; naming its point), or a long double float64 would round (naming its row); numpy's
/// own error for what it cannot convert.
pub(crate) fn points_array<'py>(
    py: Python<'py>,
    obj: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let numpy = py.import("numpy")?;
    // A masked array's mask would be dropped by reading its data, and its masked entries read as
    // points: a silently wrong result. Refused unless nothing is masked. NumPy 2 imports
    // `numpy.ma` on first use only (about 1 MB of Python objects), and no masked array exists
    // before it is imported: looked up where imported modules are, never imported here (the
    // first call imported it, which `tracemalloc` counted as a copy of the points).
    let ma = py
        .import("sys")?
        .getattr("modules")?
        .cast_into::<PyDict>()?
        .get_item("numpy.ma")?;
    let masked = match ma {
        Some(ma) => {
            obj.is_instance(&ma.getattr("MaskedArray")?)?
                && ma.getattr("is_masked")?.call1((obj,))?.is_truthy()?
        }
        None => false,
    };
    if masked {
        return Err(PyValueError::new_err(
            "points is a masked array with masked entries: drop those rows first \
             (numpy.ma.compress_rows) or fill them",
        ));
    }
    if let Ok(array) = obj.cast::<PyArray2<f64>>() {
        if readable_as_points(array) {
            return Ok(array.clone());
        }
    }
    // A list of arrays of different lengths (skimage's `find_contours` gives one per contour):
    // numpy's own message says "inhomogeneous shape" and nothing of the fix (an image user's
    // review). The reshape is for OpenCV's contours, (n, 1, 2) each, which `vstack` keeps so.
    let ragged = |err: PyErr| {
        if err.is_instance_of::<PyValueError>(py) && err.to_string().contains("inhomogeneous") {
            PyValueError::new_err(format!(
                "points holds rows or arrays of different lengths (a list of contours?): \
                 numpy.vstack(contours).reshape(-1, 2) makes one (n, 2) array of them ({err})"
            ))
        } else {
            err
        }
    };
    // A GeoDataFrame's attribute columns would be met before its geometries, and refused as
    // "not str" (a GIS user's review): a GeoPandas object is told its fix whatever it holds.
    let module: String = obj
        .get_type()
        .getattr("__module__")?
        .extract()
        .unwrap_or_default();
    if module.starts_with("geopandas.") || module.starts_with("dask_geopandas.") {
        // dask-geopandas has no `get_coordinates`: its points are computed on the driver.
        let computed = if module.starts_with("dask_") {
            " (of a dask-geopandas one: ddf.compute().get_coordinates())"
        } else {
            ""
        };
        return Err(PyTypeError::new_err(format!(
            "points is a {} of geometries, not numbers: {GEOMETRY_FIX}{computed}",
            obj.get_type().name()?
        )));
    }
    // A pandas table of more than its two coordinates (a name, a z column): the hints below
    // would advise NumPy's `points[:, :2]`, which a DataFrame does not take (a GIS user's
    // review: a name column said only "not str").
    let table_fix = ((module == "pandas" || module.starts_with("pandas."))
        && obj.get_type().name()?.to_str()? == "DataFrame")
        .then_some("; a DataFrame? pass its two coordinate columns, such as df[[\"x\", \"y\"]]");
    // None and scalars are the wrong type, not a wrong shape: numpy would make them one point.
    let ndim = numpy.getattr("ndim")?.call1((obj,)).map_err(ragged)?;
    if obj.is_none() || ndim.extract::<usize>()? == 0 {
        // One geometry (a MultiPoint, a LineString's vertices): numpy sees a scalar object.
        let hint = if is_shapely(&obj.get_type())? {
            " (a shapely geometry: pass shapely.get_coordinates(geometry))".to_string()
        } else {
            String::new()
        };
        return Err(PyTypeError::new_err(format!(
            "points must be an array-like of shape (n, 2), not {}{hint}",
            obj.get_type().name()?
        )));
    }
    // What numpy makes of it, before any conversion to float64: that decides whether it holds
    // numbers (a list of Python numbers is int64 or float64; of bools, bool; of Decimals, object).
    let given = if obj.cast::<numpy::PyUntypedArray>().is_ok() {
        obj.clone()
    } else {
        numpy.getattr("asarray")?.call1((obj,)).map_err(ragged)?
    };
    check_numbers(&numpy, &given).map_err(|err| match table_fix {
        Some(fix) => PyTypeError::new_err(format!("{}{fix}", err.value(py))),
        None => err,
    })?;
    check_no_bools_in_rows(&numpy, obj)?;
    check_long_doubles(&numpy, &given)?;
    let converted = match ascontiguousarray(py)?.call1((given.clone(), "float64")) {
        Ok(converted) => converted,
        // A Python int beyond float64 (`10**400`): a bad point, named, as a NaN is.
        Err(err) if err.is_instance_of::<PyOverflowError>(py) => {
            return Err(overflowing_point(py, &given)?.unwrap_or(err));
        }
        // A 1-d array of rows held as objects, each a pair (a Python user's review): numpy's own
        // message ("setting an array element with a sequence") named neither the points nor the
        // shape they need. Other contents (rows of other lengths, a Decimal NaN) keep numpy's.
        Err(err) if err.is_instance_of::<PyValueError>(py) && rows_of_pairs(&given)? => {
            return Err(PyValueError::new_err(format!(
                "points must be an array of shape (n, 2); got a 1-d array of {} objects, each \
                 row one object (numpy.stack(points) makes it (n, 2))",
                given.len()?
            )));
        }
        Err(err) => return Err(err),
    };
    // A finite value beyond float64 in an object array (a `Decimal`'s `float()` gives an
    // infinity, where an int's raises): named as too large, not as the infinite point it became.
    if given
        .getattr("dtype")?
        .getattr("kind")?
        .extract::<String>()?
        == "O"
        && !numpy
            .getattr("isfinite")?
            .call1((&converted,))?
            .call_method0("all")?
            .is_truthy()?
    {
        if let Some(err) = overflowing_point(py, &given)? {
            return Err(err);
        }
    }
    let converted = converted.cast_into::<numpy::PyUntypedArray>()?;
    let shape = converted.shape().to_vec();
    let converted = match shape.as_slice() {
        [_, 2] => {
            check_exact_integers(&numpy, obj, &given)?;
            converted.into_any()
        }
        [0] => converted.call_method1("reshape", ((0, 2),))?,
        _ => {
            // The shapes other tools hand over (an image user's review): rows and columns from
            // `np.nonzero`, OpenCV's contours, a point per column; and lists of contours of one
            // length, which numpy stacks (`findContours` of a single blob gives a tuple of one).
            let hint = match shape.as_slice() {
                _ if table_fix.is_some() => table_fix.unwrap_or_default(),
                [2, _] => "; points by column? pass points.T",
                [_, 1, 2] => "; OpenCV's contour layout? pass points.reshape(-1, 2)",
                [_, _, 1, 2] => {
                    "; a list of OpenCV's contours? pass numpy.vstack(contours).reshape(-1, 2)"
                }
                [_, _, 2] => "; a list of contours? pass numpy.vstack(contours)",
                [_, 3] | [_, 4] => "; pass the two coordinate columns, such as points[:, :2]",
                // A colour image passed whole (a diff review: told its shape alone).
                [h, w, 3 | 4] if *h >= 5 && *w >= 5 => COLOUR_FIX,
                // An image or a mask passed whole (an image user's review).
                shape if is_image(shape) => &format!(
                    "; an image or a mask? {IMAGE_FIX}; {LABELS_FIX}; a table? pass the two \
                     coordinate columns, such as points[:, :2]"
                ),
                _ => "",
            };
            return Err(PyValueError::new_err(format!(
                "points must be an array of shape (n, 2); got one of shape {}{hint}",
                shape_text(&shape)
            )));
        }
    };
    let array = converted.cast_into::<PyArray2<f64>>()?;
    if readable_as_points(&array) {
        Ok(array)
    } else {
        // Unaligned data (a buffer at an odd offset): a fresh array is aligned.
        let copy = array.call_method0("copy")?.cast_into::<PyArray2<f64>>()?;
        Ok(copy)
    }
}

/// Refuses integers that float64 cannot hold: beyond 2^53 numpy's conversion rounds, and two
/// points a unit apart may become one (a silently wrong result). As the command line and
/// `read_points` refuse them in a `.npy` file; a float64 array states that the rounding is
/// accepted. `given` is what numpy made of `obj` before the conversion, of shape (n, 2): an
/// int64 or uint64 array is compared whole; an object array, or a sequence numpy made floats of
/// (its ints beyond int64 beside others), is read element by element where it can hold such an
/// int.
///
/// # Errors
/// `ValueError` naming the first such row and its value.
fn check_exact_integers(
    numpy: &Bound<'_, PyModule>,
    obj: &Bound<'_, PyAny>,
    given: &Bound<'_, PyAny>,
) -> PyResult<()> {
    const EXACT: i64 = 1 << 53;
    // A plain array: an `np.matrix`'s rows would be matrices.
    let given = numpy.getattr("asarray")?.call1((given,))?;
    let dtype = given.getattr("dtype")?;
    let kind: String = dtype.getattr("kind")?.extract()?;
    let itemsize: usize = dtype.getattr("itemsize")?.extract()?;
    let refused = |row: usize, value: Bound<'_, PyAny>| {
        PyValueError::new_err(format!(
            "points row {row} has the integer coordinate {value}, beyond 2^53, past which \
             float64 (condt's coordinates) holds only some integers exactly; convert the array \
             to float64 first to accept the rounding"
        ))
    };
    let elementwise = match kind.as_str() {
        // Integers of four bytes or fewer are all doubles.
        "i" | "u" if itemsize >= 8 => {
            let beyond = given.call_method1("__gt__", (EXACT,))?;
            let beyond = if kind == "i" {
                numpy
                    .getattr("logical_or")?
                    .call1((beyond, given.call_method1("__lt__", (-EXACT,))?))?
            } else {
                beyond
            };
            let rows = beyond.call_method1("any", (1,))?;
            if !rows.call_method0("any")?.is_truthy()? {
                return Ok(());
            }
            let row: usize = rows.call_method0("argmax")?.extract()?;
            let column = beyond.get_item(row)?.call_method0("argmax")?;
            return Err(refused(row, given.get_item(row)?.get_item(column)?));
        }
        "O" => given,
        // Floats numpy made of a sequence: an int beyond int64 among them was rounded already;
        // only a magnitude of 2^53 or more can be one.
        "f" if !obj.is_instance_of::<numpy::PyUntypedArray>()
            && numpy
                .getattr("any")?
                .call1((numpy
                    .getattr("abs")?
                    .call1((&given,))?
                    .call_method1("__ge__", (EXACT as f64,))?,))?
                .is_truthy()? =>
        {
            numpy.getattr("asarray")?.call1((obj, "object"))?
        }
        _ => return Ok(()),
    };
    let integer = numpy.getattr("integer")?;
    for (k, value) in elementwise.call_method0("ravel")?.try_iter()?.enumerate() {
        let value = value?;
        let is_int = (value.is_instance_of::<pyo3::types::PyInt>()
            && !value.is_instance_of::<PyBool>())
            || value.is_instance(&integer)?;
        if is_int && (value.gt(EXACT)? || value.lt(-EXACT)?) {
            return Err(refused(k / 2, value));
        }
    }
    Ok(())
}

/// A shape as Python writes it: `(3,)`, `(4, 3)`, `()`.
pub(crate) fn shape_text(shape: &[usize]) -> String {
    match shape {
        [one] => format!("({one},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// The rows of a C-contiguous `(n, 2)` float64 array's data as points.
///
/// The view is as sound as the slice it comes from: NumPy's read-only borrow keeps Rust code
/// from writing the array, not Python code, so another Python thread may write it whenever the
/// GIL is released. Read it holding the GIL, or copy it first, holding the GIL (as
/// `reconstruct`, `triangulate` and `score` do), and read the copy without. NumPy itself
/// releases the GIL inside its own loops (a ufunc with `out=`, a large copy), so such a write in
/// another thread can still overlap the copy, as it can any extension's read of a buffer: the
/// copy narrows the window to its own length. Not yet so: the tile functions of `tiles.rs`,
/// private to `condt.dask`, which read the arrays it passes without the GIL.
pub(crate) fn as_points(flat: &[f64]) -> &[Point] {
    const _: () = assert!(
        core::mem::size_of::<Point>() == 2 * core::mem::size_of::<f64>()
            && core::mem::align_of::<Point>() == core::mem::align_of::<f64>()
    );
    // SAFETY: `Point` is `#[repr(C)]` with two `f64` fields, `x` then `y` (its documentation
    // promises this layout; the assertion above checks size and alignment), so the memory of
    // `2k` consecutive aligned `f64` is that of `k` points. Every bit pattern is a valid `f64`.
    // The pointer comes from a slice, so it is non-null and aligned for `f64`, which is
    // `Point`'s alignment; `flat.len() / 2` points lie within the slice, and the result
    // borrows `flat`, so it lives no longer than the data.
    unsafe { core::slice::from_raw_parts(flat.as_ptr().cast::<Point>(), flat.len() / 2) }
}

/// A float as Python's `repr` writes it (`nan`, `inf`, `1.5`), for messages.
fn float_text(x: f64) -> String {
    if x.is_nan() {
        "nan".into()
    } else if x.is_infinite() {
        if x > 0.0 { "inf" } else { "-inf" }.into()
    } else {
        format!("{x:?}")
    }
}

/// The library's refusal as a Python exception: `ValueError` for the input (a non-finite point
/// is named by its index and row; two points too close to measure, by their positions) and for
/// a parameter, `RuntimeError` for a broken invariant,
/// which would be a bug.
pub(crate) fn library_error(err: Error, points: &[Point]) -> PyErr {
    match err {
        Error::NonFinite { index } => match points.get(index) {
            Some(p) => PyValueError::new_err(format!(
                "point {index} has a NaN or infinite coordinate: row {index} of the points is \
                 [{}, {}]",
                float_text(p.x),
                float_text(p.y)
            )),
            None => PyValueError::new_err(err.to_string()),
        },
        Error::TooManyPoints { .. } | Error::TooCloseToMeasure { .. } => {
            PyValueError::new_err(err.to_string())
        }
        Error::InvalidParameter { name, .. } => {
            // The library names the IQR factor `k`; here it is the keyword `iqr`, as the
            // command line's option is `--iqr`: the text says `iqr` wherever it said `k`.
            let (keyword, text) = if name == "k" {
                let text = err.to_string();
                let text = text.replacen("parameter k ", "parameter iqr ", 1);
                ("iqr", text.replacen("(k is ", "(iqr is ", 1))
            } else {
                (name, err.to_string())
            };
            PyValueError::new_err(format!("{keyword}: {text}"))
        }
        Error::InvalidTriangulation(_) => PyRuntimeError::new_err(format!(
            "condt found a broken invariant (a bug; please report it): {err}"
        )),
        _ => PyRuntimeError::new_err(err.to_string()),
    }
}

/// A point file that could not be read: `OSError` (its subclass for the errno, such as
/// `FileNotFoundError`, with `filename` set) when the system refused, `ValueError` with the file
/// and line when the content is not a point file.
pub(crate) fn io_error(err: IoError) -> PyErr {
    match &err.kind {
        IoErrorKind::Io(cause) => {
            let text = cause.to_string();
            match cause.raw_os_error() {
                // OSError(errno, strerror, filename) is made the subclass its errno stands for.
                // Python adds the errno itself: Rust's " (os error 2)" would repeat it.
                Some(errno) => {
                    let text = text
                        .strip_suffix(&format!(" (os error {errno})"))
                        .unwrap_or(&text)
                        .to_string();
                    PyOSError::new_err((errno, text, err.file.clone()))
                }
                None => PyOSError::new_err(format!("{}: {text}", err.file)),
            }
        }
        _ => PyValueError::new_err(err.to_string()),
    }
}

/// An array of index pairs (or triples) as a read-only `(len, K)` int64 array; the data is
/// moved into numpy, not copied.
pub(crate) fn index_array<'py, const K: usize>(
    py: Python<'py>,
    rows: Vec<[i64; K]>,
) -> PyResult<Bound<'py, PyArray2<i64>>> {
    let len = rows.len();
    // The rows' memory as it is (no copy: a collected `flatten` copied it, growing by doubling).
    let flat: Vec<i64> = rows.into_flattened();
    let array = Array2::from_shape_vec((len, K), flat)
        .map_err(|err| PyRuntimeError::new_err(err.to_string()))?;
    let array = PyArray2::from_owned_array(py, array);
    read_only(&array)?;
    Ok(array)
}

/// A list of indices as a read-only int64 array, moved into numpy.
pub(crate) fn index_vector<'py>(
    py: Python<'py>,
    values: Vec<i64>,
) -> PyResult<Bound<'py, PyArray1<i64>>> {
    let array = PyArray1::from_vec(py, values);
    read_only(&array)?;
    Ok(array)
}

/// Makes `array` read-only: the results are cached and shared between accesses, so an
/// in-place change would change what the next access returns (`.copy()` gives a writable one).
pub(crate) fn read_only(array: &Bound<'_, PyAny>) -> PyResult<()> {
    let kwargs = PyDict::new(array.py());
    kwargs.set_item("write", false)?;
    array.call_method("setflags", (), Some(&kwargs))?;
    Ok(())
}

/// The input position argument `name` (`i`, `j`) of a result of `n` points holds, as `usize`.
///
/// # Errors
/// `IndexError` when it is no input position: negative, `n` or above, or beyond any integer the
/// machine has (`2**70`: an `IndexError` as any other, not numpy's or Python's
/// `OverflowError`); `TypeError` when it is not an integer (anything with `__index__` is) or is a
/// bool.
pub(crate) fn input_position(name: &str, value: &Bound<'_, PyAny>, n: usize) -> PyResult<usize> {
    let out_of_range = || {
        let shown = value.str().map_or_else(|_| "?".into(), |r| r.to_string());
        PyIndexError::new_err(if n == 0 {
            format!("{shown} is not an input position: there are no points")
        } else {
            format!("{shown} is not an input position (0 to {})", n - 1)
        })
    };
    // `True` would be read as 1 (a bool is an int to Python): a mistake, not a position. numpy
    // reads `a[True]` as a mask, not as row 1, and `a.item(True)` is a `TypeError`. numpy's bool
    // too: NumPy 1 gives it an `__index__` (deprecated, with a warning), so `numpy.True_` was
    // point 1 there and a `TypeError` with NumPy 2.
    if crate::params::is_bool(value) {
        return Err(PyTypeError::new_err(format!(
            "argument '{name}': an input position is an integer, not bool"
        )));
    }
    match value.extract::<i64>() {
        Ok(k) => usize::try_from(k)
            .ok()
            .filter(|&k| k < n)
            .ok_or_else(out_of_range),
        Err(err) if err.is_instance_of::<PyOverflowError>(value.py()) => Err(out_of_range()),
        // Python's own words (`'str' object cannot be interpreted as an integer`), without the
        // `TypeError: ` that the error's `Display` puts first.
        Err(err) => Err(PyTypeError::new_err(format!(
            "argument '{name}': {}",
            err.value(value.py())
        ))),
    }
}

/// An input position as `i64` (positions are below `condt::MAX_POINTS`, far below `i64::MAX`).
pub(crate) fn position(i: usize) -> i64 {
    i64::try_from(i).unwrap_or(i64::MAX)
}
