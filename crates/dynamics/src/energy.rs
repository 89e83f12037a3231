//! Mechanical energy, for conservation checks and diagnostics.

use crate::crba::crba;
use crate::data::Data;
use crate::error::Result;
use crate::kinematics::forward_kinematics;
use crate::model::Model;

/// Kinetic energy `½ q̇ᵀ M q̇` and potential energy `−Σ m_i gᵀ c_i` (J) at `(q, q̇)`.
pub fn energy(model: &Model, data: &mut Data, q: &[f64], qd: &[f64]) -> Result<(f64, f64)> {
    crate::error::check_vec("qd", qd, model.nq())?;
    let m = crba(model, data, q)?;
    let mut kinetic = 0.0;
    for i in 0..qd.len() {
        for j in 0..qd.len() {
            kinetic += 0.5 * qd[i] * m[(i, j)] * qd[j];
        }
    }
    forward_kinematics(model, data, q)?;
    let g = model.gravity();
    let potential: f64 = model
        .links()
        .iter()
        .zip(&data.world_pose)
        .map(|(l, pose)| {
            // m c in the world is R h + m p.
            let mc = pose.rot * l.inertia.h + pose.trans * l.inertia.mass;
            -g.dot(&mc)
        })
        .sum();
    Ok((kinetic, potential))
}
