//! Running two pieces of work at once, on rayon's threads with the `parallel` feature, or one
//! after the other without it (or when the caller asks for one thread).
//!
//! Owns: only the choice of how to run; it knows nothing of what the work is. The triangulation
//! (its two halves) and the pipeline's last step (curves and tally) share it.

/// `(a(), b())`, at once on rayon's threads when `parallel`.
#[cfg(feature = "parallel")]
pub(crate) fn both<A: Send, B: Send>(
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

/// `(a(), b())`: without the `parallel` feature, one after the other.
#[cfg(not(feature = "parallel"))]
pub(crate) fn both<A, B>(_parallel: bool, a: impl FnOnce() -> A, b: impl FnOnce() -> B) -> (A, B) {
    (a(), b())
}
