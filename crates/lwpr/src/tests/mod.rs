//! Unit tests of internals: derivatives against finite differences, PLS exactness.

mod derivatives;
mod pls_exact;
