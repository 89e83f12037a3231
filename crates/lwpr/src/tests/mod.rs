//! Unit tests of internals: derivatives against finite differences, PLS exactness, the
//! metric steps against each other.

pub(crate) mod activation;
pub(crate) mod const_r;
mod derivatives;
mod fused;
pub(crate) mod group;
mod guard;
mod pls_exact;
pub(crate) mod rf_2d;
mod wide;
