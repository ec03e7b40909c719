//! The text of an edge's story ([`EdgeStory`], from [`Reconstruction::provenance`]): one line
//! with the numbers that decided it, as the Python package's `EdgeStory.text` gives it. It may not
//! decide anything: every verdict and number comes from the story.
//!
//! [`Reconstruction::provenance`]: condt::Reconstruction::provenance

use condt::{EdgeStory, EndChoice, Reason};
use std::fmt::{self, Write};

/// `story` in one line: how each end chose the edge in Algorithm 1, each later change and why,
/// and whether it is kept.
///
/// ```
/// use condt::{reconstruct, Params, Point};
/// let points = [(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (2.0, 9.0)].map(Point::from);
/// let stories = reconstruct(&points, &Params::default())?.provenance();
/// let long = stories.iter().find(|s| s.edge == [0, 3]).unwrap();
/// assert_eq!(condt_io::story_text(long), "0-3: second shortest at 0, dropped by the uniformity \
///     test: |e2| = 9.220 |e1| >= 2.750 |e1|; rank 3 at 3; dropped");
/// # Ok::<(), condt::Error>(())
/// ```
pub fn story_text(story: &EdgeStory) -> String {
    let mut text = String::new();
    write_story(&mut text, story).expect("writing to a String cannot fail");
    text
}

fn write_story(f: &mut String, story: &EdgeStory) -> fmt::Result {
    let [a, b] = story.edge;
    write!(f, "{a}-{b}: ")?;
    // A baseline decided the edge (its change comes first): the ends are only Algorithm 1's
    // view, told after it.
    let baseline = story
        .changes
        .first()
        .filter(|c| c.reason == Reason::Baseline);
    if let Some(change) = baseline {
        let chosen = if change.added { "chosen" } else { "not chosen" };
        write!(
            f,
            "{chosen} by the {}; Algorithm 1 would have seen it as: ",
            change.stage.name()
        )?;
    }
    match story.ends {
        [EndChoice::Later { rank: ra }, EndChoice::Later { rank: rb }] => write!(
            f,
            "not among the two shortest at either end (ranks {ra} and {rb})"
        )?,
        [EndChoice::NotDelaunay, _] | [_, EndChoice::NotDelaunay] => {
            write!(f, "not a Delaunay edge")?
        }
        ends => {
            let mut first = true;
            for (end, choice) in [a, b].into_iter().zip(ends) {
                if !first {
                    write!(f, "; ")?;
                }
                first = false;
                match choice {
                    EndChoice::Shortest => write!(f, "shortest at {end}")?,
                    EndChoice::Second { ratio, bound, kept } => {
                        let (ratio, bound) = decimals_apart(ratio, bound);
                        write!(
                            f,
                            "second shortest at {end}, {} by the uniformity test: |e2| = {ratio} |e1| {} {bound} |e1|",
                            if kept { "kept" } else { "dropped" },
                            if kept { "<" } else { ">=" }
                        )?
                    }
                    EndChoice::Later { rank } => write!(f, "rank {rank} at {end}")?,
                    EndChoice::NotDelaunay => {}
                }
            }
        }
    }
    for change in &story.changes[usize::from(baseline.is_some())..] {
        let stage = change.stage.name();
        let verb = if change.added { "added" } else { "removed" };
        write!(f, "; {stage}: {verb} ")?;
        match change.reason {
            Reason::Repair {
                vertex,
                degree,
                selected,
            } => {
                write!(f, "at vertex {vertex} (degree {degree}), which selected ")?;
                let named: Vec<usize> = selected.iter().flatten().copied().collect();
                match named[..] {
                    [] => write!(f, "none")?,
                    [x] => write!(f, "its edge to {x} only")?,
                    [ref first @ .., last] => {
                        let first: Vec<String> = first.iter().map(usize::to_string).collect();
                        write!(f, "its edges to {} and {last}", first.join(", "))?;
                    }
                }
            }
            Reason::LongerThanThreshold {
                length,
                threshold,
                floored,
            } => {
                let (length, threshold) = told_apart(length, threshold);
                if floored {
                    write!(
                        f,
                        "length {length} above the spacing floor {threshold} (1.5 median edges)"
                    )?
                } else {
                    // T, the paper's name, is read by a learner in the viewer, who is told
                    // what it is (a viewer review: "√T unexplained").
                    write!(
                        f,
                        "length {length} above √T = {threshold} (the outlier threshold: T = \
                         Q3 + k IQR of the squared lengths)"
                    )?
                }
            }
            Reason::GivenBack => write!(f, "given back between two regular passages")?,
            Reason::LastEdge => write!(f, "given back as a curve's last edge, a curve behind it")?,
            Reason::LongAt { vertex, ratio } => write!(
                f,
                "{ratio:.2} times as long as the longest other edge at vertex {vertex}"
            )?,
            Reason::RepairedAgain => write!(
                f,
                "by the repair run again without the edges the outlier filter cut"
            )?,
            Reason::Component => write!(
                f,
                "with its component (outliers: fewer than 5 of its points clearly apart from \
                 other curves, or a closed polygon of 5 or 6)"
            )?,
            Reason::Spur => write!(f, "short spur")?,
            Reason::Clump => write!(f, "a clump: at most half its points pass smoothly")?,
            Reason::GapClosed => write!(f, "gap closed")?,
            Reason::Junction if change.added => {
                write!(f, "joined where three or four curves meet (a junction)")?
            }
            Reason::Junction => write!(f, "a chord past a junction's sample")?,
            Reason::Crossing { vertex } => write!(f, "restored the crossing at {vertex}")?,
            Reason::Tip if change.added => write!(f, "joined at a tip in place of a chord")?,
            Reason::Tip => write!(f, "a chord across a tip")?,
            Reason::Spike if change.added => {
                write!(f, "joined through a tip's samples that had no edges")?
            }
            Reason::Spike => write!(f, "a chord across a tip whose samples had no edges")?,
            Reason::Hook if change.added => {
                write!(f, "joined to put a hooked loose end back in line")?
            }
            Reason::Hook => write!(f, "passed a loose end that hooked back beside the curve")?,
            Reason::Tail { vertex, points } => write!(
                f,
                "part of an outlier tail of {points} point{} cut where it hung from {vertex}",
                if points == 1 { "" } else { "s" }
            )?,
            Reason::Detour { from, to, .. } if from == to => write!(
                f,
                "the edge that closed a loop hung on {from}, which the curve runs into less \
                 straightly than into the loop's other edge"
            )?,
            Reason::Detour { from, to, points } => {
                match points {
                    0 => write!(f, "the edge between {from} and {to} past a route")?,
                    1 => write!(
                        f,
                        "part of a detour through 1 point between {from} and {to}"
                    )?,
                    _ => write!(
                        f,
                        "part of a detour through {points} points between {from} and {to}"
                    )?,
                }
                write!(
                    f,
                    ", beside the route the curve runs into straighter at both"
                )?
            }
            Reason::NotConfirmed => write!(f, "a given-back component not clearly apart")?,
            // Only first (told above): a baseline is the whole method.
            Reason::Baseline => write!(f, "chosen by the baseline")?,
        }
    }
    write!(f, "; {}", if story.kept { "kept" } else { "dropped" })
}

/// `a` and `b` with [`SIGNIFICANT`] significant digits, or as many more as tell them apart (up
/// to 17, which tell every two doubles apart): a length just above its threshold must not read
/// as equal to it, and lengths of any scale keep their digits (fixed decimals read 1e-8 as 0).
fn told_apart(a: f64, b: f64) -> (String, String) {
    let mut digits = SIGNIFICANT;
    loop {
        let (x, y) = (significant(a, digits), significant(b, digits));
        if x != y || a == b || digits == 17 {
            return (x, y);
        }
        digits += 1;
    }
}

/// A ratio and its bound with three decimals, or as many more as tell them apart (a ratio of
/// 2.7496 read "2.750 |e1| < 2.750 |e1|").
fn decimals_apart(a: f64, b: f64) -> (String, String) {
    let mut decimals = 3;
    loop {
        let (x, y) = (format!("{a:.decimals$}"), format!("{b:.decimals$}"));
        if x != y || a == b || decimals == 17 {
            return (x, y);
        }
        decimals += 1;
    }
}

/// The fewest significant digits a length is told with.
const SIGNIFICANT: usize = 7;

/// `v` rounded to `digits` significant digits: plain from 1e-4 to 1e15, else in exponent form.
fn significant(v: f64, digits: usize) -> String {
    let magnitude = v.abs();
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    if (1e-4..1e15).contains(&magnitude) {
        // The position of the leading digit; the decimals are the significant digits after it.
        let leading = magnitude.log10().floor() as i32;
        let decimals = (digits as i32 - 1 - leading).max(0) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{v:.*e}", digits - 1)
    }
}

#[cfg(test)]
mod tests {
    use super::story_text;
    use condt::{reconstruct, Params, Point};

    /// A baseline's run: every story starts with the baseline's decision, chosen or not, and
    /// tells Algorithm 1's ends as its view only (found by a stress run: "shortest at 0; shortest
    /// at 1; Crust: added chosen by the baseline").
    #[test]
    fn a_baseline_decides_every_story_and_algorithm_1_is_only_its_view() {
        let points = [
            (0.0, 0.0),
            (1.0, 0.0),
            (1.0, 1.0),
            (0.0, 1.0),
            (0.5, 0.45),
            (3.0, 3.0),
        ]
        .map(Point::from);
        let params = Params::default().with_method(condt::Method::Crust);
        let result = reconstruct(&points, &params).unwrap();
        let stories = result.provenance();
        let (mut chosen, mut not_chosen) = (0, 0);
        for story in &stories {
            let text = story_text(story);
            let lead = if story.kept { "chosen" } else { "not chosen" };
            let [a, b] = story.edge;
            let expected =
                format!("{a}-{b}: {lead} by the Crust; Algorithm 1 would have seen it as: ");
            assert!(text.starts_with(&expected), "{text}");
            assert!(!text.contains("baseline"), "{text}");
            assert!(
                text.ends_with(if story.kept { "; kept" } else { "; dropped" }),
                "{text}"
            );
            if story.kept {
                chosen += 1;
            } else {
                not_chosen += 1;
            }
        }
        assert!(chosen > 0 && not_chosen > 0, "{chosen} {not_chosen}");
    }

    /// A ratio just under its bound reads under it (a student's review: "|e2| = 2.750 |e1| <
    /// 2.750 |e1|" for a second edge 2.7496 times the first, u = 2.75).
    #[test]
    fn a_ratio_near_its_bound_is_told_apart_from_it() {
        let points = [(0.0, 0.0), (1.0, 0.0), (-2.7496, 0.0)].map(Point::from);
        let stories = reconstruct(&points, &Params::paper()).unwrap().provenance();
        let story = stories.iter().find(|s| s.edge == [0, 2]).unwrap();
        let text = story_text(story);
        assert!(
            text.contains("kept by the uniformity test: |e2| = 2.7496 |e1| < 2.7500 |e1|"),
            "{text}"
        );
        assert_eq!(
            super::decimals_apart(1.5, 2.75),
            ("1.500".into(), "2.750".into())
        );
        assert_eq!(
            super::decimals_apart(2.75, 2.75),
            ("2.750".into(), "2.750".into())
        );
    }

    #[test]
    fn lengths_are_told_apart_at_any_scale() {
        use super::told_apart;
        // Equal to the sixth decimal (a story once read "4.046733 above √T = 4.046733").
        let (length, threshold) = told_apart(4.046_733_000_1, 4.046_733);
        assert_ne!(length, threshold);
        assert!(length.parse::<f64>().unwrap() > threshold.parse::<f64>().unwrap());
        assert_eq!(
            told_apart(861.980838, 384.055094),
            ("861.9808".into(), "384.0551".into())
        );
        // Lengths in degrees of a fine survey, and far beyond: their digits stay.
        assert_eq!(
            told_apart(1.234e-8, 1.1e-8),
            ("1.234000e-8".into(), "1.100000e-8".into())
        );
        assert_eq!(
            told_apart(2.5e300, 2.5e300),
            ("2.500000e300".into(), "2.500000e300".into())
        );
        let next = 1.0f64.next_up();
        let (a, b) = told_apart(next, 1.0);
        assert_eq!(
            (a.parse::<f64>().unwrap(), b.parse::<f64>().unwrap()),
            (next, 1.0)
        );
    }

    /// Two lines crossing at point 0 at 40°, as in `condt`'s provenance tests: the crossing's
    /// story names its vertex.
    #[test]
    fn a_restored_crossing_is_told_with_its_vertex() {
        let t = 40f64.to_radians();
        let arms = [
            (1.0, 0.0),
            (t.cos(), t.sin()),
            (-1.0, 0.0),
            (-t.cos(), -t.sin()),
        ];
        let mut points = vec![Point::new(0.0, 0.0)];
        for (k, (dx, dy)) in arms.iter().enumerate() {
            let r = |i: usize| i as f64 + 0.1 + 0.01 * k as f64;
            points.extend((1..=7).map(|i| Point::new(dx * r(i), dy * r(i))));
        }
        let stories = reconstruct(&points, &Params::default())
            .unwrap()
            .provenance();
        for edge in [[0, 15], [0, 22], [15, 22]] {
            let text = story_text(stories.iter().find(|s| s.edge == edge).unwrap());
            assert!(text.contains("crossings: ") && text.contains("restored the crossing at 0"));
        }
    }

    /// A narrow junction of three evenly spaced curves leaving point 0 (as in `condt`'s
    /// invariance test), without the smoothing passes (the stories tell the last run): the chord
    /// between the first two curves' first samples (1 and 9) gives way to point 0's edges to
    /// them, and the stories say which is which.
    #[test]
    fn a_chord_past_a_junction_and_its_replacement_are_told_apart() {
        let mut points = vec![Point::new(0.0, 0.0)];
        for degrees in [180.0_f64, 235.7, 129.0] {
            let (s, c) = degrees.to_radians().sin_cos();
            points.extend((1..=8).map(|k| Point::new(k as f64 * c, k as f64 * s)));
        }
        let stories = reconstruct(&points, &Params::default().with_smooth(false))
            .unwrap()
            .provenance();
        let text = |edge: [usize; 2]| story_text(stories.iter().find(|s| s.edge == edge).unwrap());
        let chord = text([1, 9]);
        assert!(
            chord.contains("junctions: removed a chord past a junction's sample"),
            "{chord}"
        );
        for edge in [[0, 1], [0, 9]] {
            let joined = text(edge);
            assert!(
                joined.contains("junctions: added joined where three or four curves meet"),
                "{joined}"
            );
        }
    }

    /// A T sampled as a pen draws it (the stem's end slow and dense, the bar fast): the local
    /// outlier removal drops the bar's right half, six points against the stem, because too few
    /// of them lie apart from it. Its story said "isolated component", the opposite of why (a
    /// sketching app developer's review).
    #[test]
    fn a_component_dropped_beside_a_curve_is_not_told_isolated() {
        let bar = [
            0.0, 2.0, 4.8, 8.72, 14.208, 21.8912, 29.8912, 37.8912, 45.8912, 53.8912, 61.8912,
            67.13472, 70.0,
        ];
        let stem = [
            100.0, 98.0, 95.2, 91.28, 85.792, 78.1088, 70.1088, 62.1088, 54.1088, 46.1088, 38.1088,
            30.1088, 22.1088, 14.1088, 6.46528, 1.879168, 0.0,
        ];
        let points: Vec<Point> = bar
            .iter()
            .map(|&x| Point::new(x, 100.0))
            .chain(stem.iter().map(|&y| Point::new(35.0, y)))
            .collect();
        let result = reconstruct(&points, &Params::default()).unwrap();
        assert_eq!(result.unused(), &[7, 8, 9, 10, 11, 12]);
        let stories = result.provenance();
        let story = stories.iter().find(|s| s.edge == [7, 8]).unwrap();
        let text = story_text(story);
        assert!(!text.contains("isolated"), "{text}");
        assert!(
            text.contains("fewer than 5 of its points clearly apart from other curves"),
            "{text}"
        );
    }

    /// An edge Algorithm 3 cut says what its threshold is: `√T` alone, the paper's name, left a
    /// learner in the viewer guessing (a viewer review).
    #[test]
    fn an_edge_the_outlier_filter_cut_names_its_threshold() {
        let mut points: Vec<Point> = (0..=20).map(|i| Point::new(f64::from(i), 0.0)).collect();
        // 2.5 from the line's end: Algorithm 1 keeps the edge (under u = 2.75), the filter cuts it.
        points.push(Point::new(21.5, 2.0));
        let result = reconstruct(&points, &Params::paper()).unwrap();
        assert_eq!(result.unused(), &[21]);
        let stories = result.provenance();
        let cut: Vec<String> = stories
            .iter()
            .filter(|s| s.edge[1] == 21)
            .map(story_text)
            .filter(|text| text.contains("IQR"))
            .collect();
        assert!(!cut.is_empty(), "no edge to 21 cut by the filter");
        for text in cut {
            assert!(
                text.contains("above √T = ")
                    && text.contains("(the outlier threshold: T = Q3 + k IQR of the squared"),
                "{text}"
            );
        }
    }
}
