//! The Cholesky solve of eq. 23: `A X = B` for symmetric positive definite `A` given by its
//! lower triangle.
//!
//! The factorisation runs right-looking (every finished column updates all trailing columns)
//! or, where the CPU has AVX2 or AVX-512, in panels of [`PANEL`] columns: all updates from the
//! finished columns to a panel are applied a block of 4 (AVX2) or 8 rows (AVX-512) at a time,
//! each block held in a register through all finished columns (`cholesky_x86.rs`), then the
//! panel is finished column by column. Each entry receives the same subtractions in the same
//! order (finished column 0 first) and the same division: the same bits (tested).

use crate::error::{Result, RwrError};
use crate::stats::dot;
use nalgebra::DMatrix;

/// Columns per panel of the blocked factorisation.
pub(crate) const PANEL: usize = 4;

/// Size from which the blocked factorisation runs (below, the right-looking one: a block of
/// eight rows would be mostly padding).
const PANEL_MIN: usize = 24;

/// Solves `A X = B`: overwrites the lower triangle of `A` with its Cholesky factor `L` and `B`
/// with `X`. Fails with [`RwrError::Singular`] (B then holds garbage) when `A` is not
/// numerically positive definite.
#[inline(always)]
pub(crate) fn solve_lower(a: &mut DMatrix<f64>, b: &mut DMatrix<f64>) -> Result<()> {
    #[cfg(target_arch = "x86_64")]
    if crate::simd::avx512() && a.nrows() >= PANEL_MIN {
        // SAFETY: the CPU supports AVX-512F (checked just above).
        unsafe { factor_panels(a, crate::cholesky_x86::panel_avx512)? };
    } else if crate::simd::avx2() && a.nrows() >= PANEL_MIN {
        // SAFETY: the CPU supports AVX2 (checked just above).
        unsafe { factor_panels(a, crate::cholesky_x86::panel_avx2)? };
    } else {
        factor_right(a)?;
    }
    #[cfg(not(target_arch = "x86_64"))]
    factor_right(a)?;
    let p = a.nrows();
    let l = a.as_slice();
    // The columns of B are independent: interleaved, so that their chains of divisions overlap.
    // Forward substitution, column by column of L.
    for k in 0..p {
        let lk = &l[k * p + k + 1..(k + 1) * p];
        for col in b.as_mut_slice().chunks_exact_mut(p) {
            let v = col[k] / l[k * p + k];
            col[k] = v;
            for (t, x) in col[k + 1..].iter_mut().zip(lk) {
                *t -= x * v;
            }
        }
    }
    // Back substitution with Lᵀ (columns of L are contiguous).
    for i in (0..p).rev() {
        let li = &l[i * p + i + 1..(i + 1) * p];
        for col in b.as_mut_slice().chunks_exact_mut(p) {
            let v = col[i] - dot(li, &col[i + 1..]);
            col[i] = v / l[i * p + i];
        }
    }
    Ok(())
}

/// Keeps the original diagonal, needed for the pivot test, in the unused upper triangle (row 0).
#[inline(always)]
fn keep_diagonal(a: &mut DMatrix<f64>) {
    for j in 1..a.nrows() {
        a[(0, j)] = a[(j, j)];
    }
}

/// Finishes column `j` (all its updates applied): the pivot test, `L_jj = √d`, and the column
/// below it divided by `L_jj`.
#[inline(always)]
fn finish_column(m: &mut [f64], p: usize, j: usize) -> Result<()> {
    let diag = if j == 0 { m[0] } else { m[j * p] };
    let d = m[j * p + j];
    // A pivot lost to rounding (relative to its diagonal) counts as singular.
    if !(d > 1e-13 * diag && d.is_finite()) {
        return Err(RwrError::Singular);
    }
    let d = d.sqrt();
    m[j * p + j] = d;
    for v in &mut m[j * p + j + 1..(j + 1) * p] {
        *v /= d;
    }
    Ok(())
}

/// The right-looking factorisation on contiguous columns (the same operations, in the same
/// order per element, as the textbook left-looking loop).
#[inline(always)]
pub(crate) fn factor_right(a: &mut DMatrix<f64>) -> Result<()> {
    let p = a.nrows();
    keep_diagonal(a);
    let m = a.as_mut_slice();
    for j in 0..p {
        finish_column(m, p, j)?;
        // Update the trailing columns: A[c.., c] −= L[c, j] L[c.., j].
        let (left, right) = m.split_at_mut((j + 1) * p);
        let lj = &left[j * p..(j + 1) * p];
        for c in j + 1..p {
            let l = lj[c];
            let off = (c - j - 1) * p;
            for (t, x) in right[off + c..off + p].iter_mut().zip(&lj[c..]) {
                *t -= x * l;
            }
        }
    }
    Ok(())
}

/// A kernel applying the updates from the finished columns `0..c0` to the rows `c..` of the
/// panel's columns `c0 ≤ c < c1` (column-major `p × p` slice).
pub(crate) type PanelKernel = unsafe fn(&mut [f64], usize, usize, usize);

/// The factorisation in panels of [`PANEL`] columns (see the module), the updates from the
/// finished columns by `kernel`.
///
/// # Safety
/// `kernel` must be safe to call on this CPU.
#[inline(always)]
pub(crate) unsafe fn factor_panels(a: &mut DMatrix<f64>, kernel: PanelKernel) -> Result<()> {
    let p = a.nrows();
    keep_diagonal(a);
    let m = a.as_mut_slice();
    for c0 in (0..p).step_by(PANEL) {
        let c1 = (c0 + PANEL).min(p);
        if c0 > 0 {
            kernel(m, p, c0, c1);
        }
        for c in c0..c1 {
            // The updates from the panel's finished columns, in order.
            let (left, right) = m.split_at_mut(c * p);
            for j in c0..c {
                let lj = &left[j * p..(j + 1) * p];
                let l = lj[c];
                for (t, x) in right[c..p].iter_mut().zip(&lj[c..]) {
                    *t -= x * l;
                }
            }
            finish_column(m, p, c)?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A random Gram matrix `XᵀX/n + λI` of `p` features from `n` samples (singular for
    /// `n < p` and `λ = 0`).
    fn gram(rng: &mut ChaCha8Rng, p: usize, n: usize, ridge: f64) -> DMatrix<f64> {
        let x = DMatrix::from_fn(n, p, |_, _| rng.random_range(-2.0..2.0));
        x.transpose() * &x / n as f64 + DMatrix::identity(p, p) * ridge
    }

    /// The blocked factorisation (with each kernel this CPU has: AVX2, AVX-512) gives the
    /// right-looking one's bits (the whole matrix, upper triangle included) and the same
    /// failures: every size from 1 to 80 (the learner's 19 and 71 among them), well and badly
    /// conditioned, and singular.
    #[test]
    fn the_panels_give_the_bits_of_the_right_looking_factorisation() {
        #[cfg(target_arch = "x86_64")]
        {
            use crate::cholesky_x86::{panel_avx2, panel_avx512};
            let kernels: [(&str, bool, PanelKernel); 2] = [
                ("AVX2", crate::simd::avx2(), panel_avx2),
                ("AVX-512", crate::simd::avx512(), panel_avx512),
            ];
            for (name, _, kernel) in kernels.into_iter().filter(|k| k.1) {
                let mut rng = ChaCha8Rng::seed_from_u64(5);
                let mut failed = 0;
                for p in 1..=80 {
                    for (n, ridge) in [(3 * p, 1e-4), (p + 1, 1e-12), (p / 2, 0.0)] {
                        let a = gram(&mut rng, p, n.max(1), ridge);
                        let (mut right, mut panels) = (a.clone(), a.clone());
                        let r = factor_right(&mut right);
                        // SAFETY: the CPU supports the kernel's instructions (filtered above).
                        let q = unsafe { factor_panels(&mut panels, kernel) };
                        assert_eq!(r.is_ok(), q.is_ok(), "{name}, p = {p}, n = {n}");
                        failed += r.is_err() as usize;
                        if r.is_ok() {
                            let bits = |m: &DMatrix<f64>| {
                                m.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
                            };
                            assert!(bits(&right) == bits(&panels), "{name}, p = {p}, n = {n}");
                        }
                    }
                }
                assert!(failed > 50, "{name}: singular cases: {failed}");
            }
        }
    }
}
