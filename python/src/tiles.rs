//! The native half of `condt.dask` (`python/python/condt/dask.py`): what the driver computes
//! once for the whole set, what a worker computes for one tile, and the global steps run on the
//! edges the tiles send back.
//!
//! Owns: the tile's certificate (which of its triangles and hull edges are provably the whole
//! set's), the global facts it needs (insertion ranks, the convex hull's boundary) and the
//! rounds' plumbing. It may not implement a stage: the tile runs the library's own stages and
//! tests on the library's own triangulation ([`Triangulation::triangulate_in_order`]), and every
//! global rule runs once, in the library ([`condt::tiled`]).
//!
//! Why a certified tile gives the whole set's edges: a point the tile does not hold lies inside
//! the set's convex hull, outside the rectangle whose points the tile holds (its *known*
//! region), and deeper below the hull's boundary than the band the tile was sent. A triangle of
//! the tile's Delaunay triangulation whose circumcircle misses that region has no point of the
//! whole set inside it, so it is one of the whole set's Delaunay triangles; a hull edge of the
//! tile is one of the set's when its ends are neighbours on the set's hull boundary. A vertex all of whose
//! triangles and hull edges are certified has the whole set's star. The stages read a bounded
//! number of Delaunay hops around a vertex (proximity one ring, the repair two more, the crossings
//! and the hooks eight, the junctions sixteen, the outlier tails nine, the spikes eighteen, the
//! detours six:
//! [`LATER_STAGES`]), and break ties by vertex id, which follows the set's insertion order
//! restricted to the tile: so an owned vertex whose every vertex within `reach` hops is certified
//! gets the whole set's edges.
//! Four cocircular points make the triangulation not unique; the tile reports them and the
//! driver runs the whole set in one piece instead.

use crate::convert::{as_points, index_array, index_vector, library_error, points_array};
use crate::params;
use condt::geometry::{binary_exponent, Scale};
use condt::predicates::{is_cocircular, orient2d, Orientation};
use condt::tiled::GAP_ROW;
use condt::{GatheredPass, Method, Params, Point, Stage, Triangulation};
use numpy::ndarray::Array2;
use numpy::{
    PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyNotImplementedError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::collections::VecDeque;

/// The widest spread, in binary orders of magnitude, between a set's largest coordinate
/// magnitude and its smallest nonzero one for which every tile measures exactly as the whole set
/// does (the library's fast range: a tile's power-of-two frames then lose no bit).
const MAX_TILED_SPREAD: i32 = 200;

/// The most hull corners for which tiles hold a band along the hull's boundary (the depths cost
/// a pass over the points per corner); above it, tiles near the hull grow their halos instead.
const MAX_BAND_CORNERS: usize = 512;

/// How a tiled run goes: which steps run on the tiles, and which global step runs on the driver
/// between them.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum Flow {
    /// Tiles: the proximity graph, then the repair if selected; driver: Algorithm 3, if selected.
    Repaired,
    /// Tiles: the proximity graph; driver: Algorithm 3; tiles: the repair of what it kept.
    OutliersFirst,
    /// Tiles: the proximity graph and its repair; driver: Algorithm 3 and the edges to repair
    /// again; tiles: the repair of those.
    RepairAgain,
}

impl Flow {
    fn name(self) -> &'static str {
        match self {
            Flow::Repaired => "repaired",
            Flow::OutliersFirst => "outliers_first",
            Flow::RepairAgain => "repair_again",
        }
    }
}

/// The stages after the flow that tiles run one round each, on their kept triangulations and the
/// driver's edges, with the Delaunay hops around an owned point each reads (docs/distributed.md,
/// *Later stages as rounds*): a junction's choice reads seven hops from the loose end (its walk
/// through a stranded sample or the chord past it, then the branches), twelve where the end's piece
/// is too short for a branch (five along the piece to its other end, whose own junction reads
/// seven), and the other ends choosing one of its points, up to three hops from the end, four more;
/// a crossing's arms and chord, read from the chord's ends, eight ([`_step_kept`]); the clump tests
/// one ring ([`_tests_kept`], the rule itself on the driver, [`_gathered_clumps`]), and where the
/// driver finds clumps the gap choices, tip candidates and the hooks' and junctions' joins (twelve
/// hops) on the same edges; a tip's candidate move eight, from the loose end to the other's branch
/// ([`_choices_kept`], the split test and the settling on the driver, [`_gathered_tips`]); a hooked
/// loose end's move eight: its points lie within two hops of the loose end, its tests read the
/// stars there, and a move sharing a point is read from a loose end two hops beyond that point
/// ([`_step_kept`], and its joins, settled on the tile, for rule 4 and the clumps:
/// [`_choices_kept`]); a spike's move eighteen: its points lie within six hops of each other along
/// its path, its tests read their stars, the degrees one hop beyond and, between two loose ends,
/// five points along each end's curve, and a move sharing one of its points spans as far again
/// ([`_step_kept`]); a loose end's gap choice six, its straight walk five ([`_choices_kept`],
/// agreement, the joins along lone edges and the stranded runs on the driver, [`_gathered_gaps`]);
/// the local outlier removal's rules 1 to 3 six composed ([`_local_rules_kept`]), then rule 4 on
/// the driver ([`_gathered_local_outliers`]) with the clump tests, gap choices, tip candidates and
/// the hooks' and junctions' joins (twelve hops: a junction's choice) of their result; the
/// given-back test one ring ([`_tests_kept`], the rule on the driver, [`_gathered_given_back`]); an
/// outlier tail nine: from an owned edge of a tail of four back to its loose end and on to the far
/// end of the five edges it hangs from, whose last inner point's edges are read for its degree
/// ([`_step_kept`]); a detour six: its two routes make a cycle of at most ten edges, so its points
/// lie within five hops of an owned end of an edge it removes, and their edges are read; its ends'
/// third neighbours one more (a third route, read up to five points, decides only where it
/// reaches the other end within them: a path the tile finds is one of the whole set's;
/// [`_step_kept`]). A tip's apex move also reads the spikes step's test on its chord, whose
/// ends are one hop from the apex: nineteen, for the tips and for the tip candidates that rule 4
/// and the clumps read.
const LATER_STAGES: [(Stage, usize); 11] = [
    (Stage::LocalOutliers, 19),
    (Stage::Clumps, 19),
    (Stage::GivenBack, 1),
    (Stage::Gaps, 6),
    (Stage::Junctions, 16),
    (Stage::Crossings, 8),
    (Stage::Tips, 19),
    (Stage::Spikes, 18),
    (Stage::Hooks, 8),
    (Stage::Tails, 9),
    (Stage::Detours, 6),
];

/// The hops the flow's stages read around an owned point: the proximity graph one ring, the
/// repair two more hops; twice that, for margin (docs/distributed.md, *The certificate*).
const FLOW_REACH: usize = 6;

/// How a tiled run of the stages `params` select goes, or why it cannot: the [`Flow`] of the
/// proximity graph (fixed or adaptive `u`), the repair, Algorithm 3 in either order and repairing
/// again, then the stages of [`LATER_STAGES`] one round each; each run of the smoothing passes is
/// one such run ([`_gathered_smoothing_pass`] between them).
struct Tiled {
    flow: Flow,
    /// The stages after the flow, in order.
    later: Vec<Stage>,
    /// The Delaunay hops around an owned point whose stars a tile must certify.
    reach: usize,
}

fn tiled_flow(params: &Params) -> Result<Tiled, String> {
    if params.method != Method::ConDT {
        return Err(format!("the baseline {}", params.stages()[0].name()));
    }
    let stages = params.stages();
    let in_flow = [
        Stage::Proximity,
        Stage::Repair,
        Stage::Outliers,
        Stage::RepairAgain,
    ];
    let later_reach = |stage: Stage| LATER_STAGES.iter().find(|(s, _)| *s == stage).map(|r| r.1);
    let refused = stages
        .iter()
        .find(|&&s| !in_flow.contains(&s) && later_reach(s).is_none());
    if let Some(&stage) = refused {
        let keyword = crate::params::switch_keyword(stage)
            .map(|keyword| format!(" ({keyword}=False leaves it out)"))
            .unwrap_or_default();
        return Err(format!("the {} step{keyword}", stage.name()));
    }
    let at = |stage: Stage| stages.iter().position(|&s| s == stage);
    let flow = match (at(Stage::Repair), at(Stage::Outliers)) {
        (Some(repair), Some(outliers)) if outliers < repair => Flow::OutliersFirst,
        _ if at(Stage::RepairAgain).is_some() => Flow::RepairAgain,
        _ => Flow::Repaired,
    };
    let later: Vec<Stage> = stages
        .into_iter()
        .filter(|&s| later_reach(s).is_some())
        .collect();
    let reach = later
        .iter()
        .filter_map(|&s| later_reach(s))
        .fold(FLOW_REACH, usize::max);
    Ok(Tiled { flow, later, reach })
}

/// The stages `params` select, or `NotImplementedError` naming the first that cannot be tiled.
fn tiled_params(kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<(Params, Tiled)> {
    let params = params::params(kwargs)?;
    match tiled_flow(&params) {
        Ok(tiled) => Ok((params, tiled)),
        Err(step) => Err(PyNotImplementedError::new_err(format!(
            "condt.dask tiles ConDT's stages, not {step}: use condt.reconstruct"
        ))),
    }
}

/// For the driver, before it looks for a client: checks the parameters alone, as
/// [`_tile_plan`] does, so that a call refused for them says why without a cluster (Dask's "No
/// global client found" came first, a review's find).
#[pyfunction]
#[pyo3(signature = (**params))]
pub(crate) fn _tile_params(params: Option<&Bound<'_, PyDict>>) -> PyResult<()> {
    tiled_params(params).map(|_| ())
}

/// For the driver, once: checks the points and the parameters, and returns the facts every tile
/// needs as a dict: `ranks` (each point's place in the whole set's insertion order), `boundary`
/// (each point's place along the convex hull's boundary, counter-clockwise, `-1` inside),
/// `boundary_len`, `hull` (the hull's corners, counter-clockwise), `depth` (each point's distance
/// to the hull's boundary, or `None` for a hull of over [`MAX_BAND_CORNERS`] corners), and
/// `whole` (why the set must run in one piece, or `None`).
#[pyfunction]
#[pyo3(signature = (points, **params))]
pub(crate) fn _tile_plan<'py>(
    py: Python<'py>,
    points: &Bound<'py, PyAny>,
    params: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (params, tiled) = tiled_params(params)?;
    let array = points_array(py, points)?;
    let borrowed = array.try_readonly()?;
    let points = as_points(borrowed.as_slice()?);
    let (order, boundary, hull, depth, whole) = crate::detached(py, || {
        let order = Triangulation::insertion_order(points)?;
        let (boundary, len, hull) = hull_boundary(points);
        let whole = if len < 3 {
            Some("all points lie on one line")
        } else if spread(points) > MAX_TILED_SPREAD {
            Some("the coordinates span too many orders of magnitude")
        } else {
            None
        };
        // The band along the hull's boundary (see `_run_tile`) needs each point's depth:
        // one pass per corner, so only for hulls of few corners.
        let depth = (hull.len() <= MAX_BAND_CORNERS).then(|| depths(points, &hull));
        Ok((order, (boundary, len), hull, depth, whole))
    })?
    .map_err(|err| library_error(err, points))?;
    let mut ranks = vec![0i64; points.len()];
    for (rank, &i) in order.iter().enumerate() {
        ranks[i as usize] = rank as i64;
    }
    let plan = PyDict::new(py);
    plan.set_item("ranks", index_vector(py, ranks)?)?;
    plan.set_item("boundary", index_vector(py, boundary.0)?)?;
    plan.set_item("boundary_len", boundary.1)?;
    plan.set_item("whole", whole)?;
    plan.set_item("flow", tiled.flow.name())?;
    let later: Vec<&str> = tiled.later.iter().map(|s| s.key()).collect();
    plan.set_item("later", later)?;
    plan.set_item("reach", tiled.reach)?;
    plan.set_item("outliers", params.stages().contains(&Stage::Outliers))?;
    plan.set_item("smooth", params.smooth)?;
    plan.set_item("depth", depth.map(|d| PyArray1::from_vec(py, d)))?;
    let flat: Vec<f64> = hull.iter().flat_map(|p| [p.x, p.y]).collect();
    let hull = Array2::from_shape_vec((flat.len() / 2, 2), flat)
        .map_err(|err| PyValueError::new_err(err.to_string()))?;
    plan.set_item("hull", PyArray2::from_owned_array(py, hull))?;
    Ok(plan)
}

/// The binary orders of magnitude between the largest coordinate magnitude and the smallest
/// nonzero one (0 for a set of zeros).
fn spread(points: &[Point]) -> i32 {
    let magnitudes = points.iter().flat_map(|p| [p.x.abs(), p.y.abs()]);
    let (mut low, mut high) = (f64::INFINITY, 0.0f64);
    for m in magnitudes.filter(|&m| m > 0.0) {
        low = low.min(m);
        high = high.max(m);
    }
    if high == 0.0 {
        0
    } else {
        binary_exponent(high) - binary_exponent(low)
    }
}

/// Each point's place along the convex hull's boundary, counter-clockwise, with the points on
/// its edges (the Delaunay triangulation's hull edges join neighbours along it), `-1` for a point
/// inside or an exact duplicate of a smaller position; the boundary's length (at most 2 if all
/// are collinear); and the hull's corners, counter-clockwise. Andrew's monotone chain on the exact
/// orientation, keeping the points on the hull's edges.
fn hull_boundary(points: &[Point]) -> (Vec<i64>, usize, Vec<Point>) {
    let mut sorted: Vec<usize> = (0..points.len()).collect();
    sorted.sort_by(|&a, &b| points[a].lexicographic_cmp(points[b]).then(a.cmp(&b)));
    sorted.dedup_by(|later, kept| points[*later] == points[*kept]);
    // The lower chain left to right, then the upper one back; each ends where the other starts.
    let mut chain: Vec<usize> = Vec::with_capacity(sorted.len() + 1);
    extend_chain(&mut chain, points, sorted.iter().copied());
    extend_chain(&mut chain, points, sorted.iter().rev().copied());
    let mut boundary = vec![-1i64; points.len()];
    let collinear = chain.len() >= 2 * sorted.len().saturating_sub(1);
    if collinear {
        return (boundary, sorted.len().min(2), Vec::new());
    }
    for (k, &p) in chain.iter().enumerate() {
        boundary[p] = k as i64;
    }
    let len = chain.len();
    let corners = (0..len)
        .filter(|&k| {
            let [a, b, c] = [chain[(k + len - 1) % len], chain[k], chain[(k + 1) % len]];
            orient2d(points[a], points[b], points[c]) != Orientation::Collinear
        })
        .map(|k| points[chain[k]])
        .collect();
    (boundary, len, corners)
}

/// Appends to `chain` the points of `ordered` that make no right turn (Andrew's monotone chain,
/// keeping collinear points), without its last point, which starts the next chain.
fn extend_chain(chain: &mut Vec<usize>, points: &[Point], ordered: impl Iterator<Item = usize>) {
    let start = chain.len();
    for p in ordered {
        while chain.len() >= start + 2 {
            let [a, b] = [chain[chain.len() - 2], chain[chain.len() - 1]];
            if orient2d(points[a], points[b], points[p]) != Orientation::Cw {
                break;
            }
            chain.pop();
        }
        chain.push(p);
    }
    chain.pop();
}

/// What a tile sends back: `("ok", edges, state)` with the edges it owns after the repair, in
/// input positions of the whole set, and with `keep` its certified triangulation ([`TileState`],
/// else `None`) for a second phase on the same worker ([`_step_kept`]); `("grow", None)` when a vertex within `reach` hops of an owned one
/// has an uncertified star (the known region is too small); `("cocircular", None, None)` when four
/// points there are cocircular.
///
/// The tile's points are `points` (every point of the whole set inside `known`, a rectangle
/// `[x0, y0, x1, y1]` whose sides may be infinite), listed by their `positions` in the whole set,
/// ascending, and besides them every point within `band` of the hull's boundary (`0`: none);
/// `ranks`, `boundary`, `boundary_len` and `hull` are the plan's (for its points, and the hull's
/// corners); `owned` marks the tile's own points; `bbox` is the whole set's
/// bounding box. Why the band: a Delaunay triangle on a long hull edge has a circle that runs
/// along the edge, far beyond the tile, but only a thin sliver of it lies inside the hull; with
/// the band the tile knows that sliver without holding the whole length of the edge.
#[allow(clippy::too_many_arguments)]
#[pyfunction]
#[pyo3(signature = (points, positions, ranks, owned, boundary, boundary_len, hull, band, known, bbox, reach, phase, keep=false, **params))]
pub(crate) fn _run_tile<'py>(
    py: Python<'py>,
    points: &Bound<'py, PyAny>,
    positions: PyReadonlyArray1<'py, i64>,
    ranks: PyReadonlyArray1<'py, i64>,
    owned: PyReadonlyArray1<'py, bool>,
    boundary: PyReadonlyArray1<'py, i64>,
    boundary_len: i64,
    hull: &Bound<'py, PyAny>,
    band: f64,
    known: [f64; 4],
    bbox: [f64; 4],
    reach: usize,
    phase: &str,
    keep: bool,
    params: Option<&Bound<'py, PyDict>>,
) -> PyResult<TileReport<'py>> {
    let (params, _) = tiled_params(params)?;
    let phase = Phase::named(phase)?;
    let array = points_array(py, points)?;
    let borrowed = array.try_readonly()?;
    let points = as_points(borrowed.as_slice()?);
    let hull_array = points_array(py, hull)?;
    let hull_borrowed = hull_array.try_readonly()?;
    let hull = as_points(hull_borrowed.as_slice()?);
    let (positions, ranks, owned, boundary) = (
        positions.as_slice()?,
        ranks.as_slice()?,
        owned.as_slice()?,
        boundary.as_slice()?,
    );
    let n = points.len();
    if [positions.len(), ranks.len(), owned.len(), boundary.len()] != [n; 4] {
        return Err(PyValueError::new_err("a tile's arrays differ in length"));
    }
    let outcome = crate::detached(py, || {
        crate::within_call(
            || -> Result<Result<(OwnedLists, Option<TileState>), Failure>, condt::Error> {
                let tile = Tile::new(known, bbox, boundary, boundary_len, hull, band);
                let mut order: Vec<u32> = (0..n as u32).collect();
                order.sort_unstable_by_key(|&i| ranks[i as usize]);
                let tri = Triangulation::triangulate_in_order(points, &order)?;
                if let Err(failure) = tile.certify(&tri, points, owned, reach) {
                    return Ok(Err(failure));
                }
                let owned_edges = |edges| owned_rows(owned, positions, edges);
                // The proximity graph (with its repair).
                let proximity = tri.proximity_graph(params.uniformity)?;
                let repaired = (phase == Phase::Both
                    || (phase == Phase::Repaired && params.stages().contains(&Stage::Repair)))
                .then(|| owned_edges(proximity.repair(params.repair).edges()));
                let proximity = (phase != Phase::Repaired || repaired.is_none())
                    .then(|| owned_edges(proximity.edges()));
                let lists = proximity.into_iter().chain(repaired).collect();
                let state = keep.then(|| TileState {
                    positions: positions.to_vec(),
                    owned: owned.to_vec(),
                    points: points.to_vec(),
                    order,
                    tri,
                });
                Ok(Ok((lists, state)))
            },
        )
    })?
    .map_err(|err| library_error(err, points))?;
    match outcome {
        Ok((lists, state)) => {
            let arrays = lists.into_iter().map(|edges| index_array(py, edges));
            let state = state.map(|state| Bound::new(py, state)).transpose()?;
            Ok(("ok", Some(arrays.collect::<PyResult<_>>()?), state))
        }
        Err(Failure::Grow) => Ok(("grow", None, None)),
        Err(Failure::Cocircular) => Ok(("cocircular", None, None)),
    }
}

/// A certified tile's triangulation, kept on its worker between two phases so that the second
/// ([`_step_kept`]) neither receives the tile's points again nor triangulates them again. When
/// pickled (Dask moving it to another worker) it carries the points and their insertion order,
/// and is triangulated again on arrival: the same triangulation, which its first phase certified.
#[pyclass(module = "condt._condt", name = "_TileState", frozen)]
pub(crate) struct TileState {
    /// Each tile point's position in the whole set.
    positions: Vec<i64>,
    /// Which tile points the tile owns.
    owned: Vec<bool>,
    points: Vec<Point>,
    /// The tile's points in the whole set's insertion order (indices into `points`).
    order: Vec<u32>,
    tri: Triangulation,
}

#[pymethods]
impl TileState {
    /// About the bytes the state holds: what Dask's scheduler (`dask.sizeof`, which falls back
    /// on `sys.getsizeof`) weighs when it would move the state to another worker instead of
    /// running a round where it is. Without it the scheduler took a state for a few bytes.
    fn __sizeof__(&self) -> usize {
        let n = self.points.len();
        let vertices = self.tri.num_vertices();
        // Per tile point its position, ownership, point and order; per vertex its point and
        // first edge; per point the input and vertex maps; per half-edge its origin and twin.
        n * (8 + 1 + 16 + 4)
            + vertices * (16 + 4)
            + self.tri.num_points() * 8
            + self.tri.mesh().num_half_edges() * 8
    }

    /// Pickling: the points, their insertion order, positions and ownership; the triangulation
    /// is built again from them ([`_tile_state`]).
    #[allow(clippy::type_complexity)]
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(
        Bound<'py, PyAny>,
        (
            Bound<'py, PyArray2<f64>>,
            Bound<'py, PyArray1<i64>>,
            Bound<'py, PyArray1<i64>>,
            Bound<'py, PyArray1<bool>>,
        ),
    )> {
        let rebuild = py.import("condt._condt")?.getattr("_tile_state")?;
        let flat: Vec<f64> = self.points.iter().flat_map(|p| [p.x, p.y]).collect();
        let points = Array2::from_shape_vec((self.points.len(), 2), flat)
            .map_err(|err| PyValueError::new_err(err.to_string()))?;
        let order: Vec<i64> = self.order.iter().map(|&i| i64::from(i)).collect();
        Ok((
            rebuild,
            (
                PyArray2::from_owned_array(py, points),
                PyArray1::from_vec(py, order),
                PyArray1::from_slice(py, &self.positions),
                PyArray1::from_slice(py, &self.owned),
            ),
        ))
    }
}

/// A [`TileState`] from its pickled parts: the tile's points triangulated again in `order`.
#[pyfunction]
pub(crate) fn _tile_state<'py>(
    py: Python<'py>,
    points: &Bound<'py, PyAny>,
    order: PyReadonlyArray1<'py, i64>,
    positions: PyReadonlyArray1<'py, i64>,
    owned: PyReadonlyArray1<'py, bool>,
) -> PyResult<TileState> {
    let array = points_array(py, points)?;
    let borrowed = array.try_readonly()?;
    let points = as_points(borrowed.as_slice()?).to_vec();
    let (order, positions, owned) = (order.as_slice()?, positions.as_slice()?, owned.as_slice()?);
    let n = points.len();
    let in_range = |&i: &i64| usize::try_from(i).is_ok_and(|i| i < n);
    if [order.len(), positions.len(), owned.len()] != [n; 3] || !order.iter().all(in_range) {
        return Err(PyValueError::new_err(
            "a tile state's arrays do not fit together",
        ));
    }
    let order: Vec<u32> = order.iter().map(|&i| i as u32).collect();
    let tri = crate::detached(py, || {
        crate::within_call(|| Triangulation::triangulate_in_order(&points, &order))
    })?
    .map_err(|err| library_error(err, &points))?;
    Ok(TileState {
        positions: positions.to_vec(),
        owned: owned.to_vec(),
        points,
        order,
        tri,
    })
}

/// A tile's step on a graph of its kept triangulation.
type KeptStep = for<'t> fn(&condt::Graph<'t>, &Params) -> condt::Graph<'t>;

/// The stages a round of [`_step_kept`] runs on a tile, each with its step (the repair for the
/// second phase of `outliers_first` and repairing again; the later stages whose rule reads only
/// a point's neighbourhood).
const KEPT_STEPS: [(Stage, KeptStep); 7] = [
    (Stage::Repair, |graph, params| graph.repair(params.repair)),
    (Stage::Junctions, |graph, _| graph.join_junctions()),
    (Stage::Crossings, |graph, _| graph.restore_crossings()),
    (Stage::Spikes, |graph, _| graph.repair_spikes()),
    (Stage::Hooks, |graph, _| graph.unhook()),
    (Stage::Tails, |graph, _| graph.cut_tails()),
    (Stage::Detours, |graph, _| graph.cut_detours()),
];

/// A round on a tile's kept triangulation: `step` (`"repair"`, the repair of the second phase of
/// a two-phase flow, or the key of a stage of [`LATER_STAGES`]) run on the driver's `given` edges
/// (rows of positions among the tile's points, both ends in the tile), and the edges of its
/// result whose smaller end the tile owns, in positions of the whole set, as an `(m, 2)` int64
/// array. The tile holds every edge of the whole set's graph at each vertex it certified (every
/// stage adds only Delaunay edges), so those are the whole set's.
#[pyfunction]
#[pyo3(signature = (state, given, step, **params))]
pub(crate) fn _step_kept<'py>(
    py: Python<'py>,
    state: &Bound<'py, TileState>,
    given: PyReadonlyArray2<'py, i64>,
    step: &str,
    params: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyArray2<i64>>> {
    let (params, tiled) = tiled_params(params)?;
    // One lookup for the stage and its step, so that a stage without a row is an error here,
    // never another stage's step.
    let run = KEPT_STEPS
        .iter()
        .find(|(stage, _)| {
            step == stage.key() && (*stage == Stage::Repair || tiled.later.contains(stage))
        })
        .map(|&(_, run)| run)
        .ok_or_else(|| {
            // Said for a contributor too: a stage tiled as a kept round needs its row there.
            PyValueError::new_err(format!(
                "no tiled round {step:?} for these parameters (a stage a tile runs on its \
                 kept triangulation needs its row in KEPT_STEPS, python/src/tiles.rs)"
            ))
        })?;
    let state = state.get();
    let given = tile_pairs(given.as_slice()?, state.points.len())?;
    let edges = crate::detached(py, || {
        crate::within_call(|| run(&state.tri.graph_from_edges(given), &params).edges())
    })?;
    index_array(py, owned_rows(&state.owned, &state.positions, edges))
}

/// A round of per-point tests on a tile's kept triangulation, for a stage whose rule runs on the
/// driver, on the driver's `given` edges (as for [`_step_kept`]) with `labels`, each tile point's
/// component in the driver's graph: the clump tests ([`condt::tiled::clump_tests`], which rule 4
/// of the local outlier removal reads too) or, with each tile point's `status`, the given-back
/// tests ([`condt::tiled::given_back_tests`]). The tile's owned points as positions of the whole
/// set, and their tests.
#[pyfunction]
#[pyo3(signature = (state, given, labels, step, status=None, **params))]
pub(crate) fn _tests_kept<'py>(
    py: Python<'py>,
    state: &Bound<'py, TileState>,
    given: PyReadonlyArray2<'py, i64>,
    labels: PyReadonlyArray1<'py, i64>,
    step: &str,
    status: Option<PyReadonlyArray1<'py, u8>>,
    params: Option<&Bound<'py, PyDict>>,
) -> PyResult<OwnedTests<'py>> {
    let (_, tiled) = tiled_params(params)?;
    // Rule 4 of the local outlier removal reads the clumps' tests (smooth, apart, the turn).
    let stage = [Stage::Clumps, Stage::LocalOutliers, Stage::GivenBack]
        .into_iter()
        .find(|&s| s.key() == step && tiled.later.contains(&s))
        .ok_or_else(|| {
            PyValueError::new_err(format!("no round of tests {step:?} for these parameters"))
        })?;
    let status = status
        .map(|s| s.as_slice().map(<[u8]>::to_vec))
        .transpose()?;
    if (stage == Stage::GivenBack) != status.is_some()
        || status
            .as_ref()
            .is_some_and(|s| s.len() != state.get().points.len())
    {
        return Err(PyValueError::new_err(
            "the given-back tests need each tile point's status, the others none",
        ));
    }
    let state = state.get();
    let given = tile_pairs(given.as_slice()?, state.points.len())?;
    let labels: Vec<u32> = labels
        .as_slice()?
        .iter()
        .map(|&l| u32::try_from(l))
        .collect::<Result<_, _>>()
        .map_err(|_| PyValueError::new_err("a component label is out of range"))?;
    if labels.len() != state.points.len() {
        return Err(PyValueError::new_err(
            "a tile's labels differ in length from its points",
        ));
    }
    let tests = crate::detached(py, || {
        crate::within_call(|| {
            let graph = state.tri.graph_from_edges(given);
            // Only the owned points' tests are sent, so only they are run.
            let owned = |i: usize| state.owned[i];
            match &status {
                Some(status) => condt::tiled::given_back_tests(&graph, &labels, status, owned),
                None => condt::tiled::clump_tests(&graph, &labels, owned),
            }
        })
    })?
    .map_err(|err| PyValueError::new_err(err.to_string()))?;
    let owned = (0..state.points.len()).filter(|&i| state.owned[i]);
    let positions: Vec<i64> = owned.clone().map(|i| state.positions[i]).collect();
    let tests: Vec<u8> = owned.map(|i| tests[i]).collect();
    Ok((
        PyArray1::from_vec(py, positions),
        PyArray1::from_vec(py, tests),
    ))
}

/// A tile's owned points, as positions of the whole set, and their tests (or the driver's labels
/// and statuses of every point, for the given-back round).
type OwnedTests<'py> = (Bound<'py, PyArray1<i64>>, Bound<'py, PyArray1<u8>>);

/// A round of the local outlier removal's rules 1 to 3 on a tile's kept triangulation
/// ([`condt::tiled::local_rules`]) on the driver's `given` edges and `before` (the IQR stage's
/// input), both as for [`_step_kept`]; `give_back`: whether rule 1 runs (the driver's count).
/// The edges of the result whose smaller end the tile owns, as for [`_step_kept`].
#[pyfunction]
#[pyo3(signature = (state, given, before, give_back, **params))]
pub(crate) fn _local_rules_kept<'py>(
    py: Python<'py>,
    state: &Bound<'py, TileState>,
    given: PyReadonlyArray2<'py, i64>,
    before: PyReadonlyArray2<'py, i64>,
    give_back: bool,
    params: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyArray2<i64>>> {
    local_round(py, state, [given, before], params, |graph, before| {
        condt::tiled::local_rules(graph, before, give_back).edges()
    })
}

/// Rule 1 of the local outlier removal at curves' last edges, on a tile's kept triangulation: the
/// candidates ([`condt::tiled::last_edge_candidates`]) among the driver's `given` edges (the IQR
/// stage's output) and `before` (its input), as for [`_local_rules_kept`]. The driver keeps
/// those the curves behind them show ([`_gathered_last_edges`]).
#[pyfunction]
#[pyo3(signature = (state, given, before, **params))]
pub(crate) fn _last_edges_kept<'py>(
    py: Python<'py>,
    state: &Bound<'py, TileState>,
    given: PyReadonlyArray2<'py, i64>,
    before: PyReadonlyArray2<'py, i64>,
    params: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyArray2<i64>>> {
    local_round(py, state, [given, before], params, |graph, before| {
        condt::tiled::last_edge_candidates(graph, before)
    })
}

/// A local outlier removal round's `work` on a tile's kept triangulation, given the driver's
/// edges among its points (`graphs`: the stage's input and the IQR stage's): the edges it gives
/// whose smaller end the tile owns, as for [`_step_kept`].
fn local_round<'py>(
    py: Python<'py>,
    state: &Bound<'py, TileState>,
    graphs: [PyReadonlyArray2<'py, i64>; 2],
    params: Option<&Bound<'py, PyDict>>,
    work: impl for<'t> FnOnce(&condt::Graph<'t>, &condt::Graph<'t>) -> Vec<[usize; 2]> + Send,
) -> PyResult<Bound<'py, PyArray2<i64>>> {
    let (_, tiled) = tiled_params(params)?;
    if !tiled.later.contains(&Stage::LocalOutliers) {
        return Err(PyValueError::new_err(
            "no local outliers round for these parameters",
        ));
    }
    let state = state.get();
    let [given, before] = graphs;
    let given = tile_pairs(given.as_slice()?, state.points.len())?;
    let before = tile_pairs(before.as_slice()?, state.points.len())?;
    let edges = crate::detached(py, || {
        crate::within_call(|| {
            let graph = state.tri.graph_from_edges(given);
            let before = state.tri.graph_from_edges(before);
            work(&graph, &before)
        })
    })?;
    index_array(py, owned_rows(&state.owned, &state.positions, edges))
}

/// Rule 1 of the local outlier removal at curves' last edges on the gathered `edges` (after rules
/// 1 to 3) over `n` points, with the tiles' `candidates` ([`_last_edges_kept`];
/// [`condt::tiled::give_back_gathered_last_edges`]): the edges after it, sorted by rows, or
/// `None` when it gives back none.
#[pyfunction]
pub(crate) fn _gathered_last_edges<'py>(
    py: Python<'py>,
    n: usize,
    edges: &Bound<'py, PyArray2<i64>>,
    candidates: &Bound<'py, PyArray2<i64>>,
) -> PyResult<Option<Bound<'py, PyArray2<i64>>>> {
    let (edges, candidates) = (gathered_pairs(edges)?, gathered_pairs(candidates)?);
    gathered_answer(
        py,
        crate::detached(py, || {
            condt::tiled::give_back_gathered_last_edges(n, &edges, &candidates)
        })?,
    )
}

/// Rule 4 of the local outlier removal on the gathered `edges` (after rules 1 to 3) over `n`
/// points, with every point's clump `tests`, every loose end's gap `choices`, every point's tip
/// candidates (`tips`) and the hooks' and junctions' joins (`joins`) on them
/// ([`condt::tiled::remove_gathered_local_outliers`]): the edges kept, sorted by rows, or `None`.
#[pyfunction]
pub(crate) fn _gathered_local_outliers<'py>(
    py: Python<'py>,
    n: usize,
    edges: &Bound<'py, PyArray2<i64>>,
    tests: PyReadonlyArray1<'py, u8>,
    choices: PyReadonlyArray2<'py, i64>,
    tips: PyReadonlyArray2<'py, i64>,
    joins: PyReadonlyArray2<'py, i64>,
) -> PyResult<Option<Bound<'py, PyArray2<i64>>>> {
    let rule = condt::tiled::remove_gathered_local_outliers;
    gathered_with_joins(py, n, edges, tests, (choices, tips, joins), rule)
}

/// A driver's rule that reads every point's `tests` and the joins gap closing, the tips, the hooks
/// and the junctions would make (the tiles' gap `choices`, tip candidates and end joins), on the
/// gathered `edges` over `n` points.
type RuleWithJoins = fn(
    usize,
    &[[usize; 2]],
    &[u8],
    &[[usize; GAP_ROW]],
    &[[usize; 4]],
    &[[usize; 2]],
) -> Result<Option<Vec<[usize; 2]>>, condt::Error>;

/// The `_choices_kept` round of the hooks' and junctions' joins, which rule 4 and the clump stage
/// read (those stages' own rounds are `_step_kept`'s, under their keys).
const END_JOINS: &str = "end-joins";

/// The round of choices for the tips' candidate moves that rule 4 and the clumps read (the
/// library's stages read them as if the spikes step followed, whatever the run's parameters).
const TIP_JOINS: &str = "tip-joins";

/// The rows a driver gathered for a rule with joins: gap choices, tip candidates, and the hooks'
/// and junctions' joins in one list.
type JoinRows<'py> = (
    PyReadonlyArray2<'py, i64>,
    PyReadonlyArray2<'py, i64>,
    PyReadonlyArray2<'py, i64>,
);

/// `rule` on the arrays a driver gathered: the edges kept, sorted by rows, or `None`.
fn gathered_with_joins<'py>(
    py: Python<'py>,
    n: usize,
    edges: &Bound<'py, PyArray2<i64>>,
    tests: PyReadonlyArray1<'py, u8>,
    (choices, tips, joins): JoinRows<'py>,
    rule: RuleWithJoins,
) -> PyResult<Option<Bound<'py, PyArray2<i64>>>> {
    let edges = gathered_pairs(edges)?;
    let rows: Vec<[usize; GAP_ROW]> = rows_of(&choices, "a gap choice")?;
    let tips: Vec<[usize; 4]> = rows_of(&tips, "a tip candidate")?;
    let joins: Vec<[usize; 2]> = rows_of(&joins, "a join")?;
    let tests = tests.as_slice()?;
    gathered_answer(
        py,
        crate::detached(py, || rule(n, &edges, tests, &rows, &tips, &joins))?,
    )
}

/// For the given-back round, on the driver: each point's component label and status in the
/// graph of the gathered `edges` over `n` points against `before_local`, the local outlier
/// removal's input ([`condt::tiled::given_back_standing`]), or `None` when nothing was given back.
#[pyfunction]
pub(crate) fn _given_back_standing<'py>(
    py: Python<'py>,
    n: usize,
    edges: &Bound<'py, PyArray2<i64>>,
    before_local: &Bound<'py, PyArray2<i64>>,
) -> PyResult<Option<OwnedTests<'py>>> {
    let (edges, before) = (gathered_pairs(edges)?, gathered_pairs(before_local)?);
    let standing = crate::detached(py, || condt::tiled::given_back_standing(n, &edges, &before))?
        .map_err(|err| PyValueError::new_err(err.to_string()))?;
    Ok(standing.map(|(labels, status)| {
        let labels = labels.into_iter().map(i64::from).collect();
        (
            PyArray1::from_vec(py, labels),
            PyArray1::from_vec(py, status),
        )
    }))
}

/// The given-back check on the gathered `edges` over `n` points against `before_local`, with
/// every point's `tests` ([`condt::tiled::confirm_gathered_given_back`]): the edges kept, sorted
/// by rows, or `None` when it drops none.
#[pyfunction]
pub(crate) fn _gathered_given_back<'py>(
    py: Python<'py>,
    n: usize,
    edges: &Bound<'py, PyArray2<i64>>,
    before_local: &Bound<'py, PyArray2<i64>>,
    tests: PyReadonlyArray1<'py, u8>,
) -> PyResult<Option<Bound<'py, PyArray2<i64>>>> {
    let (edges, before) = (gathered_pairs(edges)?, gathered_pairs(before_local)?);
    let tests = tests.as_slice()?;
    gathered_answer(
        py,
        crate::detached(py, || {
            condt::tiled::confirm_gathered_given_back(n, &edges, &before, tests)
        })?,
    )
}

/// The rows of an `(m, W)` int64 array of positions and small numbers, none negative (`what`
/// names the rows in the error).
fn rows_of<const W: usize>(
    array: &PyReadonlyArray2<'_, i64>,
    what: &str,
) -> PyResult<Vec<[usize; W]>> {
    // A row of another width would be read across rows: refused, not misread.
    let width = array.shape()[1];
    if width != W {
        return Err(PyValueError::new_err(format!(
            "{what} rows have {width} columns, not {W}"
        )));
    }
    array
        .as_slice()?
        .chunks_exact(W)
        .map(|row| {
            let mut out = [0usize; W];
            for (slot, &value) in out.iter_mut().zip(row) {
                *slot = usize::try_from(value)?;
            }
            Ok(out)
        })
        .collect::<Result<_, std::num::TryFromIntError>>()
        .map_err(|_| PyValueError::new_err(format!("{what} names a negative position")))
}

/// A round of choices on a tile's kept triangulation, at the points the tile owns, on the
/// driver's `given` edges (as for [`_step_kept`]): for `"gaps"` each loose end's gap choice
/// ([`condt::tiled::gap_choices`], an `(m, 10)` int64 array: positions of the whole set, the
/// kind and the walk's length as they are), for `"tips"` the tips' candidate moves
/// ([`condt::tiled::tip_candidates`], an `(m, 4)` array of positions), for `"tip-joins"` those
/// that rule 4 and the clumps read ([`TIP_JOINS`]), for `"end-joins"`
/// ([`END_JOINS`]) the edges the hooks stage's moves would add, owned by their smaller end
/// ([`condt::tiled::hook_joins`]), then those the junctions stage would join, owned by their loose
/// end ([`condt::tiled::junction_joins`]): an `(m, 2)` array of positions.
#[pyfunction]
#[pyo3(signature = (state, given, step, **params))]
pub(crate) fn _choices_kept<'py>(
    py: Python<'py>,
    state: &Bound<'py, TileState>,
    given: PyReadonlyArray2<'py, i64>,
    step: &str,
    params: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyArray2<i64>>> {
    let (_, tiled) = tiled_params(params)?;
    let has = |stage: Stage| tiled.later.contains(&stage);
    // Rule 4 of the local outlier removal and the clump stage keep pieces gap closing, a tip's or
    // hook's move or a junction would join.
    let joined = has(Stage::LocalOutliers) || has(Stage::Clumps);
    let gaps = step == Stage::Gaps.key() && (has(Stage::Gaps) || joined);
    let tip_joins = step == TIP_JOINS && joined;
    let tips = (step == Stage::Tips.key() && has(Stage::Tips)) || tip_joins;
    // The tips stage's apex form leaves tips to the spikes step where that runs.
    let spikes_follow = tip_joins || has(Stage::Spikes);
    let end_joins = step == END_JOINS && joined;
    if !gaps && !tips && !end_joins {
        return Err(PyValueError::new_err(format!(
            "no round of choices {step:?} for these parameters"
        )));
    }
    let state = state.get();
    let given = tile_pairs(given.as_slice()?, state.points.len())?;
    let position = |i: usize| state.positions[i];
    let flat: Vec<i64> = crate::detached(py, || {
        crate::within_call(|| {
            let graph = state.tri.graph_from_edges(given);
            let owned = |i: usize| state.owned[i];
            if gaps {
                // The kind (slot 1) and the walk's length (slot 4) are numbers, not points.
                let rows = condt::tiled::gap_choices(&graph, owned);
                let at = |row: &[usize; GAP_ROW], k: usize| match k {
                    1 | 4 => row[k] as i64,
                    _ => position(row[k]),
                };
                rows.iter()
                    .flat_map(|row| (0..GAP_ROW).map(move |k| at(row, k)))
                    .collect()
            } else if tips {
                let rows = condt::tiled::tip_candidates(&graph, spikes_follow, owned);
                rows.iter().flat_map(|row| row.map(position)).collect()
            } else {
                let mut rows = condt::tiled::hook_joins(&graph, owned);
                rows.extend(condt::tiled::junction_joins(&graph, owned));
                rows.iter().flat_map(|row| row.map(position)).collect()
            }
        })
    })?;
    let width = match (gaps, tips) {
        (true, _) => GAP_ROW,
        (_, true) => 4,
        _ => 2,
    };
    let rows = Array2::from_shape_vec((flat.len() / width, width), flat)
        .map_err(|err| PyValueError::new_err(err.to_string()))?;
    Ok(PyArray2::from_owned_array(py, rows))
}

/// Gap closing on the gathered `edges` over `n` points with every loose end's `choices`
/// ([`condt::tiled::close_gathered_gaps`]): the edges with the joins, sorted by rows, or `None`
/// when it adds none.
#[pyfunction]
pub(crate) fn _gathered_gaps<'py>(
    py: Python<'py>,
    n: usize,
    edges: &Bound<'py, PyArray2<i64>>,
    choices: PyReadonlyArray2<'py, i64>,
) -> PyResult<Option<Bound<'py, PyArray2<i64>>>> {
    let edges = gathered_pairs(edges)?;
    let rows: Vec<[usize; GAP_ROW]> = rows_of(&choices, "a gap choice")?;
    gathered_answer(
        py,
        crate::detached(py, || condt::tiled::close_gathered_gaps(n, &edges, &rows))?,
    )
}

/// The tips stage on the gathered `edges` over `n` points with every point's `candidates`
/// ([`condt::tiled::repair_gathered_tips`]): the edges after it, sorted by rows, or `None` when
/// it changes nothing.
#[pyfunction]
pub(crate) fn _gathered_tips<'py>(
    py: Python<'py>,
    n: usize,
    edges: &Bound<'py, PyArray2<i64>>,
    candidates: PyReadonlyArray2<'py, i64>,
) -> PyResult<Option<Bound<'py, PyArray2<i64>>>> {
    let edges = gathered_pairs(edges)?;
    let rows: Vec<[usize; 4]> = rows_of(&candidates, "a tip candidate")?;
    gathered_answer(
        py,
        crate::detached(py, || condt::tiled::repair_gathered_tips(n, &edges, &rows))?,
    )
}

/// Each position's component in the graph of the gathered `edges` over `n` points, named by its
/// smallest position ([`condt::tiled::component_labels`]), as an int64 array.
#[pyfunction]
pub(crate) fn _component_labels<'py>(
    py: Python<'py>,
    n: usize,
    edges: &Bound<'py, PyArray2<i64>>,
) -> PyResult<Bound<'py, PyArray1<i64>>> {
    let edges = gathered_pairs(edges)?;
    let labels = crate::detached(py, || condt::tiled::component_labels(n, &edges))?
        .map_err(|err| PyValueError::new_err(err.to_string()))?;
    Ok(PyArray1::from_vec(
        py,
        labels.into_iter().map(i64::from).collect(),
    ))
}

/// Whether the clump stage finds a clump on the gathered `edges` over `n` points with each
/// point's `tests` ([`condt::tiled::gathered_clumps_found`]): only then does the driver ask the
/// tiles for the gap choices and tip candidates [`_gathered_clumps`] reads.
#[pyfunction]
pub(crate) fn _gathered_clumps_found<'py>(
    py: Python<'py>,
    n: usize,
    edges: &Bound<'py, PyArray2<i64>>,
    tests: PyReadonlyArray1<'py, u8>,
) -> PyResult<bool> {
    let edges = gathered_pairs(edges)?;
    let tests = tests.as_slice()?;
    crate::detached(py, || condt::tiled::gathered_clumps_found(n, &edges, tests))?
        .map_err(|err| PyValueError::new_err(err.to_string()))
}

/// The clump stage on the gathered `edges` over `n` points with each point's `tests` from the
/// tile owning it, every loose end's gap `choices`, every point's tip candidates (`tips`) and the
/// hooks' and junctions' joins (`joins`) on them ([`condt::tiled::remove_gathered_clumps`]): the
/// edges kept, sorted by rows, or `None` when it changes nothing.
#[pyfunction]
pub(crate) fn _gathered_clumps<'py>(
    py: Python<'py>,
    n: usize,
    edges: &Bound<'py, PyArray2<i64>>,
    tests: PyReadonlyArray1<'py, u8>,
    choices: PyReadonlyArray2<'py, i64>,
    tips: PyReadonlyArray2<'py, i64>,
    joins: PyReadonlyArray2<'py, i64>,
) -> PyResult<Option<Bound<'py, PyArray2<i64>>>> {
    let rule = condt::tiled::remove_gathered_clumps;
    gathered_with_joins(py, n, edges, tests, (choices, tips, joins), rule)
}

/// A tile's owned edges, one list per graph its phase asks, in the whole set's positions.
type OwnedLists = Vec<Vec<[i64; 2]>>;

/// A tile's status, with its owned edges when it certified (one list per graph its phase asks)
/// and, when asked to keep it, its state for a second phase.
type TileReport<'py> = (
    &'static str,
    Option<Vec<Bound<'py, PyArray2<i64>>>>,
    Option<Bound<'py, TileState>>,
);

/// What a tile sends back ([`_run_tile`]'s `phase`).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum Phase {
    /// The proximity graph, repaired when the repair is selected.
    Repaired,
    /// The proximity graph alone.
    Proximity,
    /// The proximity graph, and its repair.
    Both,
}

impl Phase {
    fn named(name: &str) -> PyResult<Phase> {
        Ok(match name {
            "repaired" => Phase::Repaired,
            "proximity" => Phase::Proximity,
            "both" => Phase::Both,
            _ => return Err(PyValueError::new_err(format!("no tile phase {name:?}"))),
        })
    }
}

/// Edges as rows of a flat `(m, 2)` array of positions below `n`, smaller end first.
fn tile_pairs(flat: &[i64], n: usize) -> PyResult<Vec<[usize; 2]>> {
    let pair = |e: &[i64]| -> Option<[usize; 2]> {
        let (a, b) = (usize::try_from(e[0]).ok()?, usize::try_from(e[1]).ok()?);
        (a < n && b < n && a != b).then(|| [a.min(b), a.max(b)])
    };
    flat.chunks_exact(2)
        .map(|e| pair(e).ok_or_else(|| PyValueError::new_err("a given edge is not in the tile")))
        .collect()
}

/// Why a tile's certificate failed.
enum Failure {
    /// A star near an owned point is not provably the whole set's: the halo must grow.
    Grow,
    /// Four cocircular points near an owned point: the triangulation is not unique there.
    Cocircular,
}

/// What a tile knows of the whole set, for its certificate.
struct Tile<'a> {
    boundary: &'a [i64],
    boundary_len: i64,
    /// The parts of the bounding box outside the known region, closed rectangles.
    strips: Vec<[f64; 4]>,
    /// The same parts cut down to the convex hull, where the points are: convex polygons.
    hull_parts: Vec<Vec<Point>>,
    /// An absolute slack (in the frame of `unit`) for the polygons' rounded corners: far above
    /// their rounding error.
    corner_slack: f64,
    /// Input coordinates to the frame of `strips` and `hull_parts`.
    unit: Scale,
}

impl<'a> Tile<'a> {
    /// The tile holds every point inside `known`, and every point within `band` of the hull's
    /// boundary.
    fn new(
        known: [f64; 4],
        bbox: [f64; 4],
        boundary: &'a [i64],
        boundary_len: i64,
        hull: &[Point],
        band: f64,
    ) -> Tile<'a> {
        // The certificate's geometry in a power-of-two frame where the box's largest coordinate
        // is about 1 (exact): squares of huge or tiny coordinates would overflow or underflow.
        let extent = bbox.iter().fold(0.0f64, |m, c| m.max(c.abs()));
        let unit = Scale::power_of_two(if extent > 0.0 {
            -binary_exponent(extent)
        } else {
            0
        });
        let rect = |[x0, y0, x1, y1]: [f64; 4]| {
            let (low, high) = (
                unit.apply(Point::new(x0, y0)),
                unit.apply(Point::new(x1, y1)),
            );
            [low.x, low.y, high.x, high.y]
        };
        let (known, bbox) = (rect(known), rect(bbox));
        let hull: Vec<Point> = hull.iter().map(|&p| unit.apply(p)).collect();
        let band = unit.apply(Point::new(band, 0.0)).x;
        let corner_slack = 1e-12;
        // Where a point the tile does not hold can be: inside the hull, outside `known`, and
        // deeper than the band (a little less deep, for rounding: the driver sent every point up
        // to `band`).
        let depth = band * (1.0 - 1e-9) - corner_slack;
        let region = if depth > 0.0 {
            inner(&hull, depth)
        } else {
            hull
        };
        let strips = frame(bbox, known);
        let hull_parts = strips.iter().map(|&strip| clip(&region, strip)).collect();
        Tile {
            boundary,
            boundary_len,
            strips,
            hull_parts,
            corner_slack,
            unit,
        }
    }

    /// `Ok` when every vertex within `reach` hops of an owned point has the whole set's star and
    /// no four points there are cocircular.
    fn certify(
        &self,
        tri: &Triangulation,
        points: &[Point],
        owned: &[bool],
        reach: usize,
    ) -> Result<(), Failure> {
        if !owned.contains(&true) {
            return Ok(()); // nothing to certify
        }
        if tri.triangles().next().is_none() {
            return Err(Failure::Grow); // collinear in the tile: a larger region shows more
        }
        // The vertices within `reach` hops of an owned point, in breadth-first order (a merged
        // duplicate walks from its vertex): only their stars need certifying (speed: the halo
        // holds most of the tile's triangles).
        let mut hops = vec![usize::MAX; points.len()];
        let mut queue = VecDeque::new();
        for i in (0..points.len()).filter(|&i| owned[i]) {
            let v = tri.first_at(i);
            if hops[v] == usize::MAX {
                hops[v] = 0;
                queue.push_back(v);
            }
        }
        let mut walked = Vec::new();
        while let Some(v) = queue.pop_front() {
            walked.push(v);
            if hops[v] < reach {
                for w in tri.neighbors(v) {
                    if hops[w] == usize::MAX {
                        hops[w] = hops[v] + 1;
                        queue.push_back(w);
                    }
                }
            }
        }
        let near = |v: usize| hops[v] != usize::MAX;
        let mut certified = vec![true; points.len()];
        for [a, b, c] in tri.triangles() {
            if (near(a) || near(b) || near(c))
                && self.uncertain_circle([a, b, c].map(|v| self.unit.apply(points[v])))
            {
                for v in [a, b, c] {
                    certified[v] = false;
                }
            }
        }
        let hull: Vec<usize> = tri.hull().collect();
        for (k, &a) in hull.iter().enumerate() {
            let b = hull[(k + 1) % hull.len()];
            let (pa, pb) = (self.boundary[a], self.boundary[b]);
            let apart = (pa - pb).rem_euclid(self.boundary_len);
            if pa < 0 || pb < 0 || (apart != 1 && apart != self.boundary_len - 1) {
                certified[a] = false;
                certified[b] = false;
            }
        }
        // In the walk's order, the first vertex without the whole set's star asks for a wider
        // halo, the first cocircular quadruple in a star for the whole set in one piece.
        let mut ring = Vec::new();
        for v in walked {
            if !certified[v] {
                return Err(Failure::Grow);
            }
            ring.clear();
            ring.extend(tri.neighbors(v));
            for k in 0..ring.len() {
                let (before, w, after) = (
                    ring[(k + ring.len() - 1) % ring.len()],
                    ring[k],
                    ring[(k + 1) % ring.len()],
                );
                if ring.len() >= 3
                    && is_cocircular(points[v], points[before], points[w], points[after])
                {
                    return Err(Failure::Cocircular);
                }
            }
        }
        Ok(())
    }

    /// Whether the circumcircle of `a`, `b`, `c`, widened by a bound on its rounding error, may
    /// hold a point the tile does not: whether it meets a part of the hull outside the known
    /// region (and deeper than the band). If not, no point of the whole set lies inside it.
    fn uncertain_circle(&self, [a, b, c]: [Point; 3]) -> bool {
        // Nowhere to be (a tile that holds every point): certain, even where the circle cannot
        // be computed (a dask user's review: a sliver on a straight side of the hull, whose
        // rounded determinant is zero, kept a tile of every point from certifying).
        if self.hull_parts.iter().all(Vec::is_empty) {
            return false;
        }
        let Some((o, reach)) = circumcircle(a, b, c) else {
            return true;
        };
        let misses_box = |&[x0, y0, x1, y1]: &[f64; 4]| {
            let dx = (x0 - o.x).max(o.x - x1).max(0.0);
            let dy = (y0 - o.y).max(o.y - y1).max(0.0);
            dx * dx + dy * dy > reach * reach
        };
        let slack = reach + self.corner_slack;
        let strips = self.strips.iter().zip(&self.hull_parts);
        strips
            .into_iter()
            .any(|(strip, part)| !misses_box(strip) && meets(part, o, slack))
    }
}

/// The circumcircle of `a`, `b`, `c`: its centre and its radius widened by a bound on the
/// rounding error of both; `None` for a degenerate or overflowing triangle.
fn circumcircle(a: Point, b: Point, c: Point) -> Option<(Point, f64)> {
    let (bx, by, cx, cy) = (b.x - a.x, b.y - a.y, c.x - a.x, c.y - a.y);
    let det = bx * cy - by * cx;
    let (lb, lc) = (bx * bx + by * by, cx * cx + cy * cy);
    let (ux, uy) = (
        (cy * lb - by * lc) / (2.0 * det),
        (bx * lc - cx * lb) / (2.0 * det),
    );
    let radius = ux.hypot(uy);
    // Each product and sum rounds by a relative 2^-53; the bound takes every term at its
    // magnitude, the quotient's by the determinant's condition, and 64 roundings of each.
    let magnitude = (cy.abs() * lb + by.abs() * lc + bx.abs() * lc + cx.abs() * lb) / det.abs();
    let condition = ((bx * cy).abs() + (by * cx).abs()) / det.abs();
    let slack =
        64.0 * f64::EPSILON * (magnitude + radius * condition + radius + a.x.abs() + a.y.abs());
    let reach = radius + slack;
    (det != 0.0 && reach.is_finite()).then(|| (Point::new(a.x + ux, a.y + uy), reach))
}

/// The parts of the rectangle `outer` outside the rectangle `inner` (both `[x0, y0, x1, y1]`,
/// sides possibly infinite): up to four closed rectangles.
fn frame(outer: [f64; 4], inner: [f64; 4]) -> Vec<[f64; 4]> {
    let [ox0, oy0, ox1, oy1] = outer;
    let [ix0, iy0, ix1, iy1] = inner;
    let (mx0, mx1) = (ix0.max(ox0), ix1.min(ox1));
    let mut parts = Vec::with_capacity(4);
    if ix0 > ox0 {
        parts.push([ox0, oy0, ix0.min(ox1), oy1]);
    }
    if ix1 < ox1 {
        parts.push([ix1.max(ox0), oy0, ox1, oy1]);
    }
    if iy0 > oy0 && mx0 <= mx1 {
        parts.push([mx0, oy0, mx1, iy0.min(oy1)]);
    }
    if iy1 < oy1 && mx0 <= mx1 {
        parts.push([mx0, iy1.max(oy0), mx1, oy1]);
    }
    parts
}

/// The convex polygon `polygon` (counter-clockwise) cut to the closed rectangle `[x0, y0, x1,
/// y1]`.
fn clip(polygon: &[Point], [x0, y0, x1, y1]: [f64; 4]) -> Vec<Point> {
    let sides = [
        ((1.0, 0.0), x0),
        ((-1.0, 0.0), -x1),
        ((0.0, 1.0), y0),
        ((0.0, -1.0), -y1),
    ];
    sides
        .into_iter()
        .fold(polygon.to_vec(), |shape, (normal, offset)| {
            cut(&shape, normal, offset)
        })
}

/// The convex polygon `polygon` (counter-clockwise) moved in by `depth` from every edge: where
/// a point lies when more than `depth` from the boundary. Empty when nothing is that deep.
fn inner(polygon: &[Point], depth: f64) -> Vec<Point> {
    let len = polygon.len();
    let mut shape = polygon.to_vec();
    for k in 0..len {
        let (a, b) = (polygon[k], polygon[(k + 1) % len]);
        let length = (b.x - a.x).hypot(b.y - a.y);
        if length == 0.0 {
            continue;
        }
        // The inward normal of a counter-clockwise edge is its direction turned left.
        let normal = ((a.y - b.y) / length, (b.x - a.x) / length);
        shape = cut(&shape, normal, normal.0 * a.x + normal.1 * a.y + depth);
    }
    shape
}

/// The part of the convex polygon `shape` where `normal · p >= offset` (Sutherland and
/// Hodgman's clipping by one half-plane).
fn cut(shape: &[Point], normal: (f64, f64), offset: f64) -> Vec<Point> {
    let side = |p: Point| normal.0 * p.x + normal.1 * p.y - offset;
    let mut kept = Vec::with_capacity(shape.len() + 1);
    for (k, &p) in shape.iter().enumerate() {
        let q = shape[(k + 1) % shape.len()];
        let (sp, sq) = (side(p), side(q));
        if sp >= 0.0 {
            kept.push(p);
        }
        if (sp >= 0.0) != (sq >= 0.0) {
            let t = sp / (sp - sq);
            kept.push(Point::new(p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)));
        }
    }
    kept
}

/// Each point's distance to the boundary of the convex polygon `corners` (counter-clockwise)
/// that holds it: the least over the edges' lines, as the points lie inside.
fn depths(points: &[Point], corners: &[Point]) -> Vec<f64> {
    let len = corners.len();
    let lines: Vec<((f64, f64), f64)> = (0..len)
        .filter_map(|k| {
            let (a, b) = (corners[k], corners[(k + 1) % len]);
            let length = (b.x - a.x).hypot(b.y - a.y);
            (length > 0.0).then(|| {
                let normal = ((a.y - b.y) / length, (b.x - a.x) / length);
                (normal, normal.0 * a.x + normal.1 * a.y)
            })
        })
        .collect();
    points
        .iter()
        .map(|p| {
            let least = lines
                .iter()
                .map(|&(n, offset)| n.0 * p.x + n.1 * p.y - offset);
            least.fold(f64::INFINITY, f64::min).max(0.0)
        })
        .collect()
}

/// Whether the disk of centre `o` and radius `r` meets the convex polygon `polygon`
/// (counter-clockwise, possibly empty or degenerate).
fn meets(polygon: &[Point], o: Point, r: f64) -> bool {
    let Some(&first) = polygon.first() else {
        return false;
    };
    let mut inside = polygon.len() >= 3;
    let mut nearest = o.dist2(first);
    for (k, &p) in polygon.iter().enumerate() {
        let q = polygon[(k + 1) % polygon.len()];
        let (ex, ey) = (q.x - p.x, q.y - p.y);
        let (wx, wy) = (o.x - p.x, o.y - p.y);
        inside &= ex * wy - ey * wx >= 0.0;
        let length2 = ex * ex + ey * ey;
        let t = if length2 > 0.0 {
            ((wx * ex + wy * ey) / length2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (dx, dy) = (wx - t * ex, wy - t * ey);
        nearest = nearest.min(dx * dx + dy * dy);
    }
    inside || nearest <= r * r
}

/// The global step after the tiles: Algorithm 3 (when `params` run it) on the edges they sent,
/// in the library, as one `(m, 2)` int64 array sorted by rows.
#[pyfunction]
#[pyo3(signature = (points, edges, **params))]
pub(crate) fn _gathered_outliers<'py>(
    py: Python<'py>,
    points: &Bound<'py, PyAny>,
    edges: &Bound<'py, PyArray2<i64>>,
    params: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyArray2<i64>>> {
    let (params, _) = tiled_params(params)?;
    let array = points_array(py, points)?;
    let borrowed = array.try_readonly()?;
    let points = as_points(borrowed.as_slice()?);
    let edges = gathered_pairs(edges)?;
    let kept = crate::detached(py, || match params.outlier_factor {
        Some(k) => condt::remove_gathered_outliers(points, &edges, k, params.iqr_floor)
            .map(|(_, kept)| kept),
        None => Ok(edges),
    })?
    .map_err(|err| library_error(err, points))?;
    sorted_rows(py, kept)
}

/// Repairing again's input on the edges the tiles sent, in the library: the proximity edges not
/// above Algorithm 3's cut threshold of the repaired ones, as one `(m, 2)` int64 array sorted by
/// rows, or `None` when Algorithm 3 cuts none of them (the step then changes nothing).
#[pyfunction]
#[pyo3(signature = (points, repaired, proximity, **params))]
pub(crate) fn _gathered_repair_again<'py>(
    py: Python<'py>,
    points: &Bound<'py, PyAny>,
    repaired: &Bound<'py, PyArray2<i64>>,
    proximity: &Bound<'py, PyArray2<i64>>,
    params: Option<&Bound<'py, PyDict>>,
) -> PyResult<Option<Bound<'py, PyArray2<i64>>>> {
    let (params, _) = tiled_params(params)?;
    let array = points_array(py, points)?;
    let borrowed = array.try_readonly()?;
    let points = as_points(borrowed.as_slice()?);
    let (repaired, proximity) = (gathered_pairs(repaired)?, gathered_pairs(proximity)?);
    let Some(k) = params.outlier_factor else {
        return Ok(None);
    };
    let short = crate::detached(py, || {
        condt::gathered_repair_again_input(points, &repaired, &proximity, k, params.iqr_floor)
    })?
    .map_err(|err| library_error(err, points))?;
    short.map(|edges| sorted_rows(py, edges)).transpose()
}

/// Between two tiled runs with the smoothing passes: `None` when no pass follows the run on
/// `points` whose final edges the tiles sent (`edges`), else the points the pass moves to, as an
/// `(n, 2)` float64 array, for the next tiled run; or, where the runs of a split cannot follow
/// `condt.reconstruct`'s pass, why the whole set must run in one piece. `passes` counts the passes
/// before this run and `previous` holds the run before's edges. The library decides
/// ([`condt::gathered_smoothing_pass`]).
#[pyfunction]
#[pyo3(signature = (points, edges, passes, previous=None))]
pub(crate) fn _gathered_smoothing_pass<'py>(
    py: Python<'py>,
    points: &Bound<'py, PyAny>,
    edges: &Bound<'py, PyArray2<i64>>,
    passes: usize,
    previous: Option<&Bound<'py, PyArray2<i64>>>,
) -> PyResult<Option<Bound<'py, PyAny>>> {
    let array = points_array(py, points)?;
    let borrowed = array.try_readonly()?;
    let points = as_points(borrowed.as_slice()?);
    let edges = gathered_pairs(edges)?;
    let previous = previous.map(gathered_pairs).transpose()?;
    let pass = crate::detached(py, || {
        crate::within_call(|| {
            condt::gathered_smoothing_pass(points, &edges, passes, previous.as_deref())
        })
    })?
    .map_err(|err| library_error(err, points))?;
    Ok(match pass {
        GatheredPass::Next(moved) => {
            let flat: Vec<f64> = moved.iter().flat_map(|p| [p.x, p.y]).collect();
            let moved = Array2::from_shape_vec((moved.len(), 2), flat)
                .map_err(|err| PyValueError::new_err(err.to_string()))?;
            Some(PyArray2::from_owned_array(py, moved).into_any())
        }
        GatheredPass::InOnePiece => Some(
            "a smoothing pass moves points into a wide set"
                .into_pyobject(py)?
                .into_any(),
        ),
        GatheredPass::Done => None,
        // A way on this driver does not know: never a silently different answer.
        _ => Some(
            "a smoothing pass this driver cannot follow"
                .into_pyobject(py)?
                .into_any(),
        ),
    })
}

/// Which tiles hold each point of the whole set, and where: built once per tiled run
/// ([`_tile_index`]) for the kept tiles, whose points stay the same through the run's rounds,
/// and read by every round's [`_split_edges`]. Building it scatters a write per tile point (about
/// 3.5 per point at 1M points and 16 tiles), which every round of a 1M run paid again before.
#[pyclass(module = "condt._condt", name = "_TileIndex", frozen)]
pub(crate) struct TileIndex {
    /// The points' runs in `held`: point `i`'s holders are `held[start[i]..start[i + 1]]`.
    start: Vec<usize>,
    /// (tile, the point's place among that tile's points), grouped by point.
    held: Vec<(u32, u32)>,
    tiles: usize,
}

impl TileIndex {
    fn holders(&self, i: usize) -> &[(u32, u32)] {
        &self.held[self.start[i]..self.start[i + 1]]
    }
}

/// The index of `tiles` (each tile's positions of the whole set of `n` points, increasing) for
/// [`_split_edges`].
#[pyfunction]
pub(crate) fn _tile_index<'py>(
    py: Python<'py>,
    n: usize,
    tiles: Vec<PyReadonlyArray1<'py, i64>>,
) -> PyResult<TileIndex> {
    let tiles: Vec<&[i64]> = tiles
        .iter()
        .map(|t| t.as_slice())
        .collect::<Result<_, _>>()?;
    let place = |i: i64| usize::try_from(i).ok().filter(|&i| i < n);
    if tiles
        .iter()
        .flat_map(|t| t.iter())
        .any(|&i| place(i).is_none())
    {
        return Err(PyValueError::new_err("a position is not among the points"));
    }
    if tiles.len() > u32::MAX as usize || tiles.iter().any(|t| t.len() > u32::MAX as usize) {
        return Err(PyValueError::new_err("too many tiles or tile points"));
    }
    crate::detached(py, || {
        // Counts per point, then offsets, then each holder in its point's run.
        let mut start = vec![0usize; n + 1];
        for &i in tiles.iter().flat_map(|t| t.iter()) {
            start[i as usize + 1] += 1;
        }
        for i in 0..n {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut held = vec![(0u32, 0u32); start[n]];
        for (k, tile) in tiles.iter().enumerate() {
            for (local, &i) in tile.iter().enumerate() {
                held[fill[i as usize]] = (k as u32, local as u32);
                fill[i as usize] += 1;
            }
        }
        TileIndex {
            start,
            held,
            tiles: tiles.len(),
        }
    })
}

/// The rows of the driver's `edges` (positions among the indexed points) with both ends among
/// each tile's points, in that tile's own positions: one `(m, 2)` int64 array per tile of
/// `index`, rows in the order of `edges`. One pass over the edges for all tiles (each point lists
/// the few tiles holding it), where a pass per tile cost the driver a tenth of a tiled run at 1M
/// points and 16 tiles.
#[pyfunction]
pub(crate) fn _split_edges<'py>(
    py: Python<'py>,
    index: &Bound<'py, TileIndex>,
    edges: PyReadonlyArray2<'py, i64>,
) -> PyResult<Vec<Bound<'py, PyArray2<i64>>>> {
    let index = index.get();
    let flat = edges.as_slice()?;
    let n = index.start.len() - 1;
    if flat
        .iter()
        .any(|&i| usize::try_from(i).map_or(true, |i| i >= n))
    {
        return Err(PyValueError::new_err("a position is not among the points"));
    }
    let split = crate::detached(py, || {
        let mut out: Vec<Vec<i64>> = vec![Vec::new(); index.tiles];
        for e in flat.chunks_exact(2) {
            let to = index.holders(e[1] as usize);
            for &(k, a) in index.holders(e[0] as usize) {
                if let Some(&(_, b)) = to.iter().find(|&&(j, _)| j == k) {
                    out[k as usize].extend([i64::from(a), i64::from(b)]);
                }
            }
        }
        out
    })?;
    split
        .into_iter()
        .map(|rows| {
            let rows = Array2::from_shape_vec((rows.len() / 2, 2), rows)
                .map_err(|err| PyValueError::new_err(err.to_string()))?;
            Ok(PyArray2::from_owned_array(py, rows))
        })
        .collect()
}

/// The `edges` (in a tile's positions) whose smaller end the tile owns, in the whole set's
/// positions.
fn owned_rows(owned: &[bool], positions: &[i64], edges: Vec<[usize; 2]>) -> Vec<[i64; 2]> {
    let edges = edges.into_iter().filter(|&[a, _]| owned[a]);
    edges.map(|[a, b]| [positions[a], positions[b]]).collect()
}

/// A global rule's answer on the gathered edges: the edges after it, sorted by rows, or `None`
/// when it changes nothing; a refused input as `ValueError`.
fn gathered_answer(
    py: Python<'_>,
    answer: Result<Option<Vec<[usize; 2]>>, condt::Error>,
) -> PyResult<Option<Bound<'_, PyArray2<i64>>>> {
    let answer = answer.map_err(|err| PyValueError::new_err(err.to_string()))?;
    answer.map(|edges| sorted_rows(py, edges)).transpose()
}

/// The rows of an `(m, 2)` array of positions, smaller end first.
fn gathered_pairs(edges: &Bound<'_, PyArray2<i64>>) -> PyResult<Vec<[usize; 2]>> {
    let readonly = edges.try_readonly()?;
    let flat = readonly.as_slice()?;
    Ok(flat
        .chunks_exact(2)
        .map(|e| [e[0].min(e[1]) as usize, e[0].max(e[1]) as usize])
        .collect())
}

/// `edges` as an `(m, 2)` int64 array sorted by rows.
fn sorted_rows(py: Python<'_>, edges: Vec<[usize; 2]>) -> PyResult<Bound<'_, PyArray2<i64>>> {
    let mut rows: Vec<[i64; 2]> = edges
        .into_iter()
        .map(|[a, b]| [a as i64, b as i64])
        .collect();
    rows.sort_unstable();
    index_array(py, rows)
}
