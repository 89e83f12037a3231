//! Task-space trajectories, reference dynamics (paper eq. 2), the nominal behaviour `u0` (eq. 6
//! plus gravity compensation) and the analytical operational space controllers (eq. 4 and the
//! corrected eq. 7 of the crate README's "Choices") with a damped pseudo-inverse, model errors, and the
//! closed-loop driver that runs a controller on a robot and measures the tracking.
//!
//! ```
//! use osrl_control::{check_reachable, run_closed_loop, IkOptions, Osc, OscConfig, TrajectoryConfig};
//! use osrl_dynamics::{robots, SimConfig, SimRobot};
//! let model = robots::planar3();
//! let traj = TrajectoryConfig::default().build(&model).unwrap();
//! let reach = check_reachable(&model, &traj, &IkOptions::default()).unwrap();
//! let mut ctrl = Osc::new(model.clone(), OscConfig::default()).unwrap();
//! let mut sim = SimRobot::new(model.clone(), SimConfig::default()).unwrap();
//! sim.reset(&reach.q_start, &[0.0; 3]).unwrap();
//! let run = run_closed_loop(&mut sim, &mut ctrl, &traj, model.task_axes(), 8.0).unwrap();
//! assert!(run.metrics.tracking_rms_mm < 0.5);
//! ```

// The README's example compiles and runs (`cargo test --doc`).
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;

mod change;
mod closed_loop;
mod config;
mod controller;
pub mod damping;
mod error;
pub mod family;
mod ik;
mod linalg;
mod model_error;
mod nominal;
mod osc;
pub mod profile;
mod reference;
mod settle;
mod spec;
mod trajectory;
mod trajectory_config;
mod warp;

pub use change::RobotChange;
pub use closed_loop::{
    drive, run_closed_loop, run_steps, Ended, Metrics, Run, Series, StepObserver, StepView,
    MAX_RUN_STEPS,
};
pub use config::{Law, MetricKind, OscConfig};
pub use controller::TaskController;
pub use damping::damping;
pub use error::{ControlError, Result};
pub use ik::{check_reachable, solve_ik, IkOptions, Reach};
pub use model_error::ModelError;
pub use nominal::nominal_command;
pub use osc::{CommandInfo, Osc};
pub use reference::{reference_acceleration, task_error, TaskGains, MAX_TASK_KD, MAX_TASK_KP};
pub use settle::settle_at_start;
pub use spec::{MASS_SCALE_RANGE, MAX_COM_SHIFT, MAX_FRICTION_SCALE, MAX_PAYLOAD};
pub use trajectory::{
    Shape, Target, Trajectory, MAX_PATH_METRES, MAX_PATH_SECONDS, MIN_PATH_SECONDS,
};
pub use trajectory_config::{TrajectoryConfig, TrajectoryKind};
pub use warp::TimeWarp;
