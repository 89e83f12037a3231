//! The learned command (eq. 34): the activation-weighted blend of the trained local controllers
//! plus `u0`, extrapolated from the nearest trained ones where none is active, the nominal `u0`
//! where none is near, exploration on top, then the guards (non-finite blend, torque limits).

use super::exploration::explore;
use super::nominal::nominal_into;
use super::{Learner, State};
use crate::error::{LearnError, Result};
use rand::Rng;

/// What produced a command.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CommandSource {
    /// The blend of the trained local controllers (eq. 34).
    Learned,
    /// No trained controller active above the cutoff: the blend of the nearest ones (any
    /// activation above [`EXTRAPOLATION_CUTOFF`]).
    Extrapolated,
    /// No trained controller anywhere near: the nominal `u0`.
    Fallback,
}

/// Activation cutoff of the extrapolating blend.
pub const EXTRAPOLATION_CUTOFF: f64 = 1e-12;

/// A blend's weights: `Σ w_i` and `Σ w_i σ_i` of the controllers in it.
struct Blend {
    sum_w: f64,
    sum_sigma: f64,
    source: CommandSource,
}

impl Learner {
    /// The learned command for the reference acceleration `xdd_ref` at `(q, q̇)` into `u`: the
    /// blend (eq. 34), with exploration noise when `rng` is given, clipped to the torque limits.
    /// Stages: check → blend → nominal → explore → guard → clip. Does not allocate.
    ///
    /// # Errors
    /// [`LearnError::Dimension`] on wrong slice lengths (nothing counted); a model failure; or
    /// [`LearnError::NonFinite`] if even `u0` is not finite.
    pub fn command<R: Rng + ?Sized>(
        &mut self,
        q: &[f64],
        qd: &[f64],
        xdd_ref: &[f64],
        rng: Option<&mut R>,
        u: &mut [f64],
    ) -> Result<CommandSource> {
        self.check_command_args(q, qd, xdd_ref, u)?;
        self.stats.commands += 1;
        let source = match self.blend(q, qd, xdd_ref, u)? {
            None => self.fallback(q, qd, u)?,
            Some(blend) => self.finish_blend(q, qd, blend, rng, u)?,
        };
        let source = self.guard_non_finite(q, qd, source, u)?;
        self.clip(u);
        Ok(source)
    }

    fn check_command_args(&self, q: &[f64], qd: &[f64], xdd_ref: &[f64], u: &[f64]) -> Result<()> {
        let (n, m) = (self.n, self.m);
        if q.len() != n || qd.len() != n || u.len() != n || xdd_ref.len() != m {
            return Err(LearnError::Dimension {
                what: "command arguments",
                expected: n,
                got: q.len(),
            });
        }
        Ok(())
    }

    /// Eq. 34 without `u0`: `Σ w_i u^i` into `u` over the trained controllers active above the
    /// cutoff, or, if there are none, over those with any activation (extrapolation). `None`
    /// before the warm-up ends or where no trained controller is near.
    fn blend(
        &mut self,
        q: &[f64],
        qd: &[f64],
        xdd_ref: &[f64],
        u: &mut [f64],
    ) -> Result<Option<Blend>> {
        let State::Ready(models) = &mut self.state else {
            return Ok(None);
        };
        let (ws, f) = (&mut self.ws, &self.features);
        let trained_ess = self.cfg.controllers.trained_ess;
        f.controller_common(&mut ws.phi, xdd_ref, qd);
        let mut source = CommandSource::Learned;
        let (mut sum_w, mut sum_sigma) = (0.0, 0.0);
        for cut in [self.cfg.partition.activation_cutoff, EXTRAPOLATION_CUTOFF] {
            models.forward.activations(q, qd, cut, &mut ws.acts)?;
            u.fill(0.0);
            for a in &ws.acts {
                let Some(local) = models.locals.map.get(&a.id) else {
                    continue;
                };
                if local.untrained(trained_ess) {
                    continue;
                }
                f.controller_local(&mut ws.phi, q, &local.center);
                local.rwr.mean_into(&ws.phi, &mut ws.ui)?;
                for (o, v) in u.iter_mut().zip(&ws.ui) {
                    *o += a.w * v;
                }
                sum_w += a.w;
                sum_sigma += a.w * local.rwr.sigma();
            }
            if sum_w > 0.0 {
                break;
            }
            source = CommandSource::Extrapolated;
        }
        if sum_w <= 0.0 {
            return Ok(None);
        }
        Ok(Some(Blend {
            sum_w,
            sum_sigma,
            source,
        }))
    }

    /// Normalises the blend, adds `u0` (residual controllers) and the exploration noise.
    fn finish_blend<R: Rng + ?Sized>(
        &mut self,
        q: &[f64],
        qd: &[f64],
        blend: Blend,
        rng: Option<&mut R>,
        u: &mut [f64],
    ) -> Result<CommandSource> {
        if blend.source == CommandSource::Extrapolated {
            self.stats.extrapolations += 1;
        }
        let sigma = self.cfg.exploration.scale * blend.sum_sigma / blend.sum_w;
        for v in u.iter_mut() {
            *v /= blend.sum_w;
        }
        if self.cfg.experimental.residual {
            let u0 = &mut self.ws.u0;
            nominal_into(&self.cfg.nominal, self.state.models_mut(), self.gravity_frozen, q, qd, u0)?;
            for (v, o) in u.iter_mut().zip(u0.iter()) {
                *v += o;
            }
        }
        if let (Some(rng), State::Ready(models)) = (rng, &self.state) {
            explore(&self.cfg, &self.features, models, &mut self.ws, q, sigma, rng, u);
        }
        Ok(blend.source)
    }

    /// The nominal `u0` as the command where no trained controller is near (counted).
    fn fallback(&mut self, q: &[f64], qd: &[f64], u: &mut [f64]) -> Result<CommandSource> {
        self.stats.fallbacks += 1;
        self.nominal(q, qd, u)?;
        Ok(CommandSource::Fallback)
    }

    /// Guard: a non-finite blend (a diverged local model) falls back to `u0`, counted.
    fn guard_non_finite(
        &mut self,
        q: &[f64],
        qd: &[f64],
        source: CommandSource,
        u: &mut [f64],
    ) -> Result<CommandSource> {
        if u.iter().all(|v| v.is_finite()) {
            return Ok(source);
        }
        self.stats.non_finite += 1;
        let source = self.fallback(q, qd, u)?;
        if u.iter().any(|v| !v.is_finite()) {
            return Err(LearnError::NonFinite("the nominal command u0"));
        }
        Ok(source)
    }

    /// Guard: every joint within its torque limit; a command with a clipped joint is counted.
    fn clip(&mut self, u: &mut [f64]) {
        let mut clipped = false;
        for (v, lim) in u.iter_mut().zip(&self.cfg.guards.torque_limits) {
            let c = v.clamp(-lim, *lim);
            clipped |= c != *v;
            *v = c;
        }
        self.stats.clipped += clipped as u64;
    }
}
