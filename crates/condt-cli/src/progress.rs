//! The progress bar on standard error: one line that follows a long run through reading,
//! triangulating and reconstructing, and writing, and is cleared when the run ends.
//!
//! Owns: whether a bar is shown (standard error is a terminal and `--quiet` was not given) and
//! what it says. It may not change what a command computes or writes: the output files are the
//! same with and without it, and without a terminal nothing of it runs (no thread, no drawing,
//! no counting writer).
//!
//! Phases: [`Progress::reading`] (the bytes of the input read, against the file's size when it
//! is known, else a spinner with the count), [`Progress::computing`] (a spinner with the elapsed
//! time), [`Progress::triangulating`] (a bar of the points inserted, the library's counter),
//! [`Progress::stage`] (each stage and smoothing pass as the pipeline reaches it),
//! [`Progress::writing`]
//! (the bytes written). The library's readers take a path and report nothing, so the bytes read
//! are the process's own count of bytes read (`rchar` of `/proc/self/io`, Linux only; elsewhere
//! a spinner).

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::borrow::Cow;
use std::io::{self, IsTerminal, Write};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc;
use std::thread::JoinHandle;
use std::time::Duration;

/// How often the spinner turns and the elapsed time is redrawn.
const TICK: Duration = Duration::from_millis(100);

/// How many bytes the writer lets pass before it moves the bar.
const WRITE_STEP: u64 = 1 << 18;

/// Where a bar is drawn: standard error, or a test's screen.
type Target = Box<dyn Fn() -> ProgressDrawTarget>;

/// The progress of one command; does nothing when hidden.
pub(crate) struct Progress {
    /// `None`: nothing is shown.
    target: Option<Target>,
    /// The bar of the phase under way. Each phase has a bar of its own, made whole before it is
    /// first drawn: changing one bar's style, message and length one by one would draw the
    /// mixtures in between.
    bar: Option<ProgressBar>,
    /// The thread that follows the bytes read, while reading.
    watcher: Option<Watcher>,
}

impl Progress {
    /// A bar on standard error if it is a terminal and `quiet` is false; otherwise nothing.
    pub(crate) fn new(quiet: bool) -> Progress {
        if quiet || !io::stderr().is_terminal() {
            Progress::hidden()
        } else {
            Progress::to(Box::new(ProgressDrawTarget::stderr))
        }
    }

    /// Shows nothing.
    pub(crate) fn hidden() -> Progress {
        Progress {
            target: None,
            bar: None,
            watcher: None,
        }
    }

    /// Bars drawn on what `target` makes.
    fn to(target: Target) -> Progress {
        Progress {
            target: Some(target),
            bar: None,
            watcher: None,
        }
    }

    /// Whether anything is shown.
    pub(crate) fn is_shown(&self) -> bool {
        self.target.is_some()
    }

    /// Starts a phase: a bar of `template` that counts from 0 against `length`.
    fn phase(&mut self, template: &str, length: Option<u64>, message: Cow<'static, str>) {
        self.stop_watching();
        let Some(target) = &self.target else { return };
        if let Some(old) = self.bar.take() {
            old.finish_and_clear();
        }
        let style = ProgressStyle::with_template(template)
            .unwrap_or_else(|_| ProgressStyle::default_spinner())
            .progress_chars("=> ");
        let bar = ProgressBar::with_draw_target(length, target())
            .with_style(style)
            .with_message(message);
        bar.enable_steady_tick(TICK);
        self.bar = Some(bar);
    }

    /// Reading `shown`, of `size` bytes when known.
    pub(crate) fn reading(&mut self, shown: &str, size: Option<u64>) {
        if !self.is_shown() {
            return;
        }
        let counter = ReadCounter::start();
        let template = match (size, &counter) {
            (Some(_), Some(_)) => {
                "{spinner} reading {msg} [{bar:30}] {binary_bytes}/{binary_total_bytes} ({elapsed})"
            }
            (None, Some(_)) => "{spinner} reading {msg}: {binary_bytes} ({elapsed})",
            (_, None) => "{spinner} reading {msg} ({elapsed})",
        };
        self.phase(template, size, Cow::Owned(shown.to_string()));
        if let (Some(bar), Some(counter)) = (&self.bar, counter) {
            self.watcher = Watcher::start(bar.clone(), counter, size);
        }
    }

    /// `count` bytes of the input read so far (for a reader that reports them).
    #[allow(dead_code)] // Until the readers of `condt_io` report their progress.
    pub(crate) fn read_bytes(&self, count: u64) {
        if let Some(bar) = &self.bar {
            bar.set_position(count);
        }
    }

    /// The library at work: `what` (for instance "triangulating and reconstructing"), a spinner
    /// with the elapsed time until [`Progress::stage`] or [`Progress::inserted`] say more.
    pub(crate) fn computing(&mut self, what: &'static str) {
        self.phase("{spinner} {msg} ({elapsed})", None, Cow::Borrowed(what));
    }

    /// The library entered the stage `name` (a spinner: a stage has no count).
    pub(crate) fn stage(&mut self, name: &str) {
        self.phase(
            "{spinner} stage {msg} ({elapsed})",
            None,
            Cow::Owned(name.to_string()),
        );
    }

    /// Runs `work`, which triangulates `total` points and adds to `inserted` as it inserts
    /// them, with a bar that follows the count (read every [`TICK`] by a second thread while
    /// `work` runs; nothing runs beside it when nothing is shown).
    pub(crate) fn triangulating<R>(
        &mut self,
        total: usize,
        inserted: &AtomicUsize,
        work: impl FnOnce() -> R,
    ) -> R {
        if !self.is_shown() {
            return work();
        }
        self.inserted(0, total as u64);
        let Some(bar) = self.bar.clone() else {
            return work();
        };
        let (stop, stopped) = mpsc::channel::<()>();
        std::thread::scope(|scope| {
            // A thread that cannot be started (a limit on threads or memory) leaves the bar
            // where it is: the work runs all the same.
            let _ = std::thread::Builder::new().spawn_scoped(scope, move || {
                while let Err(mpsc::RecvTimeoutError::Timeout) = stopped.recv_timeout(TICK) {
                    bar.set_position(inserted.load(Ordering::Relaxed) as u64);
                }
            });
            let result = work();
            let _ = stop.send(());
            result
        })
    }

    /// `count` of `total` points inserted into the triangulation.
    pub(crate) fn inserted(&mut self, count: u64, total: u64) {
        if !self.is_shown() {
            return;
        }
        if self.bar.as_ref().and_then(ProgressBar::length) != Some(total) {
            self.phase(
                "{spinner} triangulating [{bar:30}] {human_pos}/{human_len} points ({elapsed})",
                Some(total),
                Cow::Borrowed(""),
            );
        }
        if let Some(bar) = &self.bar {
            bar.set_position(count);
        }
    }

    /// Writing `shown`. With `cleared` (the output is the terminal the bar is on) the bar is
    /// taken away instead, not to be drawn into the output.
    pub(crate) fn writing(&mut self, shown: &str, cleared: bool) {
        if cleared {
            self.finish();
            return;
        }
        self.phase(
            "{spinner} writing {msg}: {binary_bytes} ({elapsed})",
            None,
            Cow::Owned(shown.to_string()),
        );
    }

    /// Runs `write` on `out`, counting the bytes on the bar when it is shown; without a bar
    /// `out` is handed over as it is.
    pub(crate) fn count_written(
        &self,
        out: &mut dyn Write,
        write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
    ) -> io::Result<()> {
        match &self.bar {
            None => write(out),
            Some(bar) => {
                let mut counting = Counting {
                    out,
                    bar,
                    pending: 0,
                };
                let result = write(&mut counting);
                bar.inc(counting.pending);
                result
            }
        }
    }

    /// Runs `f` with the bar taken off the terminal (for lines on standard error).
    pub(crate) fn suspend<R>(&self, f: impl FnOnce() -> R) -> R {
        match &self.bar {
            Some(bar) => bar.suspend(f),
            None => f(),
        }
    }

    /// Takes the bar away for good; nothing is shown after.
    pub(crate) fn finish(&mut self) {
        self.stop_watching();
        self.target = None;
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }

    fn stop_watching(&mut self) {
        if let Some(watcher) = self.watcher.take() {
            watcher.stop();
        }
    }
}

impl Drop for Progress {
    /// On every way out, an error too: the message that follows starts on a clean line.
    fn drop(&mut self) {
        self.finish();
    }
}

/// A writer that moves the bar by the bytes passed on, every [`WRITE_STEP`] bytes.
struct Counting<'a> {
    out: &'a mut dyn Write,
    bar: &'a ProgressBar,
    pending: u64,
}

impl Write for Counting<'_> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let n = self.out.write(buf)?;
        self.pending += n as u64;
        if self.pending >= WRITE_STEP {
            self.bar.inc(self.pending);
            self.pending = 0;
        }
        Ok(n)
    }

    fn write_all(&mut self, buf: &[u8]) -> io::Result<()> {
        self.out.write_all(buf)?;
        self.pending += buf.len() as u64;
        if self.pending >= WRITE_STEP {
            self.bar.inc(self.pending);
            self.pending = 0;
        }
        Ok(())
    }

    fn flush(&mut self) -> io::Result<()> {
        self.out.flush()
    }
}

/// The bytes this process has read since [`ReadCounter::start`]: `rchar` of `/proc/self/io`,
/// which counts every `read` and `pread` of every thread, from files, pipes and terminals
/// alike, less what reading `/proc/self/io` itself took.
struct ReadCounter {
    start: u64,
    /// The bytes of `/proc/self/io` read to follow the count.
    own: u64,
}

impl ReadCounter {
    fn start() -> Option<ReadCounter> {
        // Elsewhere a `/proc/self/io` may be another process's: under Wine, Windows builds see
        // the Unix files, opened by the wineserver, whose count the bar then showed.
        if !cfg!(target_os = "linux") {
            return None;
        }
        let mut counter = ReadCounter { start: 0, own: 0 };
        counter.start = counter.rchar()?;
        Some(counter)
    }

    fn rchar(&mut self) -> Option<u64> {
        let text = std::fs::read_to_string("/proc/self/io").ok()?;
        self.own += text.len() as u64;
        text.lines()
            .find_map(|line| line.strip_prefix("rchar:"))
            .and_then(|n| n.trim().parse().ok())
    }

    fn read(&mut self) -> Option<u64> {
        // The count read includes every earlier reading of `/proc/self/io`, not this one.
        let own = self.own;
        let now = self.rchar()?;
        Some(now.saturating_sub(self.start).saturating_sub(own))
    }
}

/// The thread that moves the bar by the bytes read, every [`TICK`], until stopped.
struct Watcher {
    stop: mpsc::Sender<()>,
    thread: JoinHandle<()>,
}

impl Watcher {
    /// `None` when the thread cannot be started (a limit on threads or memory): the bar then
    /// stays still, and the run goes on.
    fn start(bar: ProgressBar, mut counter: ReadCounter, size: Option<u64>) -> Option<Watcher> {
        let (stop, stopped) = mpsc::channel();
        let thread = std::thread::Builder::new()
            .spawn(move || {
                while let Err(mpsc::RecvTimeoutError::Timeout) = stopped.recv_timeout(TICK) {
                    if let Some(read) = counter.read() {
                        bar.set_position(size.map_or(read, |size| read.min(size)));
                    }
                }
            })
            .ok()?;
        Some(Watcher { stop, thread })
    }

    fn stop(self) {
        let _ = self.stop.send(());
        let _ = self.thread.join();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use indicatif::TermLike;
    use std::sync::{Arc, Mutex};

    /// A terminal that keeps every line drawn.
    #[derive(Debug, Clone, Default)]
    struct Screen(Arc<Mutex<String>>);

    impl TermLike for Screen {
        fn width(&self) -> u16 {
            120
        }
        fn move_cursor_up(&self, _: usize) -> io::Result<()> {
            Ok(())
        }
        fn move_cursor_down(&self, _: usize) -> io::Result<()> {
            Ok(())
        }
        fn move_cursor_right(&self, _: usize) -> io::Result<()> {
            Ok(())
        }
        fn move_cursor_left(&self, _: usize) -> io::Result<()> {
            Ok(())
        }
        fn write_line(&self, s: &str) -> io::Result<()> {
            self.write_str(s)?;
            self.write_str("\n")
        }
        fn write_str(&self, s: &str) -> io::Result<()> {
            self.0.lock().unwrap().push_str(s);
            Ok(())
        }
        fn clear_line(&self) -> io::Result<()> {
            Ok(())
        }
        fn flush(&self) -> io::Result<()> {
            Ok(())
        }
    }

    fn on_screen() -> (Progress, Screen) {
        let screen = Screen::default();
        let drawn = screen.clone();
        let target = move || ProgressDrawTarget::term_like_with_hz(Box::new(drawn.clone()), 200);
        (Progress::to(Box::new(target)), screen)
    }

    /// Draws the bar as it is now (the drawing is otherwise limited to a rate).
    fn draw(progress: &Progress) {
        if let Some(bar) = &progress.bar {
            bar.force_draw();
        }
    }

    #[test]
    fn every_phase_is_drawn_and_the_output_passes_unchanged() {
        let (mut progress, screen) = on_screen();
        assert!(progress.is_shown());
        progress.reading("points.txt", Some(1000));
        draw(&progress);
        progress.read_bytes(500);
        draw(&progress);
        progress.computing("triangulating and reconstructing");
        draw(&progress);
        progress.inserted(10, 40);
        draw(&progress);
        progress.inserted(40, 40);
        draw(&progress);
        progress.stage("repair");
        draw(&progress);
        progress.writing("out.edges", false);
        draw(&progress);
        let mut out = Vec::new();
        let text = vec![b'x'; 3 * WRITE_STEP as usize + 7];
        progress
            .count_written(&mut out, |w| w.write_all(&text))
            .unwrap();
        assert_eq!(out, text, "written as it is");
        assert_eq!(
            progress.bar.as_ref().map(ProgressBar::position),
            Some(text.len() as u64)
        );
        progress.suspend(|| ());
        progress.finish();
        assert!(!progress.is_shown());
        let drawn = screen.0.lock().unwrap().clone();
        for seen in [
            "reading points.txt",
            "triangulating and reconstructing",
            "10/40 points",
            "stage repair",
            "writing out.edges",
        ] {
            assert!(drawn.contains(seen), "{seen:?} not in {drawn:?}");
        }
        // The size read is drawn where the bytes read can be counted (Linux): elsewhere the
        // reading is a spinner, and this test failed on Windows.
        assert_eq!(
            drawn.contains("1000 B"),
            ReadCounter::start().is_some(),
            "{drawn:?}"
        );
    }

    #[test]
    fn a_hidden_progress_does_nothing() {
        let mut progress = Progress::hidden();
        assert!(!progress.is_shown());
        progress.reading("points.txt", None);
        progress.computing("triangulating");
        progress.inserted(1, 2);
        progress.stage("proximity");
        progress.writing("-", false);
        let mut out = Vec::new();
        progress
            .count_written(&mut out, |w| w.write_all(b"0 1\n"))
            .unwrap();
        assert_eq!(out, b"0 1\n");
        assert_eq!(progress.suspend(|| 7), 7);
        progress.finish();
    }

    #[test]
    fn the_bytes_read_are_counted() {
        let Some(mut counter) = ReadCounter::start() else {
            return; // No /proc/self/io here: the bar is a spinner.
        };
        let file = tempfile::NamedTempFile::new().unwrap();
        std::fs::write(file.path(), vec![b'1'; 100_000]).unwrap();
        let before = counter.read().unwrap();
        let _ = std::fs::read(file.path()).unwrap();
        let after = counter.read().unwrap();
        // Other tests' threads read too: at least the file.
        assert!(after - before >= 100_000, "{before} {after}");
    }
}
