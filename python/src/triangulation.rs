//! `Triangulation`: a `condt::Triangulation` as Python reads it.
//!
//! Owns: the Python view of the kernel's result in input positions, arrays made once and cached
//! read-only. It may not build or change a triangulation.

use crate::convert::{index_array, index_vector, input_position, position};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;

/// The Delaunay triangulation of a set of points, in input positions: what
/// ``condt.triangulate`` returns.
///
/// Exact duplicate points are merged into the first of them: a duplicate is in no triangle of
/// its own and shares its point's neighbours. Arrays are ``int64`` and read-only.
///
/// >>> import condt
/// >>> t = condt.triangulate([(0, 0), (4, 0), (4, 3), (0, 3), (1, 1)])
/// >>> len(t.triangles), len(t.edges)
/// (4, 8)
/// >>> sorted(t.neighbors(4).tolist())
/// [0, 1, 2, 3]
/// >>> sorted(t.hull.tolist())
/// [0, 1, 2, 3]
#[pyclass(module = "condt", frozen)]
pub(crate) struct Triangulation {
    tri: condt::Triangulation,
    triangles: PyOnceLock<Py<PyArray2<i64>>>,
    edges: PyOnceLock<Py<PyArray2<i64>>>,
    hull: PyOnceLock<Py<PyArray1<i64>>>,
}

impl Triangulation {
    pub(crate) fn new(tri: condt::Triangulation) -> Self {
        Triangulation {
            tri,
            triangles: PyOnceLock::new(),
            edges: PyOnceLock::new(),
            hull: PyOnceLock::new(),
        }
    }
}

#[pymethods]
impl Triangulation {
    /// The triangles, a ``(t, 3)`` array of input positions, each counter-clockwise: the rows
    /// ``condt triangulate`` writes, in its order. Points all on one line have none.
    #[getter]
    fn triangles<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        let triangles = self.triangles.get_or_try_init(py, || {
            let tri = &self.tri;
            let rows = crate::detached(py, || {
                tri.triangles()
                    .map(|t| t.map(position))
                    .collect::<Vec<[i64; 3]>>()
            })?;
            index_array(py, rows).map(Bound::unbind)
        })?;
        Ok(triangles.bind(py).clone())
    }

    /// The edges, an ``(m, 2)`` array of input positions ``[i, j]``, ``i < j``, sorted: the rows
    /// ``condt triangulate --edges`` writes (for collinear points, their chain).
    #[getter]
    fn edges<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        let edges = self.edges.get_or_try_init(py, || {
            let tri = &self.tri;
            let rows = crate::detached(py, || {
                crate::within_call(|| {
                    let mut rows: Vec<[i64; 2]> = tri.edges().map(|e| e.map(position)).collect();
                    rows.sort_unstable();
                    rows
                })
            })?;
            index_array(py, rows).map(Bound::unbind)
        })?;
        Ok(edges.bind(py).clone())
    }

    /// The Delaunay neighbours of input point ``i``, counter-clockwise (for a hull point, from
    /// one hull neighbour through the interior to the other), as a new read-only int64 array.
    ///
    /// Raises ``IndexError`` when ``i`` is not an input position.
    fn neighbors<'py>(
        &self,
        py: Python<'py>,
        i: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<i64>>> {
        let index = input_position("i", i, self.tri.num_points())?;
        index_vector(py, self.tri.neighbors(index).map(position).collect())
    }

    /// The convex hull, input positions counter-clockwise from some hull point, each hull edge
    /// once (points on a hull edge included, as the Rust ``Mesh::hull`` gives them).
    ///
    /// On points all on one line (no triangle) the walk goes out along the line and back: the
    /// inner points appear twice, the two ends once. One distinct point has no hull edge: the
    /// array is empty.
    ///
    /// >>> import condt
    /// >>> condt.triangulate([(0, 0), (1, 0), (2, 0), (3, 0)]).hull.tolist()
    /// [0, 1, 2, 3, 2, 1]
    #[getter]
    fn hull<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<i64>>> {
        let hull = self.hull.get_or_try_init(py, || {
            index_vector(py, self.tri.hull().map(position).collect()).map(Bound::unbind)
        })?;
        Ok(hull.bind(py).clone())
    }

    /// The number of distinct points (exact duplicates count once).
    #[getter]
    fn num_vertices(&self) -> usize {
        self.tri.num_vertices()
    }

    /// The number of input points.
    fn __len__(&self) -> usize {
        self.tri.num_points()
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
        format!(
            "<condt.Triangulation: {} points, {} distinct>",
            self.tri.num_points(),
            self.tri.num_vertices()
        )
    }
}
