#![doc = include_str!("../README.md")]
#![warn(missing_docs)]
#![allow(clippy::needless_range_loop)] // index loops mirror the maths

mod config;
#[cfg(feature = "datasets")]
pub mod datasets;
mod distance;
mod error;
mod fast;
mod head;
mod io;
mod model;
mod norm;
mod numeric;
pub mod params;
mod partition;
mod pls;
mod predict;
mod rf;
mod scratch;
mod update;
mod validate;

pub use config::{Kernel, LwprConfig, MetricInit, PruneRule};
pub use error::{LwprError, MAX_NORMALISED};
pub use io::{FORMAT_VERSION, MAGIC, MAX_MODEL_BYTES};

/// Most inputs, and most outputs, of a model ([`Lwpr::new`]): a receptive field holds
/// `n_in × n_in` matrices.
pub const MAX_DIMS: usize = 1000;
pub use model::{Lwpr, UpdateInfo, Warnings};
pub use norm::{Norm, NormKeyword, NORM_RANGE};
pub use params::Params;
pub use partition::{LocalModel, RfView};
pub use predict::Support;
pub use rf::{Activation, RfEvent, RfId};

#[cfg(test)]
mod tests;
