//! The learner's models once the warm-up is over: the gravity model `ĝ` (and its static
//! variant), the forward model (the partition) and the local controllers on it; made from the
//! warm-up's scales.

use crate::config::LearnerConfig;
use crate::error::{LearnError, Result};
use crate::forward::ForwardModel;
use crate::gravity::GravityModel;
use crate::local::LocalControllers;
use osrl_dynamics::Measurement;
use serde::{Deserialize, Serialize};

/// Everything the learner has learned.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub(crate) struct Models {
    pub gravity: GravityModel,
    /// The static gravity model (`gravity.static_gate`), used for `u0` once `ĝ` is frozen.
    pub gravity_static: Option<GravityModel>,
    /// The null-space correction's model (`gravity.null_correction`, `null_gravity.rs`): made
    /// at its first sample, so a controller trained without it can learn one later.
    pub gravity_null: Option<GravityModel>,
    /// The null-space correction's global part (`gravity.null_scale`, `null_scale.rs`); saved
    /// (format 13).
    pub null_scale: super::null_scale::NullScale,
    pub forward: ForwardModel,
    pub locals: LocalControllers,
    /// Standard deviation of each joint's torque during the warm-up (N·m).
    pub torque_scale: Vec<f64>,
    /// Bounds `[lo, hi]` of each joint's learned velocity gain `β_{q̇_j, j}` (`inertia.rs`),
    /// from the warm-up; empty: none (also after loading: the saved gains were bounded).
    #[serde(skip)]
    pub velocity_gain_lo: Vec<f64>,
    #[serde(skip)]
    pub velocity_gain_hi: Vec<f64>,
    /// Buffer of the static model's `ĝ` while blending (`nominal.rs`).
    #[serde(skip)]
    pub g_static: Vec<f64>,
    /// The last `ĝ(q)` (`gravity_cache.rs`).
    #[serde(skip)]
    pub g_cache: super::gravity_cache::GravityCache,
    /// The cost's metric `N` (`controllers.metric`, `metric.rs`), from the warm-up; `None`:
    /// `N = I`. Saved with the model (format 10), so a loaded learner learns on in it.
    pub metric: Option<super::metric::Metric>,
}

/// Standard deviation of `f` over the warm-up, at least 1e-3.
fn std_of(warm: &[Measurement], f: &dyn Fn(&Measurement) -> f64) -> f64 {
    let k = warm.len() as f64;
    let mean = warm.iter().map(f).sum::<f64>() / k;
    let var = warm.iter().map(|w| (f(w) - mean).powi(2)).sum::<f64>() / k;
    var.sqrt().max(1e-3)
}

impl Models {
    /// Checks the LWPR sections of `cfg` for `n` joints and `m` task dimensions by building the
    /// models [`Models::from_warm_up`] builds from them, at unit scales: a bad section is
    /// refused when the learner is made, not a warm-up later.
    ///
    /// # Errors
    /// [`LearnError::InvalidConfig`] naming the section (`partition.lwpr`, `gravity.lwpr`).
    pub fn check_config(cfg: &LearnerConfig, n: usize, m: usize) -> Result<()> {
        let (unit, vs, x) = (
            vec![1.0; n],
            cfg.partition.velocity_scale,
            &cfg.experimental,
        );
        fn named(section: &'static str) -> impl Fn(LearnError) -> LearnError {
            move |e| LearnError::InvalidConfig(format!("{section}: {e}"))
        }
        let g = &cfg.gravity.lwpr;
        GravityModel::new(n, g, x.gravity_velocity_products, vs, 1.0, &unit)
            .map_err(named("gravity.lwpr"))?;
        if let Some(gate) = cfg.gravity.static_gate {
            GravityModel::new_static(n, g, gate, vs, 1.0, &unit).map_err(named("gravity.lwpr"))?;
        }
        let p = &cfg.partition.lwpr;
        ForwardModel::new(n, m, p, vs, &unit, 1.0, x.forward_uses_q)
            .map_err(named("partition.lwpr"))?;
        Ok(())
    }

    /// The models for `n` joints and `m` task dimensions, scaled by the warm-up `warm` (control
    /// period `dt`): torques per joint, task accelerations, joint accelerations.
    pub fn from_warm_up(
        cfg: &LearnerConfig,
        n: usize,
        m: usize,
        dt: f64,
        warm: &[Measurement],
    ) -> Result<Self> {
        let torque: Vec<f64> = (0..n).map(|i| std_of(warm, &|w| w.u[i])).collect();
        let acc = (0..m)
            .map(|k| std_of(warm, &|w| w.xdd[k]))
            .fold(0.0, f64::max);
        let jacc = (1..warm.len())
            .map(|k| ((&warm[k].qd - &warm[k - 1].qd) / dt).amax())
            .fold(0.0, f64::max)
            .max(1.0)
            / 3.0;
        let vs = cfg.partition.velocity_scale;
        let x = &cfg.experimental;
        let gravity = GravityModel::new(
            n,
            &cfg.gravity.lwpr,
            x.gravity_velocity_products,
            vs,
            jacc,
            &torque,
        )?;
        let gravity_static = match cfg.gravity.static_gate {
            Some(gate) => Some(GravityModel::new_static(
                n,
                &cfg.gravity.lwpr,
                gate,
                vs,
                jacc,
                &torque,
            )?),
            None => None,
        };
        let forward = ForwardModel::new(
            n,
            m,
            &cfg.partition.lwpr,
            vs,
            &torque,
            acc,
            x.forward_uses_q,
        )?;
        let share = cfg.controllers.damping_bound;
        let (velocity_gain_lo, velocity_gain_hi) = if share > 0.0 && x.residual {
            let inv = super::inertia::inverse_inertia_diagonal(warm, dt);
            super::inertia::velocity_gain_bounds(&cfg.nominal.kd, &inv, dt, share)
        } else {
            (Vec::new(), Vec::new())
        };
        let metric = match cfg.controllers.cost_metric() {
            crate::config::CostMetric::Identity => None,
            crate::config::CostMetric::InverseInertia => {
                super::metric::Metric::inverse_inertia(warm, dt)
            }
        };
        Ok(Self {
            metric,
            velocity_gain_lo,
            velocity_gain_hi,
            gravity,
            gravity_static,
            gravity_null: None,
            null_scale: Default::default(),
            forward,
            locals: LocalControllers::default(),
            g_static: vec![0.0; n],
            g_cache: super::gravity_cache::GravityCache::with_joints(n),
            torque_scale: torque,
        })
    }

    /// Re-creates the query buffers that serialisation skips.
    pub fn restore_buffers(&mut self) {
        self.g_static = vec![0.0; self.torque_scale.len()];
        self.g_cache = super::gravity_cache::GravityCache::with_joints(self.torque_scale.len());
        self.gravity.restore_buffers();
        for g in [self.gravity_static.as_mut(), self.gravity_null.as_mut()]
            .into_iter()
            .flatten()
        {
            g.restore_buffers();
        }
        self.forward.restore_buffers();
    }

    /// Checks what a loaded file says beyond its LWPR models (the static gravity model's gate
    /// and postures).
    ///
    /// # Errors
    /// [`crate::LearnError::Load`] naming what is inconsistent.
    pub fn check_loaded(&self) -> Result<()> {
        for g in [self.gravity_static.as_ref(), self.gravity_null.as_ref()]
            .into_iter()
            .flatten()
        {
            g.check_loaded()?;
        }
        self.null_scale.check().map_err(crate::LearnError::Load)
    }

    /// `Â = Σ w_i Â_i(q) / Σ w_i` (m×n row-major into `a`) over the activations `acts` of fields
    /// whose local dynamics have been fitted; `false` if there is none.
    pub fn blended_gain(
        &self,
        features: &super::Features,
        acts: &[lwpr::Activation],
        q: &[f64],
        a: &mut [f64],
    ) -> bool {
        self.weighted_gain(features, acts, q, a, |_, w| w)
    }

    /// `Â` of the command's blend (eq. 34's weights): as [`Self::blended_gain`] with the weight
    /// `c_i (w_i − cutoff)` of `command.rs`'s blend (confidence `c_i` from the controller's
    /// effective sample size against `trained_ess`), so a field enters the `Â` continuously, as
    /// it enters the command, and an untrained controller's field has no say in it. The command
    /// forms it with [`Self::blended_gain`]'s in one pass ([`Self::command_and_blended_gain`]).
    #[cfg(test)]
    pub fn command_gain(
        &self,
        features: &super::Features,
        acts: &[lwpr::Activation],
        q: &[f64],
        (cutoff, trained_ess): (f64, f64),
        a: &mut [f64],
    ) -> bool {
        self.weighted_gain(features, acts, q, a, |local, w| {
            crate::local::blend_weight(local.ess, trained_ess, w, cutoff)
        })
    }

    /// [`Self::command_gain`] into `a_cmd` and [`Self::blended_gain`] into `a_plain` in one pass
    /// over the fields (each field's `Â_i(q)` formed once): the same bits as the two calls.
    /// Returns whether each is known.
    pub fn command_and_blended_gain(
        &self,
        features: &super::Features,
        acts: &[lwpr::Activation],
        q: &[f64],
        (cutoff, trained_ess): (f64, f64),
        a_cmd: &mut [f64],
        a_plain: &mut [f64],
    ) -> (bool, bool) {
        a_cmd.fill(0.0);
        a_plain.fill(0.0);
        let (mut sum_v, mut sum_w) = (0.0, 0.0);
        for (local, w) in self.fitted(acts) {
            let v = crate::local::blend_weight(local.ess, trained_ess, w, cutoff);
            let (v, w) = (if v > 0.0 { v } else { 0.0 }, if w > 0.0 { w } else { 0.0 });
            if w == 0.0 && v == 0.0 {
                continue;
            }
            if local.gain_table.is_empty() {
                let theta = local.dynamics.theta();
                if v > 0.0 {
                    features.add_gain(theta, q, &local.center, v, a_cmd);
                }
                if w > 0.0 {
                    features.add_gain(theta, q, &local.center, w, a_plain);
                }
            } else {
                let table = &local.gain_table;
                features.add_gain_table_pair(table, q, &local.center, (v, a_cmd), (w, a_plain));
            }
            sum_v += v;
            sum_w += w;
        }
        (normalise(a_cmd, sum_v), normalise(a_plain, sum_w))
    }

    /// The fields of `acts` whose local dynamics have been fitted, with their activations.
    fn fitted<'a>(
        &'a self,
        acts: &'a [lwpr::Activation],
    ) -> impl Iterator<Item = (&'a crate::local::Local, f64)> + 'a {
        acts.iter().filter_map(|act| {
            let local = self.locals.map.get(&act.id)?;
            (local.dynamics_updates > 0).then_some((local, act.w))
        })
    }

    /// `Σ v_i Â_i(q) / Σ v_i` with `v_i = weight(local_i, w_i)` over the fields with fitted
    /// local dynamics and `v_i > 0`; `false` if there is none.
    fn weighted_gain(
        &self,
        features: &super::Features,
        acts: &[lwpr::Activation],
        q: &[f64],
        a: &mut [f64],
        weight: impl Fn(&crate::local::Local, f64) -> f64,
    ) -> bool {
        a.fill(0.0);
        let mut sum_w = 0.0;
        for (local, w) in self.fitted(acts) {
            let w = weight(local, w);
            if !(w > 0.0) {
                continue;
            }
            if local.gain_table.is_empty() {
                features.add_gain(local.dynamics.theta(), q, &local.center, w, a);
            } else {
                features.add_gain_table(&local.gain_table, q, &local.center, w, a);
            }
            sum_w += w;
        }
        normalise(a, sum_w)
    }
}

/// Divides the blend `a` by its total weight `sum`; whether there was any (`a` untouched if not).
fn normalise(a: &mut [f64], sum: f64) -> bool {
    if sum > 0.0 {
        a.iter_mut().for_each(|v| *v /= sum);
    }
    sum > 0.0
}
