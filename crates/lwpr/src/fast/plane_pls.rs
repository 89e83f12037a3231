//! Step (b) of an update — the PLS step of one output — for two regression inputs and two
//! directions (the most two inputs allow), with every dimension a constant: the arithmetic of
//! `update_regression` (`update/regression.rs`), the same expressions in the same order (so the
//! same bits, checked by a test against the reference), on the state viewed as fixed-size
//! arrays, without its run-time lengths and per-element bounds checks.
//!
//! Written out term by term where the general code sums in a particular order: a dot product
//! of two (`numeric::dot`) is `(0 + a₀b₀) + a₁b₁`; adding `0.0` is kept because it is not an
//! identity for `−0.0`.

use crate::pls::Pls;
use crate::update::regression::{PlsScratch, RegOut};

/// The first `N` elements of an RF's state as an array (the state is never shorter).
#[inline(always)]
pub(crate) fn arr<const N: usize>(v: &mut [f64]) -> &mut [f64; N] {
    v.first_chunk_mut()
        .expect("RF state shorter than its dimensions")
}

/// `numeric::dot` of two 2-vectors, in its order.
#[inline(always)]
fn dot2(a: &[f64], b: [f64; 2]) -> f64 {
    let mut r = 0.0;
    r += a[0] * b[0];
    r += a[1] * b[1];
    r
}

/// `update_regression::<2>` (`update/regression.rs`) for two regression inputs (steps (a, output part) and (b)):
/// the same arithmetic on fixed-size arrays; `x̃` from `ws.xmz`, the new projections into
/// `ws.s`, `n_data` and `λ` as before this update.
#[inline(always)]
pub(crate) fn regression_2d(
    out: &mut Pls,
    omega: f64,
    y: f64,
    w: f64,
    ws: &mut PlsScratch,
) -> RegOut {
    let (r, sn) = regression_2d_core(out, omega, y, w, *arr::<2>(&mut ws.xmz));
    *arr(&mut ws.s) = sn;
    r
}

/// [`regression_2d`] on `x̃ = xmz` (a copy of the input), returning the new projections
/// instead of writing them to the scratch: what `fast/group.rs` calls for each RF
/// of a group.
#[inline(always)]
pub(crate) fn regression_2d_core(
    out: &mut Pls,
    omega: f64,
    y: f64,
    w: f64,
    xmz: [f64; 2],
) -> (RegOut, [f64; 2]) {
    let n_data = *arr::<2>(&mut out.n_data);
    let lambda = *arr::<2>(&mut out.lambda);
    out.beta0 = (omega * out.beta0 + w * y) / (omega + w);
    let ymz = y - out.beta0;
    let Pls {
        u,
        p,
        sxy,
        ssx,
        beta,
        ss_s2,
        ss_yres,
        sum_w,
        sum_e_cv2,
        ssp,
        sum_e2,
        beta0,
        ..
    } = out;
    let (u, p, sxy, ssx) = (arr::<4>(u), arr::<4>(p), arr::<4>(sxy), arr::<4>(ssx));
    let (beta, ss_s2, ss_yres) = (arr::<2>(beta), arr::<2>(ss_s2), arr::<2>(ss_yres));
    let (sum_w, sum_e_cv2) = (arr::<2>(sum_w), arr::<2>(sum_e_cv2));
    // Projections with the old directions, keeping the residual inputs.
    let s0 = dot2(&u[0..2], xmz);
    let x1 = [xmz[0] - p[0] * s0, xmz[1] - p[1] * s0];
    let s = [s0, dot2(&u[2..4], x1)];
    let xres = [xmz, x1];
    let mut e_cv = [0.0; 2];
    let mut yres = 0.0;
    for j in 0..2 {
        yres += beta[j] * s[j];
        sum_w[j] = sum_w[j] * lambda[j] + w;
        e_cv[j] = ymz - yres;
    }
    let mut ws2 = 0.0;
    // Numerical guard (`update_regression`): the sum of every `u`, `β`, `p` computed.
    let mut chk = 0.0;
    for j in 0..2 {
        let lam = lambda[j];
        let lam_slow = 0.9 + 0.1 * lam;
        let t = if j == 0 { ymz } else { e_cv[0] };
        let (wt, wsj) = (w * t, w * s[j]);
        let xj = xres[j];
        let mut norm2 = 0.0;
        for k in 0..2 {
            let v = sxy[2 * j + k] * lam_slow + wt * xj[k];
            sxy[2 * j + k] = v;
            norm2 += v * v;
        }
        if norm2 > 1e-24 {
            let inv = 1.0 / norm2.sqrt();
            for k in 0..2 {
                u[2 * j + k] = sxy[2 * j + k] * inv;
                chk += u[2 * j + k];
            }
        }
        ss_s2[j] = lam * ss_s2[j] + s[j] * wsj;
        ss_yres[j] = lam * ss_yres[j] + t * wsj;
        let inv_s2 = 1.0 / ss_s2[j];
        beta[j] = ss_yres[j] * inv_s2;
        chk += beta[j];
        for k in 0..2 {
            let v = lam * ssx[2 * j + k] + wsj * xj[k];
            ssx[2 * j + k] = v;
            p[2 * j + k] = v * inv_s2;
            chk += p[2 * j + k];
        }
        ws2 += wsj * wsj * inv_s2;
    }
    *ssp = lambda[1] * *ssp + ws2;
    // The new projections (`pls::project`).
    let n0 = dot2(&u[0..2], xmz);
    let xu = [xmz[0] - p[0] * n0, xmz[1] - p[1] * n0];
    let sn = [n0, dot2(&u[2..4], xu)];
    // Both directions predict once the second has seen enough data (`Pls::n_pred`).
    let np = if n_data[1] > 4.0 { 2 } else { 1 };
    let ypred: f64 = (0..np).map(|j| beta[j] * sn[j]).sum();
    let e_cv_r = e_cv[np - 1];
    let e = ymz - ypred;
    if n_data[0] * (1.0 - lambda[0]) > 0.1 {
        *sum_e2 = *sum_e2 * lambda[1] + w * e * e;
        for j in 0..2 {
            sum_e_cv2[j] = sum_e_cv2[j] * lambda[j] + w * e_cv[j] * e_cv[j];
        }
    }
    let r = RegOut {
        yp: ypred + *beta0,
        e_cv: e_cv_r,
        e,
        chk,
    };
    (r, sn)
}
