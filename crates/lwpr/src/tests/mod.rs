//! Unit tests of internals: derivatives against finite differences, PLS exactness, the
//! metric steps against each other.

mod derivatives;
mod fused;
mod pls_exact;
mod wide;
