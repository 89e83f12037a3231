//! Step (d) of an update, the distance metric: its buffers, and the terms each output adds to
//! the gradient of the leave-one-out cost
//! `J = (1/W) Σ w (y − ŷ)² / (1 − w sᵀP s)² + (γ/n) Σ D_ij²` (`docs/lwpr.md`, "The distance
//! metric"). The derivatives with respect to `M` are in `metric_derivatives.rs`, the step in
//! `metric_step.rs`.
//!
//! With several outputs per RF (shared mode) the cost is the mean over outputs of their
//! leave-one-out costs plus one penalty; each output's transient multiplier `T` scales its own
//! term, so with one output this is exactly the reference step.

use crate::pls::Pls;

/// Derivative buffers, one entry per metric element.
#[derive(Clone, Debug, Default)]
pub(crate) struct MetricScratch {
    /// `x − c` (kernel dims).
    pub dx: Vec<f64>,
    /// `M (x − c)`.
    pub mdx: Vec<f64>,
    /// `∂w/∂M`.
    pub dwdm: Vec<f64>,
    /// `∂J2/∂M` of the penalty, then reused for the total gradient.
    pub dj2: Vec<f64>,
    /// `∂²w/∂M²` (element-wise).
    pub ddw: Vec<f64>,
    /// `∂²J2/∂M²` (element-wise).
    pub ddj2: Vec<f64>,
    /// The diagonal of `D` (full metrics).
    pub ddiag: Vec<f64>,
    /// One row (`nk`).
    pub row: Vec<f64>,
    /// Scratch of the fast full-metric step above 4 dimensions (`fast/wide.rs`), sized by
    /// the caller of [`MetricScratch::new`].
    pub wide: Vec<f64>,
}

impl MetricScratch {
    /// Buffers for `nk` kernel dimensions and `mlen` metric elements, and `wide` elements of
    /// scratch for the fast step.
    pub fn new(nk: usize, mlen: usize, wide: usize) -> MetricScratch {
        MetricScratch {
            dx: vec![0.0; nk],
            mdx: vec![0.0; nk],
            dwdm: vec![0.0; mlen],
            dj2: vec![0.0; mlen],
            ddw: vec![0.0; mlen],
            ddj2: vec![0.0; mlen],
            ddiag: vec![0.0; nk],
            row: vec![0.0; nk],
            wide: vec![0.0; wide],
        }
    }
}

/// Sums over outputs of `T·w/W`, `T·∂J1/∂w`, `T·∂²J1/∂w²` and their count.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct MetricAcc {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub n: usize,
}

/// One output's part of the metric gradient (the `∂J1/∂w` terms) from its PLS state after the
/// regression step, with `s` the new projections, `e_cv` and `e` from that step (`ps`: scratch
/// of the same length). Updates the memory traces `H`, `r`. Does nothing while
/// `n_data[0]·(1 − λ[0]) ≤ 0.1`. Returns whether the guard below skipped the terms.
///
/// A numerical guard the reference library lacks: when the sample's leverage
/// `h = w Σ_j s_j²/SSs2_j` is not below 1 (or is NaN), the leave-one-out factor `1/(1 − h)` is
/// undefined and this output adds nothing (its traces are not updated either). A true leverage
/// lies in `[0, 1)`; `h ≥ 1` arises because `s` comes from the projections just updated while
/// `SSs2` was summed with the old ones, or when `SSs2` has decayed to nothing under fast
/// forgetting (the division then gives `±∞` and the RF's state turns NaN).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn output_terms<const R: usize>(
    pls: &mut Pls,
    nr: usize,
    w: f64,
    s: &[f64],
    ps: &mut [f64],
    e_cv: f64,
    e: f64,
    meta: bool,
    acc: &mut MetricAcc,
) -> bool {
    let r = if R > 0 { R } else { pls.n_reg };
    let (n_data, ss_s2, lambda) = (&pls.n_data[..r], &pls.ss_s2[..r], &pls.lambda[..r]);
    let (h_tr, r_tr) = (&mut pls.h_tr[..r], &mut pls.r_tr[..r]);
    let (s, ps) = (&s[..r], &mut ps[..r]);
    let l0 = 1.0 - lambda[0];
    let ok = |j: usize| n_data[j] * l0 > 0.1;
    if !ok(0) {
        return false;
    }
    let mut h = 0.0;
    for j in 0..r {
        if ok(j) {
            h += s[j] * s[j] / ss_s2[j];
        }
    }
    h *= w;
    let big_w = pls.sum_w[0];
    let big_e = if r == 1 || n_data[r - 1] > 2.0 * nr as f64 {
        pls.sum_e_cv2[r - 1]
    } else {
        pls.sum_e_cv2[r - 2]
    };
    let t = (pls.sum_e2 / (big_e + 1e-10)).powi(4).min(1.0);
    let e_cv2 = e_cv * e_cv;
    let mut dj1 = -big_e / big_w + e_cv2;
    let mut spse = 0.0;
    for j in 0..r {
        if ok(j) {
            // `s_j / SSs2_j`, kept for the second-derivative sum.
            ps[j] = s[j] / ss_s2[j];
            let pse = e * ps[j];
            dj1 -= 2.0 * pse * h_tr[j] + 2.0 * ps[j] * ps[j] * r_tr[j];
            spse += s[j] * pse;
        }
    }
    dj1 /= big_w;
    // The leverage guard (see above; false for a NaN `h` too), tested here so that the terms
    // before it need not wait.
    let leverage_ok = h < 1.0;
    if !leverage_ok {
        return true;
    }
    if meta {
        let mut ddj1 = 2.0 * (e * e * h / w - e_cv2 / big_w) + big_e / (big_w * big_w);
        for j in 0..r {
            if ok(j) {
                ddj1 += 4.0 * (e * ps[j] / big_w + ps[j] * spse) * h_tr[j];
            }
        }
        acc.c += t * ddj1 / big_w;
    }
    acc.a += t * w / big_w;
    acc.b += t * dj1;
    acc.n += 1;
    let (fh, fr) = (w / (1.0 - h), w * w * e_cv2 / (1.0 - h));
    for j in 0..r {
        if ok(j) {
            let lam = lambda[j];
            h_tr[j] = lam * h_tr[j] + fh * s[j] * e_cv * t;
            r_tr[j] = lam * r_tr[j] + fr * s[j] * s[j] * t;
        }
    }
    false
}
