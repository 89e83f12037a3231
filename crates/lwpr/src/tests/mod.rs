//! Unit tests of internals: derivatives against finite differences, PLS exactness, the
//! metric steps against each other.

mod activation;
mod const_r;
mod derivatives;
mod dot;
mod fused;
mod group;
mod guard;
mod head_bounds;
mod heads;
mod overflow;
mod paths;
mod pls_exact;
mod rf_2d;
mod shapes;
mod wide;
