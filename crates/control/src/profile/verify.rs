//! The last check of a computed default: eq. 7 (`N = I`, the default task gains, the true
//! model) on the simulated robot along the default path for two periods must track within
//! [`TRACKING_BOUND_MM`] RMS without saturating a torque. (Steps at a joint limit are not
//! refused: where the null space drifts to a hard stop while the task is tracked, the
//! published-arms table reports them.)

use crate::closed_loop::{run_closed_loop, Metrics};
use crate::config::OscConfig;
use crate::error::{ControlError, Result};
use crate::osc::Osc;
use crate::trajectory::Trajectory;
use osrl_dynamics::{Model, SimConfig, SimRobot};

/// Largest RMS tracking error (mm) of eq. 7 on a computed default path (issue 28's bound).
pub const TRACKING_BOUND_MM: f64 = 0.05;

/// Runs eq. 7 from rest at `start` for two periods of `traj` (the default simulator, 500 Hz)
/// and returns its metrics, or an error saying what missed the bound.
pub(super) fn eq7_tracks(model: &Model, traj: &Trajectory, start: &[f64]) -> Result<Metrics> {
    let mut sim = SimRobot::new(model.clone(), SimConfig::default())?;
    sim.reset(start, &vec![0.0; model.nq()])?;
    let mut osc = Osc::new(model.clone(), OscConfig::default())?;
    let seconds = 2.0 * traj.period();
    let m = run_closed_loop(&mut sim, &mut osc, traj, model.task_axes(), seconds)?.metrics;
    if m.tracking_rms_mm > TRACKING_BOUND_MM || m.torque_saturation_steps > 0 {
        return Err(ControlError::Unreachable(format!(
            "eq. 7 tracks it at {:.4} mm RMS (bound {TRACKING_BOUND_MM} mm) with {} saturated \
             torque steps and {} steps at a joint limit",
            m.tracking_rms_mm, m.torque_saturation_steps, m.limit_steps
        )));
    }
    Ok(m)
}
