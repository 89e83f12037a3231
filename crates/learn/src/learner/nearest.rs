//! The nearest trained controllers, where the blend's support is thin
//! (`controllers.neighbour_cutoff`; `docs/learner.md`, "Thin support").
//!
//! Where `S = Σ c_i w̃_i < w0` the command fades its blend by `κ = smoothstep(S / w0)`. The
//! share `1 − κ` went to `u0` alone, whose PD pull to the rest posture takes the arm out of the
//! trained region for good (rest lies outside it). It goes instead to the blend of the trained
//! controllers near the state, weighted relative to the nearest one:
//!
//! ```text
//! v_i = c_i w_i / max_k c_k w_k − ε,   ū_far = Σ_{v_i > 0} v_i (u^i − u0)(x_i) / Σ v_i
//! ```
//!
//! (`ε` the relative taper, so a field leaves the blend at weight 0), each controller evaluated
//! at the state `x_i` pulled radially into its field's support (where `w_i` equals the blend's
//! cutoff), so a far state does not extrapolate a linear controller without bound. Pulled in,
//! `u0(x) + (u^i − u0)(x_i)` is the field's command at its edge plus `u0`'s change from there:
//! `ĝ`'s difference, and a PD pull towards the field's edge instead of towards rest. `ū_far`
//! fades into `u0` by `λ = smoothstep(t)`, `t = ln(w_max / w_far) / ln(w_cut / w_far)` of the
//! nearest confidence-weighted activation `w_max`, from 1 at the blend's cutoff to 0 at
//! `w_far` (`neighbour_cutoff`): far from every trained field the command is `u0` as before,
//! and it is continuous in the state everywhere.

use super::{Learner, State};
use crate::error::Result;
use crate::local::{confidence, smoothstep};

/// Relative taper of the neighbours' weights: `v_i = c_i w_i / max − NEIGHBOUR_TAPER`.
pub(crate) const NEIGHBOUR_TAPER: f64 = 0.05;

impl Learner {
    /// `λ ū_far` (module doc) at `(q, q̇)` for `xdd_ref` into `ws.u_far`; `false` (and
    /// `ws.u_far` unspecified) where the option is off or no trained field is above
    /// `neighbour_cutoff`. The common part of `ws.phi` is left as `(xdd_ref, q̇)` sets it.
    /// Does not allocate.
    ///
    /// # Errors
    /// A model failure.
    pub(super) fn nearest_blend(&mut self, q: &[f64], qd: &[f64], xdd_ref: &[f64]) -> Result<bool> {
        let far = self.cfg.controllers.neighbour_cutoff;
        let n = q.len();
        let State::Ready(models) = &mut self.state else {
            return Ok(false);
        };
        if !(far > 0.0) {
            return Ok(false);
        }
        let (ws, f) = (&mut self.ws, &self.features);
        let trained_ess = self.cfg.controllers.trained_ess;
        let (cut, spread) = (
            self.cfg.partition.activation_cutoff,
            self.cfg.controllers.step_spread,
        );
        models.forward.activations(q, qd, far, &mut ws.acts_far)?;
        let top = ws.acts_far.iter().fold(0.0f64, |top, a| {
            let c = (models.locals.map.get(&a.id)).map_or(0.0, |l| confidence(l.ess, trained_ess));
            top.max(c * a.w)
        });
        if !(top > far) {
            return Ok(false);
        }
        let lambda = smoothstep((top / far).ln() / (cut / far).ln());
        let ln_cut = cut.ln();
        ws.u_far.fill(0.0);
        let mut sum = 0.0;
        for a in &ws.acts_far {
            let Some(local) = models.locals.map.get(&a.id) else {
                continue;
            };
            let v = confidence(local.ess, trained_ess) * a.w / top - NEIGHBOUR_TAPER;
            if !(v > 0.0) {
                continue;
            }
            // Pulled radially into the field's support: `w = exp(−d²/2)`, so the factor
            // `√(ln w_cut / ln w)` takes the state to where `w = w_cut`.
            let k = if a.w < cut {
                (ln_cut / a.w.ln()).sqrt()
            } else {
                1.0
            };
            let c = &local.center;
            for i in 0..n {
                ws.q_pull[i] = c[i] + k * (q[i] - c[i]);
                ws.qd_pull[i] = c[n + i] + k * (qd[i] - c[n + i]);
            }
            f.controller_common(&mut ws.phi, xdd_ref, &ws.qd_pull);
            f.controller_local(&mut ws.phi, &ws.q_pull, c);
            local.mean_held(&ws.phi, spread, &mut ws.ui, &mut ws.ui_from)?;
            for (o, x) in ws.u_far.iter_mut().zip(&ws.ui) {
                *o += v * x;
            }
            sum += v;
        }
        ws.u_far.iter_mut().for_each(|o| *o *= lambda / sum);
        f.controller_common(&mut ws.phi, xdd_ref, qd);
        Ok(true)
    }
}
