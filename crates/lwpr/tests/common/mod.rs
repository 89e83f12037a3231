//! The benchmark data sets for tests and examples: re-exported from [`lwpr::datasets`].
#![allow(unused_imports)]

pub use lwpr::datasets::*;
