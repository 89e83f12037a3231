//! The PLS steps of an update in one receptive field (`docs/lwpr.md`, "One update"): (a) the
//! weighted means, (b) the PLS regression, (e) the growth test and (f) forgetting.

use crate::numeric::dot;
use crate::params::Params;
use crate::pls::{project, Pls};
use crate::rf::Rf;

/// Scratch for the PLS step, sized once for `nr` regression dimensions.
#[derive(Clone, Debug, Default)]
pub(crate) struct PlsScratch {
    /// Input minus the RF's weighted mean.
    pub xmz: Vec<f64>,
    /// Residual inputs `xres_j`, `nr × nr`.
    pub xres: Vec<f64>,
    /// Projections `s_j` (after an update: with the new `u`, `p`).
    pub s: Vec<f64>,
    /// Leave-one-out residuals `e_cv,j`.
    pub e_cv: Vec<f64>,
    /// Working residual for projections.
    pub xu: Vec<f64>,
    /// `s_j / SSs2_j` (metric step).
    pub ps: Vec<f64>,
    /// Outputs whose metric terms the leverage guard skipped ([`crate::update::metric::output_terms`])
    /// in the current sub-model update.
    pub skipped: usize,
}

impl PlsScratch {
    /// Buffers for `nr` regression dimensions.
    pub fn new(nr: usize) -> PlsScratch {
        PlsScratch {
            xmz: vec![0.0; nr],
            xres: vec![0.0; nr * nr],
            s: vec![0.0; nr],
            e_cv: vec![0.0; nr],
            xu: vec![0.0; nr],
            skipped: 0,
            ps: vec![0.0; nr],
        }
    }
}

/// Step (a) for the inputs: with `ω = sum_w[0]·λ[0]` (passed in, shared by all outputs),
/// updates the RF's weighted mean and variance and writes `x̃ = x − mean_x` into `xmz`.
#[inline(always)]
pub(crate) fn update_input_means(
    nr: usize,
    rf: &mut Rf,
    omega: f64,
    x: &[f64],
    w: f64,
    xmz: &mut [f64],
) {
    let inv = 1.0 / (omega + w);
    let (x, xmz) = (&x[..nr], &mut xmz[..nr]);
    let (mean_x, var_x) = (&mut rf.mean_x[..nr], &mut rf.var_x[..nr]);
    for i in 0..nr {
        let m = (omega * mean_x[i] + w * x[i]) * inv;
        mean_x[i] = m;
        let d = x[i] - m;
        xmz[i] = d;
        var_x[i] = (omega * var_x[i] + w * d * d) * inv;
    }
}

/// Outcome of [`update_regression`] for one output.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct RegOut {
    /// The RF's prediction `β₀ + Σ β_j s_j` (normalised), before this update's forgetting step.
    pub yp: f64,
    /// Leave-one-out residual of the last trusted direction.
    pub e_cv: f64,
    /// Residual of the updated model.
    pub e: f64,
    /// The sum of every `β_j`, `p_j` and `u_j` the step computed: finite iff they all are (a
    /// numerical guard: `β_j` and `p_j` divide by `SSs2_j`, which fast forgetting can let
    /// decay to nothing; a finite sum that overflows is flagged too, such an RF has diverged).
    pub chk: f64,
}

/// Steps (a, output part) and (b): updates `β₀` with `(ω, inv)` from the input means, then one
/// weighted PLS update with sample `(x̃, y)` and weight `w`. `ws.s` holds the new projections.
/// (The PLS state is sliced to its `R` directions once, so the loops need no bounds checks.)
#[inline(always)]
pub(crate) fn update_regression<const R: usize>(
    pls: &mut Pls,
    nr: usize,
    omega: f64,
    y: f64,
    w: f64,
    ws: &mut PlsScratch,
) -> RegOut {
    pls.beta0 = (omega * pls.beta0 + w * y) / (omega + w);
    let ymz = y - pls.beta0;
    let r = if R > 0 { R } else { pls.n_reg };
    let nn = r * nr;
    let PlsScratch {
        xmz,
        xres,
        s,
        e_cv,
        xu,
        ..
    } = ws;
    let (xmz, xres, s, e_cv) = (&xmz[..nr], &mut xres[..nn], &mut s[..r], &mut e_cv[..r]);
    let Pls {
        u,
        p,
        sxy,
        ssx,
        beta,
        ss_s2,
        ss_yres,
        sum_w,
        n_data,
        lambda,
        sum_e_cv2,
        ssp,
        sum_e2,
        ..
    } = &mut *pls;
    let (u, p, sxy, ssx) = (&mut u[..nn], &mut p[..nn], &mut sxy[..nn], &mut ssx[..nn]);
    let (beta, ss_s2, ss_yres) = (&mut beta[..r], &mut ss_s2[..r], &mut ss_yres[..r]);
    let (sum_w, n_data, lambda) = (&mut sum_w[..r], &n_data[..r], &lambda[..r]);
    let sum_e_cv2 = &mut sum_e_cv2[..r];
    // Projection with the old directions, keeping every residual.
    xres[..nr].copy_from_slice(xmz);
    for j in 0..r {
        let (done, rest) = xres.split_at_mut((j + 1) * nr);
        let xj = &done[j * nr..];
        let sj = dot(&u[j * nr..(j + 1) * nr], xj);
        s[j] = sj;
        if j + 1 < r {
            let (pj, rest) = (&p[j * nr..(j + 1) * nr], &mut rest[..nr]);
            for i in 0..nr {
                rest[i] = xj[i] - pj[i] * sj;
            }
        }
    }
    let mut yres = 0.0;
    for j in 0..r {
        yres += beta[j] * s[j];
        sum_w[j] = sum_w[j] * lambda[j] + w;
        e_cv[j] = ymz - yres;
    }
    let mut ws2 = 0.0;
    // Numerical guard (`RegOut::chk`).
    let mut chk = 0.0;
    for j in 0..r {
        let lam = lambda[j];
        let lam_slow = 0.9 + 0.1 * lam;
        let t = if j == 0 { ymz } else { e_cv[j - 1] };
        let wt = w * t;
        let wsj = w * s[j];
        let xj = &xres[j * nr..(j + 1) * nr];
        let sxy = &mut sxy[j * nr..(j + 1) * nr];
        let mut norm2 = 0.0;
        for i in 0..nr {
            let v = sxy[i] * lam_slow + wt * xj[i];
            sxy[i] = v;
            norm2 += v * v;
        }
        if norm2 > 1e-24 {
            let inv = 1.0 / norm2.sqrt();
            for (u, &v) in u[j * nr..(j + 1) * nr].iter_mut().zip(sxy.iter()) {
                *u = v * inv;
                chk += *u;
            }
        }
        ss_s2[j] = lam * ss_s2[j] + s[j] * wsj;
        ss_yres[j] = lam * ss_yres[j] + t * wsj;
        let inv_s2 = 1.0 / ss_s2[j];
        beta[j] = ss_yres[j] * inv_s2;
        chk += beta[j];
        let ssx = &mut ssx[j * nr..(j + 1) * nr];
        let pj = &mut p[j * nr..(j + 1) * nr];
        for i in 0..nr {
            let v = lam * ssx[i] + wsj * xj[i];
            ssx[i] = v;
            pj[i] = v * inv_s2;
            chk += pj[i];
        }
        ws2 += wsj * wsj * inv_s2;
    }
    *ssp = lambda[r - 1] * *ssp + ws2;
    // New projections.
    project(u, p, nr, r, xmz, xu, s);
    // `Pls::n_pred`.
    let np = if n_data[r - 1] > 2.0 * nr as f64 {
        r
    } else {
        r - 1
    };
    let ypred: f64 = (0..np).map(|j| beta[j] * s[j]).sum();
    let e_cv_r = if np == 0 { ymz } else { e_cv[np - 1] };
    let e = ymz - ypred;
    if n_data[0] * (1.0 - lambda[0]) > 0.1 {
        *sum_e2 = *sum_e2 * lambda[r - 1] + w * e * e;
        for j in 0..r {
            sum_e_cv2[j] = sum_e_cv2[j] * lambda[j] + w * e_cv[j] * e_cv[j];
        }
    }
    RegOut {
        yp: ypred + pls.beta0,
        e_cv: e_cv_r,
        e,
        chk,
    }
}

/// PLS growth test and step (e): adds direction `R+1` when the last direction explains
/// enough more than the one before. Returns whether a direction was added.
/// (The test is inlined into the update; the growth itself is a separate, cold function.)
#[inline(always)]
pub(crate) fn check_grow(out: &mut Pls, p: &Params) -> bool {
    let r = out.n_reg;
    let nr = p.nr();
    if r >= nr || r < 2 {
        return false;
    }
    let mse_r = out.sum_e_cv2[r - 1] / out.sum_w[r - 1] + 1e-10;
    let mse_r1 = out.sum_e_cv2[r - 2] / out.sum_w[r - 2] + 1e-10;
    if mse_r < p.cfg.add_threshold * mse_r1
        && out.n_data[r - 1] > 0.99 * out.n_data[0]
        && out.n_data[r - 1] * (1.0 - out.lambda[r - 1]) > 0.5
    {
        grow(out, p);
        true
    } else {
        false
    }
}

/// Adds direction `R+1` (`u = p = e_{R+1}`).
#[cold]
#[inline(never)]
fn grow(out: &mut Pls, p: &Params) {
    let r = out.n_reg;
    let nr = p.nr();
    for v in [&mut out.u, &mut out.p, &mut out.sxy, &mut out.ssx] {
        v.resize((r + 1) * nr, 0.0);
    }
    out.u[r * nr + r] = 1.0;
    out.p[r * nr + r] = 1.0;
    for v in [
        &mut out.beta,
        &mut out.ss_yres,
        &mut out.n_data,
        &mut out.sum_e_cv2,
        &mut out.h_tr,
        &mut out.r_tr,
    ] {
        v.push(0.0);
    }
    out.ss_s2.push(p.cfg.init_s2);
    out.sum_w.push(1e-10);
    out.lambda.push(p.cfg.init_lambda);
    out.n_reg = r + 1;
    out.ssp = 0.0;
}

/// Step (f): `n_data_j ← λ_j n_data_j + 1`, then the forgetting schedule.
#[inline(always)]
pub(crate) fn forget(pls: &mut Pls, tau: f64, final_lambda: f64) {
    for j in 0..pls.n_reg {
        pls.n_data[j] = pls.n_data[j] * pls.lambda[j] + 1.0;
        pls.lambda[j] = tau * pls.lambda[j] + final_lambda * (1.0 - tau);
    }
}
