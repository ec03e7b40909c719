//! `Reconstruction`, `Curve` and `EdgeStory`: a finished `condt::Reconstruction` as Python reads it.
//!
//! Owns: the Python view of a result (arrays made once, when first read, and cached read-only),
//! the explanation of an edge as text and numbers, and the GeoJSON and shapely outputs. It may
//! not run a stage: every number comes from the result or its `provenance`.

use crate::convert::{index_array, index_vector, input_position, position, read_only};
use condt::{Change, EndChoice, Point, Reason};
use numpy::{PyArray1, PyArray2};
use pyo3::exceptions::{PyImportError, PyKeyError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyList, PyTuple};
use pyo3::PyTypeInfo;
use std::sync::{Arc, OnceLock};

/// The curves through a set of points, and every stage that found them: what
/// ``condt.reconstruct`` returns.
///
/// Every index is an input position: the row of the point in the array given to
/// ``reconstruct``. Index arrays are ``int64`` and read-only (they are made once, on first
/// access, and shared; ``.copy()`` gives a writable one).
///
/// >>> import condt
/// >>> square = [(0, 0), (1, 0), (1, 1), (0, 1)]
/// >>> r = condt.reconstruct(square)
/// >>> r.edges.tolist()
/// [[0, 1], [0, 3], [1, 2], [2, 3]]
/// >>> [(c.points.tolist(), c.closed) for c in r.curves]
/// [([0, 1, 2, 3], True)]
/// >>> r.unused.tolist()
/// []
/// >>> list(r.stages)
/// ['proximity', 'repair', 'iqr-outliers', 'repair-again', 'local-outliers', 'clumps', 'given-back', 'gaps', 'junctions', 'crossings', 'tips', 'spikes', 'hooks', 'tails', 'detours']
#[pyclass(module = "condt", frozen)]
pub(crate) struct Reconstruction {
    /// Shared with its `Curve`s, which must not hold the `Reconstruction` itself: the result
    /// caches them, and a cycle of Python references without `__traverse__` is never freed.
    shared: Arc<Shared>,
    edges: PyOnceLock<Py<PyArray2<i64>>>,
    unused: PyOnceLock<Py<PyArray1<i64>>>,
    curves: PyOnceLock<Vec<Py<Curve>>>,
    stages: PyOnceLock<Py<PyDict>>,
    /// Every edge's story, computed on the first `explain` (O(n log n)).
    stories: OnceLock<Vec<condt::EdgeStory>>,
}

/// What a result and its curves read: the library's result and the points as given.
struct Shared {
    result: condt::Reconstruction,
    /// A copy of the points as given: GeoJSON, shapely and `Curve.coords` read the input
    /// coordinates from it, since the result keeps none. The copy the work ran on, not the
    /// caller's array, which the caller may change (`lib.rs`, `reconstruct`).
    points: Vec<Point>,
}

impl Reconstruction {
    pub(crate) fn new(result: condt::Reconstruction, points: Vec<Point>) -> Self {
        Reconstruction {
            shared: Arc::new(Shared { result, points }),
            edges: PyOnceLock::new(),
            unused: PyOnceLock::new(),
            curves: PyOnceLock::new(),
            stages: PyOnceLock::new(),
            stories: OnceLock::new(),
        }
    }
}

impl Shared {
    /// The input coordinates of input positions `indices`, as a new `(len, 2)` float64 array.
    fn coordinates<'py>(
        &self,
        py: Python<'py>,
        indices: impl Iterator<Item = usize>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rows: Vec<[f64; 2]> = indices
            .map(|i| self.points.get(i).map_or([f64::NAN; 2], |p| [p.x, p.y]))
            .collect();
        let len = rows.len();
        let flat: Vec<f64> = rows.into_flattened();
        let array = numpy::ndarray::Array2::from_shape_vec((len, 2), flat)
            .map_err(|err| PyRuntimeError::new_err(err.to_string()))?;
        Ok(PyArray2::from_owned_array(py, array))
    }
}

#[pymethods]
impl Reconstruction {
    /// The final edges, an ``(m, 2)`` int64 array of input positions ``[i, j]``, ``i < j``,
    /// sorted: the rows ``condt reconstruct -o out.edges`` writes.
    #[getter]
    fn edges<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        let edges = self.edges.get_or_try_init(py, || {
            let list = self.shared.result.edge_list();
            let rows = crate::detached(py, || {
                list.iter()
                    .map(|&[a, b]| [i64::from(a), i64::from(b)])
                    .collect::<Vec<_>>()
            })?;
            index_array(py, rows).map(Bound::unbind)
        })?;
        Ok(edges.bind(py).clone())
    }

    /// The curves, a list of ``Curve``, sorted as ``condt reconstruct`` writes them (``.txt``).
    #[getter]
    fn curves(&self, py: Python<'_>) -> PyResult<Vec<Py<Curve>>> {
        let curves = self.curves.get_or_try_init(py, || {
            (0..self.shared.result.curves().len())
                .map(|index| {
                    let curve = Curve {
                        shared: Arc::clone(&self.shared),
                        index,
                        points: PyOnceLock::new(),
                        coords: PyOnceLock::new(),
                    };
                    Py::new(py, curve)
                })
                .collect::<PyResult<Vec<_>>>()
        })?;
        Ok(curves.iter().map(|c| c.clone_ref(py)).collect())
    }

    /// Exact duplicates, a ``(k, 2)`` int64 array of rows ``[i, first]``: point ``i`` repeats
    /// the earlier point ``first`` and was merged into it (ascending by ``i``). The edges and
    /// curves name ``first`` only; ``i`` shares its fate (it is in ``unused`` exactly when
    /// ``first`` is).
    ///
    /// >>> import condt
    /// >>> condt.reconstruct([(0, 0), (1, 0), (0, 1), (1, 0)]).merged.tolist()
    /// [[3, 1]]
    #[getter]
    fn merged<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        let tri = self.shared.result.triangulation();
        let rows: Vec<[i64; 2]> = tri.merged().map(|pair| pair.map(position)).collect();
        index_array(py, rows)
    }

    /// Where the last run's stages saw each point, a ``(n, 2)`` float64 array (read-only): the
    /// input positions, or after smoothing passes the moved ones, on which the stages' lengths,
    /// ratios and rings (``stages``, ``explain``) were measured. A pass places points relative
    /// to the set's lower-left corner, so a point it did not move may read a unit in the last
    /// place off its input. ``condt.triangulate(r.stage_points)`` is the triangulation the
    /// stages walked except where four or more points lie on one circle (evenly spaced samples
    /// of an arc, moved or not): there the run chose its diagonals in its own frame and order,
    /// so ``explain`` may not know an edge of that triangulation.
    ///
    /// >>> import condt
    /// >>> r = condt.reconstruct([(0, 0), (1, 0), (0, 1)], paper=True)
    /// >>> r.stage_points.tolist()
    /// [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]
    #[getter]
    fn stage_points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let result = &self.shared.result;
        let flat: Vec<f64> = (0..result.num_points())
            .flat_map(|i| {
                let p = result.stage_point(i);
                [p.x, p.y]
            })
            .collect();
        let array = numpy::ndarray::Array2::from_shape_vec((result.num_points(), 2), flat)
            .map_err(|err| PyRuntimeError::new_err(err.to_string()))?;
        let array = PyArray2::from_owned_array(py, array);
        read_only(array.as_any())?;
        Ok(array)
    }

    /// The result itself: it never changes, so a copy is the same object.
    fn __copy__(slf: PyRef<'_, Self>) -> PyRef<'_, Self> {
        slf
    }

    /// The result itself, as ``__copy__``.
    fn __deepcopy__<'py>(slf: PyRef<'py, Self>, _memo: &Bound<'py, PyAny>) -> PyRef<'py, Self> {
        slf
    }

    /// The input positions whose point ended with no edge (outliers), ascending, int64.
    #[getter]
    fn unused<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<i64>>> {
        let unused = self.unused.get_or_try_init(py, || {
            let values = self
                .shared
                .result
                .unused()
                .iter()
                .map(|&i| position(i))
                .collect();
            index_vector(py, values).map(Bound::unbind)
        })?;
        Ok(unused.bind(py).clone())
    }

    /// Pairs of points that look like one point given twice a little apart (a border exported
    /// from both sides with a small disagreement, a grey image's contour at a level): the two lie
    /// 16 times nearer each other than either lies to any other point, whatever the stages made
    /// of them (a curve of two points, unused points), when at least three pairs, and more than
    /// one in 64 points, lie beside other pairs, as a curve given twice has them (chance makes
    /// pairs, but apart). An ``(m, 2)`` int64 array of input positions, the lower first,
    /// ascending; empty without that pattern. ``reconstruct``
    /// warns of them (``UserWarning``), as the command line notes them; ``condt.snap`` merges
    /// points within a distance.
    ///
    /// >>> import condt
    /// >>> condt.reconstruct([(0, 0), (1, 0), (2, 0), (3, 1)]).twin_pairs.shape
    /// (0, 2)
    #[getter]
    fn twin_pairs<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        let rows = self
            .shared
            .result
            .twin_pairs()
            .into_iter()
            .map(|pair| pair.map(position))
            .collect();
        index_array(py, rows)
    }

    /// Every stage that ran, in order: a dict from the stage's key (``"proximity"``,
    /// ``"repair"``, ``"iqr-outliers"``, ``"repair-again"``, ``"local-outliers"``, ``"clumps"``,
    /// ``"given-back"``, ``"gaps"``, ``"junctions"``, ``"crossings"``, ``"tips"``, ``"spikes"``,
    /// ``"hooks"``, ``"tails"``, ``"detours"``,
    /// or a baseline's ``"nn-crust"``, ``"crust"``: the words of ``condt reconstruct
    /// --timings``) to the ``(m, 2)`` edges it left, as ``edges`` gives the final ones. With smoothing passes,
    /// the stages are the last pass's.
    #[getter]
    fn stages<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let stages = self.stages.get_or_try_init(py, || {
            let result = &self.shared.result;
            let graphs: Vec<(&'static str, Vec<[i64; 2]>)> = crate::detached(py, || {
                crate::within_call(|| {
                    result
                        .stages()
                        .map(|report| {
                            let edges = report.graph.edges();
                            let rows = edges
                                .into_iter()
                                .map(|[a, b]| [position(a), position(b)])
                                .collect();
                            (report.stage.key(), rows)
                        })
                        .collect()
                })
            })?;
            let dict = PyDict::new(py);
            for (name, rows) in graphs {
                dict.set_item(name, index_array(py, rows)?)?;
            }
            Ok::<_, PyErr>(dict.unbind())
        })?;
        // A new dict each time (the arrays are shared): changing it changes nothing here.
        stages.bind(py).copy()
    }

    /// Why the edge between input positions ``i`` and ``j`` (either order) was kept or dropped:
    /// an ``EdgeStory`` with the text ``condt``'s HTML viewer shows and its numbers.
    ///
    /// The stories of all edges are computed on the first call (``O(n log n)``) and kept.
    ///
    /// An exact duplicate of an earlier point is that point (it shares the first one's edges, as
    /// in the triangulation): ``explain(4, 1)``, point 4 repeating point 0, tells the story of
    /// the edge 0-1, and the story's ``edge`` is ``(0, 1)``.
    ///
    /// With a baseline (``method="crust"`` or ``"nn-crust"``) the baseline's decision is the
    /// first change, ``reason`` ``"baseline"`` (``added`` whether it chose the edge); the ends
    /// still tell how ConDT's Algorithm 1 would have seen the edge, which the baseline did not
    /// use, and the text says so ("chosen by the Crust; Algorithm 1 would have seen it as: ...").
    ///
    /// The stories are the last run's: after smoothing passes (the default on noisy points) that
    /// is the run on the moved points, whose Delaunay triangulation can differ from the input's.
    ///
    /// Raises ``IndexError`` when ``i`` or ``j`` is not an input position, ``ValueError`` when
    /// they are the same point (the same position, or duplicates), ``KeyError`` when the edge is
    /// neither an edge of the triangulation the last run walked nor one a stage added (the
    /// message says when smoothing passes moved the points).
    ///
    /// >>> import condt
    /// >>> r = condt.reconstruct([(0, 0), (1, 0), (2, 0), (2, 9)])
    /// >>> story = r.explain(3, 0)
    /// >>> print(story)
    /// 0-3: second shortest at 0, dropped by the uniformity test: |e2| = 9.220 |e1| >= 2.750 |e1|; rank 3 at 3; dropped
    /// >>> story.kept, story.ends[0]["choice"], round(story.ends[0]["ratio"], 3)
    /// (False, 'second', 9.22)
    /// >>> r.explain(0, 1).kept
    /// True
    fn explain(
        &self,
        py: Python<'_>,
        i: &Bound<'_, PyAny>,
        j: &Bound<'_, PyAny>,
    ) -> PyResult<EdgeStory> {
        let n = self.shared.result.num_points();
        let (a, b) = (input_position("i", i, n)?, input_position("j", j, n)?);
        if a == b {
            return Err(PyValueError::new_err(format!(
                "explain({a}, {b}): an edge joins two points, not a point to itself"
            )));
        }
        // A duplicate is merged into its first point, whose edges the stories name (the
        // triangulation the stages walked says which that is).
        let tri = self.shared.result.triangulation();
        let (first_a, first_b) = (tri.first_at(a), tri.first_at(b));
        if first_a == first_b {
            return Err(PyValueError::new_err(format!(
                "explain({a}, {b}): {a} and {b} are the same point (duplicates: the first is \
                 {first_a}), and no edge joins a point to itself"
            )));
        }
        let edge = [first_a.min(first_b), first_a.max(first_b)];
        let stories = match self.stories.get() {
            Some(stories) => stories,
            None => {
                let result = &self.shared.result;
                let computed = crate::detached(py, || crate::within_call(|| result.provenance()))?;
                self.stories.get_or_init(|| computed)
            }
        };
        let story = stories
            .binary_search_by_key(&edge, |s| s.edge)
            .map(|k| &stories[k])
            .map_err(|_| {
                let walked = match self.shared.result.smoothing() {
                    Some(smoothing) => {
                        let passes = match smoothing.passes {
                            1 => "1 smoothing pass".to_string(),
                            n => format!("{n} smoothing passes"),
                        };
                        format!(
                            "an edge of the last run's Delaunay triangulation (of the points \
                             where {passes} moved them)"
                        )
                    }
                    None => "a Delaunay edge".to_string(),
                };
                PyKeyError::new_err(format!(
                    "{a}-{b} is not {walked}, nor an edge a stage added: no stage saw it"
                ))
            })?;
        let passes = self
            .shared
            .result
            .smoothing()
            .map_or(0, |smoothing| smoothing.passes);
        Ok(EdgeStory::new(story, passes))
    }

    /// The curves as GeoJSON text, what ``condt reconstruct -o out.geojson`` writes: a
    /// FeatureCollection with one LineString per curve (a closed one repeats its first point)
    /// and a ``closed`` property, on the input coordinates.
    ///
    /// ``crs``: the document's ``"crs"`` member, as ``condt reconstruct`` carries on a GeoJSON
    /// input's or writes ``--crs``: a JSON object's text (what ``read_points_with_crs`` gives), a
    /// ``dict`` (any mapping, written by ``json.dumps``), or a name such as ``"EPSG:32632"``,
    /// written as ``--crs`` writes it (a named crs, ``urn:ogc:def:crs:EPSG::32632``); ``None``,
    /// the default, writes none; the text ``"null"`` writes ``"crs": null`` (GeoJSON 2008: no
    /// crs can be assumed). ``TypeError`` for any other type; ``ValueError`` for text that starts
    /// as JSON (``{``) and is not one JSON object, or other JSON than an object, a string or
    /// ``null`` (``[1, 2]``, ``4326``). A pyproj ``CRS`` (a GeoDataFrame's ``.crs``) is written by
    /// its authority's name (``EPSG:32632``; ``ValueError`` for one without); PROJJSON
    /// (``CRS.to_json()``) is refused, as GDAL reads a file carrying it as EPSG:4326. For
    /// longitudes and latitudes (EPSG:4326, OGC:CRS84) RFC 7946 wants no ``crs``: leave it
    /// ``None``. Without a ``crs``, coordinates that cannot be a longitude
    /// and latitude (beyond 180 and 90: pixels, metres) get a ``UserWarning``, as the command line
    /// notes them; ``crs="null"`` says the frame is none and silences it.
    ///
    /// >>> import condt, json
    /// >>> r = condt.reconstruct([(0, 0), (1, 0), (0.5, 2)], paper=True)
    /// >>> doc = json.loads(r.to_geojson())
    /// >>> doc["features"][0]["geometry"]["coordinates"]
    /// [[0, 0], [1, 0], [0.5, 2], [0, 0]]
    /// >>> crs = {"type": "name", "properties": {"name": "EPSG:32632"}}
    /// >>> json.loads(r.to_geojson(crs=crs))["crs"] == crs
    /// True
    /// >>> json.loads(r.to_geojson(crs="EPSG:32632"))["crs"]["properties"]["name"]
    /// 'urn:ogc:def:crs:EPSG::32632'
    #[pyo3(signature = (*, crs = None))]
    fn to_geojson(&self, py: Python<'_>, crs: Option<&Bound<'_, PyAny>>) -> PyResult<String> {
        let crs: Option<String> = match crs {
            None => None,
            Some(text) if text.is_instance_of::<pyo3::types::PyString>() => {
                // As the command line's --crs takes it: a JSON object, or a name.
                let text: String = text.extract()?;
                Some(condt_io::crs_member(&text).map_err(crs_refused)?)
            }
            // A pyproj CRS (a GeoDataFrame's `.crs`): written by its authority's name, the
            // one form of it GeoJSON readers take (a GIS user's review: it was a TypeError).
            Some(value) if value.hasattr("to_authority")? => {
                let name = value.call_method0("to_authority")?;
                if name.is_none() {
                    return Err(PyValueError::new_err(format!(
                        "crs {} has no authority code, which GeoJSON's crs member names: pass \
                         a name such as \"EPSG:32632\", or reproject the points to one \
                         (GeoDataFrame.to_crs) before reconstructing",
                        value.str()?
                    )));
                }
                let (authority, code): (String, String) = name.extract()?;
                let text = format!("{authority}:{code}");
                Some(condt_io::crs_member(&text).map_err(PyValueError::new_err)?)
            }
            // GeoJSON's crs member is an object: a number or a list written there is a mistake.
            Some(value)
                if !value.is_instance(&py.import("collections.abc")?.getattr("Mapping")?)? =>
            {
                return Err(pyo3::exceptions::PyTypeError::new_err(format!(
                    "crs must be JSON text, a name (\"EPSG:4326\" for an EPSG code), a dict, \
                     a pyproj CRS or None, not {}",
                    value.get_type().name()?
                )));
            }
            // Any mapping, as a dict (`json.dumps` takes dicts alone), checked as JSON text is.
            Some(value) => {
                // NaN and infinities refused here: `json.dumps` writes them as `NaN` and
                // `Infinity`, which no JSON reader takes, and the object was then said to be "not
                // one JSON object" (a Python user's review).
                let strict = PyDict::new(py);
                strict.set_item("allow_nan", false)?;
                let text: String = py
                    .import("json")?
                    .getattr("dumps")?
                    .call((PyDict::type_object(py).call1((value,))?,), Some(&strict))
                    .map_err(|err| {
                        if err.is_instance_of::<PyValueError>(py) {
                            PyValueError::new_err(format!(
                                "crs holds a number JSON cannot write (NaN or infinite): {err}"
                            ))
                        } else {
                            pyo3::exceptions::PyTypeError::new_err(format!(
                                "crs must be JSON text or a JSON-serializable object: {err}"
                            ))
                        }
                    })?
                    .extract()?;
                Some(condt_io::crs_member(&text).map_err(crs_refused)?)
            }
        };
        // As the command line notes it: without a crs member, readers take the coordinates for
        // longitudes and latitudes (a GIS user's review: Python said nothing).
        if crs.is_none() {
            if let Some(p) = condt_io::not_longitude_latitude(&self.shared.points) {
                let message = format!(
                    "coordinates such as ({}, {}) are no longitude and latitude, which GeoJSON \
                     readers take them for without a crs member: crs= names the input's system \
                     (\"EPSG:32632\", for instance)",
                    p.x, p.y
                );
                crate::user_warning(py, message)?;
            }
        }
        // Without the GIL, as the other calls that take time on large results (0.22 s for the
        // 40 MB of scripts/scale.py's curves-1M).
        let shared = &self.shared;
        let written = py.detach(|| {
            let mut out = Vec::new();
            condt_io::write_geojson_with_crs(
                &mut out,
                &shared.result,
                &shared.points,
                crs.as_deref(),
            )
            .map(|()| out)
        });
        let out = written.map_err(|err| match err.kind() {
            std::io::ErrorKind::InvalidInput => PyValueError::new_err(err.to_string()),
            _ => PyRuntimeError::new_err(err.to_string()),
        })?;
        String::from_utf8(out).map_err(|err| PyRuntimeError::new_err(err.to_string()))
    }

    /// The curves as one ``shapely.MultiLineString`` on the input coordinates, a closed curve
    /// repeating its first point (``.is_closed``), in the order of ``curves``. Needs shapely 2
    /// (``pip install shapely``); ``ImportError`` without it.
    fn to_shapely<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        let py = slf.py();
        let shapely = py.import("shapely").map_err(|err| {
            PyImportError::new_err(format!(
                "Reconstruction.to_shapely() needs shapely (pip install shapely): {err}"
            ))
        })?;
        let this = slf.get();
        let lines = PyList::empty(py);
        for curve in this.shared.result.curves() {
            let closing = curve.points().next().filter(|_| curve.is_closed());
            lines.append(this.shared.coordinates(py, curve.points().chain(closing))?)?;
        }
        shapely.getattr("MultiLineString")?.call1((lines,))
    }

    /// How many smoothing passes ran (``smooth``; 0 where none did): the edges are the last
    /// pass's. ``condt.dask.reconstruct``'s result says the same of a tiled run.
    ///
    /// >>> import condt
    /// >>> condt.reconstruct([(0, 0), (1, 0), (1, 1), (0, 1)]).passes
    /// 0
    #[getter]
    fn passes(&self) -> usize {
        self.shared
            .result
            .smoothing()
            .map_or(0, |smoothing| smoothing.passes)
    }

    /// Wall-clock seconds of each timed step, in the order they ran, by the words of ``condt
    /// reconstruct --timings``: ``earlier-passes`` when smoothing passes ran (the first
    /// reconstruction and every pass but the last), ``triangulation``, each stage (the keys of
    /// ``stages``) and ``curves`` (their assembly and the tally).
    ///
    /// >>> import condt
    /// >>> r = condt.reconstruct([(0, 0), (1, 0), (1, 1), (0, 1)], paper=True)
    /// >>> list(r.timings)
    /// ['triangulation', 'proximity', 'repair', 'iqr-outliers', 'curves']
    #[getter]
    fn timings<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let timings = PyDict::new(py);
        for (step, time) in self.shared.result.timings() {
            timings.set_item(step, time.as_secs_f64())?;
        }
        Ok(timings)
    }

    /// The number of input points.
    fn __len__(&self) -> usize {
        self.shared.result.num_points()
    }

    fn __repr__(&self) -> String {
        let curves = self.shared.result.curves();
        let closed = curves.iter().filter(|c| c.is_closed()).count();
        let counted = |n: usize, word: &str| format!("{n} {word}{}", if n == 1 { "" } else { "s" });
        format!(
            "<condt.Reconstruction: {}, {}, {} ({closed} closed), {} unused>",
            counted(self.shared.result.num_points(), "point"),
            counted(self.shared.result.edge_list().len(), "edge"),
            counted(curves.len(), "curve"),
            self.shared.result.unused().len()
        )
    }
}

/// One curve of a ``Reconstruction``: its points in order along it, and whether it closes.
///
/// ``points`` are input positions (int64; a closed curve does not repeat its first point);
/// ``coords`` are their coordinates, an ``(len, 2)`` float64 array.
///
/// >>> import condt
/// >>> r = condt.reconstruct([(0, 0), (1, 0), (1, 1), (0, 1)])
/// >>> curve = r.curves[0]
/// >>> curve.closed, len(curve), curve.points.tolist()
/// (True, 4, [0, 1, 2, 3])
/// >>> curve.coords.tolist()
/// [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
#[pyclass(module = "condt", frozen)]
pub(crate) struct Curve {
    /// The result's data, not the `Reconstruction` (which caches its curves: no cycle).
    shared: Arc<Shared>,
    index: usize,
    points: PyOnceLock<Py<PyArray1<i64>>>,
    coords: PyOnceLock<Py<PyArray2<f64>>>,
}

impl Curve {
    fn curve(&self) -> &condt::Curve {
        &self.shared.result.curves()[self.index]
    }
}

#[pymethods]
impl Curve {
    /// The input positions of its points, in order along it (int64, read-only).
    #[getter]
    fn points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<i64>>> {
        let points = self.points.get_or_try_init(py, || {
            let values = self.curve().points().map(position).collect();
            index_vector(py, values).map(Bound::unbind)
        })?;
        Ok(points.bind(py).clone())
    }

    /// Whether the last point joins back to the first.
    #[getter]
    fn closed(&self) -> bool {
        self.curve().is_closed()
    }

    /// The coordinates of its points, in order along it: a ``(len, 2)`` float64 array
    /// (read-only, as every result array).
    #[getter]
    fn coords<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let coords = self.coords.get_or_try_init(py, || {
            let array = self.shared.coordinates(py, self.curve().points())?;
            read_only(array.as_any())?;
            Ok::<_, PyErr>(array.unbind())
        })?;
        Ok(coords.bind(py).clone())
    }

    /// The number of points along the curve (a closed curve counts its first point once).
    fn __len__(&self) -> usize {
        self.curve().len()
    }

    /// The object itself: it never changes, so a copy is the same object.
    fn __copy__(slf: PyRef<'_, Self>) -> PyRef<'_, Self> {
        slf
    }

    /// The object itself, as ``__copy__``.
    fn __deepcopy__<'py>(slf: PyRef<'py, Self>, _memo: &Bound<'py, PyAny>) -> PyRef<'py, Self> {
        slf
    }

    fn __repr__(&self) -> String {
        let curve = self.curve();
        format!(
            "<condt.Curve: {} points, {}>",
            curve.len(),
            if curve.is_closed() { "closed" } else { "open" }
        )
    }
}

/// Why one edge was kept or dropped: ``Reconstruction.explain`` returns it.
///
/// - ``edge``: the two input positions, smaller first;
/// - ``kept``: whether it is in the result;
/// - ``ends``: how each end saw it in Algorithm 1, two dicts with ``at`` (the end) and
///   ``choice``: ``"shortest"``, ``"second"`` (with ``ratio`` = ``|e2| / |e1|``, ``bound`` and
///   ``kept``, the uniformity test's numbers), ``"later"`` (with ``rank``) or ``"not-delaunay"``;
/// - ``changes``: what each later stage did to it, dicts with ``stage`` (its key, as in
///   ``stages``), ``added`` and ``reason``: ``"repair"`` (``vertex``, ``degree``, ``selected``:
///   the neighbours Algorithm 2 selected there), ``"longer-than-threshold"`` (``length``,
///   ``threshold``, ``floored``), ``"given-back"``,
///   ``"last-edge"`` (given back as a curve's last edge), ``"long-at"`` (``vertex``, ``ratio``),
///   ``"repaired-again"``, ``"component"``, ``"spur"``, ``"clump"``, ``"gap-closed"``,
///   ``"junction"``, ``"crossing"`` (``vertex``), ``"tip"``, ``"spike"``, ``"hook"``, ``"tail"``
///   (``vertex``, ``points``), ``"detour"`` (``from``, ``to``, ``points``; ``from == to``: the
///   edge that closed a loop hung on that point), ``"baseline"`` or ``"not-confirmed"``;
/// - ``text`` (and ``str()``): all of it in a sentence, as the HTML viewer shows it; after
///   smoothing passes it ends by saying that its lengths are between the points where the
///   stages saw them, as the viewer does.
///
/// ``ends`` and ``changes`` are new dicts and lists at each read, so the story never changes
/// (a copy is the story itself): what a caller changes in them is the caller's.
#[pyclass(module = "condt", frozen)]
pub(crate) struct EdgeStory {
    story: condt::EdgeStory,
    /// The smoothing passes that moved the points the story measured (0: none).
    passes: usize,
}

impl EdgeStory {
    fn new(story: &condt::EdgeStory, passes: usize) -> EdgeStory {
        EdgeStory {
            story: story.clone(),
            passes,
        }
    }
}

#[pymethods]
impl EdgeStory {
    /// The two input positions, smaller first.
    #[getter]
    fn edge(&self) -> (usize, usize) {
        let [a, b] = self.story.edge;
        (a, b)
    }

    /// Whether the edge is in the result.
    #[getter]
    fn kept(&self) -> bool {
        self.story.kept
    }

    /// How each end saw the edge in Algorithm 1 (see the class).
    #[getter]
    fn ends<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let [a, b] = self.story.edge;
        let ends = [(a, self.story.ends[0]), (b, self.story.ends[1])]
            .into_iter()
            .map(|(at, choice)| end_dict(py, at, choice))
            .collect::<PyResult<Vec<_>>>()?;
        PyTuple::new(py, ends)
    }

    /// What each later stage did to the edge (see the class).
    #[getter]
    fn changes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let changes = PyList::empty(py);
        for change in &self.story.changes {
            changes.append(change_dict(py, change)?)?;
        }
        Ok(changes)
    }

    /// All of it in a sentence, as the HTML viewer shows it.
    #[getter]
    fn text(&self) -> String {
        let text = condt_io::story_text(&self.story);
        // Its lengths are the moved points' (an image user's review: pixels 1 apart read
        // "|e2| = 1.250 |e1|", and only the viewer said why).
        match self.passes {
            0 => text,
            1 => {
                format!("{text} (lengths where the stages saw the points, after 1 smoothing pass)")
            }
            n => format!(
                "{text} (lengths where the stages saw the points, after {n} smoothing passes)"
            ),
        }
    }

    fn __str__(&self) -> String {
        self.text()
    }

    /// The object itself: it never changes, so a copy is the same object.
    fn __copy__(slf: PyRef<'_, Self>) -> PyRef<'_, Self> {
        slf
    }

    /// The object itself, as ``__copy__``.
    fn __deepcopy__<'py>(slf: PyRef<'py, Self>, _memo: &Bound<'py, PyAny>) -> PyRef<'py, Self> {
        slf
    }

    fn __repr__(&self) -> String {
        format!("<condt.EdgeStory {}>", self.text())
    }
}

fn end_dict<'py>(py: Python<'py>, at: usize, choice: EndChoice) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    dict.set_item("at", at)?;
    match choice {
        EndChoice::Shortest => dict.set_item("choice", "shortest")?,
        EndChoice::Second { ratio, bound, kept } => {
            dict.set_item("choice", "second")?;
            dict.set_item("ratio", ratio)?;
            dict.set_item("bound", bound)?;
            dict.set_item("kept", kept)?;
        }
        EndChoice::Later { rank } => {
            dict.set_item("choice", "later")?;
            dict.set_item("rank", rank)?;
        }
        EndChoice::NotDelaunay => dict.set_item("choice", "not-delaunay")?,
    }
    Ok(dict)
}

fn change_dict<'py>(py: Python<'py>, change: &Change) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    dict.set_item("stage", change.stage.key())?;
    dict.set_item("added", change.added)?;
    let reason = match change.reason {
        Reason::Repair {
            vertex,
            degree,
            selected,
        } => {
            dict.set_item("vertex", vertex)?;
            dict.set_item("degree", degree)?;
            dict.set_item(
                "selected",
                selected.iter().flatten().copied().collect::<Vec<_>>(),
            )?;
            "repair"
        }
        Reason::LongerThanThreshold {
            length,
            threshold,
            floored,
        } => {
            dict.set_item("length", length)?;
            dict.set_item("threshold", threshold)?;
            dict.set_item("floored", floored)?;
            "longer-than-threshold"
        }
        Reason::GivenBack => "given-back",
        Reason::LastEdge => "last-edge",
        Reason::LongAt { vertex, ratio } => {
            dict.set_item("vertex", vertex)?;
            dict.set_item("ratio", ratio)?;
            "long-at"
        }
        Reason::Component => "component",
        Reason::Spur => "spur",
        Reason::GapClosed => "gap-closed",
        Reason::Junction => "junction",
        Reason::Crossing { vertex } => {
            dict.set_item("vertex", vertex)?;
            "crossing"
        }
        Reason::Tip => "tip",
        Reason::Spike => "spike",
        Reason::Hook => "hook",
        Reason::Tail { vertex, points } => {
            dict.set_item("vertex", vertex)?;
            dict.set_item("points", points)?;
            "tail"
        }
        Reason::Detour { from, to, points } => {
            dict.set_item("from", from)?;
            dict.set_item("to", to)?;
            dict.set_item("points", points)?;
            "detour"
        }
        Reason::Clump => "clump",
        Reason::RepairedAgain => "repaired-again",
        Reason::Baseline => "baseline",
        Reason::NotConfirmed => "not-confirmed",
    };
    dict.set_item("reason", reason)?;
    Ok(dict)
}

/// `crs_member`'s refusal as Python's `ValueError`; PROJJSON's with the form Python has beside
/// a name: the pyproj CRS itself.
fn crs_refused(why: String) -> PyErr {
    if why.starts_with("PROJJSON") {
        PyValueError::new_err(format!("{why}, or the pyproj CRS itself (gdf.crs)"))
    } else {
        PyValueError::new_err(why)
    }
}
