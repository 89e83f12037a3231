#![doc = include_str!("../README.md")]
// `!(x > 0.0)` is this crate's idiom for "not positive, or NaN": the negated comparisons are
// deliberate.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod adapt;
pub mod analytical;
mod compare;
pub mod e8;
pub mod e9;
mod error;
pub mod family;
pub mod jobs;
pub mod learned;
pub mod reproduce;
pub mod results;
mod setup;
mod sizes;
pub mod stats;
pub mod toy;

pub use error::{ExperimentError, Result};

// The root README's Rust examples compile (and the quick ones run) as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
mod root_readme {}
pub use jobs::{Job, JobResult, Observer, Quiet, Trained};
pub use reproduce::{reproduce, FigureInputs, Reproduction};
pub use results::Results;
pub use setup::Setup;
pub use sizes::{ChangeSizes, E9Sizes, RobotSizes, Sizes};

/// The set-up of `robot` among `setups`.
pub(crate) fn setup_of<'a>(setups: &'a [(&str, Setup)], robot: &str) -> Result<&'a Setup> {
    setups
        .iter()
        .find(|(r, _)| *r == robot)
        .map(|(_, s)| s)
        .ok_or_else(|| ExperimentError::Invalid(format!("no set-up for robot {robot}")))
}
