//! Points read in longitude and latitude, and what their reader is told of it.
//!
//! Owns: the test of whether a set can be longitudes and latitudes, and the notes on what
//! reading them as plane coordinates does (the stretch of east-west gaps, the antimeridian).
//! It may not change a point: the command line and the Python package say the notes, each in
//! its own way (a note on standard error, a `UserWarning`), from this one text.

use condt::Point;

/// Where an input in degrees (a header naming `lon` and `lat`, GeoJSON without a projected crs)
/// lies: ConDT measures lengths in the plane, so in degrees an east-west gap counts `1 / cos`
/// of its latitude times a north-south one as long, and a line across the antimeridian has no
/// edge across. Neither was said where a GIS user would look: a fjord 200 m wide sampled every
/// 100 m came back whole in metres and cut off by a chord (62 edges) in degrees at 60 to 70
/// degrees north; two GPS drives of one road, 97 and 119 edges of 487 changed at 60 (a GIS user's
/// review).
///
/// ```
/// use condt::Point;
/// // A survey at 60 degrees north: an east-west gap counts twice as long as it is.
/// let survey = [Point::new(10.0, 60.0), Point::new(10.001, 60.0005)];
/// let notes = condt_io::Degrees::of(&survey).unwrap().notes("README.md");
/// assert!(notes[0].contains("counts 2.0 times as long"));
/// // Metres under such names are no longitudes and latitudes: nothing to say.
/// assert!(condt_io::Degrees::of(&[Point::new(560_000.0, 6_650_000.0)]).is_none());
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Degrees {
    /// The largest absolute latitude.
    farthest: f64,
    /// Whether the points' longitudes lie across 180 and -180 ([`straddles_antimeridian`]).
    both_sides: bool,
}

impl Degrees {
    /// `None` when any point is no longitude and latitude (projected coordinates under such
    /// names, or the columns swapped). Longitudes from 180 to 360 are: climate data's 0 to 360,
    /// and points shifted across the antimeridian as the note advises, which then lost the note
    /// on the stretch they still have.
    pub fn of(points: &[Point]) -> Option<Degrees> {
        let degrees = |p: &Point| (-180.0..=360.0).contains(&p.x) && p.y.abs() <= 90.0;
        if points.is_empty() || !points.iter().all(degrees) {
            return None;
        }
        let farthest = points.iter().fold(0.0f64, |far, p| far.max(p.y.abs()));
        Some(Degrees {
            farthest,
            both_sides: straddles_antimeridian(points),
        })
    }

    /// The notes, none where there is nothing to say: the stretch where it exceeds 5 % (beyond
    /// 18.2 degrees of latitude; noisy tracks changed from 15 on, in that review), whose advice
    /// to project ends with `see` (where the reader's documentation says how), and the
    /// antimeridian.
    pub fn notes(&self, see: &str) -> Vec<String> {
        let mut notes = Vec::new();
        let shrink = self.farthest.to_radians().cos();
        if shrink < 0.95 {
            // Within 0.6 degrees of a pole the ratio is no measure: at the pole itself, a fix
            // at latitude 90, it was "0.00" and "16331239353195370.0 times".
            let (shrink, stretch) = if shrink < 0.01 {
                ("under 0.01".to_string(), "over 100".to_string())
            } else {
                (format!("{shrink:.2}"), format!("{:.1}", 1.0 / shrink))
            };
            notes.push(format!(
                "longitudes and latitudes are read as plane coordinates: at latitude \
                 {farthest:.0}, the points' farthest from the equator, a degree of longitude is \
                 {shrink} of one of latitude on the ground, so an east-west gap counts \
                 {stretch} times as long as a north-south one of the same metres, and curves \
                 may break or join otherwise than on the ground; project the points \
                 ({projection}) first where that matters ({see})",
                farthest = self.farthest,
                // UTM's zones end at 84 degrees north and 80 south.
                projection = if self.farthest > 80.0 {
                    "a polar stereographic projection"
                } else {
                    "a UTM zone"
                },
            ));
        }
        if self.both_sides {
            notes.push(
                "points lie on both sides of the antimeridian (longitudes near 180 and -180): \
                 no edge joins across it, so a curve that crosses it comes out cut in two there; \
                 add 360 to the negative longitudes first to reconstruct it whole, or project"
                    .to_string(),
            );
        }
        notes
    }
}

/// Whether the longitudes of `points` (all within -180 to 360) lie across 180 and -180: they do
/// where, in tenths of a degree around the circle, the widest run of longitudes no point has is
/// not the one at the antimeridian (a set of both sides, or of the whole globe). A set all of
/// whose longitudes are in -180 to 180 only: past 180 they were shifted across already. It was
/// "within a degree of both": a coast sampled 3 degrees apart across it was cut in two without
/// a word (a diff review).
fn straddles_antimeridian(points: &[Point]) -> bool {
    const BINS: usize = 3600;
    if points.iter().any(|p| p.x > 180.0) {
        return false;
    }
    let mut occupied = vec![false; BINS];
    for p in points {
        let bin = ((p.x + 180.0) * 10.0) as usize; // 180 itself in the last bin, as -180 first
        occupied[bin.min(BINS - 1)] = true;
    }
    // Each empty run's length, going round from the last occupied bin; the run that wraps
    // from the last bin to the first is the antimeridian's.
    let (Some(first), Some(last)) = (
        occupied.iter().position(|&o| o),
        occupied.iter().rposition(|&o| o),
    ) else {
        return false;
    };
    let at_antimeridian = BINS - 1 - last + first;
    let (mut widest_elsewhere, mut run) = (0, 0);
    for &o in &occupied[first..=last] {
        run = if o { 0 } else { run + 1 };
        widest_elsewhere = widest_elsewhere.max(run);
    }
    // Equal: no gap at all (a whole globe) or two alike; the note then errs on the side of saying.
    widest_elsewhere >= at_antimeridian
}
