//! ConDT curve reconstruction: the stages of Algorithms 1–3 on the Delaunay half-edge mesh.
//!
//! Reference: the ConDT paper ("ConDT: a proximity graph on the Delaunay triangulation for curve
//! reconstruction", sections 3 and 4), read from `shared/seeds/condt-paper.txt`; `docs/condt.md`
//! maps every line of its algorithms to this code and records each reading of an ambiguity.
//!
//! Owns: running the stages in order, their parameters and the inspectable result. Each stage has
//! its own module and reads the finished [`Triangulation`]; none may modify it.
//!
//! ```
//! use condt::condt::{reconstruct, Params};
//! use condt::Point;
//! // Twelve points on a circle: one closed curve through all of them.
//! let circle: Vec<Point> = (0..12)
//!     .map(|k| {
//!         let t = k as f64 * std::f64::consts::TAU / 12.0;
//!         Point::new(t.cos(), t.sin())
//!     })
//!     .collect();
//! let result = reconstruct(&circle, &Params::default())?;
//! assert_eq!(result.curves.len(), 1);
//! assert!(result.curves[0].closed);
//! assert_eq!(result.edges.len(), 12);
//! assert!(result.unused.is_empty());
//! # Ok::<(), condt::Error>(())
//! ```

mod nonmanifold;
mod outliers;
mod proximity;

pub use crate::graph::Edge;
pub use nonmanifold::Repair;

use crate::curve::{curves_of, Curve};
use crate::error::Error;
use crate::geometry::Point;
use crate::graph::CurveGraph;
use crate::mesh::VertexId;
use crate::triangulate::{triangulate, Triangulation};
use alloc::vec::Vec;
use core::time::Duration;

/// The local uniformity test of Algorithm 1, line 6.
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum Uniformity {
    /// Keep the second shortest edge `e2` when `|e2| < u |e1|`; the paper uses `u = 2.75`.
    Fixed(f64),
    /// Section 4.1: `u` of each point is the mean length of its Delaunay edges over `|e1|`, so
    /// `e2` is kept when it is shorter than that mean.
    Adaptive,
}

impl Default for Uniformity {
    fn default() -> Self {
        Uniformity::Fixed(2.75)
    }
}

/// Parameters of a reconstruction.
///
/// ```
/// use condt::condt::{Params, Repair, Uniformity};
/// let p = Params::default();
/// assert_eq!(p.uniformity, Uniformity::Fixed(2.75));
/// assert_eq!(p.outlier_factor, Some(1.7));
/// assert_eq!(p.repair, Repair::Paper);
/// ```
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Params {
    /// Stage 1: the uniformity test.
    pub uniformity: Uniformity,
    /// Stage 2: the non-manifold repair.
    pub repair: Repair,
    /// Stage 3: the IQR factor, or `None` to skip outlier removal.
    pub outlier_factor: Option<f64>,
    /// Remove outliers before the non-manifold repair instead of after it (the paper's order).
    /// Outlier edges can make a curve vertex non-manifold, and the repair then cuts a sharp
    /// corner there; `docs/condt.md` (note 6) measures both orders.
    pub outliers_first: bool,
    /// Run the per-vertex stage on rayon (only with the `parallel` feature, and only from
    /// 65,536 points, below which waking the workers costs more than they save; same result).
    pub parallel: bool,
}

impl Default for Params {
    fn default() -> Self {
        Params {
            uniformity: Uniformity::default(),
            repair: Repair::default(),
            outlier_factor: Some(1.7),
            outliers_first: false,
            parallel: cfg!(feature = "parallel"),
        }
    }
}

/// Wall-clock time of each stage (all zero without the `std` feature, which has no clock).
#[derive(Copy, Clone, Debug, Default, PartialEq)]
pub struct StageTimes {
    /// Delaunay triangulation.
    pub triangulation: Duration,
    /// Stage 1, the proximity graph.
    pub proximity: Duration,
    /// Stage 2, non-manifold repair.
    pub repair: Duration,
    /// Stage 3, outlier removal.
    pub outliers: Duration,
    /// Stage 4, curve assembly.
    pub curves: Duration,
}

/// An edge between two input positions, `[a, b]` with `a < b`.
pub type InputEdge = [u32; 2];

/// Everything a reconstruction computed, stage by stage, in input positions. Exact duplicates
/// are one point, reported under the smallest input position holding it (see
/// [`Triangulation::vertex_of_input`]).
#[derive(Clone, Debug)]
pub struct Reconstruction {
    /// The parameters it ran with.
    pub params: Params,
    /// The Delaunay triangulation the stages walked.
    pub triangulation: Triangulation,
    /// The intermediate graphs in vertex ids; [`Reconstruction::proximity`] and its siblings
    /// translate them to input positions on demand.
    stages: Stages,
    /// The final edges (the output of whichever of the two ran last), sorted.
    pub edges: Vec<InputEdge>,
    /// Whether stage 3 found an outlier and filtered.
    pub outlier_filter_applied: bool,
    /// Final degree of every input point (duplicates share their point's degree).
    pub degrees: Vec<u32>,
    /// Stage 4: the curves, as input positions.
    pub curves: Vec<Curve>,
    /// Input positions whose point ended with no edge (outliers), ascending.
    pub unused: Vec<usize>,
    /// Time per stage.
    pub times: StageTimes,
}

impl Reconstruction {
    /// Stage 1: the ConDT proximity graph, sorted, in input positions.
    pub fn proximity(&self) -> Vec<InputEdge> {
        to_input_edges(&self.triangulation, self.stages.proximity())
    }

    /// The output of the non-manifold repair, sorted, in input positions.
    pub fn repaired(&self) -> Vec<InputEdge> {
        to_input_edges(&self.triangulation, self.stages.repaired())
    }

    /// The output of the outlier removal, sorted, in input positions.
    pub fn filtered(&self) -> Vec<InputEdge> {
        to_input_edges(&self.triangulation, self.stages.filtered())
    }

    /// The coordinates of input position `index` (as triangulated; duplicates coincide anyway).
    pub fn point(&self, index: usize) -> Point {
        self.triangulation
            .point(self.triangulation.vertex_of_input(index))
    }
}

/// The edge lists of stages 1 to 3, in vertex ids, in the order stages 2 and 3 ran. A stage
/// that changed nothing (no vertex to repair, no outlier) stores no copy of its input.
#[derive(Clone, Debug)]
struct Stages {
    outliers_first: bool,
    proximity: Vec<Edge>,
    /// The output of the stage that ran second (repair, unless `outliers_first`).
    first: Option<Vec<Edge>>,
    /// The output of the stage that ran third.
    second: Option<Vec<Edge>>,
}

impl Stages {
    fn proximity(&self) -> &[Edge] {
        &self.proximity
    }

    fn after_first(&self) -> &[Edge] {
        self.first.as_deref().unwrap_or(&self.proximity)
    }

    /// The final graph.
    fn last(&self) -> &[Edge] {
        self.second.as_deref().unwrap_or(self.after_first())
    }

    fn repaired(&self) -> &[Edge] {
        if self.outliers_first {
            self.last()
        } else {
            self.after_first()
        }
    }

    fn filtered(&self) -> &[Edge] {
        if self.outliers_first {
            self.after_first()
        } else {
            self.last()
        }
    }
}

/// Starts a closed curve at its smallest index, heading to the smaller of its two neighbours, and
/// an open one at its smaller end, so the output never depends on the internal numbering.
fn canonical_direction(curve: &mut Curve) {
    let v = &mut curve.vertices;
    if v.len() < 2 {
        return;
    }
    if curve.closed {
        let first = (0..v.len()).min_by_key(|&i| v[i]).unwrap_or(0);
        v.rotate_left(first);
        if v[v.len() - 1] < v[1] {
            v[1..].reverse();
        }
    } else if v[v.len() - 1] < v[0] {
        v.reverse();
    }
}

/// Vertex-id edges to sorted input-position edges, in O(n).
fn to_input_edges(tri: &Triangulation, edges: &[Edge]) -> Vec<InputEdge> {
    let pairs = edges.iter().map(|&[a, b]| {
        let (a, b) = (tri.input_index(a) as u32, tri.input_index(b) as u32);
        [a.min(b), a.max(b)]
    });
    crate::graph::sort_pairs(tri.num_input_points(), pairs, edges.len(), |a| a as usize)
}

/// A clock that reads zero without `std`.
struct Stopwatch {
    #[cfg(feature = "std")]
    start: std::time::Instant,
}

impl Stopwatch {
    fn start() -> Self {
        Stopwatch {
            #[cfg(feature = "std")]
            start: std::time::Instant::now(),
        }
    }

    /// Time since the start or the previous lap.
    fn lap(&mut self) -> Duration {
        #[cfg(feature = "std")]
        {
            let now = std::time::Instant::now();
            let elapsed = now - self.start;
            self.start = now;
            elapsed
        }
        #[cfg(not(feature = "std"))]
        Duration::ZERO
    }
}

/// Triangulates `points` and reconstructs the curves through them.
///
/// # Errors
/// As [`triangulate`]: non-finite coordinates, an over-wide dynamic range, too many points.
pub fn reconstruct(points: &[Point], params: &Params) -> Result<Reconstruction, Error> {
    let mut clock = Stopwatch::start();
    let tri = triangulate(points)?;
    let triangulation_time = clock.lap();
    let mut result = reconstruct_triangulation(tri, params);
    result.times.triangulation = triangulation_time;
    Ok(result)
}

/// Runs the ConDT stages on an existing triangulation.
pub fn reconstruct_triangulation(tri: Triangulation, params: &Params) -> Reconstruction {
    let mut clock = Stopwatch::start();
    let mut times = StageTimes::default();
    let proximity = proximity::proximity_graph(&tri, params.uniformity, params.parallel);
    times.proximity = clock.lap();
    let run_repair = |input: &[Edge], times: &mut StageTimes, clock: &mut Stopwatch| {
        let out = nonmanifold::repair(&tri, input, params.repair);
        times.repair = clock.lap();
        out
    };
    let run_outliers = |input: &[Edge], times: &mut StageTimes, clock: &mut Stopwatch| {
        let out = match params.outlier_factor {
            Some(factor) => outliers::remove_outliers(&tri, input, factor),
            None => outliers::Filtered {
                edges: None,
                applied: false,
            },
        };
        times.outliers = clock.lap();
        out
    };
    let (repaired, filtered) = if params.outliers_first {
        let filtered = run_outliers(&proximity, &mut times, &mut clock);
        let input = filtered.edges.as_deref().unwrap_or(&proximity);
        (run_repair(input, &mut times, &mut clock), filtered)
    } else {
        let repaired = run_repair(&proximity, &mut times, &mut clock);
        let input = repaired.as_deref().unwrap_or(&proximity);
        let filtered = run_outliers(input, &mut times, &mut clock);
        (repaired, filtered)
    };
    let outlier_filter_applied = filtered.applied;
    let (first, second) = if params.outliers_first {
        (filtered.edges, repaired)
    } else {
        (repaired, filtered.edges)
    };
    let stages = Stages {
        outliers_first: params.outliers_first,
        proximity,
        first,
        second,
    };
    let last = stages.last();
    let n = tri.num_input_points();
    let graph = CurveGraph::new(n, last);
    let in_parallel = params.parallel && n >= PARALLEL_FROM;
    let (curves, tally) = both(
        in_parallel,
        || curves_in_input_positions(&tri, &graph),
        || tally(&tri, &graph, last.len()),
    );
    times.curves = clock.lap();
    Reconstruction {
        params: *params,
        triangulation: tri,
        stages,
        edges: tally.edges,
        outlier_filter_applied,
        degrees: tally.degrees,
        curves,
        unused: tally.unused,
        times,
    }
}

/// Fewest points for which stages split their work over rayon's workers: below it, waking them
/// costs more than they save (10k points on a curve, two workers: proximity 0.59 ms in two
/// ranges against 0.38 ms in one sweep, curves 0.24 against 0.16 ms).
pub(crate) const PARALLEL_FROM: usize = 1 << 16;

/// `(a(), b())`, run at once on rayon when `parallel`.
#[cfg(feature = "parallel")]
fn both<A: Send, B: Send>(
    parallel: bool,
    a: impl FnOnce() -> A + Send,
    b: impl FnOnce() -> B + Send,
) -> (A, B) {
    if parallel {
        rayon::join(a, b)
    } else {
        (a(), b())
    }
}

#[cfg(not(feature = "parallel"))]
fn both<A, B>(_parallel: bool, a: impl FnOnce() -> A, b: impl FnOnce() -> B) -> (A, B) {
    (a(), b())
}

/// Stage 4's curves, in input positions, each in its canonical direction, sorted.
fn curves_in_input_positions(tri: &Triangulation, graph: &CurveGraph) -> Vec<Curve> {
    let mut curves = curves_of(graph);
    for curve in curves.iter_mut() {
        for v in curve.vertices.iter_mut() {
            *v = tri.input_index(VertexId::new(*v)) as u32;
        }
        canonical_direction(curve);
    }
    curves.sort_by(|a, b| a.vertices.cmp(&b.vertices));
    curves
}

/// The final graph seen from the input positions.
struct Tally {
    degrees: Vec<u32>,
    unused: Vec<usize>,
    edges: Vec<InputEdge>,
}

/// One pass over the input positions gives the degrees, the unused points and the final edges
/// already sorted: an edge is listed by its smaller input position. For the common vertex of
/// degree <= 2 both candidates are written and the count advances only past those that belong
/// (whether they do is a coin toss, so it is not branched on).
fn tally(tri: &Triangulation, graph: &CurveGraph, edge_count: usize) -> Tally {
    let n = tri.num_input_points();
    // Without duplicates every input position stands for its own vertex: no need to look.
    let has_duplicates = tri.num_vertices() < n;
    let mut degrees = Vec::with_capacity(n);
    let mut unused = Vec::new();
    // Room for the two candidates a vertex writes past the last edge it lists.
    let mut edges: Vec<InputEdge> = alloc::vec![[0, 0]; edge_count + 2];
    let mut count = 0;
    let input_of = |w: VertexId| {
        if w.is_infinite() {
            0
        } else {
            tri.input_index(w) as u32
        }
    };
    for (i, &v) in tri.input_to_vertex().iter().enumerate() {
        let degree = graph.degree(v);
        degrees.push(degree as u32);
        let i = i as u32;
        if degree == 0 {
            unused.push(i as usize);
        } else if degree <= 2 {
            let [x, y] = graph.first_two(v).map(input_of);
            // A duplicate input point lists nothing: its edges are under the first copy.
            let listing = !has_duplicates || input_of(v) == i;
            for j in [x.min(y), x.max(y)] {
                edges[count] = [i, j];
                count += usize::from(listing & (j > i));
            }
        } else if !has_duplicates || input_of(v) == i {
            let first = count;
            for k in 0..degree {
                let j = input_of(graph.neighbor(v, k));
                if j > i {
                    edges[count] = [i, j];
                    count += 1;
                }
            }
            edges[first..count].sort_unstable();
        }
    }
    edges.truncate(count);
    Tally {
        degrees,
        unused,
        edges,
    }
}
