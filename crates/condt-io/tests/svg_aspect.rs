//! SVG panels take the shape of the data (a GIS review: every panel was square, so a long thin
//! river filled a tenth of the picture), their sides' ratio kept between 1:4 and 4:1.

use condt::{reconstruct, Params, Point};
use condt_io::{write_svg, write_svg_stages};

/// The number in `attribute="…"` of the first element that has it.
fn attribute(svg: &str, attribute: &str) -> f64 {
    let start = svg.find(&format!(" {attribute}=\"")).unwrap() + attribute.len() + 3;
    let end = start + svg[start..].find('"').unwrap();
    svg[start..end].parse().unwrap()
}

/// The extent of the circles' centres: `(x min, x max, y min, y max)`.
fn circle_extent(svg: &str) -> (f64, f64, f64, f64) {
    let mut extent = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for circle in svg.split("<circle ").skip(1) {
        let (x, y) = (
            attribute(&format!(" {circle}"), "cx"),
            attribute(&format!(" {circle}"), "cy"),
        );
        // The legend's swatches are below the panels.
        if circle.contains("r=\"6\"") {
            continue;
        }
        extent = (
            extent.0.min(x),
            extent.1.max(x),
            extent.2.min(y),
            extent.3.max(y),
        );
    }
    extent
}

/// A river: a gentle wave `length` long and about `length / 20` high, sampled densely.
fn river(length: f64, vertical: bool) -> Vec<Point> {
    (0..200)
        .map(|k| {
            let t = k as f64 / 199.0 * length;
            let across = length / 40.0 * (t / length * 6.0).sin();
            if vertical {
                Point::new(across, t)
            } else {
                Point::new(t, across)
            }
        })
        .collect()
}

fn drawings(points: &[Point]) -> (String, String) {
    let r = reconstruct(points, &Params::default()).unwrap();
    let (mut alone, mut stages) = (Vec::new(), Vec::new());
    write_svg(&mut alone, &r, points).unwrap();
    write_svg_stages(&mut stages, &r).unwrap();
    (
        String::from_utf8(alone).unwrap(),
        String::from_utf8(stages).unwrap(),
    )
}

#[test]
fn a_long_thin_river_fills_a_wide_panel() {
    let (alone, stages) = drawings(&river(1000.0, false));
    // A 4:1 panel of the area of a 600-sided square, its title band and the legend's.
    assert_eq!(attribute(&alone, "width"), 1200.0);
    assert_eq!(attribute(&alone, "height"), 300.0 + 44.0 + 48.0);
    let (x0, x1, y0, y1) = circle_extent(&alone);
    assert!(
        x1 - x0 > 0.9 * 1200.0,
        "the river spans the panel: {x0} to {x1}"
    );
    assert!(y1 - y0 > 0.9 * (300.0 - 32.0) * 0.2, "{y0} to {y1}");
    // The stage panels go one to a row, each as wide; the legend wraps to their width.
    let panels = stages.matches("class=\"title\"").count();
    assert_eq!(attribute(&stages, "width"), 1200.0);
    let legend = attribute(&stages, "height") - panels as f64 * 344.0;
    assert!(legend == 48.0 || legend == 96.0, "{legend}");
}

#[test]
fn a_tall_river_gets_a_tall_panel_and_a_square_set_a_square_one() {
    let (alone, stages) = drawings(&river(1000.0, true));
    // The panel is 300 wide, and the legend takes two lines.
    assert_eq!(attribute(&alone, "width"), 300.0);
    assert_eq!(attribute(&alone, "height"), 1200.0 + 44.0 + 96.0);
    let (_, _, y0, y1) = circle_extent(&alone);
    assert!(y1 - y0 > 0.9 * 1200.0, "{y0} to {y1}");
    // Three narrow panels to a row, their titles made to fit them.
    assert!(
        stages.contains("M300 0V") && stages.contains("M600 0V"),
        "separators"
    );
    assert!(!stages.contains("M900 0V"));
    for size in stages
        .split("font-size=\"")
        .skip(1)
        .map(|s| &s[..s.find('"').unwrap()])
    {
        let size: f64 = size.parse().unwrap();
        assert!((14.0..=26.0).contains(&size), "{size}");
    }
    // A circle: the square panels as before, 600 by 600, three to a row.
    let circle: Vec<Point> = (0..60)
        .map(|k| {
            let t = k as f64 * std::f64::consts::TAU / 60.0;
            Point::new(t.cos(), t.sin())
        })
        .collect();
    let (alone, stages) = drawings(&circle);
    assert_eq!(
        (attribute(&alone, "width"), attribute(&alone, "height")),
        (600.0, 692.0)
    );
    assert_eq!(attribute(&stages, "width"), 1800.0);
    // A ratio within the limits is followed: 2:1 gives a panel of about 849 by 424, two to a
    // row.
    let wide: Vec<Point> = circle.iter().map(|p| Point::new(2.0 * p.x, p.y)).collect();
    let (alone, stages) = drawings(&wide);
    assert_eq!(
        (attribute(&alone, "width"), attribute(&alone, "height")),
        (849.0, 424.0 + 92.0)
    );
    assert_eq!(attribute(&stages, "width"), 1698.0);
}

/// A viewer review: in the narrow panels of a tall set, "5. after repairing again without the
/// cut edges" ran into the next panel, and the titles' sizes jumped from panel to panel. Now
/// every title has one size, a title too long for its panel goes on two lines, and a stage that
/// changed nothing says so.
#[test]
fn stage_titles_share_a_size_fit_their_panels_and_tell_a_stage_that_changed_nothing() {
    let (_, stages) = drawings(&river(1000.0, true));
    let titles: Vec<&str> = stages
        .split("<text class=\"title\"")
        .skip(1)
        .map(|t| &t[..t.find("</text>").unwrap()])
        .collect();
    assert_eq!(titles.len(), 16);
    let size = |t: &str| attribute(t, "font-size");
    assert!(
        titles.iter().all(|t| size(t) == size(titles[0])),
        "{titles:?}"
    );
    let panel = 300.0;
    for title in &titles {
        let text = &title[title.find('>').unwrap() + 1..];
        // Each line as a bold character about 0.6 of the size wide estimates it.
        for line in text
            .split("<tspan")
            .map(|l| &l[l.find('>').map_or(0, |k| k + 1)..])
        {
            let line = line.trim_end_matches("</tspan>");
            let width = 0.6 * size(title) * line.chars().count() as f64;
            assert!(width <= panel - 24.0, "{line:?} is {width} wide");
        }
    }
    assert!(
        titles.iter().any(|t| t.contains("<tspan")),
        "a long title on two lines"
    );
    // On a clean river the repair changes nothing; the proximity graph is never "no change".
    let repair = titles
        .iter()
        .find(|t| t.contains("3. after non-manifold"))
        .unwrap();
    assert!(repair.contains("(no change)"), "{repair}");
    assert!(!titles[1].contains("(no change)"), "{}", titles[1]);
}

/// Dense points are drawn smaller (a viewer review: at 1,559 points the dots of 2.5 units
/// covered the edges between them); sparse ones keep their size.
#[test]
fn dots_shrink_where_the_points_stand_close() {
    let radius = |svg: &str| -> f64 {
        let at = svg.find("<circle ").unwrap();
        attribute(&svg[at..], "r")
    };
    let sparse: Vec<Point> = (0..12)
        .map(|k| {
            let t = k as f64 * std::f64::consts::TAU / 12.0;
            Point::new(t.cos(), t.sin())
        })
        .collect();
    let dense: Vec<Point> = (0..2000)
        .map(|k| {
            let t = k as f64 * std::f64::consts::TAU / 2000.0;
            Point::new(t.cos(), t.sin())
        })
        .collect();
    let ((sparse_alone, _), (dense_alone, _)) = (drawings(&sparse), drawings(&dense));
    assert_eq!(radius(&sparse_alone), 2.5);
    let small = radius(&dense_alone);
    assert!((0.6..1.0).contains(&small), "{small}");
}

/// A viewer review: the stage panels of a dense set looked alike, with nothing to say what each
/// stage did. Each panel from the second stage on marks the edges its stage removed (red) and
/// added (green) with translucent halos under its own: as many as the stage's graph differs
/// from the one before.
#[test]
fn stage_panels_draw_what_their_stage_removed_and_added() {
    let mut points: Vec<Point> = (0..60)
        .map(|k| {
            let t = k as f64 * std::f64::consts::TAU / 60.0;
            Point::new(t.cos(), t.sin())
        })
        .collect();
    // Outliers inside the circle, which the stages cut away.
    points.extend([(0.1, 0.2), (0.15, 0.25), (-0.3, 0.1), (0.9, 0.05)].map(Point::from));
    let r = reconstruct(&points, &Params::default()).unwrap();
    let graphs: Vec<Vec<[usize; 2]>> = r.stages().map(|s| s.graph.edges()).collect();
    let (mut removed, mut added) = (0, 0);
    for pair in graphs.windows(2) {
        removed += pair[0].iter().filter(|e| !pair[1].contains(e)).count();
        added += pair[1].iter().filter(|e| !pair[0].contains(e)).count();
    }
    assert!(removed > 0, "the stages cut something");
    let mut out = Vec::new();
    write_svg_stages(&mut out, &r).unwrap();
    let svg = String::from_utf8(out).unwrap();
    let segments = |colour: &str| -> usize {
        svg.split(&format!("fill=\"none\" stroke=\"{colour}\" stroke-width="))
            .skip(1)
            .map(|path| {
                let d = &path[path.find(" d=\"").unwrap() + 4..];
                d[..d.find('"').unwrap()].matches('M').count()
            })
            .sum()
    };
    assert_eq!(segments("#d62728"), removed);
    assert_eq!(segments("#2ca02c"), added);
    assert!(svg.contains("removed by the stage") && svg.contains("added by the stage"));
}
