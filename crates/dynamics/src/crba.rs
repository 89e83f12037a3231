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

/// CRBA on the joint poses already in `data`: compiled for AVX2 where the CPU has it (the
/// 3-vector and 3×3 operations in wider registers). Rust never contracts `a * b + c` into an
/// FMA, so both copies give the same bits.
pub(crate) fn crba_pass(model: &Model, data: &mut Data) {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2 (checked above).
        return unsafe { crba_pass_avx2(model, data) };
    }
    crba_pass_body(model, data)
}

/// [`crba_pass_body`] with AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn crba_pass_avx2(model: &Model, data: &mut Data) {
    crba_pass_body(model, data)
}

/// CRBA on the joint poses already in `data`.
///
/// Column `i` of `M` is `F_i = I^c_i S_i` walked towards the base, `M_ij = S_jᵀ ᶦX*_j F_i`
/// (Featherstone's algorithm 6.2), one column at a time so that `F_i` stays in registers (a
/// walk level by level, as Pinocchio's, stores and reloads every column at each level and was
/// 5 % slower).
#[inline(always)]
fn crba_pass_body(model: &Model, data: &mut Data) {
    let n = model.nq();
    if n == 0 {
        return;
    }
    let links = &model.links()[..n];
    // Composite inertias, tip to base.
    data.ic[n - 1] = links[n - 1].inertia;
    for i in (1..n).rev() {
        let child = data.ic[i].to_parent(&data.joint_pose[i]);
        data.ic[i - 1] = links[i - 1].inertia.add(&child);
    }
    let mass = &mut data.mass;
    for i in 0..n {
        // F = I^c_i S_i, then walk it to the base in registers: M_ij = S_jᵀ F.
        let mut f = data.ic[i].mul_motion(&links[i].motion(1.0));
        mass[(i, i)] = links[i].project(&f);
        for j in (0..i).rev() {
            f = data.joint_pose[j + 1].force_to_parent(&f);
            let m = links[j].project(&f);
            mass[(i, j)] = m;
            mass[(j, i)] = m;
        }
    }
}
