//! Composite rigid-body algorithm: the joint-space mass matrix `M(q)`.

use crate::data::{update_joint_poses, Data};
use crate::error::{check_vec, Result};
use crate::inertia::Inertia;
use crate::model::{Link, Model};
use crate::spatial::Pose;
use crate::subspace::{AnyAxis, Subspace, UnitAxis};
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

/// One copy of the pass per kind of motion subspace: every joint revolute about `±e_k` (the
/// model knows, [`Model::revolute_axis`]) or any joint; for the common arms (6 or 7 joints
/// about one axis) with the number of joints a constant: the loops unrolled, every index
/// known (7 % faster on `sarcos7`).
#[inline(always)]
fn crba_pass_body(model: &Model, data: &mut Data) {
    match (model.revolute_axis(), model.nq()) {
        (Some(0), 7) => pass_n::<UnitAxis<0>, 7>(model, data),
        (Some(1), 7) => pass_n::<UnitAxis<1>, 7>(model, data),
        (Some(2), 7) => pass_n::<UnitAxis<2>, 7>(model, data),
        (Some(0), 6) => pass_n::<UnitAxis<0>, 6>(model, data),
        (Some(1), 6) => pass_n::<UnitAxis<1>, 6>(model, data),
        (Some(2), 6) => pass_n::<UnitAxis<2>, 6>(model, data),
        (Some(0), _) => pass::<UnitAxis<0>>(model, data),
        (Some(1), _) => pass::<UnitAxis<1>>(model, data),
        (Some(2), _) => pass::<UnitAxis<2>>(model, data),
        _ => pass::<AnyAxis>(model, data),
    }
}

/// CRBA on the joint poses already in `data`, tip to base.
///
/// The composite inertia `I^c_i` is final once the links beyond `i` are added, so column `i` of
/// `M` follows at once ([`column`]): the next composite inertia, a chain of dependent
/// transforms, then overlaps the walk of this column (as two loops, all inertias first, the
/// pass took 10 % longer).
#[inline(always)]
fn pass<S: Subspace>(model: &Model, data: &mut Data) {
    let n = model.nq();
    if n == 0 {
        return;
    }
    let links = &model.links()[..n];
    let poses = &data.joint_pose[..n];
    let ics = &mut data.ic[..n];
    let mass = data.mass.as_mut_slice();
    let mut ic = links[n - 1].inertia;
    for i in (0..n).rev() {
        if i + 1 < n {
            ic = links[i].inertia.add(&ic.to_parent(&poses[i + 1]));
        }
        ics[i] = ic;
        column::<S>(links, poses, &ic, i, &mut mass[i * n..i * n + i + 1]);
    }
    mirror_upper(mass, n);
}

/// Column `i` of `M` down to the diagonal into `col` (rows `0..=i`) from the composite inertia
/// `ic = I^c_i`: `F_i = I^c_i S_i` walked towards the base, `M_ji = S_jᵀ ʲX*_i F_i`
/// (Featherstone's algorithm 6.2), with `F_i` in registers (a walk level by level, as
/// Pinocchio's, stores and reloads every column at each level and was 5 % slower).
#[inline(always)]
fn column<S: Subspace>(links: &[Link], poses: &[Pose], ic: &Inertia, i: usize, col: &mut [f64]) {
    let mut f = S::column(&links[i], ic);
    col[i] = S::project(&links[i], &f);
    for j in (0..i).rev() {
        f = poses[j + 1].force_to_parent(&f);
        col[j] = S::project(&links[j], &f);
    }
}

/// [`pass`] for `N ≤ 8` joints, `N` a constant: the same operations on the same values, both
/// triangles written in the walk (every index known, no mirror pass), each column a separate
/// copy ([`column_n`]) so that every walk is unrolled.
#[inline(always)]
fn pass_n<S: Subspace, const N: usize>(model: &Model, data: &mut Data) {
    let links: &[Link; N] = model.links().try_into().expect("N joints");
    let poses: &[Pose; N] = data.joint_pose[..].try_into().expect("N joints");
    let ics: &mut [Inertia; N] = (&mut data.ic[..]).try_into().expect("N joints");
    let mass: &mut [f64] = &mut data.mass.as_mut_slice()[..N * N];
    let mut ic = links[N - 1].inertia;
    macro_rules! columns_down {
        ($($i:literal)*) => {$(
            if $i < N {
                column_n::<S, N, $i>(links, poses, &mut ic, ics, mass);
            }
        )*};
    }
    columns_down!(7 6 5 4 3 2 1 0);
}

/// Column `I` of [`pass_n`]: `ic` becomes `I^c_I`, then the walk to the base.
#[inline(always)]
fn column_n<S: Subspace, const N: usize, const I: usize>(
    links: &[Link; N],
    poses: &[Pose; N],
    ic: &mut Inertia,
    ics: &mut [Inertia; N],
    mass: &mut [f64],
) {
    if I + 1 < N {
        *ic = links[I].inertia.add(&ic.to_parent(&poses[I + 1]));
    }
    ics[I] = *ic;
    let mut f = S::column(&links[I], ic);
    mass[I * N + I] = S::project(&links[I], &f);
    for j in (0..I).rev() {
        f = poses[j + 1].force_to_parent(&f);
        let m = S::project(&links[j], &f);
        mass[I * N + j] = m;
        mass[j * N + I] = m;
    }
}

/// Copies the upper triangle of the column-major `n × n` matrix `mass` into the lower one:
/// column `j` below the diagonal (contiguous) from row `j` of the columns right of it.
#[inline(always)]
fn mirror_upper(mass: &mut [f64], n: usize) {
    for j in 0..n.saturating_sub(1) {
        let (left, right) = mass.split_at_mut((j + 1) * n);
        let below = &mut left[j * n + j + 1..];
        for (m, &u) in below.iter_mut().zip(right[j..].iter().step_by(n)) {
            *m = u;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::robots;
    use crate::subspace::unit_axis_models;

    /// The unit-axis path (with the joint count constant for 6 and 7 joints) gives the general
    /// path's bits: the same products without their zero terms, in the same order.
    #[test]
    fn unit_axis_path_gives_the_general_bits() {
        let bits = |m: &DMatrix<f64>| m.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        for model in unit_axis_models() {
            let k = model.revolute_axis().expect("a shared unit axis");
            let n = model.nq();
            let q: Vec<f64> = (0..n).map(|i| 0.3 * i as f64 - 0.7).collect();
            let mut data = model.data();
            let fast = crba(&model, &mut data, &q).unwrap().clone();
            let fast_ic = data.ic.clone();
            update_joint_poses(&model, &mut data, &q);
            pass::<AnyAxis>(&model, &mut data);
            // Zeros may differ in sign only (`0 · x` terms dropped).
            let zero_signs = |m: &DMatrix<f64>| m.map(|x| if x == 0.0 { 0.0 } else { x });
            assert_eq!(
                bits(&zero_signs(&fast)),
                bits(&zero_signs(&data.mass)),
                "{} (axis {k})",
                model.name()
            );
            assert_eq!(fast_ic, data.ic, "{}", model.name());
        }
        assert_eq!(robots::random_arm(6, 1, false).revolute_axis(), None);
    }
}
