//! `--timings`: one line on standard error per step of a command, with its wall-clock time.
//!
//! Owns the clock of the binary's own steps (reading, writing) and the format of the lines; the
//! library's steps (triangulation, stages, curve assembly, smoothing passes) are the times the
//! library recorded in the [`Reconstruction`], printed as they are.
//!
//! Every line reads `condt: time STEP SECONDS s`, optionally followed by a note in parentheses:
//! STEP is one word (letters and hyphens), SECONDS a decimal number. `scripts/scale.py` parses
//! them; the format is tested in `tests/cli.rs`.

use crate::cli::note;
use condt::Reconstruction;
use std::time::{Duration, Instant};

/// The clock of one command; prints nothing when `--timings` was not given.
pub(crate) struct Timings {
    on: bool,
    /// The start of the command, for the total.
    start: Instant,
    /// The end of the previous step the binary timed itself.
    lap: Instant,
}

impl Timings {
    pub(crate) fn new(on: bool) -> Self {
        let now = Instant::now();
        Timings {
            on,
            start: now,
            lap: now,
        }
    }

    /// Prints the time since the previous lap (or the start) as `step`.
    pub(crate) fn lap(&mut self, step: &str) {
        let elapsed = self.quiet_lap();
        self.line(step, elapsed, "");
    }

    /// The time since the previous lap, not printed (the library's call, which
    /// [`Timings::reconstruction`] splits).
    pub(crate) fn quiet_lap(&mut self) -> Duration {
        let now = Instant::now();
        let elapsed = now - self.lap;
        self.lap = now;
        elapsed
    }

    /// Prints the library's own record of a reconstruction that took `call` in all: the
    /// triangulation, the earlier passes when smoothing ran, each stage of the last pass, the
    /// curve assembly and what is left of `call` besides them (`other`).
    pub(crate) fn reconstruction(&self, result: &Reconstruction, call: Duration) {
        let mut counted = Duration::ZERO;
        let mut show = |step: &str, time: Duration, comment: &str| {
            counted += time;
            self.line(step, time, comment);
        };
        // The stages are the last pass's; the first reconstruction and every pass but the last
        // (each a triangulation and all the stages) are in `earlier-passes`.
        let comment = match result.smoothing().map(|smoothing| smoothing.passes) {
            Some(1) => "(the first reconstruction, before the one smoothing pass)".to_string(),
            Some(2) => "(the first reconstruction and the first of 2 smoothing passes)".to_string(),
            Some(passes) => format!(
                "(the first reconstruction and the first {} of {passes} smoothing passes)",
                passes - 1
            ),
            None => String::new(),
        };
        for (step, time) in result.timings() {
            let comment = if step == "earlier-passes" {
                &comment[..]
            } else {
                ""
            };
            show(step, time, comment);
        }
        // What the library did outside the steps it timed: the parameter check, starting its
        // worker thread, copying the input points when smoothing ran.
        self.line("other", call.saturating_sub(counted), "");
    }

    /// The time from the command's start to the end of its last step, printed as `total`: the
    /// steps' lines add up to it (up to their rounding), where the time since the start would
    /// also hold the printing of the last line.
    pub(crate) fn total(&self) {
        self.line("total", self.lap - self.start, "");
    }

    fn line(&self, step: &str, time: Duration, comment: &str) {
        if self.on {
            let space = if comment.is_empty() { "" } else { " " };
            note(format_args!(
                "time {step} {:.6} s{space}{comment}",
                time.as_secs_f64()
            ));
        }
    }
}
