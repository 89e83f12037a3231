//! Applying resolved values to a model, and the model quantities the defaults are computed from.

use super::check::bad;
use super::PathFrame;
use crate::error::Result;
use crate::trajectory::Trajectory;
use osrl_dynamics::Model;

/// The effective inertia of each joint at `q` with every other joint free, `m_i = 1 / (M⁻¹)_ii`,
/// and with every other joint locked, `M_ii` (kg·m² or kg; `m_i ≤ M_ii`).
pub(super) fn joint_inertias(model: &Model, q: &[f64]) -> Result<(Vec<f64>, Vec<f64>)> {
    let mut data = model.data();
    let m = osrl_dynamics::crba(model, &mut data, q)?.clone_owned();
    let Some(chol) = m.clone().cholesky() else {
        return bad(
            "home",
            format!(
                "the mass matrix of {} is not positive definite there",
                model.name()
            ),
        );
    };
    let inv = chol.inverse();
    let n = model.nq();
    Ok((
        (0..n).map(|i| 1.0 / inv[(i, i)]).collect(),
        (0..n).map(|i| m[(i, i)]).collect(),
    ))
}

/// The model with the profile's postures, gains and torque limits (the model itself when
/// nothing changes, so built-in robots stay bit-identical).
pub(super) fn apply(
    model: &Model,
    home: &[f64],
    rest: &[f64],
    kp: &[f64],
    kd: &[f64],
    tau: &[f64],
) -> Result<Model> {
    let s = model.spec();
    let same_tau = model.tau_max().zip(tau).all(|(a, &b)| a == b);
    if s.q_start == home && s.q_rest == rest && s.kp == kp && s.kd == kd && same_tau {
        return Ok(model.clone());
    }
    let mut spec = s.clone();
    spec.q_start = home.to_vec();
    spec.q_rest = rest.to_vec();
    spec.kp = kp.to_vec();
    spec.kd = kd.to_vec();
    for (l, &t) in spec.links.iter_mut().zip(tau) {
        l.limits.tau_max = t;
    }
    Ok(Model::new(spec)?)
}

/// The figure-8 of the default period and ramp in `frame`.
pub(super) fn figure8(frame: &PathFrame) -> Result<Trajectory> {
    let d = crate::TrajectoryConfig::default();
    let v = nalgebra::Vector3::from;
    Trajectory::figure8(
        v(frame.centre),
        v(frame.e1),
        v(frame.e2),
        frame.a,
        frame.b,
        d.period,
        d.ramp,
    )
}
