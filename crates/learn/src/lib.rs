#![doc = include_str!("../README.md")]
//!
//! ## The measurement boundary, checked by the compiler
//! The learner's types hold no robot model. The training driver is generic over
//! [`osrl_dynamics::Robot`], which offers measurements and commands but no model, so code that
//! only has a `Robot` cannot read the dynamics:
//!
//! ```compile_fail
//! fn peek<R: osrl_dynamics::Robot>(robot: &R) -> f64 {
//!     robot.model().total_mass() // error: `Robot` has no `model`
//! }
//! ```
//!
//! Only the evaluation ([`eval`]) reads a model — the simulator's, to compute the analytical
//! optimum it compares against.
// `!(x > 0.0)` is this crate's idiom for "not positive, or NaN" (inputs are validated so that
// NaN fails): the negated comparisons are deliberate.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod config;
mod controller;
mod dob;
mod error;
pub mod eval;
mod forward;
mod gravity;
pub mod io;
mod learner;
mod local;
mod saved;
pub mod train;
mod variant;

pub use config::CONTROL_PERIOD_RANGE;
pub use config::{
    AdaptationConfig, AdaptationSource, ControllerConfig, CostKind, CostMetric, DynamicsConfig,
    DynamicsRegression, ExplorationConfig, GravityConfig, GuardConfig, LearnerConfig, NoiseProcess,
    NominalConfig, PartitionConfig,
};
pub use controller::{LearnedController, SourceCounts};
pub use dob::Dob;
pub use error::{LearnError, Result};
pub use forward::ForwardModel;
pub use gravity::{GravityModel, StaticGate};
pub use learner::{
    AdaptationSignal, CommandSource, Learner, LearnerStats, EXTRAPOLATION_CUTOFF, PERIOD_TOLERANCE,
};
pub use local::LocalSummary;
pub use saved::{load_robot, ModelInfo, SavedModel, MODEL_MAGIC, MODEL_VERSION};
pub use variant::Variant;
