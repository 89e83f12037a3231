//! [`LearnerConfig::validate`]: every field against its documented range, the error naming it.

use super::LearnerConfig;
use crate::error::{LearnError, Result};

/// `Err(InvalidConfig(msg))` unless `ok`.
fn ensure(ok: bool, msg: impl FnOnce() -> String) -> Result<()> {
    if ok {
        Ok(())
    } else {
        Err(LearnError::InvalidConfig(msg()))
    }
}

fn finite_at_least(x: f64, lo: f64) -> bool {
    x.is_finite() && x >= lo
}

/// Most warm-up transitions (a day at 500 Hz would be 43 M): the learner keeps each one until
/// the models are created (about 200 bytes), so this bounds that memory near 200 MB.
pub const MAX_WARMUP_SAMPLES: usize = 1_000_000;

/// Largest `|q_rest|` (rad or m): a rest posture further out is no posture (the data sheets'
/// joint ranges are within ±2π), and its PD torque overflows the cost.
const MAX_ABS_REST: f64 = 1e3;

/// The normalisation divisors a user gave an LWPR section, each within LWPR's range
/// ([`lwpr::Norm::check_values`]): the learner sets its models' scales itself, but the saved
/// configuration keeps these values.
fn check_norms(section: &str, cfg: &lwpr::LwprConfig) -> Result<()> {
    for (key, norm) in [("norm_in", &cfg.norm_in), ("norm_out", &cfg.norm_out)] {
        norm.check_values(&format!("{section}.{key}"))
            .map_err(|e| LearnError::InvalidConfig(e.to_string()))?;
    }
    Ok(())
}

impl LearnerConfig {
    /// Checks every field's range and that the nominal behaviour and the torque limits have `n`
    /// joints.
    ///
    /// # Errors
    /// [`LearnError::InvalidConfig`] naming the first field out of range, with its value.
    pub fn validate(&self, n: usize) -> Result<()> {
        self.validate_nominal(n)?;
        self.validate_models()?;
        self.validate_controllers()?;
        self.adaptation.validate()?;
        self.validate_guards(n)
    }

    fn validate_nominal(&self, n: usize) -> Result<()> {
        let nom = &self.nominal;
        for (what, v) in [
            ("nominal.kp", &nom.kp),
            ("nominal.kd", &nom.kd),
            ("nominal.q_rest", &nom.q_rest),
        ] {
            ensure(v.len() == n && v.iter().all(|x| x.is_finite()), || {
                format!("{what} needs {n} finite values, got {v:?}")
            })?;
        }
        ensure(nom.q_rest.iter().all(|q| q.abs() <= MAX_ABS_REST), || {
            format!(
                "nominal.q_rest must lie within ±{MAX_ABS_REST:?} (rad or m), got {:?}",
                nom.q_rest
            )
        })?;
        // The PD of the babbling and the returns home needs a restoring stiffness.
        let (kp_max, kd_max) = (osrl_dynamics::MAX_JOINT_KP, osrl_dynamics::MAX_JOINT_KD);
        ensure(nom.kp.iter().all(|k| *k > 0.0 && *k <= kp_max), || {
            format!(
                "nominal.kp must lie in (0, {kp_max:?}] (N·m/rad) for every joint, got {:?}",
                nom.kp
            )
        })?;
        ensure(nom.kd.iter().all(|k| (0.0..=kd_max).contains(k)), || {
            format!(
                "nominal.kd must lie in [0, {kd_max:?}] (N·m·s/rad) for every joint, got {:?}",
                nom.kd
            )
        })
    }

    fn validate_models(&self) -> Result<()> {
        check_norms("partition.lwpr", &self.partition.lwpr)?;
        check_norms("gravity.lwpr", &self.gravity.lwpr)?;
        let p = &self.partition;
        let c = p.activation_cutoff;
        ensure(c > 0.0 && c < 1.0, || {
            format!("partition.activation_cutoff {c} must be in (0, 1)")
        })?;
        ensure(p.learn_every >= 1, || {
            "partition.learn_every must be ≥ 1".into()
        })?;
        if let Some(t) = p.prune_untrained_after {
            ensure(t > 0.0 && t.is_finite(), || {
                format!("partition.prune_untrained_after {t} must be finite and > 0 (s)")
            })?;
        }
        // It normalises the models' velocity inputs: LWPR's range for a normalisation.
        let (lo, hi) = lwpr::NORM_RANGE;
        let vs = p.velocity_scale;
        ensure((lo..=hi).contains(&vs), || {
            format!("partition.velocity_scale {vs:e} must be within [{lo:e}, {hi:e}] (rad/s)")
        })?;
        if let Some(g) = &self.gravity.static_gate {
            g.validate().map_err(LearnError::InvalidConfig)?;
        }
        let w = self.gravity.dynamic_weight;
        ensure(finite_at_least(w, 0.0), || {
            format!("gravity.dynamic_weight {w} must be finite and ≥ 0")
        })?;
        let g = &self.gravity;
        ensure(g.null_support > 0.0 && g.null_support.is_finite(), || {
            format!(
                "gravity.null_support {} must be finite and > 0",
                g.null_support
            )
        })?;
        ensure(finite_at_least(g.null_ridge, 0.0), || {
            format!("gravity.null_ridge {} must be finite and ≥ 0", g.null_ridge)
        })?;
        ensure(finite_at_least(g.null_scale_memory, 1.0), || {
            format!(
                "gravity.null_scale_memory {} must be finite and ≥ 1",
                g.null_scale_memory
            )
        })?;
        ensure(finite_at_least(g.null_scale_ridge, 0.0), || {
            format!(
                "gravity.null_scale_ridge {} must be finite and ≥ 0",
                g.null_scale_ridge
            )
        })?;
        let [lo, hi] = g.null_scale_explained;
        ensure((0.0..hi).contains(&lo) && hi <= 1.0, || {
            format!("gravity.null_scale_explained [{lo}, {hi}] must have 0 ≤ lo < hi ≤ 1")
        })?;
        ensure(g.null_min_samples >= 1, || {
            "gravity.null_min_samples must be ≥ 1".into()
        })?;
        let d = &self.dynamics;
        ensure(d.forgetting > 0.0 && d.forgetting <= 1.0, || {
            format!("dynamics.forgetting {} must be in (0, 1]", d.forgetting)
        })?;
        ensure(d.learn_every >= 1 && d.solve_every >= 1, || {
            "dynamics.learn_every and dynamics.solve_every must be ≥ 1".into()
        })?;
        ensure(d.trust_region.is_finite() && d.trust_region >= 0.0, || {
            format!("dynamics.trust_region {} must be ≥ 0", d.trust_region)
        })?;
        ensure(finite_at_least(d.weight_power, 1.0), || {
            format!("dynamics.weight_power {} must be ≥ 1", d.weight_power)
        })
    }

    fn validate_controllers(&self) -> Result<()> {
        let c = &self.controllers;
        ensure(finite_at_least(c.trained_ess, 1.0), || {
            format!("controllers.trained_ess {} must be ≥ 1", c.trained_ess)
        })?;
        ensure(c.update_every >= 1, || {
            "controllers.update_every must be ≥ 1".into()
        })?;
        ensure((0.0..=1.0).contains(&c.null_space_shrink), || {
            format!(
                "controllers.null_space_shrink {} must be in [0, 1]",
                c.null_space_shrink
            )
        })?;
        ensure((0.0..=1.0).contains(&c.command_projection), || {
            format!(
                "controllers.command_projection {} must be in [0, 1]",
                c.command_projection
            )
        })?;
        ensure(c.prior_weight > 0.0 && c.prior_weight.is_finite(), || {
            format!(
                "controllers.prior_weight {} must be finite and > 0",
                c.prior_weight
            )
        })?;
        ensure(
            c.neighbour_cutoff == 0.0
                || (c.neighbour_cutoff > 0.0
                    && c.neighbour_cutoff < self.partition.activation_cutoff),
            || {
                format!(
                    "controllers.neighbour_cutoff {} must be 0 (off) or in (0, \
                     partition.activation_cutoff = {})",
                    c.neighbour_cutoff, self.partition.activation_cutoff
                )
            },
        )?;
        ensure(finite_at_least(c.damping_bound, 0.0), || {
            format!(
                "controllers.damping_bound {} must be finite and ≥ 0",
                c.damping_bound
            )
        })?;
        ensure(c.step_spread >= 1, || {
            "controllers.step_spread must be ≥ 1".into()
        })?;
        ensure(!c.bilinear || self.experimental.position_features, || {
            "controllers.bilinear needs the position features `q − c` \
             (experimental.position_features)"
                .into()
        })?;
        let e = &self.exploration;
        ensure(finite_at_least(e.correlation_time, 0.0), || {
            format!(
                "exploration.correlation_time {} must be finite and ≥ 0 (s)",
                e.correlation_time
            )
        })?;
        ensure(finite_at_least(e.scale, 0.0), || {
            format!("exploration.scale {} must be finite and ≥ 0", e.scale)
        })?;
        ensure(finite_at_least(e.cap, 0.0), || {
            format!("exploration.cap {} must be finite and ≥ 0", e.cap)
        })?;
        if let Some(r) = e.max_rate {
            ensure(finite_at_least(r, 0.0), || {
                format!("exploration.max_rate {r} must be finite and ≥ 0 (N·m/s)")
            })?;
        }
        if let Some(cap) = self.experimental.null_space_cap {
            ensure(finite_at_least(cap, 0.0), || {
                format!("experimental.null_space_cap {cap} must be finite and ≥ 0")
            })?;
        }
        c.rwr.validate()?;
        Ok(())
    }

    fn validate_guards(&self, n: usize) -> Result<()> {
        let g = &self.guards;
        let tl = &g.torque_limits;
        ensure(
            (tl.is_empty() || tl.len() == n) && tl.iter().all(|t| *t > 0.0 && t.is_finite()),
            || {
                format!(
                    "guards.torque_limits needs {n} finite values > 0 (N·m) or none (a huge \
                     value for a joint without a limit), got {tl:?}"
                )
            },
        )?;
        ensure(
            g.torque_rate_limit.is_none_or(|r| r > 0.0 && r.is_finite()),
            || {
                format!(
                    "guards.torque_rate_limit {:?} must be finite and > 0 (N·m/s; a huge value for no \
                 limit), or unset",
                    g.torque_rate_limit
                )
            },
        )?;
        ensure(
            (10..=MAX_WARMUP_SAMPLES).contains(&g.warmup_samples),
            || {
                format!(
                    "guards.warmup_samples {} must be within [10, {MAX_WARMUP_SAMPLES}]",
                    g.warmup_samples
                )
            },
        )?;
        let a = g.max_abs_acceleration;
        ensure(a > 0.0 && a.is_finite(), || {
            format!("guards.max_abs_acceleration {a} must be finite and > 0 (m/s²)")
        })?;
        ensure(
            g.max_abs_velocity > 0.0 && g.max_abs_velocity.is_finite(),
            || {
                format!(
                    "guards.max_abs_velocity {} must be finite and > 0 (rad/s)",
                    g.max_abs_velocity
                )
            },
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One change to a configuration.
    type Edit = Box<dyn Fn(&mut LearnerConfig)>;

    /// Each edit alone makes the default configuration invalid, with the field named.
    #[test]
    fn values_that_crashed_or_could_not_be_saved_are_refused_by_name() {
        let n = 3;
        let edits: Vec<(&str, Edit)> = vec![
            ("nominal.kp", Box::new(|c| c.nominal.kp = vec![-1.0; 3])),
            ("nominal.kd", Box::new(|c| c.nominal.kd[1] = -0.5)),
            ("nominal.kp", Box::new(|c| c.nominal.kp[2] = 1e300)),
            ("nominal.kd", Box::new(|c| c.nominal.kd[0] = 1e300)),
            ("nominal.q_rest", Box::new(|c| c.nominal.q_rest[1] = -1e300)),
            (
                "guards.warmup_samples",
                Box::new(|c| c.guards.warmup_samples = 1 << 40),
            ),
            (
                "max_abs_velocity",
                Box::new(|c| c.guards.max_abs_velocity = f64::INFINITY),
            ),
            (
                "max_abs_acceleration",
                Box::new(|c| c.guards.max_abs_acceleration = f64::INFINITY),
            ),
            (
                "torque_rate_limit",
                Box::new(|c| c.guards.torque_rate_limit = Some(f64::INFINITY)),
            ),
            (
                "partition.lwpr.norm_in",
                Box::new(|c| c.partition.lwpr.norm_in = lwpr::Norm::Scalar(f64::NAN)),
            ),
            (
                "gravity.lwpr.norm_out",
                Box::new(|c| c.gravity.lwpr.norm_out = lwpr::Norm::List(vec![1.0, 0.0, 1.0])),
            ),
        ];
        let mut base = LearnerConfig::default();
        base.nominal.kp = vec![10.0; n];
        base.nominal.kd = vec![1.0; n];
        base.nominal.q_rest = vec![0.0; n];
        base.guards.torque_limits = vec![50.0; n];
        base.validate(n).unwrap();
        for (key, edit) in edits {
            let mut c = base.clone();
            edit(&mut c);
            let e = c.validate(n).expect_err(key).to_string();
            assert!(e.contains(key), "{key}: {e}");
        }
        base.guards.warmup_samples = MAX_WARMUP_SAMPLES;
        base.validate(n).unwrap();
    }
}
