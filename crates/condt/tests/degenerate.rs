//! Named regression tests, one per degenerate family the triangulator must handle.

mod common;

use common::*;
use condt::{reconstruct, triangulate, Error, Params, Point};

/// `points` moved by `f`, point by point.
fn moved(points: &[Point], f: impl Fn(Point) -> Point) -> Vec<Point> {
    points.iter().map(|&p| f(p)).collect()
}

/// `points`, an `n` x `n` grid however moved, triangulates validly into its `2 (n - 1)^2` cells.
fn assert_whole_grid(points: &[Point], n: usize) {
    let tri = triangulate(points).unwrap();
    tri.validate().unwrap();
    assert_eq!(tri.triangles().count(), 2 * (n - 1) * (n - 1));
}

fn pts(coords: &[(f64, f64)]) -> Vec<Point> {
    coords.iter().map(|&c| Point::from(c)).collect()
}

#[test]
fn no_points() {
    let tri = triangulate(&[]).unwrap();
    tri.validate().unwrap();
    assert_eq!(
        (
            tri.num_vertices(),
            tri.edges().count(),
            tri.triangles().count()
        ),
        (0, 0, 0)
    );
    assert_eq!(tri.hull().count(), 0);
}

#[test]
fn one_point() {
    let tri = triangulate(&pts(&[(3.0, 4.0)])).unwrap();
    tri.validate().unwrap();
    assert_eq!(tri.num_vertices(), 1);
    assert_eq!(tri.edges().count(), 0);
    assert_eq!(tri.neighbors(0).count(), 0);
}

#[test]
fn two_points_make_one_edge() {
    let tri = triangulate(&pts(&[(0.0, 0.0), (1.0, 1.0)])).unwrap();
    tri.validate().unwrap();
    assert_eq!(edge_set(&tri).into_iter().collect::<Vec<_>>(), vec![(0, 1)]);
    assert_eq!(tri.neighbors(0).collect::<Vec<_>>(), vec![1]);
    assert_eq!(tri.neighbors(1).collect::<Vec<_>>(), vec![0]);
}

#[test]
fn collinear_points_form_a_chain_in_line_order() {
    // Shuffled points of the line y = -3x + 7, including negative coordinates and -0.0.
    let xs = [
        4.0, -2.0, 0.0, 7.0, -4.0, -0.0, 1.0, 3.0, -5.0, 2.0, 6.0, -3.0, 5.0, -1.0,
    ];
    let line: Vec<Point> = xs.iter().map(|&x| Point::new(x, -3.0 * x + 7.0)).collect();
    let tri = triangulate(&line).unwrap();
    tri.validate().unwrap();
    assert!(tri.is_degenerate());
    assert_eq!(tri.num_vertices(), 13, "0.0 and -0.0 are the same point");
    // Every vertex is joined exactly to its nearest neighbours along the line.
    for i in tri.distinct_points() {
        let x = tri.point(i).x;
        let mut around: Vec<f64> = tri.neighbors(i).map(|j| tri.point(j).x).collect();
        around.sort_by(f64::total_cmp);
        let expected: Vec<f64> = [x - 1.0, x + 1.0]
            .into_iter()
            .filter(|t| (-5.0..=7.0).contains(t))
            .collect();
        assert_eq!(around, expected, "neighbours of x = {x}");
    }
}

#[test]
fn vertical_and_tiny_collinear_runs() {
    let vertical: Vec<Point> = (0..50)
        .rev()
        .map(|i| Point::new(1e-3, i as f64 * 0.25))
        .collect();
    let tri = triangulate(&vertical).unwrap();
    tri.validate().unwrap();
    assert_eq!(tri.edges().count(), 49);
    for n in 3..6 {
        let tri = triangulate(&vertical[..n]).unwrap();
        tri.validate().unwrap();
        assert_eq!(tri.edges().count(), n - 1);
    }
}

#[test]
fn collinear_run_then_one_point_off_the_line() {
    let mut p: Vec<Point> = (0..100).map(|i| Point::new(i as f64, i as f64)).collect();
    p.push(Point::new(0.0, 1.0));
    let tri = triangulate(&p).unwrap();
    tri.validate().unwrap();
    assert_eq!(tri.triangles().count(), 99);
    assert_hull_convex_and_enclosing(&tri);
}

#[test]
fn exact_duplicates_merge_into_the_smallest_index() {
    let p = pts(&[
        (1.0, 1.0),
        (0.0, 0.0),
        (2.0, 0.0),
        (0.0, 0.0),
        (1.0, 1.0),
        (0.0, 0.0),
        (1.0, 3.0),
    ]);
    let tri = triangulate(&p).unwrap();
    tri.validate().unwrap();
    assert_eq!(tri.num_vertices(), 4);
    let map: Vec<usize> = (0..p.len()).map(|i| tri.input_of(tri.vertex(i))).collect();
    assert_eq!(map, vec![0, 1, 2, 1, 0, 1, 6]);
    // Every input point is accounted for: kept, or merged into a vertex at the same place.
    for (i, &expected) in p.iter().enumerate() {
        assert_eq!(tri.point(i), expected);
        assert_eq!(tri.point(tri.input_of(tri.vertex(i))), expected);
    }
    let kept: Vec<usize> = tri.distinct_points().collect();
    assert_eq!(kept, vec![0, 1, 2, 6]);
    let first: Vec<usize> = (0..p.len()).map(|i| tri.first_at(i)).collect();
    assert_eq!(first, map);
    let merged: Vec<[usize; 2]> = tri.merged().collect();
    assert_eq!(merged, vec![[3, 1], [4, 0], [5, 1]]);
}

#[test]
fn all_points_identical() {
    let p = vec![Point::new(-7.5, 2.25); 1000];
    let tri = triangulate(&p).unwrap();
    tri.validate().unwrap();
    assert_eq!(tri.num_vertices(), 1);
    let kept = tri.vertex(0);
    assert!((0..p.len()).all(|i| tri.vertex(i) == kept));
    assert_eq!(tri.input_of(kept), 0);
    assert_eq!(tri.distinct_points().collect::<Vec<_>>(), vec![0]);
}

#[test]
fn duplicates_of_collinear_points() {
    let p = pts(&[
        (2.0, 2.0),
        (0.0, 0.0),
        (2.0, 2.0),
        (1.0, 1.0),
        (0.0, 0.0),
        (1.0, 1.0),
    ]);
    let tri = triangulate(&p).unwrap();
    tri.validate().unwrap();
    assert_eq!(
        edge_set(&tri).into_iter().collect::<Vec<_>>(),
        vec![(0, 3), (1, 3)]
    );
}

#[test]
fn integer_grid_is_fully_cocircular_yet_valid() {
    for side in [2usize, 3, 10, 101] {
        let g = grid(side, side as u64);
        let tri = triangulate(&g).unwrap();
        tri.validate().unwrap();
        // A k x k grid: every unit square cut by one diagonal.
        assert_eq!(tri.triangles().count(), 2 * (side - 1) * (side - 1));
        assert_eq!(tri.hull().count(), 4 * (side - 1));
    }
}

#[test]
fn grid_with_every_point_doubled() {
    let mut g = grid(30, 1);
    g.extend(grid(30, 2));
    let tri = triangulate(&g).unwrap();
    tri.validate().unwrap();
    assert_eq!(tri.num_vertices(), 900);
    assert_eq!(tri.triangles().count(), 2 * 29 * 29);
}

#[test]
fn integer_points_on_one_circle() {
    // The 20 lattice points with x^2 + y^2 = 625, plus the centre: 20 cocircular points.
    let mut p = Vec::new();
    for x in -25i32..=25 {
        for y in -25i32..=25 {
            if x * x + y * y == 625 {
                p.push(Point::new(x as f64, y as f64));
            }
        }
    }
    assert_eq!(p.len(), 20);
    let ring = triangulate(&p).unwrap();
    ring.validate().unwrap();
    assert_eq!(ring.triangles().count(), 18);
    p.push(Point::new(0.0, 0.0));
    let wheel = triangulate(&p).unwrap();
    wheel.validate().unwrap();
    assert_eq!(
        wheel.neighbors(20).count(),
        20,
        "the centre sees every rim point"
    );
}

#[test]
fn coordinates_offset_by_a_million() {
    let base = uniform(5000, 11);
    let shifted = moved(&base, |p| Point::new(p.x + 1e6, p.y + 1e6));
    let tri = triangulate(&shifted).unwrap();
    tri.validate().unwrap();
    assert_hull_convex_and_enclosing(&tri);
    assert_whole_grid(
        &moved(&grid(50, 3), |p| Point::new(p.x + 1e6, p.y - 1e6)),
        50,
    );
}

#[test]
fn huge_coordinates_near_1e15() {
    let base = uniform(3000, 12);
    let huge = moved(&base, |p| Point::new(p.x * 1e15, p.y * 1e15));
    triangulate(&huge).unwrap().validate().unwrap();
    // Points 1 unit apart at 1e15: only a few bits of each coordinate differ.
    assert_whole_grid(
        &moved(&grid(20, 4), |p| Point::new(1e15 + p.x, 1e15 + p.y)),
        20,
    );
}

#[test]
fn tiny_coordinates_near_1e_200_give_the_same_mesh() {
    let base = uniform(3000, 13);
    // Scaling by a power of two is exact, so the triangulation must be the same edge for edge.
    let factor = 2f64.powi(-665); // about 1.2e-200
    let tiny = moved(&base, |p| Point::new(p.x * factor, p.y * factor));
    let (a, b) = (triangulate(&base).unwrap(), triangulate(&tiny).unwrap());
    b.validate().unwrap();
    assert_eq!(edge_set(&a), edge_set(&b));
    assert_whole_grid(
        &moved(&grid(10, 5), |p| Point::new(p.x * 1e-310, p.y * 1e-310)),
        10,
    );
}

#[test]
fn non_finite_coordinates_are_refused_by_index() {
    for (bad, index) in [(f64::NAN, 2), (f64::INFINITY, 0), (f64::NEG_INFINITY, 3)] {
        let mut p = uniform(4, 1);
        p[index].y = bad;
        assert_eq!(triangulate(&p).unwrap_err(), Error::NonFinite { index });
    }
}

/// Magnitudes 2^260 apart: beyond the fast predicates' range, decided by the exact integers.
#[test]
fn a_dynamic_range_beyond_2_pow_200_is_triangulated() {
    let p = pts(&[(1.0, 1.0), (0.0, 1e-50), (1e-70, 0.5), (1e-80, 0.0)]);
    let tri = triangulate(&p).unwrap();
    tri.validate().unwrap();
    // The four points are in convex position: (0, 1e-50) lies left of the line from (1e-80, 0)
    // to (1e-70, 0.5), which lies above the line from (0, 1e-50) to (1, 1).
    assert_eq!(tri.triangles().count(), 2);
    assert_eq!(tri.hull().count(), 4);
}

/// Found by quickcheck: a cocircular rectangle whose insertion order depended on the bit patterns
/// of negative coordinates, so a translation across zero changed the triangulation.
#[test]
fn translation_across_zero_keeps_a_cocircular_triangulation() {
    let p = pts(&[(2.0, 0.0), (2.0, 2.0), (1.0, 0.0), (1.0, 2.0), (0.0, 64.0)]);
    let moved: Vec<Point> = p.iter().map(|q| Point::new(q.x + 1.0, q.y - 1.0)).collect();
    assert_eq!(
        edge_set(&triangulate(&p).unwrap()),
        edge_set(&triangulate(&moved).unwrap())
    );
}

#[test]
fn same_input_gives_the_same_mesh() {
    let p = small_integers(2000, 30, 9);
    let (a, b) = (triangulate(&p).unwrap(), triangulate(&p).unwrap());
    let tris = |t: &condt::Triangulation| t.triangles().collect::<Vec<_>>();
    assert_eq!(tris(&a), tris(&b));
}

#[test]
fn points_on_hull_edge_extensions_past_sharp_corners() {
    // A hull corner turning by more than 90 degrees, and points on the backward extension of
    // the edge after it: collinear with one hull edge, past the far end of the one before (the
    // walk slides along ghosts there and must not go back and forth between the two).
    let mut coords = vec![(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)];
    for t in 1..40 {
        let t = t as f64 * 0.25;
        coords.push((1.0 + 0.5 * t, -t));
        coords.push((-0.5 * t, t * 2.0));
    }
    // Many orders: the insertion order is the triangulator's, but point sets of several sizes
    // give it different rounds.
    for n in 4..coords.len() {
        let tri = triangulate(&pts(&coords[..n])).unwrap();
        tri.validate().unwrap();
    }
    // The same on a dense convex curve, where every point is a hull point when inserted.
    let curve: Vec<(f64, f64)> = (0..3000)
        .map(|k| {
            let t = k as f64 * 0.002;
            (3.0 * t.cos(), 2.0 * t.sin())
        })
        .collect();
    let tri = triangulate(&pts(&curve)).unwrap();
    tri.validate().unwrap();
    assert_eq!(tri.hull().count(), curve.len());
}

/// Found by a review of the public API: a triangle range starting near `usize::MAX / 3` wrapped
/// round (three times it overflows) and, in a release build, read the first triangles' corners.
/// It panics, as any range past the triangles does.
#[test]
fn a_triangle_range_past_the_end_panics_rather_than_wrap_round() {
    let tri = triangulate(&[(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)].map(Point::from)).unwrap();
    let mesh = tri.mesh();
    assert_eq!(mesh.corner_slice(0..1).len(), 3);
    let start = usize::MAX / 3 + 1;
    for range in [start..start + 1, start..start, 0..start] {
        let caught = std::panic::catch_unwind(|| mesh.corner_slice(range.clone()).len());
        assert!(caught.is_err(), "{range:?}");
    }
}

/// The triangles of `points`' triangulation, each and the list sorted: comparable whatever the
/// insertion order.
fn sorted_triangles(points: &[Point]) -> Vec<[usize; 3]> {
    let tri = triangulate(points).unwrap();
    let mut triangles: Vec<[usize; 3]> = tri
        .triangles()
        .map(|mut t| {
            t.sort_unstable();
            t
        })
        .collect();
    triangles.sort_unstable();
    triangles
}

/// Repeats do not change a triangulation: a 4 x 4 grid (cocircular squares, where the two-halves
/// construction and the one-piece one may choose other diagonals) given 4,097 times over, past the
/// 65,536 points from which a set is built in two halves, gives the grid's own triangles and
/// reconstruction. (The size that decided the cut counted the repeats: the triangles changed.)
#[test]
fn repeats_past_the_halves_bound_give_the_triangulation_of_the_distinct_points() {
    let grid = |copies: usize| -> Vec<Point> {
        (0..16 * copies)
            .map(|i| Point::new((i % 4) as f64, (i / 4 % 4) as f64))
            .collect()
    };
    let (once, repeated) = (grid(1), grid(4097));
    assert!(repeated.len() >= 1 << 16);
    assert_eq!(sorted_triangles(&repeated), sorted_triangles(&once));
    for params in [Params::default(), Params::paper()] {
        let edges = |points: &[Point]| {
            reconstruct(points, &params)
                .unwrap()
                .edges()
                .collect::<Vec<_>>()
        };
        assert_eq!(edges(&repeated), edges(&once));
    }
}

/// Repeats do not change a small triangulation either (a triangulator tester's review): a 16 x
/// 16 grid and two points far off, whose grid shares one cell of the insertion order's grid,
/// given once to eight times over in blocks (up to 2,064 points, and past the 1,024 from which a
/// cell was ordered as a set of its own): the triangles of the distinct points, and the same
/// reconstruction. Before, six copies took other diagonals in 196 of 496
/// triangles.
#[test]
fn repeats_of_a_small_cocircular_set_give_the_triangulation_of_the_distinct_points() {
    let mut distinct: Vec<Point> = (0..256)
        .map(|i| Point::new((i % 16) as f64, (i / 16) as f64))
        .collect();
    distinct.push(Point::new(1e5, 1e5));
    distinct.push(Point::new(-1e5, 3e5));
    let once = sorted_triangles(&distinct);
    let edges = |points: &[Point]| {
        reconstruct(points, &Params::default())
            .unwrap()
            .edges()
            .collect::<Vec<_>>()
    };
    let edges_once = edges(&distinct);
    for copies in 2..=8 {
        // In blocks: position i of every block is point i (the first copy is kept).
        let blocks: Vec<Point> = (0..copies).flat_map(|_| distinct.iter().copied()).collect();
        assert_eq!(sorted_triangles(&blocks), once, "{copies} blocks");
        assert_eq!(edges(&blocks), edges_once, "{copies} blocks");
    }
}

/// Lengths whose rounded squares come out one ulp apart in the wrong order (a reviewer of the
/// paper's preset found them): Algorithm 2's "shortest edge" is the exactly shortest. Point 0's
/// squared distances to 1 and 2 differ by 6.4e-18 in truth (1 nearer) and by one ulp the other
/// way as `dist2` rounds them. (Algorithm 1's ranking: `proximity.rs`'s unit tests.)
#[test]
fn the_shortest_edge_is_the_exactly_shortest_where_rounding_swaps_two() {
    let points = pts(&[
        (0.9497985626218988, 0.6303992934263946),
        (0.788009549780357, 0.1066306096972589),
        (0.4476113389882713, 0.8502112838881093),
        (1.0005471995840087, 1.210975474746823),
    ]);
    let [p, a, b] = [points[0], points[1], points[2]];
    assert!(
        p.dist2(a) > p.dist2(b),
        "the rounded order is the wrong one"
    );
    // Point 0 has degree 3 in the proximity graph. Its shortest edge is 0-1, whose partner
    // beyond 120 degrees is 0-3 (168 degrees; 0-2 and 0-3 meet at 71): with 0-2 taken for the
    // shortest, no partner qualified and 0-2 was kept alone.
    let edges: Vec<[usize; 2]> = reconstruct(&points, &Params::paper())
        .unwrap()
        .edges()
        .collect();
    assert_eq!(edges, [[0, 1], [0, 2], [0, 3]]);
}
