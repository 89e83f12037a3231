//! The home posture at rest: the posture in which the analytical controller (eq. 7, the true
//! model) holds the start of a path at rest. The IK posture reaches the start point, but the
//! nominal pull of `u0` towards `q_rest` is not balanced there in the null space of the task, so
//! a controller started from it first swings its redundant joints; at this posture it does not.

use crate::error::{ControlError, Result};
use crate::{Osc, OscConfig, Target, TaskController, Trajectory};
use nalgebra::Vector3;
use osrl_dynamics::{Model, Robot, SimConfig, SimRobot};

/// Starting at rest at `q_start` (e.g. [`crate::Reach::q_start`]), holds the start point of
/// `traj` with eq. 7 on a noise-free simulation of `model` until every joint is still
/// (`|q̇| < 1e-9` rad/s) and returns that posture. The posture keeps the start point to the
/// controller's accuracy (a nanometre on the built-in arms).
///
/// # Errors
/// The controller's or the simulator's, or [`ControlError::Unreachable`] if the arm has not come
/// to rest within 60 simulated seconds or ended at a joint limit.
pub fn settle_at_start(model: &Model, traj: &Trajectory, q_start: &[f64]) -> Result<Vec<f64>> {
    let n = model.nq();
    let mut sim = SimRobot::new(model.clone(), SimConfig::default())?;
    sim.reset(q_start, &vec![0.0; n])?;
    let mut osc = Osc::new(model.clone(), OscConfig::default())?;
    let start = traj.sample(0.0).x;
    let hold = Target {
        x: start,
        xd: Vector3::zeros(),
        xdd: Vector3::zeros(),
    };
    let mut u = vec![0.0; n];
    let steps = (60.0 / sim.control_period()).round() as usize;
    for _ in 0..steps {
        let meas = sim.measurement();
        if meas.qd.amax() < 1e-9 && meas.t > 0.0 {
            let q = meas.q.as_slice().to_vec();
            let (lo, hi) = (model.q_min(), model.q_max());
            if q.iter()
                .zip(lo.zip(hi))
                .any(|(v, (a, b))| *v <= a || *v >= b)
            {
                return Err(ControlError::Unreachable(
                    "the arm comes to rest on the path start only at a joint limit".into(),
                ));
            }
            return Ok(q);
        }
        osc.command(meas, &hold, &mut u)?;
        sim.step(&u)?;
    }
    Err(ControlError::Unreachable(
        "the arm does not come to rest on the path start within 60 s of eq. 7".into(),
    ))
}

#[cfg(test)]
mod tests {
    use super::settle_at_start;
    use crate::{check_reachable, IkOptions, TrajectoryConfig};
    use osrl_dynamics::{forward_kinematics, robots, Data};

    /// At the settled posture the arm is at the path start and eq. 7 keeps it still.
    #[test]
    fn the_settled_home_is_on_the_path_start_and_at_rest() {
        for model in [robots::planar3(), robots::sarcos7()] {
            let traj = TrajectoryConfig::default().build(&model).unwrap();
            let reach = check_reachable(&model, &traj, &IkOptions::default()).unwrap();
            let home = settle_at_start(&model, &traj, &reach.q_ik).unwrap();
            assert!(reach.at_rest);
            assert_eq!(home, reach.q_start);
            let mut data = Data::new(&model);
            forward_kinematics(&model, &mut data, &home).unwrap();
            let x = data.ee_pos;
            let x0 = traj.sample(0.0).x;
            for &a in model.task_axes() {
                assert!((x[a] - x0[a]).abs() < 1e-6, "{} axis {a}", model.name());
            }
            let moved = home
                .iter()
                .zip(&reach.q_ik)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(moved < 1.0, "{}: {moved}", model.name());
        }
    }
}
