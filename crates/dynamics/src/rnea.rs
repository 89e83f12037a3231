//! Recursive Newton–Euler inverse dynamics: `τ = M(q) q̈ + C(q, q̇) q̇ + g(q)`, and from it the
//! gravity torques `g(q)` and the non-inertial torques `h(q, q̇)` of the paper's `M q̈ + h = u`.

use crate::data::{update_joint_poses, Data};
use crate::error::{check_vec, Result};
use crate::model::Model;
use crate::spatial::Motion;
use nalgebra::DVector;

/// Rigid-body inverse dynamics (no friction) into `data.tau`; returns it.
///
/// Fails on a wrong length or a non-finite entry; never allocates.
pub fn rnea<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
) -> Result<&'a DVector<f64>> {
    let n = model.nq();
    check_vec("q", q, n)?;
    check_vec("qd", qd, n)?;
    check_vec("qdd", qdd, n)?;
    update_joint_poses(model, data, q);
    rnea_passes(model, data, Some(qd), Some(qdd), true);
    Ok(&data.tau)
}

/// Gravity torques `g(q)` into `data.g`; returns them.
pub fn gravity<'a>(model: &Model, data: &'a mut Data, q: &[f64]) -> Result<&'a DVector<f64>> {
    check_vec("q", q, model.nq())?;
    update_joint_poses(model, data, q);
    rnea_passes(model, data, None, None, true);
    data.g.copy_from(&data.tau);
    Ok(&data.g)
}

/// Non-inertial torques `h(q, q̇) = C(q, q̇) q̇ + g(q) + τ_f(q̇)` into `data.h` (friction into
/// `data.friction`); returns `h`.
pub fn nonlinear_effects<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    qd: &[f64],
) -> Result<&'a DVector<f64>> {
    let n = model.nq();
    check_vec("q", q, n)?;
    check_vec("qd", qd, n)?;
    update_joint_poses(model, data, q);
    rnea_passes(model, data, Some(qd), None, true);
    model.friction(qd, data.friction.as_mut_slice());
    data.h.copy_from(&data.tau);
    data.h += &data.friction;
    Ok(&data.h)
}

/// The two RNEA passes on the joint poses already in `data`; `None` means zero. The result is in
/// `data.tau`.
pub(crate) fn rnea_passes(
    model: &Model,
    data: &mut Data,
    qd: Option<&[f64]>,
    qdd: Option<&[f64]>,
    with_gravity: bool,
) {
    let n = model.nq();
    // The base "accelerates" upwards against gravity, so gravity acts on every link.
    let mut v_parent = Motion::default();
    let mut a_parent = Motion::default();
    if with_gravity {
        a_parent.lin = -model.gravity();
    }
    // Forward pass: velocities, accelerations and the force each body needs.
    for (i, l) in model.links().iter().enumerate() {
        let x = &data.joint_pose[i];
        let qd_i = qd.map_or(0.0, |v| v[i]);
        let qdd_i = qdd.map_or(0.0, |v| v[i]);
        let vj = l.motion(qd_i);
        let v = x.motion_to_child(&v_parent) + vj;
        let a = x.motion_to_child(&a_parent) + l.motion(qdd_i) + v.cross_motion(&vj);
        let inertia = &l.inertia;
        data.f[i] = inertia.mul_motion(&a) + v.cross_force(&inertia.mul_motion(&v));
        data.v[i] = v;
        data.a[i] = a;
        v_parent = v;
        a_parent = a;
    }
    // Backward pass: project onto the joint subspaces and hand the forces to the parents.
    for i in (0..n).rev() {
        let f = data.f[i];
        data.tau[i] = model.links()[i].project(&f);
        if i > 0 {
            let fp = data.joint_pose[i].force_to_parent(&f);
            data.f[i - 1] += fp;
        }
    }
}
