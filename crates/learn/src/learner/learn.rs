//! [`Learner::learn`]: the measurement guards, the warm-up, and the hand-over to the learning
//! step of `hindsight.rs` once the models exist.

use super::{Learner, Models, State};
use crate::error::{LearnError, Result};
use osrl_dynamics::Measurement;

/// How far the time between the two measurements of a transition given to
/// [`Learner::learn`] may be from the control period, as a fraction of it. The learner takes
/// each transition as one control period under the held command; half a period tells the next
/// measurement (one period on) from the same one (0) or one after a missed step (2 periods),
/// and leaves room for a real robot's timing jitter and for a time summed up from rounded
/// periods.
pub const PERIOD_TOLERANCE: f64 = 0.5;

impl Learner {
    /// Checks a measurement: right sizes, finite, and not absurd (`guards`).
    ///
    /// # Errors
    /// [`LearnError::BadMeasurement`] saying what is wrong.
    pub fn check(&self, meas: &Measurement) -> Result<()> {
        let (n, m) = (self.n, self.m);
        let sizes = [meas.q.len(), meas.qd.len(), meas.u.len()];
        let task = [meas.x.len(), meas.xd.len(), meas.xdd.len()];
        if sizes.iter().any(|&k| k != n) || task.iter().any(|&k| k != m) {
            return Err(LearnError::BadMeasurement(format!(
                "sizes do not match a robot with {n} joints and {m} task dimensions"
            )));
        }
        let all = meas
            .q
            .iter()
            .chain(meas.qd.iter())
            .chain(meas.u.iter())
            .chain(meas.x.iter())
            .chain(meas.xd.iter())
            .chain(meas.xdd.iter());
        if let Some(v) = all.clone().find(|v| !v.is_finite()) {
            return Err(LearnError::BadMeasurement(format!("non-finite value {v}")));
        }
        let g = &self.cfg.guards;
        if meas.xdd.amax() > g.max_abs_acceleration || meas.qd.amax() > g.max_abs_velocity {
            return Err(LearnError::BadMeasurement(format!(
                "absurd: |ẍ| = {:.3e} m/s² (limit {:.3e}), |q̇| = {:.3e} rad/s (limit {:.3e})",
                meas.xdd.amax(),
                g.max_abs_acceleration,
                meas.qd.amax(),
                g.max_abs_velocity
            )));
        }
        Ok(())
    }

    /// `cur` follows `prev` by one control period, within [`PERIOD_TOLERANCE`].
    fn check_step(&self, prev: &Measurement, cur: &Measurement) -> Result<()> {
        let step = cur.t - prev.t;
        if (step - self.dt).abs() <= PERIOD_TOLERANCE * self.dt {
            Ok(())
        } else {
            Err(LearnError::BadMeasurement(format!(
                "cur.t − prev.t = {step:?} s is not one control period ({:?} s ± {:.0} %)",
                self.dt,
                PERIOD_TOLERANCE * 100.0
            )))
        }
    }

    /// Learns from the transition `prev → cur` (the command `cur.u` was held in between); `cur`
    /// one control period after `prev` (within [`PERIOD_TOLERANCE`]).
    ///
    /// # Errors
    /// [`LearnError::BadMeasurement`] for a rejected measurement (counted; nothing else
    /// changes), or a model failure.
    pub fn learn(&mut self, prev: &Measurement, cur: &Measurement) -> Result<()> {
        let checked = self
            .check_step(prev, cur)
            .and_then(|_| self.check(cur))
            .and_then(|_| self.check(prev));
        if let Err(e) = checked {
            self.stats.rejected += 1;
            return Err(e);
        }
        match &mut self.state {
            State::Ready(_) => self.learn_ready(prev, cur),
            State::WarmUp(warm) => {
                if warm.is_empty() {
                    warm.push(prev.clone());
                }
                warm.push(cur.clone());
                if warm.len() > self.cfg.guards.warmup_samples {
                    self.init_models()?;
                }
                Ok(())
            }
        }
    }

    /// The models from the warm-up data, then the warm-up replayed into them.
    fn init_models(&mut self) -> Result<()> {
        let warm = match std::mem::replace(&mut self.state, State::WarmUp(Vec::new())) {
            State::WarmUp(w) => w,
            ready => {
                self.state = ready;
                return Ok(());
            }
        };
        let models = match Models::from_warm_up(&self.cfg, self.n, self.m, self.dt, &warm) {
            Ok(models) => models,
            Err(e) => {
                self.state = State::WarmUp(warm);
                return Err(e);
            }
        };
        self.state = State::Ready(Box::new(models));
        for k in 1..warm.len() {
            self.learn_ready(&warm[k - 1], &warm[k])?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use crate::learner::fixture;
    use crate::Learner;

    /// The models are made after `warmup_samples` transitions, and the warm-up is replayed
    /// into them (every transition counts as a sample once).
    #[test]
    fn the_warm_up_becomes_the_models_and_is_replayed() {
        let mut cfg = fixture::config();
        cfg.guards.warmup_samples = 50;
        let mut learner = Learner::new(3, 2, 0.002, cfg).unwrap();
        let mut sim = fixture::robot();
        fixture::sweep(&mut learner, &mut sim, 49);
        assert!(!learner.ready());
        assert_eq!(learner.stats().samples, 0);
        assert!(learner.forward_model().is_none());
        fixture::sweep(&mut learner, &mut sim, 1);
        assert!(learner.ready());
        assert_eq!(learner.stats().samples, 50);
        assert!(learner.n_local_models() > 0);
        fixture::sweep(&mut learner, &mut sim, 10);
        assert_eq!(learner.stats().samples, 60);
    }

    /// With `controllers.bilinear` every controller has `m n` more features and the learner
    /// still learns; without the position features the option is refused.
    #[test]
    fn bilinear_controllers_have_the_products_and_need_the_position_features() {
        let mut cfg = fixture::config();
        cfg.controllers.bilinear = true;
        let (mut learner, _, _) = fixture::ready(cfg.clone(), 50, 2000);
        assert_eq!(learner.features.controller_len(), 2 + 3 + 3 + 1 + 2 * 3);
        let models = fixture::models(&mut learner);
        let locals = &models.locals.map;
        assert!(locals.values().any(|l| l.updates > 0));
        for local in locals.values() {
            let theta = local.rwr.theta();
            assert_eq!(theta.nrows(), 15);
            assert!(theta.iter().all(|x| x.is_finite()));
        }
        // The products are fitted, not left at their start.
        let products = |l: &crate::local::Local| l.rwr.theta().rows(9, 6).amax();
        assert!(locals.values().any(|l| l.updates > 0 && products(l) > 0.0));
        cfg.experimental.position_features = false;
        let err = Learner::new(3, 2, 0.002, cfg).unwrap_err().to_string();
        assert!(err.contains("controllers.bilinear"), "{err}");
    }
}
