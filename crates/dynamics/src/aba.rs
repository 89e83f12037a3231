//! Articulated-body algorithm: forward dynamics `q̈ = M⁻¹(τ − C q̇ − g)` in O(n).

use crate::data::{update_joint_poses, Data};
use crate::error::{check_vec, DynamicsError, Result};
use crate::inertia::ArticulatedInertia;
use crate::model::{JointKind, Model};
use crate::spatial::Motion;
use nalgebra::DVector;

/// Joint accelerations under joint torques `tau` (rigid body, no friction) into `data.qdd`;
/// returns them.
///
/// Fails on a wrong length, a non-finite entry, or a non-positive articulated inertia along a
/// joint axis (a singular mass matrix, e.g. a chain that ends in massless links).
pub fn aba<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    qd: &[f64],
    tau: &[f64],
) -> Result<&'a DVector<f64>> {
    let n = model.nq();
    check_vec("q", q, n)?;
    check_vec("qd", qd, n)?;
    check_vec("tau", tau, n)?;
    update_joint_poses(model, data, q);
    for (u, &t) in data.u.iter_mut().zip(tau) {
        *u = t;
    }
    aba_passes(model, data, qd)?;
    Ok(&data.qdd)
}

/// Forward dynamics of the robot with friction: `q̈ = M⁻¹(u − h(q, q̇))`, into `data.qdd`.
pub fn forward_dynamics<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    qd: &[f64],
    u: &[f64],
) -> Result<&'a DVector<f64>> {
    let n = model.nq();
    check_vec("q", q, n)?;
    check_vec("qd", qd, n)?;
    check_vec("u", u, n)?;
    update_joint_poses(model, data, q);
    for (i, l) in model.links().iter().enumerate() {
        data.u[i] = u[i] - l.friction.torque(qd[i]);
    }
    aba_passes(model, data, qd)?;
    Ok(&data.qdd)
}

/// `U = I^A S` (angular and linear parts) and `d = Sᵀ U`: the columns of `I^A` along the joint's
/// subspace.
#[inline]
fn joint_columns(
    kind: JointKind,
    ia: &ArticulatedInertia,
    s: &nalgebra::Vector3<f64>,
) -> (nalgebra::Vector3<f64>, nalgebra::Vector3<f64>, f64) {
    match kind {
        JointKind::Revolute => {
            let ua = ia.a * s;
            (ua, ia.b.tr_mul(s), s.dot(&ua))
        }
        JointKind::Prismatic => {
            let ul = ia.c * s;
            (ia.b * s, ul, s.dot(&ul))
        }
    }
}

/// The three ABA passes on the joint poses in `data`, with the net joint torques in `data.u`.
pub(crate) fn aba_passes(model: &Model, data: &mut Data, qd: &[f64]) -> Result<()> {
    let n = model.nq();
    let links = model.links();
    // Pass 1: velocities, velocity-product accelerations and bias forces.
    let mut v_parent = Motion::default();
    for (i, l) in links.iter().enumerate() {
        let vj = l.motion(qd[i]);
        let v = data.joint_pose[i].motion_to_child(&v_parent) + vj;
        data.v[i] = v;
        data.c[i] = v.cross_motion(&vj);
        data.ia[i] = ArticulatedInertia::from_rigid(&l.inertia);
        data.pa[i] = v.cross_force(&l.inertia.mul_motion(&v));
        v_parent = v;
    }
    // Pass 2: articulated inertias and bias forces, tip to base.
    for i in (0..n).rev() {
        let s = &links[i].axis;
        let ia = data.ia[i];
        let (ua, ul, d) = joint_columns(links[i].kind, &ia, s);
        if !(d > 0.0) {
            return Err(DynamicsError::Singular { joint: i, value: d });
        }
        let inv_d = 1.0 / d;
        let u = data.u[i] - links[i].project(&data.pa[i]);
        data.u_ang[i] = ua;
        data.u_lin[i] = ul;
        data.d_inv[i] = inv_d;
        data.u[i] = u;
        if i > 0 {
            let mut ia_a = ia;
            ia_a.sub_rank1(&ua, &ul, inv_d);
            let mut pa = data.pa[i] + ia_a.mul_motion(&data.c[i]);
            pa.ang += ua * (u * inv_d);
            pa.lin += ul * (u * inv_d);
            let x = &data.joint_pose[i];
            let ia_p = ia_a.to_parent(x);
            data.ia[i - 1].add_assign(&ia_p);
            let pa_p = x.force_to_parent(&pa);
            data.pa[i - 1] += pa_p;
        }
    }
    // Pass 3: accelerations, base to tip.
    let mut a_parent = Motion::new(nalgebra::Vector3::zeros(), -model.gravity());
    for (i, l) in links.iter().enumerate() {
        let a = data.joint_pose[i].motion_to_child(&a_parent) + data.c[i];
        let qdd =
            (data.u[i] - data.u_ang[i].dot(&a.ang) - data.u_lin[i].dot(&a.lin)) * data.d_inv[i];
        data.qdd[i] = qdd;
        let a = a + l.motion(qdd);
        data.a[i] = a;
        a_parent = a;
    }
    Ok(())
}
