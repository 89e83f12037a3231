//! Locally Weighted Projection Regression (LWPR): incremental, online nonlinear regression by
//! locally linear models (Vijayakumar, D'Souza & Schaal, *Neural Computation* 17, 2005), a
//! faithful reimplementation of the reference library of Klanke, Vijayakumar & Schaal
//! (JMLR 2008) as specified in `shared/LWPR.md`.
//!
//! Each receptive field (RF) has a centre `c` and a distance metric `D = MᵀM`; its activation is
//! `w = K((x − c)ᵀ D (x − c))` (Gaussian or BiSquare kernel) and it fits a local linear model by
//! incremental partial least squares (PLS) that adds projection directions as needed. `D` is
//! learned by gradient descent on a leave-one-out cost (optionally with IDBD meta learning of the
//! rates); new RFs appear where no RF is active enough (`w_gen`), overlapping ones are pruned
//! (`w_prune`). The prediction is the activation-weighted blend `ŷ = Σ w_k ŷ_k / Σ w_k`.
//!
//! Beyond the reference library, for the learned operational space controller:
//! - **shared receptive fields** ([`LwprConfig::shared_rfs`]): one partition for all outputs,
//!   each RF regressing every output (its own PLS per output; the metric descends the mean of the
//!   outputs' leave-one-out costs);
//! - **localisation on a subset of inputs** ([`LwprConfig::kernel_dims`],
//!   [`LwprConfig::regression_dims`]): the kernel lives on some inputs (paper eq. 33), the local
//!   regression on others (eq. 32);
//! - **read access to the partition** ([`Lwpr::activations`], [`Lwpr::rfs`], [`RfView`]) with
//!   stable [`RfId`]s and [`RfEvent`]s when RFs are added or pruned, and removal of an RF by
//!   its owner ([`Lwpr::remove_rf`], e.g. fields a learner never uses);
//! - **no silent zero**: prediction without any active RF is [`LwprError::NoActiveRf`];
//! - **numerical guards** in the update, counted in [`UpdateInfo`] and [`Lwpr::warnings`]:
//!   normalisations must lie in [`NORM_RANGE`] (a config error otherwise, also for `"std"`
//!   resolved by [`LwprConfig::resolve_std`]); samples beyond ±[`MAX_NORMALISED`] once
//!   normalised are refused ([`LwprError::Scale`]);
//!   the metric terms of a sample whose leverage is not below 1 are skipped (the reference
//!   step divides by `1 − h` there); an RF whose prediction, regression or metric stops being
//!   finite is removed and announced as [`RfEvent::Pruned`]. Under fast forgetting with
//!   inputs that rarely move (a robot at rest), the reference algorithm's RFs turn NaN and
//!   poison the predictions and saved models; with the guards they do not (an internal trace,
//!   such as the meta-learning memory, may be non-finite for a while first: predictions do not
//!   read it, and the RF goes once it reaches the metric).
//!
//! The reference library's accuracy benchmarks (the 2-D cross and its 21-D rotation) are in
//! `datasets`, behind the cargo feature of that name (off by default); `osrl bench lwpr --json`
//! runs them.
//!
//! Update and predict reuse buffers held by the model and do not allocate in steady state.
//! Models save and load bit-exactly ([`Lwpr::save`], [`Lwpr::load`]).
//!
//! # Example
//! ```
//! use lwpr::{Lwpr, LwprConfig};
//! use rand::{RngExt, SeedableRng};
//!
//! let cfg = LwprConfig { init_d: lwpr::MetricInit::Scalar(20.0), ..Default::default() };
//! let mut model = Lwpr::new(1, 1, &cfg)?;
//! let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0);
//! for _ in 0..5000 {
//!     let x: f64 = rng.random_range(-1.0..1.0);
//!     model.update(&[x], &[(3.0 * x).sin()])?;
//! }
//! let mut y = [0.0];
//! model.predict(&[0.5], &mut y)?;
//! assert!((y[0] - 1.5f64.sin()).abs() < 0.1);
//! // Far outside the data there is no support, and the model says so:
//! assert!(matches!(model.predict(&[40.0], &mut y), Err(lwpr::LwprError::NoActiveRf { .. })));
//! # Ok::<(), lwpr::LwprError>(())
//! ```

#![allow(clippy::needless_range_loop)] // index loops mirror the maths

mod config;
#[cfg(feature = "datasets")]
pub mod datasets;
mod distance;
mod error;
mod fast;
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
pub use io::{write_atomic, FORMAT_VERSION, MAGIC};
pub use model::{Lwpr, UpdateInfo, Warnings};
pub use norm::{Norm, NormKeyword, NORM_RANGE};
pub use params::Params;
pub use partition::{LocalModel, RfView};
pub use predict::Support;
pub use rf::{Activation, RfEvent, RfId};

#[cfg(test)]
mod tests;
