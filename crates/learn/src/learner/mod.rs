//! The learner (paper section IV, `docs/learner.md`): the gravity model, the forward model whose
//! receptive fields partition the state space, and a local RWR controller per field, learned
//! from measured transitions only — it never sees a robot model.
//!
//! | file | concept |
//! |---|---|
//! | `features.rs` | the feature layouts `φ` (eq. 31) and `φ_d` (local dynamics) |
//! | `nominal.rs` | `u0` and `ĝ` |
//! | `command.rs` | the eq. 34 blend, extrapolation, fallback, guards |
//! | `exploration.rs` | exploration noise |
//! | `hindsight.rs` | the learning step: partition, relabelling, local updates |
//! | `cost.rs` | the cost and the hindsight shrinkage |
//! | `null_space.rs` | the null space of `Â` |
//! | `models.rs` | the models made after the warm-up |
//! | `inertia.rs` | the joints' inverse inertia measured in the warm-up; the velocity gain bounds |
//! | `adapt.rs` | re-adaptation when the local dynamics stop predicting |
//! | `load.rs` | the load correction of `u0` while re-adapting |
//! | `null_gravity.rs` | the correction of `u0` in the null space of `Â`, from the holds |

mod adapt;
#[cfg(test)]
mod adapt_tests;
mod command;
#[cfg(test)]
mod construction_tests;
mod cost;
#[cfg(test)]
mod dynamics_tests;
mod exploration;
#[cfg(test)]
mod exploration_rate_tests;
mod features;
#[cfg(test)]
pub(crate) mod fixture;
mod gravity_cache;
#[cfg(test)]
mod gravity_cache_tests;
mod guards;
mod hindsight;
mod hold;
mod inertia;
#[cfg(test)]
mod inertia_tests;
mod load;
mod metric;
#[cfg(test)]
mod metric_tests;
mod models;
mod nearest;
#[cfg(test)]
mod nearest_tests;
mod nominal;
mod null_gravity;
#[cfg(test)]
mod null_gravity_tests;
mod null_scale;
mod null_space;
mod projection;
mod readapt;
mod state;
mod stats;

pub use adapt::AdaptationSignal;
pub use command::{CommandSource, EXTRAPOLATION_CUTOFF};
pub(crate) use features::Features;
pub use guards::RateLimiter;
pub use learn::PERIOD_TOLERANCE;
pub use load::LoadCorrection;
pub(crate) use models::Models;
pub use state::Learner;
pub(crate) use state::State;
pub use stats::LearnerStats;

mod learn;
