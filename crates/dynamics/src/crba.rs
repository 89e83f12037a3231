//! Composite rigid-body algorithm: the joint-space mass matrix `M(q)`.

use crate::data::{update_joint_poses, Data};
use crate::error::{check_vec, Result};
use crate::model::Model;
use nalgebra::DMatrix;

/// Mass matrix `M(q)` (symmetric, n×n, kg·m²) into `data.mass`; returns it.
///
/// Fails on a wrong length or a non-finite entry; never allocates.
pub fn crba<'a>(model: &Model, data: &'a mut Data, q: &[f64]) -> Result<&'a DMatrix<f64>> {
    check_vec("q", q, model.nq())?;
    update_joint_poses(model, data, q);
    crba_pass(model, data);
    Ok(&data.mass)
}

/// CRBA on the joint poses already in `data`.
pub(crate) fn crba_pass(model: &Model, data: &mut Data) {
    let n = model.nq();
    let links = model.links();
    for (ic, link) in data.ic.iter_mut().zip(&links[..n]) {
        *ic = link.inertia;
    }
    // Composite inertias, tip to base.
    for i in (1..n).rev() {
        let child = data.ic[i].to_parent(&data.joint_pose[i]);
        data.ic[i - 1] = data.ic[i - 1].add(&child);
    }
    for i in 0..n {
        // F = I^c_i S_i, then walk it to the base: M_ij = S_jᵀ F.
        let mut f = data.ic[i].mul_motion(&links[i].motion(1.0));
        data.mass[(i, i)] = links[i].project(&f);
        for j in (0..i).rev() {
            f = data.joint_pose[j + 1].force_to_parent(&f);
            let m = links[j].project(&f);
            data.mass[(i, j)] = m;
            data.mass[(j, i)] = m;
        }
    }
}
