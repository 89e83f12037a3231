//! Unit tests of internals: derivatives against finite differences, PLS exactness.

mod derivatives;
mod fused;
mod pls_exact;
