//! The default path's placement (centre at the tip at home, a vertical plane facing the arm,
//! a size proportional to the reach) and the feasibility check of a path: reachable by IK over
//! a whole cycle inside the joint limits ([`check_reachable`]) and within the torque limits
//! (the inverse dynamics of the IK motion need at most [`TORQUE_SHARE`] of every limit).

use crate::error::{ControlError, Result};
use crate::ik::{check_reachable, solve_ik, IkOptions, Reach};
use crate::trajectory::Trajectory;
use nalgebra::{DVector, Vector3};
use osrl_dynamics::{forward_kinematics, rnea, Model};

/// Largest share of a torque limit that the path's inverse dynamics may take, leaving the rest
/// to the feedback and the null-space behaviour.
pub const TORQUE_SHARE: f64 = 0.8;
/// Path samples per cycle of the torque check.
const TORQUE_SAMPLES: usize = 200;

/// The tip at `home` on the task axes (other coordinates 0) and the default plane `(e1, e2)`.
pub(super) fn default_frame(
    model: &Model,
    home: &[f64],
) -> Result<(Vector3<f64>, Vector3<f64>, Vector3<f64>)> {
    let mut data = model.data();
    forward_kinematics(model, &mut data, home)?;
    let axes = model.task_axes();
    let mut centre = Vector3::zeros();
    for &a in axes {
        centre[a] = data.ee_pos[a];
    }
    let unit = |a: usize| Vector3::from_fn(|r, _| if r == a { 1.0 } else { 0.0 });
    let horizontal: Vec<usize> = axes.iter().copied().filter(|&a| a < 2).collect();
    if !axes.contains(&2) || horizontal.is_empty() {
        return Ok((centre, unit(axes[0]), unit(axes[axes.len() - 1])));
    }
    let base = model.links()[0].origin.trans;
    let d = Vector3::new(centre.x - base.x, centre.y - base.y, 0.0);
    let e1 = if horizontal.len() == 1 {
        unit(horizontal[0])
    } else if d.norm() > 1e-6 {
        Vector3::new(-d.y, d.x, 0.0).normalize()
    } else {
        Vector3::x()
    };
    Ok((centre, e1, Vector3::z()))
}

/// What the feasibility check measured.
pub(super) struct Feasible {
    pub reach: Reach,
    /// Largest `|τᵢ| / τ_max,i` of the IK motion's inverse dynamics over a cycle.
    pub peak_torque_ratio: f64,
}

/// Checks that `model` (its rest posture and limits as the profile sets them) can follow
/// `traj`: [`check_reachable`], then the inverse dynamics (friction included) of the IK motion
/// over one cycle, by central differences of IK postures, within [`TORQUE_SHARE`] of the limits.
///
/// # Errors
/// [`ControlError::Unreachable`] from the reach check, or naming the joint, time and torque
/// that exceeds its share.
pub(super) fn feasible(model: &Model, traj: &Trajectory) -> Result<Feasible> {
    let opts = IkOptions::default();
    let reach = check_reachable(model, traj, &opts)?;
    let (n, k) = (model.nq(), TORQUE_SAMPLES);
    let dt = traj.period() / k as f64;
    let mut data = model.data();
    let mut q = reach.q_start.clone();
    let mut path = Vec::with_capacity(k + 3);
    for i in 0..k + 3 {
        let t = traj.ramp() + (i as f64 - 1.0) * dt;
        solve_ik(model, &mut data, &traj.sample(t).x, &mut q, &opts)?;
        path.push(DVector::from_column_slice(&q));
    }
    let tau_max: Vec<f64> = model.tau_max().collect();
    let mut peak: f64 = 0.0;
    let mut friction = vec![0.0; n];
    for i in 1..k + 2 {
        let qd = (&path[i + 1] - &path[i - 1]) / (2.0 * dt);
        let qdd = (&path[i + 1] - 2.0 * &path[i] + &path[i - 1]) / (dt * dt);
        let tau = rnea(
            model,
            &mut data,
            path[i].as_slice(),
            qd.as_slice(),
            qdd.as_slice(),
        )?
        .clone_owned();
        model.friction(qd.as_slice(), &mut friction);
        for j in 0..n {
            let ratio = (tau[j] + friction[j]).abs() / tau_max[j];
            if ratio > TORQUE_SHARE {
                return Err(ControlError::Unreachable(format!(
                    "following the path by IK needs {:.1} at joint '{}' (t = {:.2} s), more \
                     than {:.0} % of its torque limit {}",
                    tau[j] + friction[j],
                    model.links()[j].joint_name,
                    (i as f64 - 1.0) * dt,
                    100.0 * TORQUE_SHARE,
                    tau_max[j]
                )));
            }
            peak = peak.max(ratio);
        }
    }
    Ok(Feasible {
        reach,
        peak_torque_ratio: peak,
    })
}
