//! The figures of the experiments, each a [`crate::plot::Figure`] built from the numbers and
//! time series of a run.

pub mod change;
pub mod commands;
pub mod learned;
pub mod path;
pub mod safety;
pub mod toy;

/// E9's figure of one robot (issue 27): tracking and command nMSE per held-out path.
pub use crate::family::figure as held_out;
