//! The null-space correction of `u0` (`gravity.null_correction`; `docs/learner.md`,
//! "Null-space correction"): a model `r(q)` of what `ĝ` and the load correction `c` miss at the
//! holds at path postures, `u − ĝ(q) − c(q)` from still samples (where `u = g(q)`), enters the
//! command only through its part in the null space of the blended `Â`:
//!
//! ```text
//! u ← u + (I − Â⁺Â) r(q) · S / (S + S0)
//! ```
//!
//! with `S` the model's total activation at `q` and `S0 = gravity.null_support`, so a new field
//! fades in. To first order `Â (I − Â⁺Â) = 0`: the task acceleration the trained controllers
//! learned to produce does not move, where a change of `ĝ` itself would move it by `Â Δĝ`
//! (`docs/decisions.md`, D25: holds that retrained `ĝ` made the tracking worse). The relabelling
//! counts the correction as part of `u0`, so neither the local controllers nor the load
//! correction learn it.
//!
//! With the global scale (`null_scale.rs`) learned, `r(q) · S / (S + S0)` becomes
//! `r(q) · S / (S + S0) + a (k ĝ(q) − c(q))`, `a` the scale's share: where one scale of `ĝ`
//! explains the holds, it carries their gravity error to every posture, and the load correction
//! keeps its task part only. At a held posture `u0`'s null-space part is the measured gravity's
//! for the `(a, k)` of that hold (the fields keep the targets they were taught).

use super::load::LoadCorrection;
use super::nominal::gravity_into;
use super::stats::Scratch;
use super::{Learner, Models};
use crate::config::LearnerConfig;
use crate::error::Result;
use crate::gravity::GravityModel;
use osrl_dynamics::Measurement;

/// Whether the correction's global part learns and acts (`null_scale.rs`):
/// `gravity.null_scale`, or a re-adapting learner with `adaptation.null_scale`.
pub(crate) fn scale_on(cfg: &LearnerConfig) -> bool {
    cfg.gravity.null_scale || (cfg.adaptation.enabled && cfg.adaptation.null_scale)
}

/// The faded correction at `q` into `ws.z`, projected with the `Â` in `ws.a_hat` (in the cost's
/// metric); `false` (and `ws.z` unspecified) where there is none: the option off, no trustworthy
/// field yet and no global scale, or a singular `Â N⁻¹ Âᵀ`. With the global scale learned, the
/// correction is `k ĝ(q) + r(q) − c(q)` before the projection: the null-space part of `u0` is
/// then `ĝ`'s, the scale's and the holds' model's, and the load correction `c` (at the
/// activations in `ws.acts`) keeps its task part only. Does not allocate.
///
/// # Errors
/// A model failure (a non-finite prediction).
pub(crate) fn null_correction_into_z(
    cfg: &LearnerConfig,
    models: &mut Models,
    ws: &mut Scratch,
    q: &[f64],
    frozen: bool,
    load: &LoadCorrection,
) -> Result<bool> {
    if !cfg.gravity.null_correction {
        return Ok(false);
    }
    let share = match scale_on(cfg) {
        true => models.null_scale.share(cfg.gravity.null_scale_explained),
        false => 0.0,
    };
    let global = share > 0.0;
    let local = match models.gravity_null.as_mut() {
        Some(r) => r.predict_everywhere(q, &mut ws.z)?,
        None => None,
    };
    match local {
        Some(ln_s) => {
            // S / (S + S0) = 1 / (1 + S0 / S), from the logarithm (no overflow or underflow).
            let fade = 1.0 / (1.0 + (cfg.gravity.null_support.ln() - ln_s).exp());
            ws.z.iter_mut().for_each(|v| *v *= fade);
        }
        None if global => ws.z.fill(0.0),
        None => return Ok(false),
    }
    if global {
        // z += a (k ĝ − c).
        gravity_into(&cfg.gravity, Some(&mut *models), frozen, q, &mut ws.g_null)?;
        ws.c_null.fill(0.0);
        load.add_into(&ws.acts, &mut ws.c_null);
        let k = models.null_scale.scale();
        for ((z, g), c) in ws.z.iter_mut().zip(&ws.g_null).zip(&ws.c_null) {
            *z += share * (k * g - c);
        }
    }
    Ok(super::metric::project_scratch_z(models.metric.as_ref(), ws))
}

/// The correction's model for `n` joints: the static gravity model's kind (kernel and
/// regression on `q`, still samples within the static gate's budget per posture) with the ridge
/// `gravity.null_ridge` on its fields' slopes.
fn new_model(cfg: &LearnerConfig, n: usize, torque_scale: &[f64]) -> Result<GravityModel> {
    let mut lwpr = cfg.gravity.lwpr.clone();
    lwpr.init_s2 = lwpr.init_s2.max(cfg.gravity.null_ridge);
    // The kernel and the regression use `q` only: the acceleration scale is unused.
    GravityModel::new_static(
        n,
        &lwpr,
        cfg.gravity.static_gate.unwrap_or_default(),
        cfg.partition.velocity_scale,
        1.0,
        torque_scale,
    )
}

/// One hold's targets for the holds' model, in place of each row's `e` (rows `q0, q̇0, q1, q̇1,
/// e, c, ĝ, dt`, `e = u − ĝ(q1)`, `c` the load correction there): `e − c` without the global
/// scale; with it (`null_scale.rs`) the scale first learns the hold if `learns`, then the
/// targets are `e − a k ĝ(q1) − (1 − a) c` with the updated scale `k` and share `a`, what the
/// global part and the load correction's remaining part leave. Allocates per hold.
fn hold_targets(
    cfg: &LearnerConfig,
    models: &mut Models,
    learns: bool,
    rows: &mut [f64],
    n: usize,
) {
    let width = 7 * n + 1;
    let on = scale_on(cfg);
    let gate = cfg.gravity.null_scale_explained;
    if on && learns {
        let (g, e): (Vec<f64>, Vec<f64>) = rows
            .chunks_exact(width)
            .flat_map(|row| (0..n).map(move |j| (row[6 * n + j], row[4 * n + j])))
            .unzip();
        let gc = &cfg.gravity;
        let (memory, ridge) = (gc.null_scale_memory, gc.null_scale_ridge);
        (models.null_scale).learn_hold(&g, &e, &models.torque_scale, memory, ridge);
    }
    let share = match on {
        true => models.null_scale.share(gate),
        false => 0.0,
    };
    let k = models.null_scale.scale();
    for row in rows.chunks_exact_mut(width) {
        let (e, rest) = row[4 * n..7 * n].split_at_mut(n);
        let (c, g) = rest.split_at(n);
        if share > 0.0 {
            for ((ej, cj), gj) in e.iter_mut().zip(c).zip(g) {
                *ej = *ej - share * k * gj - (1.0 - share) * cj;
            }
        } else {
            e.iter_mut().zip(c).for_each(|(ej, cj)| *ej -= cj);
        }
    }
}

impl Learner {
    /// `u0` as the command adds it, into `u0`: `ĝ` and the pull to rest ([`Learner::nominal`]),
    /// the load correction `c`, and the null-space correction under the `Â` of the command's
    /// blend at `(q, q̇)`. Returns whether `ĝ` had support. The evaluation's `nominal_nmse`.
    ///
    /// # Errors
    /// A model failure; slices must have `n` entries.
    pub fn nominal_in_command(&mut self, q: &[f64], qd: &[f64], u0: &mut [f64]) -> Result<bool> {
        let known = self.nominal(q, qd, u0)?;
        let super::State::Ready(models) = &mut self.state else {
            return Ok(known);
        };
        let (cfg, ws) = (&self.cfg, &mut self.ws);
        let cut = cfg.partition.activation_cutoff;
        models.forward.activations(q, qd, cut, &mut ws.acts)?;
        if cfg.experimental.residual {
            self.load.add_into(&ws.acts, u0);
        }
        // Its own `Â` at this state, not a command's (`command_gains`).
        self.with_fresh_gains(|l| l.add_null_correction(q, u0))?;
        Ok(known)
    }

    /// Keeps the transition `prev → cur` of a hold at a path posture for the null-space
    /// correction if it is still (the static gate): the gravity error `u − ĝ(q)` and the load
    /// correction `c(q)` at `cur`. The correction learns a hold's samples at its end
    /// ([`Learner::end_hold`]), with the target `u − ĝ − c` (or, with the global scale, what it
    /// leaves: `hold_targets`).
    ///
    /// # Errors
    /// A model failure; nothing before the models exist.
    pub(super) fn learn_null_gravity(
        &mut self,
        prev: &Measurement,
        cur: &Measurement,
    ) -> Result<()> {
        let dt = cur.t - prev.t;
        let super::State::Ready(models) = &mut self.state else {
            return Ok(());
        };
        let gate = self.cfg.gravity.static_gate.unwrap_or_default();
        if !(dt > 0.0) || !gate.is_still(prev.qd.as_slice(), cur.qd.as_slice(), dt) {
            return Ok(());
        }
        let (cfg, ws) = (&self.cfg, &mut self.ws);
        let (q, qd, u) = (cur.q.as_slice(), cur.qd.as_slice(), cur.u.as_slice());
        gravity_into(
            &cfg.gravity,
            Some(models),
            self.gravity_frozen,
            q,
            &mut ws.z,
        )?;
        ws.load_c.fill(0.0);
        if !self.load.is_empty() && cfg.experimental.residual {
            let cut = cfg.partition.activation_cutoff;
            models.forward.activations(q, qd, cut, &mut ws.acts)?;
            self.load.add_into(&ws.acts, &mut ws.load_c);
        }
        for ((p, ui), g) in ws.pi.iter_mut().zip(u).zip(&ws.z) {
            *p = ui - g;
        }
        let row = &mut self.hold.rows;
        row.extend_from_slice(prev.q.as_slice());
        row.extend_from_slice(prev.qd.as_slice());
        row.extend_from_slice(q);
        row.extend_from_slice(qd);
        row.extend_from_slice(&ws.pi);
        row.extend_from_slice(&ws.load_c);
        row.extend_from_slice(&ws.z);
        row.push(dt);
        Ok(())
    }

    /// The end of a hold at a path posture (the training driver's `posture_holds`): the
    /// null-space correction learns the hold's still samples if there are at least
    /// `gravity.null_min_samples` of them, else none; either way they are dropped. A hold cut
    /// short (a run that ends in it) thus never leaves a field fitted to a few samples. The
    /// model is made at its first samples, so a controller trained without it can learn one.
    /// While the re-adaptation has detected a change, the budget of samples per posture is
    /// lifted, so postures held before the change learn the changed robot.
    ///
    /// # Errors
    /// A model failure (the model keeps the samples learned before it).
    pub fn end_hold(&mut self) -> Result<()> {
        let mut rows = std::mem::take(&mut self.hold.rows);
        let n = self.n;
        let width = 7 * n + 1;
        let super::State::Ready(models) = &mut self.state else {
            return Ok(());
        };
        let result = if rows.len() / width >= self.cfg.gravity.null_min_samples.max(1) {
            if models.gravity_null.is_none() {
                models.gravity_null = Some(new_model(&self.cfg, n, &models.torque_scale)?);
            }
            // The global scale learns while a change is re-adapted (or always, with the option).
            let learns = self.cfg.gravity.null_scale || self.adapt.readapting();
            hold_targets(&self.cfg, models, learns, &mut rows, n);
            let r = models.gravity_null.as_mut().expect("made above");
            // While a detected change is re-adapted, the postures already held must learn again.
            r.set_unbudgeted(self.adapt.readapting());
            rows.chunks_exact(width).try_for_each(|s| {
                let (q0, rest) = s.split_at(n);
                let (qd0, rest) = rest.split_at(n);
                let (q1, rest) = rest.split_at(n);
                let (qd1, rest) = rest.split_at(n);
                let (target, rest) = rest.split_at(n);
                r.learn(q0, qd0, q1, qd1, target, rest[2 * n])
            })
        } else {
            Ok(())
        };
        // Keep the buffer's capacity for the next hold.
        self.hold.rows = rows;
        self.hold.rows.clear();
        result
    }
}
