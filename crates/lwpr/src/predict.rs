//! Prediction `ŷ = Σ w ŷ_k / Σ w` over trustworthy RFs with `w > cutoff`, with optional
//! confidence bounds and Jacobian `∂ŷ/∂x`.

use crate::error::{check_len, check_vec};
use crate::model::Lwpr;
use crate::pls::{dot, project};
use crate::rf::SubModel;
use crate::scratch::{quad, same_bits};
use crate::LwprError;

/// How much support a prediction had.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Support {
    /// The smallest, over sub-models, total activation `Σ w` of the RFs that predicted.
    pub sum_w: f64,
}

#[derive(Clone, Copy, PartialEq)]
enum Want {
    Plain,
    Conf,
    Jac,
}

impl Lwpr {
    /// Predicts `y` (length `n_out`) at `x` (length `n_in`).
    ///
    /// Fails with [`LwprError::NoActiveRf`] when, for some output, no trustworthy RF has
    /// `w > cutoff` (the model has no support there); `y` is then left untouched.
    pub fn predict(&mut self, x: &[f64], y: &mut [f64]) -> Result<Support, LwprError> {
        check_len("y", y.len(), self.p.n_out)?;
        let s = self.predict_impl(x, Want::Plain)?;
        y.copy_from_slice(&self.ws.y);
        Ok(s)
    }

    /// Like [`Lwpr::predict`], also writing a confidence bound per output into `conf`
    /// (the reference library's `sqrt(Σ w σ²_k + Σ w (ŷ_k − ŷ)²) / Σ w`, in output units).
    pub fn predict_conf(
        &mut self,
        x: &[f64],
        y: &mut [f64],
        conf: &mut [f64],
    ) -> Result<Support, LwprError> {
        check_len("y", y.len(), self.p.n_out)?;
        check_len("conf", conf.len(), self.p.n_out)?;
        let s = self.predict_impl(x, Want::Conf)?;
        y.copy_from_slice(&self.ws.y);
        conf.copy_from_slice(&self.ws.conf);
        Ok(s)
    }

    /// Like [`Lwpr::predict`], also writing the Jacobian `∂ŷ/∂x` (row-major, `n_out × n_in`,
    /// user units) into `jac`. RFs at `w ≤ cutoff` are left out, as in the reference library.
    pub fn predict_jacobian(
        &mut self,
        x: &[f64],
        y: &mut [f64],
        jac: &mut [f64],
    ) -> Result<Support, LwprError> {
        check_len("y", y.len(), self.p.n_out)?;
        check_len("jac", jac.len(), self.p.n_out * self.p.n_in)?;
        let s = self.predict_impl(x, Want::Jac)?;
        y.copy_from_slice(&self.ws.y);
        jac.copy_from_slice(&self.ws.jac);
        Ok(s)
    }

    /// Predicts every output it can: writes into `support` each output's total activation
    /// `Σ w`, and where that is 0 (no RF active) sets the output to 0 as the reference library
    /// does. Never fails with [`LwprError::NoActiveRf`].
    pub fn predict_with_support(
        &mut self,
        x: &[f64],
        y: &mut [f64],
        support: &mut [f64],
    ) -> Result<(), LwprError> {
        check_len("y", y.len(), self.p.n_out)?;
        check_len("support", support.len(), self.p.n_out)?;
        self.predict_impl_mode(x, Want::Plain, false)?;
        y.copy_from_slice(&self.ws.y);
        support.copy_from_slice(&self.ws.support);
        Ok(())
    }

    fn predict_impl(&mut self, x: &[f64], want: Want) -> Result<Support, LwprError> {
        self.predict_impl_mode(x, want, true)
    }

    fn predict_impl_mode(
        &mut self,
        x: &[f64],
        want: Want,
        strict: bool,
    ) -> Result<Support, LwprError> {
        check_vec("x", x, self.p.n_in)?;
        // A repeated query (same input bits, same kind) on an unchanged model: the results are
        // still in the buffers.
        let key = (want as u8, strict);
        if let Some((k, res)) = self.ws.pred_cache {
            if k == key && same_bits(x, &self.ws.pred_x) {
                return res.map_err(|output| LwprError::NoActiveRf { output });
            }
        }
        let res = self.predict_compute(x, want, strict);
        self.ws.pred_cache = match &res {
            Ok(s) => Some((key, Ok(*s))),
            Err(LwprError::NoActiveRf { output }) => Some((key, Err(*output))),
            Err(_) => None,
        };
        self.ws.pred_x.copy_from_slice(x);
        res
    }

    fn predict_compute(
        &mut self,
        x: &[f64],
        want: Want,
        strict: bool,
    ) -> Result<Support, LwprError> {
        // Plain predictions get a copy of their own, without the branches (and the registers)
        // of the confidence and Jacobian code; each copy is a function of its own.
        #[cfg(target_arch = "x86_64")]
        if crate::simd::has_avx2() {
            // SAFETY: the CPU supports AVX2 (checked at run time).
            return unsafe {
                match want {
                    Want::Plain => self.predict_plain_avx2(x, strict),
                    _ => self.predict_avx2(x, want, strict),
                }
            };
        }
        match want {
            Want::Plain => self.predict_dims::<true, false>(x, want, strict),
            _ => self.predict_dims::<false, false>(x, want, strict),
        }
    }

    /// [`Lwpr::predict_impl_mode`] for plain predictions, compiled with AVX2 (same results,
    /// see `crate::simd`).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    #[inline(never)]
    unsafe fn predict_plain_avx2(&mut self, x: &[f64], strict: bool) -> Result<Support, LwprError> {
        self.predict_dims::<true, true>(x, Want::Plain, strict)
    }

    /// [`Lwpr::predict_impl_mode`] with confidence or Jacobian, compiled with AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    #[inline(never)]
    unsafe fn predict_avx2(
        &mut self,
        x: &[f64],
        want: Want,
        strict: bool,
    ) -> Result<Support, LwprError> {
        self.predict_dims::<false, true>(x, want, strict)
    }

    /// Small input spaces get a copy with constant dimensions (as the update does).
    #[inline(always)]
    fn predict_dims<const PLAIN: bool, const AVX: bool>(
        &mut self,
        x: &[f64],
        want: Want,
        strict: bool,
    ) -> Result<Support, LwprError> {
        match (self.p.nk(), self.p.nr()) {
            (1, 1) => self.predict_core::<1, 1, PLAIN, AVX>(x, want, strict),
            (2, 2) => self.predict_core::<2, 2, PLAIN, AVX>(x, want, strict),
            // The learned controllers' model shapes, as in the update.
            (14, 21) => self.predict_core::<14, 21, PLAIN, AVX>(x, want, strict),
            (7, 21) => self.predict_core::<7, 21, PLAIN, AVX>(x, want, strict),
            (6, 9) => self.predict_core::<6, 9, PLAIN, AVX>(x, want, strict),
            (3, 9) => self.predict_core::<3, 9, PLAIN, AVX>(x, want, strict),
            (21, 21) => self.predict_core::<21, 21, PLAIN, AVX>(x, want, strict),
            _ => self.predict_core::<0, 0, PLAIN, AVX>(x, want, strict),
        }
    }

    #[inline(always)]
    fn predict_core<const NK: usize, const NR: usize, const PLAIN: bool, const AVX: bool>(
        &mut self,
        x: &[f64],
        want: Want,
        strict: bool,
    ) -> Result<Support, LwprError> {
        let want = if PLAIN { Want::Plain } else { want };
        let Lwpr { p, subs, ws, .. } = self;
        ws.load_x(p, x);
        let nk = if NK > 0 { NK } else { p.nk() };
        let nr = if NR > 0 { NR } else { p.nr() };
        let (n_in, ml, ny) = (p.n_in, p.mlen(), p.n_local_out());
        let diag = p.cfg.diag_only;
        let cutoff = p.cfg.cutoff;
        let qb = ws.qb_cutoff;
        let mut min_sw = f64::INFINITY;
        if want == Want::Jac {
            ws.jac.iter_mut().for_each(|v| *v = 0.0);
        }
        for (s, sub) in subs.iter_mut().enumerate() {
            let o0 = s * ny;
            for o in o0..o0 + ny {
                ws.yacc[o] = 0.0;
                ws.wyy[o] = 0.0;
                ws.wconf[o] = 0.0;
            }
            if want == Want::Jac {
                ws.dwdx.iter_mut().for_each(|v| *v = 0.0);
            }
            let SubModel {
                rfs,
                centers,
                ms,
                ds,
            } = sub;
            let kern = if diag { &*ds } else { &*ms };
            let mut sum_w = 0.0;
            if PLAIN && NK == 2 && !diag && !crate::rf_update::general_only() {
                // The 2-D cross test's shape: the active RFs first, their distances four at a
                // time (the same bits), then their sums as in the loop below (`Σ w ŷ` only: a
                // plain prediction needs no confidence).
                ws.active.clear();
                let active = &mut ws.active;
                let xk = [ws.xk[0], ws.xk[1]];
                crate::activation::for_each_q::<AVX>(centers, ms, &xk, |i, q| {
                    // The distance first: most RFs are far, and it is already in a register.
                    if q < qb && rfs[i].trustworthy {
                        let w = p.kernel(q).0;
                        if w > cutoff {
                            active.push((i, w, 0.0, 0.0));
                        }
                    }
                });
                for a in 0..ws.active.len() {
                    let (i, w, _, _) = ws.active[a];
                    let rf = &mut rfs[i];
                    sum_w += w;
                    let xc = &mut ws.pls.xmz[..nr];
                    let (xr, mean_x) = (&ws.xr[..nr], &rf.mean_x[..nr]);
                    for k in 0..nr {
                        xc[k] = xr[k] - mean_x[k];
                    }
                    for (lo, pls) in rf.outs.iter_mut().enumerate() {
                        pls.refresh_slope(nr);
                        let yk = pls.beta0 + dot(&pls.slope[..nr], xc);
                        ws.yacc[o0 + lo] += w * yk;
                    }
                }
            } else {
                let rf_chunks = centers.chunks_exact(nk).zip(kern.chunks_exact(ml));
                for (i, (rf, (c, md))) in rfs.iter_mut().zip(rf_chunks).enumerate() {
                    if !rf.trustworthy {
                        continue;
                    }
                    let q = quad(diag, c, md, &ws.xk[..nk], &mut ws.met.dx, qb);
                    if q >= qb {
                        continue;
                    }
                    let (w, dwdq, _) = p.kernel(q);
                    if w <= cutoff {
                        continue;
                    }
                    sum_w += w;
                    let xc = &mut ws.pls.xmz[..nr];
                    let (xr, mean_x) = (&ws.xr[..nr], &rf.mean_x[..nr]);
                    for k in 0..nr {
                        xc[k] = xr[k] - mean_x[k];
                    }
                    if want == Want::Jac {
                        // ∂w/∂x_K = 2 (dw/dq) D (x − c).
                        let dd = &ds[i * ml..(i + 1) * ml];
                        for k in 0..nk {
                            let dxk = ws.xk[k] - c[k];
                            ws.ddx[k] = if diag { 2.0 * dwdq * dd[k] * dxk } else { 0.0 };
                        }
                        if !diag {
                            for k in 0..nk {
                                ws.met.dx[k] = ws.xk[k] - c[k];
                            }
                            for k in 0..nk {
                                let row = &dd[k * nk..(k + 1) * nk];
                                ws.ddx[k] = 2.0 * dwdq * dot(row, &ws.met.dx);
                            }
                        }
                        for k in 0..nk {
                            ws.dwdx[k] += ws.ddx[k];
                        }
                    }
                    if want != Want::Conf {
                        for pls in rf.outs.iter_mut() {
                            pls.refresh_slope(nr);
                        }
                    }
                    for (lo, pls) in rf.outs.iter().enumerate() {
                        let o = o0 + lo;
                        let yk = if want == Want::Conf {
                            let np = pls.n_pred(nr).max(1);
                            let (xu, sv) = (&mut ws.pls.xu, &mut ws.pls.s);
                            project(&pls.u, &pls.p, nr, np, xc, xu, sv);
                            let mut yk = pls.beta0;
                            let mut ss = 0.0;
                            for j in 0..np {
                                yk += pls.beta[j] * sv[j];
                                ss += sv[j] * sv[j] / pls.ss_s2[j];
                            }
                            let gamma = pls.sum_e_cv2[np - 1] / (pls.sum_w[np - 1] - pls.ssp);
                            ws.wconf[o] += w * gamma * (1.0 + w * ss);
                            yk
                        } else {
                            pls.beta0 + dot(&pls.slope[..nr], xc)
                        };
                        ws.yacc[o] += w * yk;
                        ws.wyy[o] += w * yk * yk;
                        if want == Want::Jac {
                            let row = &mut ws.jac[o * n_in..(o + 1) * n_in];
                            for (k, &d) in p.rdims.iter().enumerate() {
                                row[d] += w * pls.slope[k];
                            }
                            for (k, &d) in p.kdims.iter().enumerate() {
                                row[d] += yk * ws.ddx[k];
                            }
                        }
                    }
                }
            }
            if sum_w <= 0.0 && strict {
                return Err(LwprError::NoActiveRf { output: o0 });
            }
            min_sw = min_sw.min(sum_w);
            if sum_w <= 0.0 {
                for o in o0..o0 + ny {
                    ws.y[o] = 0.0;
                    ws.support[o] = 0.0;
                }
                continue;
            }
            for o in o0..o0 + ny {
                ws.support[o] = sum_w;
                let yn = ws.yacc[o] / sum_w;
                let no = p.norm_out[o];
                ws.y[o] = yn * no;
                if want == Want::Conf {
                    let r = ws.wconf[o] + ws.wyy[o] - ws.yacc[o] * yn;
                    ws.conf[o] = r.abs().sqrt() / sum_w * no;
                }
                if want == Want::Jac {
                    let row = &mut ws.jac[o * n_in..(o + 1) * n_in];
                    for (k, &d) in p.kdims.iter().enumerate() {
                        row[d] -= yn * ws.dwdx[k];
                    }
                    for (d, v) in row.iter_mut().enumerate() {
                        *v *= no / (sum_w * p.norm_in[d]);
                    }
                }
            }
        }
        Ok(Support { sum_w: min_sw })
    }
}
