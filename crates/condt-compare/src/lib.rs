//! Nothing here: this crate holds the comparisons of condt's kernel with spade and delaunator,
//! in `tests/` and `benches/`, so that no other crate depends on a competitor.
