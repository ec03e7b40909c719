//! Two classical reconstructions on ConDT's triangulation, to compare methods on identical
//! Delaunay edges: [`Triangulation::nn_crust`] and [`Triangulation::crust`]. They read the finished
//! triangulation (the Crust also triangulates a second set through the public entry), may not
//! change a triangulation, and share no rule with the stages (or they would not be baselines).
//! Lengths whose rounded squares tie are ordered exactly, and only exact ties go to the smaller
//! vertex id (which follows the insertion order, so an orientation could change them);
//! NN-Crust's right angle is decided exactly too; the Crust's circumcentres are rounded
//! ([`Triangulation::crust`] says where that shows). Duplicates are merged as everywhere.

use crate::adjacency::{ordered, Edge};
use crate::error::Error;
use crate::geometry::{lower_left, Point};
use crate::graph::Graph;
use crate::mesh::VertexId;
use crate::predicates::distance_order;
use crate::triangulate::{triangulate_with, Triangulation};
use alloc::borrow::Cow;
use alloc::vec::Vec;

impl Triangulation {
    /// The NN-Crust (T. K. Dey and P. Kumar, "A simple provable algorithm for curve
    /// reconstruction", SODA 1999): each point's edges to its nearest neighbour and to its nearest
    /// *half neighbour*, one at least 90 degrees from the nearest (both Delaunay edges: the ring is
    /// all it reads). Exact for smooth curves sampled below a third of the local feature size.
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// // Eight points on a circle, and the edges between consecutive ones.
    /// let angles = (0..8).map(|k| k as f64 * std::f64::consts::TAU / 8.0);
    /// let points: Vec<Point> = angles.map(|t| Point::new(t.cos(), t.sin())).collect();
    /// let tri = triangulate(&points)?;
    /// let edges = tri.nn_crust().edges();
    /// assert_eq!(edges.len(), 8);
    /// assert!(edges.iter().all(|&[a, b]| b == a + 1 || (a, b) == (0, 7)));
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn nn_crust(&self) -> Graph<'_> {
        Graph::new(self, Cow::Owned(nn_crust_edges(self)))
    }

    /// The Crust (N. Amenta, M. Bern and D. Eppstein, "The crust and the beta-skeleton:
    /// combinatorial curve reconstruction", 1998): the Delaunay edges between points once the
    /// circumcentres of the Delaunay triangles (Voronoi vertices) join the set. Exact for smooth
    /// curves sampled below 0.252 of the local feature size. The circumcentres are rounded to
    /// doubles: where one lies on or within rounding of a Delaunay edge (a right angle, a
    /// straight run, a grid, written in decimals) the answer can differ from the exact Crust of
    /// the same points by that edge (the triangle `(0.9, 0.1)`, `(0.9, 1.4)`, `(2.0, 1.4)`
    /// keeps its hypotenuse, whose exact Voronoi vertex lies on it).
    ///
    /// # Errors
    /// [`Error::TooManyPoints`] when the points and the circumcentres together exceed
    /// [`MAX_POINTS`](crate::MAX_POINTS).
    ///
    /// ```
    /// use condt::{triangulate, Point};
    /// let angles = (0..12).map(|k| k as f64 * std::f64::consts::TAU / 12.0);
    /// let points: Vec<Point> = angles.map(|t| Point::new(2.0 * t.cos(), t.sin())).collect();
    /// let tri = triangulate(&points)?;
    /// let crust = tri.crust()?;
    /// assert_eq!(crust.num_edges(), 12);
    /// assert!(crust.degrees().iter().all(|&d| d == 2));
    /// # Ok::<(), condt::Error>(())
    /// ```
    pub fn crust(&self) -> Result<Graph<'_>, Error> {
        let edges = crust_edges(self, cfg!(feature = "parallel"))?;
        Ok(Graph::new(self, Cow::Owned(edges)))
    }
}

/// [`Triangulation::nn_crust`]'s edges in vertex ids, sorted.
pub(crate) fn nn_crust_edges(tri: &Triangulation) -> Vec<Edge> {
    let mut edges: Vec<Edge> = Vec::new();
    for v in tri.vertices() {
        let p = tri.vertex_point(v);
        let neighbours = || {
            tri.mesh()
                .neighbors(v)
                .filter(|&w| tri.is_vertex(w))
                .map(|w| (p.dist2(tri.vertex_point(w)), w))
        };
        // Exact lengths, then id (which follows the insertion order, so that only an exact tie
        // depends on the orientation).
        let closer = |a: &(f64, VertexId), b: &(f64, VertexId)| {
            let at = |(length2, w): (f64, VertexId)| (tri.vertex_point(w), length2);
            distance_order(p, at(*a), at(*b)).then(a.1.cmp(&b.1))
        };
        let Some((_, nearest)) = neighbours().min_by(closer) else {
            continue;
        };
        edges.push(ordered(v, nearest));
        let towards = tri.vertex_point(nearest);
        let half = neighbours()
            .filter(|&(_, w)| at_least_right_angle(p, towards, tri.vertex_point(w)))
            .min_by(closer);
        if let Some((_, w)) = half {
            edges.push(ordered(v, w));
        }
    }
    edges.sort_unstable();
    edges.dedup();
    edges
}

/// [`Triangulation::crust`]'s edges in vertex ids, sorted; the second triangulation on rayon's
/// threads only when `parallel` (the same edges).
///
/// # Errors
/// [`Error::TooManyPoints`] past the kernel's limit ([`crust_fits`] tells beforehand).
pub(crate) fn crust_edges(tri: &Triangulation, parallel: bool) -> Result<Vec<Edge>, Error> {
    // In the stages' frame (an exact power-of-two scaling: no ordinary circumcentre overflows),
    // relative to the corner of the samples' box: an exact translation leaves these differences
    // as they were, so the edges do not depend on where the set lies. But the differences round
    // (`-0.1 - (-4.9)`), and samples on one line may no longer be (an embedded review: the second
    // triangulation had edges through samples). So where the samples' triangulation in that
    // frame is not theirs, they stay where they are and only the circumcentres, computed from
    // the corner and added back, round (then the edges can depend on where the set lies).
    let samples: Vec<VertexId> = tri.vertices().collect();
    let corner = lower_left(samples.iter().map(|&v| tri.vertex_point(v))).unwrap_or_default();
    let relative = |v: VertexId| difference(tri.vertex_point(v), corner);
    let moved: Vec<Point> = samples.iter().map(|&v| relative(v)).collect();
    // The samples, and what takes a centre from the corner's frame into theirs.
    let (mut points, back) = if same_triangles(
        tri,
        &samples,
        &triangulate_with(&moved, parallel, None, None)?,
    ) {
        (moved, Point::new(0.0, 0.0))
    } else {
        let own = samples.iter().map(|&v| tri.vertex_point(v)).collect();
        (own, corner)
    };
    let mesh = tri.mesh();
    points.extend(mesh.triangles().filter_map(|t| {
        let [a, b, c] = mesh.triangle_vertices(t).map(relative);
        let centre = circumcentre(a, b, c)?;
        let placed = Point::new(centre.x + back.x, centre.y + back.y);
        (placed.x.is_finite() && placed.y.is_finite()).then_some(placed)
    }));
    let with_centres = triangulate_with(&points, parallel, None, None)?;
    let num_samples = samples.len();
    let mut edges: Vec<Edge> = with_centres
        .edges()
        .filter(|&[a, b]| a < num_samples && b < num_samples)
        .map(|[a, b]| ordered(samples[a], samples[b]))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    Ok(edges)
}

/// `Ok` when [`crust_edges`] can triangulate the points with their circumcentres, else its error.
pub(crate) fn crust_fits(tri: &Triangulation) -> Result<(), Error> {
    let count = tri.num_vertices() + tri.mesh().triangles().count();
    let limit = crate::MAX_POINTS;
    if count > limit {
        return Err(Error::TooManyPoints { count, limit });
    }
    Ok(())
}

fn difference(a: Point, b: Point) -> Point {
    Point::new(a.x - b.x, a.y - b.y)
}

/// Whether `moved` (the `samples` of `tri`, its vertices in id order, moved) has the triangles of
/// `tri`. Ids skip where a duplicate was merged, so a vertex is named by its place in `samples`.
fn same_triangles(tri: &Triangulation, samples: &[VertexId], moved: &Triangulation) -> bool {
    let sorted = |triangles: &mut dyn Iterator<Item = [usize; 3]>| {
        let mut list: Vec<[usize; 3]> = triangles
            .map(|mut t| {
                t.sort_unstable();
                t
            })
            .collect();
        list.sort_unstable();
        list
    };
    let mesh = tri.mesh();
    let mut own = mesh.triangles().map(|t| {
        mesh.triangle_vertices(t)
            .map(|v| samples.binary_search(&v).unwrap_or(usize::MAX))
    });
    sorted(&mut own) == sorted(&mut moved.triangles())
}

fn dot(a: Point, b: Point) -> f64 {
    a.x * b.x + a.y * b.y
}

/// Whether the angle at `p` between `q` and `w` is at least 90 degrees, NN-Crust's half-neighbour
/// test, exactly: `(w - p) · (q - p) <= 0`. The rounded product decides where it lies beyond its
/// error (two differences, two products and a sum, each within 2^-53 of its value: under 2^-50
/// of the products' magnitudes together, in the stages' frame where nothing underflows); nearer
/// zero, big integers (a methods review: on a square's corners written as `cos` and `sin` of
/// multiples of 90 degrees, the rounded product read a right angle where the doubles make one
/// a hair under it, and the square closed).
fn at_least_right_angle(p: Point, q: Point, w: Point) -> bool {
    let (u, v) = (difference(w, p), difference(q, p));
    let rounded = dot(u, v);
    let error = (u.x * v.x).abs() + (u.y * v.y).abs();
    if rounded.abs() > error / (1u64 << 50) as f64 {
        rounded < 0.0
    } else {
        crate::predicates::dot_sign(w, p, q, p) != core::cmp::Ordering::Greater
    }
}

/// The circumcentre of a triangle, relative to its first corner; `None` when not finite (a sliver
/// whose centre lies beyond the range of doubles, where it would change no edge between samples).
fn circumcentre(a: Point, b: Point, c: Point) -> Option<Point> {
    let (ab, ac) = (difference(b, a), difference(c, a));
    let denominator = 2.0 * (ab.x * ac.y - ab.y * ac.x);
    let (lb, lc) = (dot(ab, ab), dot(ac, ac));
    let x = a.x + (ac.y * lb - ab.y * lc) / denominator;
    let y = a.y + (ab.x * lc - ac.x * lb) / denominator;
    (x.is_finite() && y.is_finite()).then_some(Point::new(x, y))
}

#[cfg(test)]
mod tests {
    use crate::sample::{sample, Sampling, Shape};
    use crate::{triangulate, Point};
    use alloc::vec;
    use alloc::vec::Vec;

    /// A smooth closed curve sampled at spacing 0.2 of its local feature size, well within both
    /// methods' sampling bounds (1/3 for NN-Crust, 0.252 for the Crust).
    fn ellipse_and_circle() -> crate::sample::Sample {
        sample(
            &[
                Shape::Ellipse {
                    center: Point::new(0.0, 0.0),
                    radii: (3.0, 1.0),
                    rotation: 0.3,
                },
                Shape::circle(Point::new(10.0, 0.0), 2.0),
            ],
            &Sampling::new(0.2),
        )
        .unwrap()
    }

    #[test]
    fn nn_crust_reconstructs_well_sampled_closed_curves() {
        let truth = ellipse_and_circle();
        let tri = triangulate(&truth.points).unwrap();
        assert_eq!(tri.nn_crust().edges(), truth.edges);
    }

    #[test]
    fn crust_reconstructs_well_sampled_closed_curves() {
        let truth = ellipse_and_circle();
        let tri = triangulate(&truth.points).unwrap();
        assert_eq!(tri.crust().unwrap().edges(), truth.edges);
    }

    /// A methods review: a square's corners written as `cos` and `sin` of multiples of 90
    /// degrees. At corners 0 and 3 the angle to the other corner is a hair under 90 degrees in
    /// these doubles (the exact dot products with the nearest neighbour's edge are +1.2e-16, by
    /// fractions), so neither takes the other as its half neighbour; the rounded product read
    /// 0 there and closed the square.
    #[test]
    fn nn_crust_decides_the_right_angle_exactly() {
        let points = [
            (1.0, 0.0),
            (6.123233995736766e-17, 1.0),
            (-1.0, 1.2246467991473532e-16),
            (-1.8369701987210297e-16, -1.0),
        ]
        .map(Point::from);
        let tri = triangulate(&points).unwrap();
        assert_eq!(tri.nn_crust().edges(), vec![[0, 1], [1, 2], [2, 3]]);
    }

    #[test]
    fn nn_crust_keeps_the_half_neighbour_across_a_gap_in_density() {
        // Three points close together and a fourth far to the right of the last: the last one's
        // nearest neighbour is its left neighbour, its half neighbour the far point.
        let points = [(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (10.0, 0.5)].map(Point::from);
        let tri = triangulate(&points).unwrap();
        assert_eq!(tri.nn_crust().edges(), vec![[0, 1], [1, 2], [2, 3]]);
    }

    #[test]
    fn crust_of_collinear_points_is_their_chain_and_duplicates_are_merged() {
        let points = [(0.0, 0.0), (2.0, 0.0), (1.0, 0.0), (2.0, 0.0)].map(Point::from);
        let tri = triangulate(&points).unwrap();
        assert_eq!(tri.crust().unwrap().edges(), vec![[0, 2], [1, 2]]);
        assert_eq!(tri.nn_crust().edges(), vec![[0, 2], [1, 2]]);
    }

    /// Samples on one line whose differences round (an embedded review: shifted to the box's
    /// corner, `-0.1 * k - (-4.9)` rounds, the samples left the line, and the second
    /// triangulation gave edges through samples), and a square turned 45 degrees sampled every
    /// 0.1 (decimal coordinates, collinear runs): the chain, and one closed curve.
    #[test]
    fn crust_of_rounded_collinear_runs_passes_through_no_sample() {
        let line: Vec<Point> = (0..50)
            .map(|k| Point::new(0.1 * k as f64, -0.1 * k as f64))
            .collect();
        let tri = triangulate(&line).unwrap();
        let chain: Vec<[usize; 2]> = (0..49).map(|k| [k, k + 1]).collect();
        assert_eq!(tri.crust().unwrap().edges(), chain);
        let corners = [(3.0, 0.0), (0.0, 3.0), (-3.0, 0.0), (0.0, -3.0)];
        let mut diamond = Vec::new();
        for side in 0..4 {
            let ((x0, y0), (x1, y1)) = (corners[side], corners[(side + 1) % 4]);
            for k in 0..30 {
                let t = k as f64 / 30.0;
                diamond.push(Point::new(x0 + (x1 - x0) * t, y0 + (y1 - y0) * t));
            }
        }
        let tri = triangulate(&diamond).unwrap();
        let crust = tri.crust().unwrap();
        assert!(crust.degrees().iter().all(|&d| d == 2));
        assert_eq!(
            crate::curves_from_edges(diamond.len(), &crust.edges()).len(),
            1
        );
    }

    #[test]
    fn as_a_method_each_baseline_is_the_whole_reconstruction() {
        use crate::{reconstruct, Method, Params, Stage};
        let truth = ellipse_and_circle();
        let tri = triangulate(&truth.points).unwrap();
        for (method, stage, edges) in [
            (Method::NnCrust, Stage::NnCrust, tri.nn_crust().edges()),
            (Method::Crust, Stage::Crust, tri.crust().unwrap().edges()),
        ] {
            let params = Params::default().with_method(method);
            let result = reconstruct(&truth.points, &params).unwrap();
            let stages: Vec<Stage> = result.stages().map(|r| r.stage).collect();
            assert_eq!(stages, vec![stage]);
            assert_eq!(result.edges().collect::<Vec<_>>(), edges);
            assert_eq!(result.curves().len(), 2);
            let stories = result.provenance();
            let chosen: Vec<[usize; 2]> = stories
                .iter()
                .filter(|s| {
                    s.changes
                        .iter()
                        .any(|c| c.reason == crate::Reason::Baseline && c.added)
                })
                .map(|s| s.edge)
                .collect();
            assert_eq!(chosen, edges);
            // Every other edge's story has the baseline's decision too, not chosen.
            assert!(stories
                .iter()
                .all(|s| s.changes.len() == 1 && s.kept == s.changes[0].added));
        }
    }

    #[test]
    fn both_are_the_same_at_every_power_of_two_scale_and_offset_free() {
        let truth = ellipse_and_circle();
        let base = triangulate(&truth.points).unwrap();
        let expected = (base.nn_crust().edges(), base.crust().unwrap().edges());
        for factor in [2f64.powi(-600), 2f64.powi(600)] {
            let scaled: Vec<Point> = truth
                .points
                .iter()
                .map(|p| Point::new(p.x * factor, p.y * factor))
                .collect();
            let tri = triangulate(&scaled).unwrap();
            assert_eq!(
                (tri.nn_crust().edges(), tri.crust().unwrap().edges()),
                expected
            );
        }
    }
}
