//! A prediction defined everywhere (not in the reference library): the normalised blend of the
//! trustworthy RFs with the cutoff taken *relative to the nearest RF* and tapered, `ŷ = Σ v_k ŷ_k
//! / Σ v_k` with `v_k = w_k / w_max − cutoff` over `w_k > cutoff · w_max`, each RF's local model
//! evaluated at the input pulled radially into that RF's support ellipsoid (where `w ≥ cutoff`),
//! in logarithms so that nothing underflows far from the data.
//!
//! Where [`Lwpr::predict`] drops an RF whose activation falls to the cutoff (its prediction jumps
//! by the RF's share, a large one where `Σ w` is small) and fails where none is left, this one is
//! continuous in `x` and finite wherever one RF is trustworthy: far from every RF it tends to the
//! nearest one's model at the edge of its support. Where the nearest RF is fully active (`w_max`
//! near 1) it blends the same RFs as [`Lwpr::predict`], each weight lowered by about the cutoff.

use crate::distance::quad;
use crate::error::{check_len, check_vec};
use crate::model::Lwpr;
use crate::numeric::dot;
use crate::params::Params;
use crate::rf::SubModel;
use crate::scratch::Scratch;
use crate::{Kernel, LwprError};

/// `ln w` of an RF at squared distance `q` (`−∞` outside a bisquare's support).
#[inline(always)]
fn ln_w(p: &Params, q: f64) -> f64 {
    match p.cfg.kernel {
        Kernel::Gaussian => -0.5 * q,
        Kernel::Bisquare => {
            let a = 1.0 - 0.25 * q;
            if a > 0.0 {
                2.0 * a.ln()
            } else {
                f64::NEG_INFINITY
            }
        }
    }
}

impl Lwpr {
    /// Predicts `y` at `x` from the trustworthy RFs near the nearest one (module doc); returns
    /// `ln S`, `S = w_max Σ_k v_k` the tapered total activation (very negative far from every
    /// RF, never `−∞` there; continuous; the smallest over the sub-models). Does not allocate; does not use or change the cached prediction.
    ///
    /// # Errors
    /// [`LwprError::NoActiveRf`] when a sub-model has no trustworthy RF with `w > 0`;
    /// [`LwprError::PredictionOverflow`] when the blend overflows; wrong lengths; a non-finite
    /// input. On an error `y` is untouched.
    pub fn predict_everywhere(&mut self, x: &[f64], y: &mut [f64]) -> Result<f64, LwprError> {
        check_vec("x", x, self.p.n_in)?;
        check_len("y", y.len(), self.p.n_out)?;
        let (p, ws) = (&self.p, &mut self.ws);
        ws.load_x(p, x);
        let ny = p.n_local_out();
        let mut min_ln = f64::INFINITY;
        for (s, sub) in self.subs.iter_mut().enumerate() {
            let o0 = s * ny;
            let ln_sum = sub_everywhere(p, sub, ws, o0);
            if ln_sum == f64::NEG_INFINITY {
                return Err(LwprError::NoActiveRf { output: o0 });
            }
            min_ln = min_ln.min(ln_sum);
        }
        // Checked before `y` is written (`ws.y` holds the cached prediction: not used here).
        let value = |o: usize| ws.yacc[o] * p.norm_out[o];
        if let Some(output) = (0..y.len()).find(|&o| !value(o).is_finite()) {
            let value = value(output);
            return Err(LwprError::PredictionOverflow { output, value });
        }
        for (o, v) in y.iter_mut().enumerate() {
            *v = value(o);
        }
        Ok(min_ln)
    }
}

/// The blend of sub-model `sub` (outputs `o0..`) at the input in `ws`, normalised, into
/// `ws.yacc`; returns `ln S` (`−∞`: no trustworthy RF).
///
/// Two passes: the largest activation `w_max`, then the RFs with `w_k > ε w_max` (`ε` the
/// cutoff), weighted `v_k = w_k / w_max − ε` — continuous in `x` (`w_max` is) and never all 0,
/// and exactly 0 for the RFs skipped. `S = w_max Σ v_k`.
fn sub_everywhere(p: &Params, sub: &mut SubModel, ws: &mut Scratch, o0: usize) -> f64 {
    let (nk, nr, ny, ml) = (p.nk(), p.nr(), p.n_local_out(), p.mlen());
    let (diag, eps) = (p.cfg.diag_only, p.cfg.cutoff.max(0.0));
    let q_edge = ws.qb_cutoff;
    let SubModel {
        rfs,
        centers,
        ms,
        ds,
        ..
    } = sub;
    let kern = if diag { &*ds } else { &*ms };
    // Pass 1: the nearest RF's ln w.
    let mut top = f64::NEG_INFINITY;
    let mut bound = f64::INFINITY;
    let rf_chunks = centers.chunks_exact(nk).zip(kern.chunks_exact(ml));
    for (rf, (c, md)) in rfs.iter().zip(rf_chunks) {
        if rf.trustworthy {
            let q = quad(false, diag, c, md, &ws.xk[..nk], &mut ws.met.dx, bound);
            if q < bound {
                bound = q;
                top = top.max(ln_w(p, q));
            }
        }
    }
    if top == f64::NEG_INFINITY {
        return top;
    }
    // Pass 2: the RFs above ε of the nearest.
    let ln_eps = eps.ln();
    // Beyond this the Gaussian's relative weight is ≤ ε (a bisquare's RFs are few: no bound).
    let q_far = match p.cfg.kernel {
        Kernel::Gaussian => bound - 2.0 * ln_eps,
        Kernel::Bisquare => f64::INFINITY,
    };
    let acc = &mut ws.yacc[o0..o0 + ny];
    acc.fill(0.0);
    let mut sum_v = 0.0;
    let rf_chunks = centers.chunks_exact(nk).zip(kern.chunks_exact(ml));
    for (rf, (c, md)) in rfs.iter_mut().zip(rf_chunks) {
        if !rf.trustworthy {
            continue;
        }
        let q = quad(false, diag, c, md, &ws.xk[..nk], &mut ws.met.dx, q_far);
        let rel = ln_w(p, q) - top;
        if rel <= ln_eps {
            continue;
        }
        let v = rel.exp() - eps;
        sum_v += v;
        // The regression input, with the kernel dimensions pulled onto the support's edge.
        let xr: &[f64] = if q > q_edge {
            let f = (q_edge / q).sqrt();
            ws.xr_pull[..nr].copy_from_slice(&ws.xr[..nr]);
            for k in 0..nk {
                let r = ws.k_to_r[k];
                if r < nr {
                    ws.xr_pull[r] = c[k] + f * (ws.xk[k] - c[k]);
                }
            }
            &ws.xr_pull[..nr]
        } else {
            &ws.xr[..nr]
        };
        let xc = &mut ws.pls.xmz[..nr];
        for k in 0..nr {
            xc[k] = xr[k] - rf.mean_x[k];
        }
        for (lo, pls) in rf.outs.iter_mut().enumerate() {
            pls.refresh_slope(nr);
            acc[lo] += v * (pls.beta0 + dot(&pls.slope[..nr], xc));
        }
    }
    if sum_v.is_nan() || sum_v <= 0.0 {
        return f64::NEG_INFINITY;
    }
    acc.iter_mut().for_each(|a| *a /= sum_v);
    top + sum_v.ln()
}

#[cfg(test)]
mod tests {
    use crate::{Lwpr, LwprConfig, LwprError, MetricInit};

    /// A 1-D model of `sin` learned on `[−1, 1]` (fixed kernels, several RFs).
    fn sine_model() -> Lwpr {
        let cfg = LwprConfig {
            init_d: MetricInit::Scalar(50.0),
            update_d: false,
            ..LwprConfig::default()
        };
        let mut m = Lwpr::new(1, 1, &cfg).unwrap();
        for k in 0..20_000 {
            let x = ((k as f64) * 0.618_033_988_7).fract() * 2.0 - 1.0;
            m.update(&[x], &[x.sin()]).unwrap();
        }
        m
    }

    /// The largest change of `predict_everywhere` between neighbours of a grid of `steps` on
    /// `[−4, 4]` (every prediction must succeed and be finite).
    fn largest_step(m: &mut Lwpr, steps: usize) -> f64 {
        let (mut prev, mut largest, mut y) = (None::<f64>, 0.0f64, [0.0]);
        for k in 0..=steps {
            let x = -4.0 + 8.0 * k as f64 / steps as f64;
            m.predict_everywhere(&[x], &mut y).unwrap();
            assert!(y[0].is_finite(), "x = {x}");
            if let Some(p) = prev {
                largest = largest.max((y[0] - p).abs());
            }
            prev = Some(y[0]);
        }
        largest
    }

    /// Inside the data it agrees with `predict`; outside, where `predict` has no support, it is
    /// the edge value of the nearest RF (constant far out); across every RF's cutoff it has no
    /// step: four times finer steps shrink the largest change about fourfold.
    #[test]
    fn continuous_everywhere_and_equal_to_predict_inside() {
        let mut m = sine_model();
        assert!(m.n_rfs_total() > 3);
        let (mut a, mut b) = ([0.0], [0.0]);
        for x in [-0.9, -0.3, 0.0, 0.4, 0.8] {
            m.predict(&[x], &mut a).unwrap();
            let ln_s = m.predict_everywhere(&[x], &mut b).unwrap();
            assert!((a[0] - b[0]).abs() < 1e-3, "x = {x}: {a:?} vs {b:?}");
            assert!(ln_s > -1.0, "support at {x}: {ln_s}");
        }
        assert!(matches!(
            m.predict(&[5.0], &mut a),
            Err(LwprError::NoActiveRf { .. })
        ));
        let ln_far = m.predict_everywhere(&[5.0], &mut a).unwrap();
        let ln_farther = m.predict_everywhere(&[50.0], &mut b).unwrap();
        assert!(ln_farther < ln_far && ln_far < -10.0);
        assert!((a[0] - b[0]).abs() < 1e-9, "{a:?} vs {b:?}");
        // The nearest RF's edge lies beyond the data: sin(1) extrapolated a little.
        assert!((a[0] - 1.0f64.sin()).abs() < 0.3, "{a:?}");
        let (coarse, fine) = (largest_step(&mut m, 2000), largest_step(&mut m, 8000));
        assert!(fine < 0.35 * coarse, "a step: {fine} vs {coarse}");
    }

    /// Without a trustworthy RF it fails as `predict` does, leaving `y` untouched.
    #[test]
    fn an_empty_model_has_no_support() {
        let mut m = Lwpr::new(2, 1, &LwprConfig::default()).unwrap();
        let mut y = [7.0];
        assert!(matches!(
            m.predict_everywhere(&[0.0, 0.0], &mut y),
            Err(LwprError::NoActiveRf { .. })
        ));
        assert_eq!(y, [7.0]);
    }
}
