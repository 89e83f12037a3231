//! Articulated-body algorithm: forward dynamics `q̈ = M⁻¹(τ − C q̇ − g)` in O(n).

use crate::data::{update_joint_poses, Data};
use crate::error::{check_vec, DynamicsError, Result};
use crate::inertia::ArticulatedInertia;
use crate::model::Model;
use crate::spatial::Motion;
use crate::subspace::{AnyAxis, Subspace, UnitAxis};
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

/// The three ABA passes on the joint poses in `data`, with the net joint torques in `data.u`:
/// one copy per kind of motion subspace, as in [`crate::crba`] (every joint revolute about one
/// `±e_k`, or any joint), the same values up to the sign of zeros.
pub(crate) fn aba_passes(model: &Model, data: &mut Data, qd: &[f64]) -> Result<()> {
    match model.revolute_axis() {
        Some(0) => passes::<UnitAxis<0>>(model, data, qd),
        Some(1) => passes::<UnitAxis<1>>(model, data, qd),
        Some(2) => passes::<UnitAxis<2>>(model, data, qd),
        _ => passes::<AnyAxis>(model, data, qd),
    }
}

/// [`aba_passes`] for the motion subspace `S`.
#[inline(always)]
fn passes<S: Subspace>(model: &Model, data: &mut Data, qd: &[f64]) -> Result<()> {
    let n = model.nq();
    let links = model.links();
    // Pass 1: velocities, velocity-product accelerations and bias forces.
    let mut v_parent = Motion::default();
    for (i, l) in links.iter().enumerate() {
        let v = S::add_motion(l, data.joint_pose[i].motion_to_child(&v_parent), qd[i]);
        data.v[i] = v;
        data.c[i] = S::cross_joint(l, &v, qd[i]);
        data.ia[i] = ArticulatedInertia::from_rigid(&l.inertia);
        data.pa[i] = v.cross_force(&l.inertia.mul_motion(&v));
        v_parent = v;
    }
    // Pass 2: articulated inertias and bias forces, tip to base.
    for i in (0..n).rev() {
        let ia = data.ia[i];
        let (ua, ul, d) = S::columns(&links[i], &ia);
        if !(d > 0.0) {
            return Err(DynamicsError::Singular { joint: i, value: d });
        }
        let inv_d = 1.0 / d;
        let u = data.u[i] - S::project(&links[i], &data.pa[i]);
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
        let a = S::add_motion(l, a, qdd);
        data.a[i] = a;
        a_parent = a;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::update_joint_poses;
    use crate::subspace::unit_axis_models;

    /// The unit-axis passes give the general passes' bits (zeros up to their sign) in every
    /// quantity they leave in `data`, at states with zero and non-zero velocities and torques.
    #[test]
    fn unit_axis_passes_give_the_general_bits() {
        let bits = |d: &Data| {
            let z = |x: f64| if x == 0.0 { 0.0f64 } else { x }.to_bits();
            let mut b: Vec<u64> = d.qdd.iter().map(|&x| z(x)).collect();
            for m in d.v.iter().chain(&d.a).chain(&d.c) {
                b.extend(m.ang.iter().chain(m.lin.iter()).map(|&x| z(x)));
            }
            for ia in &d.ia {
                b.extend(
                    ia.a.iter()
                        .chain(ia.b.iter())
                        .chain(ia.c.iter())
                        .map(|&x| z(x)),
                );
            }
            for f in &d.pa {
                b.extend(f.ang.iter().chain(f.lin.iter()).map(|&x| z(x)));
            }
            b.extend(d.u.iter().chain(&d.d_inv).map(|&x| z(x)));
            b
        };
        for model in unit_axis_models() {
            assert!(model.revolute_axis().is_some(), "{}", model.name());
            let n = model.nq();
            for scale in [0.0, 1.0] {
                let q: Vec<f64> = (0..n).map(|i| 0.3 * i as f64 - 0.7).collect();
                let qd: Vec<f64> = (0..n).map(|i| scale * (0.4 - 0.15 * i as f64)).collect();
                let tau: Vec<f64> = (0..n).map(|i| scale * (1.5 - 0.5 * i as f64)).collect();
                let mut fast = model.data();
                aba(&model, &mut fast, &q, &qd, &tau).unwrap();
                let mut general = model.data();
                update_joint_poses(&model, &mut general, &q);
                general.u.copy_from_slice(&tau);
                passes::<AnyAxis>(&model, &mut general, &qd).unwrap();
                assert_eq!(
                    bits(&fast),
                    bits(&general),
                    "{} at scale {scale}",
                    model.name()
                );
            }
        }
    }
}
