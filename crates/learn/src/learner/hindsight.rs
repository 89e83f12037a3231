//! The learning step once the models exist (paper section IV, `docs/learner.md`): the supervised
//! models learn the transition, the local controllers follow the partition, and the executed
//! command becomes a hindsight sample — relabelled with the measured `ẍ`, its target shrunk in
//! the null space of `Â`, weighted by the transformed cost — for every active local controller,
//! whose M-step runs when due.

use super::cost::{cost, shrink_target};
use super::nominal::nominal_into;
use super::null_gravity::null_correction_into_z;
use super::stats::{LearnerStats, Scratch};
use super::{AdaptationSignal, LoadCorrection};
use super::{Features, Learner, Models, State};
use crate::config::{AdaptationSource, DynamicsRegression, LearnerConfig};
use crate::error::Result;
use crate::local::{LocalSpec, MStep, Pace};
use lwpr::RfEvent;
use osrl_dynamics::Measurement;

/// The parts of a ready learner that one learning step uses.
struct Step<'a> {
    cfg: &'a LearnerConfig,
    features: &'a Features,
    models: &'a mut Models,
    stats: &'a mut LearnerStats,
    ws: &'a mut Scratch,
    n: usize,
    m: usize,
    dt: f64,
    gravity_frozen: bool,
    static_frozen: bool,
    adapt: &'a mut AdaptationSignal,
    load: &'a mut LoadCorrection,
}

impl Learner {
    /// One learning step's view of the learner; `None` before the models exist.
    fn step(&mut self) -> Option<Step<'_>> {
        let State::Ready(models) = &mut self.state else {
            return None;
        };
        Some(Step {
            cfg: &self.cfg,
            features: &self.features,
            models,
            stats: &mut self.stats,
            ws: &mut self.ws,
            n: self.n,
            m: self.m,
            dt: self.dt,
            gravity_frozen: self.gravity_frozen,
            static_frozen: self.static_frozen,
            adapt: &mut self.adapt,
            load: &mut self.load,
        })
    }

    /// Learns from a checked transition `prev → cur` once the models exist (nothing before).
    pub(crate) fn learn_ready(&mut self, prev: &Measurement, cur: &Measurement) -> Result<()> {
        match self.step() {
            Some(mut step) => step.run(prev, cur),
            None => Ok(()),
        }
    }

    /// Learns from `prev → cur` in the static gravity model alone (its gate decides whether the
    /// transition is still), nothing else: the training driver's holds at path postures
    /// (`TrainConfig::posture_holds`). Nothing before the models exist.
    ///
    /// # Errors
    /// [`crate::LearnError::BadMeasurement`] for a rejected measurement (counted), or a model
    /// failure.
    pub fn learn_static_gravity(&mut self, prev: &Measurement, cur: &Measurement) -> Result<()> {
        if let Err(e) = self.check(cur).and_then(|_| self.check(prev)) {
            self.stats.rejected += 1;
            return Err(e);
        }
        if self.cfg.gravity.null_correction {
            return self.learn_null_gravity(prev, cur);
        }
        match self.step() {
            Some(mut step) => step.learn_static(prev, cur, false),
            None => Ok(()),
        }
    }
}

impl Step<'_> {
    /// Stages: supervised models → prune → follow the partition → relabel → cost → local
    /// updates.
    fn run(&mut self, prev: &Measurement, cur: &Measurement) -> Result<()> {
        self.stats.samples += 1;
        self.learn_supervised(prev, cur)?;
        self.prune_idle_untrained()?;
        self.follow_partition(cur)?;
        let known = self.relabel(cur)?;
        self.learn_load(cur)?;
        let r = cost(self.cfg, known, self.models.metric.as_ref(), self.ws);
        self.update_locals(prev, cur, r)
    }

    /// The models that learn from every transition without rewards: `ĝ` (unless frozen; its
    /// static variant also when frozen, if configured) and the forward model (every
    /// `partition.learn_every`-th transition).
    fn learn_supervised(&mut self, prev: &Measurement, cur: &Measurement) -> Result<()> {
        let (q, qd, u) = (cur.q.as_slice(), cur.qd.as_slice(), cur.u.as_slice());
        let dt = cur.t - prev.t;
        let (q0, qd0) = (prev.q.as_slice(), prev.qd.as_slice());
        if dt > 0.0 && !self.gravity_frozen {
            self.models.gravity.learn(q0, qd0, q, qd, u, dt)?;
        }
        self.learn_static(
            prev,
            cur,
            self.gravity_frozen && !self.cfg.gravity.static_on_policy,
        )?;
        let every = self.cfg.partition.learn_every as u64;
        let ad = &self.cfg.adaptation;
        let frozen = ad.enabled && ad.freeze_partition;
        if !frozen && self.stats.samples.is_multiple_of(every) {
            self.models.forward.learn(q, qd, u, cur.xdd.as_slice())?;
        }
        Ok(())
    }

    /// The static gravity model learns the transition if it is still (its gate), unless
    /// `off`, paused by the re-adaptation, or frozen.
    fn learn_static(&mut self, prev: &Measurement, cur: &Measurement, off: bool) -> Result<()> {
        let (q, qd, u) = (cur.q.as_slice(), cur.qd.as_slice(), cur.u.as_slice());
        let dt = cur.t - prev.t;
        let (q0, qd0) = (prev.q.as_slice(), prev.qd.as_slice());
        let ad = &self.cfg.adaptation;
        let paused = ad.enabled && ad.pause_static_gravity && self.adapt.strength > 0.0;
        let static_on = !off && !paused && !self.static_frozen;
        if let (true, true, Some(g)) = (dt > 0.0, static_on, self.models.gravity_static.as_mut()) {
            // With a load correction in `u0`, the static model keeps the gravity without it
            // (`c` at the last relabelled state, the previous one: the arm is still).
            let u = if self.load.is_empty() {
                u
            } else {
                for ((z, ui), c) in self.ws.z.iter_mut().zip(u).zip(&self.ws.load_c) {
                    *z = ui - c;
                }
                self.ws.z.as_slice()
            };
            g.learn(q0, qd0, q, qd, u, dt)?;
        }
        Ok(())
    }

    /// Once per second of learning: removes from the partition the fields whose controller is
    /// untrained and that were idle for `partition.prune_untrained_after`; their `Pruned` events
    /// then drop the controllers.
    fn prune_idle_untrained(&mut self) -> Result<()> {
        let Some(after) = self.cfg.partition.prune_untrained_after else {
            return Ok(());
        };
        let per_second = (1.0 / self.dt).round().max(1.0) as u64;
        let idle = (after / self.dt).ceil() as u64;
        let now = self.stats.samples;
        if !now.is_multiple_of(per_second) || now <= idle {
            return Ok(());
        }
        self.ws.stale.clear();
        let ess = self.cfg.controllers.trained_ess;
        let models = &mut *self.models;
        models
            .locals
            .stale_untrained(ess, now - idle, &mut self.ws.stale);
        for id in &self.ws.stale {
            self.stats.pruned_untrained += models.forward.remove(*id)? as u64;
        }
        Ok(())
    }

    /// New receptive fields get a controller, pruned ones lose theirs (exactly one each).
    fn follow_partition(&mut self, cur: &Measurement) -> Result<()> {
        let (q, qd) = (cur.q.as_slice(), cur.qd.as_slice());
        self.ws.events.clear();
        self.models.forward.drain_events(&mut self.ws.events);
        let init_u: &[f64] = if self.cfg.experimental.residual {
            &[]
        } else {
            cur.u.as_slice()
        };
        let spec = LocalSpec {
            features: *self.features,
            dynamics_forgetting: self.cfg.dynamics.forgetting,
            dynamics_trust_region: self.cfg.dynamics.trust_region,
            rwr: &self.cfg.controllers.rwr,
            trained_ess: self.cfg.controllers.trained_ess,
        };
        let models = &mut *self.models;
        let (n, cutoff) = (self.n, self.cfg.partition.activation_cutoff);
        for event in &self.ws.events {
            match *event {
                RfEvent::Added { id, .. } => {
                    let center = models
                        .forward
                        .center(id)
                        .unwrap_or_else(|| [q, qd].concat());
                    // Start from the trained neighbours' blend at the new centre.
                    let (cq, cqd) = center.split_at(n);
                    models
                        .forward
                        .activations(cq, cqd, cutoff, &mut self.ws.acts)?;
                    let init = models.locals.neighbour_blend(
                        &self.ws.acts,
                        &center,
                        self.features,
                        spec.trained_ess,
                    );
                    let now = self.stats.samples;
                    models.locals.add(id, center, init, init_u, &spec, now)?;
                }
                RfEvent::Pruned { id, .. } => {
                    models.locals.remove(id);
                    self.load.remove(id);
                }
            }
        }
        Ok(())
    }

    /// Hindsight relabelling: the executed `u` with the measured `ẍ` is a sample of the policy
    /// that commands that `ẍ`. Sets `ws.du = u − u0`, the regression target (`u − u0`, shrunk in
    /// the null space of `Â`, or `u`), the active fields and `Â`; returns whether `Â` is known.
    fn relabel(&mut self, cur: &Measurement) -> Result<bool> {
        let (q, qd, u) = (cur.q.as_slice(), cur.qd.as_slice(), cur.u.as_slice());
        let ws = &mut *self.ws;
        let models = &mut *self.models;
        let cutoff = self.cfg.partition.activation_cutoff;
        models.forward.activations(q, qd, cutoff, &mut ws.acts)?;
        nominal_into(
            &self.cfg.nominal,
            &self.cfg.gravity,
            Some(&mut *models),
            self.gravity_frozen,
            q,
            qd,
            &mut ws.u0,
        )?;
        let residual = self.cfg.experimental.residual;
        ws.load_c.fill(0.0);
        if !self.load.is_empty() {
            if residual {
                self.load.add_into(&ws.acts, &mut ws.load_c);
            }
            for (o, c) in ws.u0.iter_mut().zip(&ws.load_c) {
                *o += c;
            }
        }
        let known = models.blended_gain(self.features, &ws.acts, q, &mut ws.a_hat);
        // The command's null-space correction is part of its `u0` (`null_gravity.rs`).
        if known
            && residual
            && null_correction_into_z(self.cfg, models, ws, q, self.gravity_frozen, self.load)?
        {
            for (o, z) in ws.u0.iter_mut().zip(&ws.z) {
                *o += z;
            }
        }
        for (i, &ui) in u.iter().enumerate() {
            ws.du[i] = ui - ws.u0[i];
            ws.target[i] = if residual { ws.du[i] } else { ui };
        }
        if known && residual {
            let kappa = self.cfg.controllers.null_space_shrink;
            shrink_target(kappa, models.metric.as_ref(), ws);
        }
        Ok(known)
    }

    /// The load correction learns while re-adapting (`load.rs`): each active field's offset
    /// moves towards `c + ε`, `ε = u − û` the executed command minus the policy's command for the
    /// measured `ẍ`. Nothing without `adaptation.load_correction`, in the non-residual variant,
    /// or at strength 0.
    fn learn_load(&mut self, cur: &Measurement) -> Result<()> {
        let ad = &self.cfg.adaptation;
        let on = ad.enabled && ad.load_correction && self.cfg.experimental.residual;
        let strength = if self.adapt.readapting() {
            self.adapt.strength.max(ad.load_floor)
        } else {
            0.0
        };
        if !on || !(strength > 0.0) {
            return Ok(());
        }
        let ws = &mut *self.ws;
        let known = super::load::policy_at(
            self.cfg,
            self.features,
            self.models,
            cur,
            &ws.acts,
            &mut ws.phi,
            &mut ws.ui,
            &mut ws.pi,
        )?;
        if !known {
            return Ok(());
        }
        // c + ε = u − (u0 − c) − û.
        for (i, p) in ws.pi.iter_mut().enumerate() {
            *p = cur.u[i] - (ws.u0[i] - ws.load_c[i]) - *p;
        }
        let gain = strength * self.dt / ad.load_time_constant;
        self.load.learn(&ws.acts, &ws.load_c, &ws.pi, gain);
        Ok(())
    }

    /// Every active field: its local dynamics learn `u → ẍ`, its controller the hindsight sample
    /// with cost `r`, and the M-steps run when due (counted). With `adaptation.enabled`, the
    /// fields first predict `ẍ` (every `check_every` steps) for the re-adaptation's level, and
    /// forget and learn at its strength — the controllers of a continuing learner, after a
    /// detection, at least at `controller_floor` (`adapt.rs`).
    fn update_locals(&mut self, prev: &Measurement, cur: &Measurement, r: f64) -> Result<()> {
        let (q, qd, u) = (cur.q.as_slice(), cur.qd.as_slice(), cur.u.as_slice());
        let (q0, qd0, u0) = (prev.q.as_slice(), prev.qd.as_slice(), prev.u.as_slice());
        let xdd = cur.xdd.as_slice();
        let (f, ws) = (self.features, &mut *self.ws);
        f.controller_common(&mut ws.phi, xdd, qd);
        let dc = &self.cfg.dynamics;
        // The difference form needs one control period between the transitions.
        let step = cur.t - prev.t;
        let difference = dc.regression == DynamicsRegression::Difference;
        let inv_dt = 1.0 / step;
        let consecutive = step > 0.5 * self.dt && step < 1.5 * self.dt;
        if difference {
            f.dynamics_common_difference(&mut ws.phi_d, (u, u0), (qd, qd0), inv_dt);
            for ((t, x), x0) in ws.xdd_target.iter_mut().zip(xdd).zip(prev.xdd.iter()) {
                *t = (x - x0) * inv_dt;
            }
        } else {
            f.dynamics_common(&mut ws.phi_d, u, qd);
            ws.xdd_target.copy_from_slice(xdd);
        }
        let now = self.stats.samples;
        let dyn_now = now.is_multiple_of(dc.learn_every as u64) && (!difference || consecutive);
        let update_every = self.cfg.controllers.update_every;
        let ad = &self.cfg.adaptation;
        let check =
            ad.enabled && now.is_multiple_of(ad.check_every as u64) && (!difference || consecutive);
        let adapting = ad.enabled && self.adapt.strength > 0.0;
        // The controllers forget at least while the strength is above 0 (`adapt.rs`).
        let forgetting = ad.enabled && self.adapt.controller_strength(ad) > 0.0;
        let pace = Pace {
            solve_every: self.cfg.dynamics.solve_every as u64,
            solve_always: adapting,
            trust_scale: if adapting {
                self.adapt.trust_scale(ad)
            } else {
                1.0
            },
            spread: self.cfg.controllers.step_spread,
            features: *self.features,
        };
        let (lo, hi) = (&self.models.velocity_gain_lo, &self.models.velocity_gain_hi);
        let floor = if difference {
            ad.residual_floor_difference * ad.residual_floor_difference
        } else {
            ad.residual_floor * ad.residual_floor
        };
        let command_floor = ad.command_floor * ad.command_floor;
        let by_command = ad.signal == AdaptationSource::Command;
        let (mut se, mut sv) = (0.0, 0.0);
        for a in &ws.acts {
            let Some(local) = self.models.locals.map.get_mut(&a.id) else {
                continue;
            };
            local.last_active = now;
            f.controller_local(&mut ws.phi, q, &local.center);
            if check && by_command && local.updates > 0 {
                // The controller's prediction of its hindsight target, before it learns it.
                local.rwr.mean_into(&ws.phi, &mut ws.ui)?;
                let e: f64 = ws
                    .target
                    .iter()
                    .zip(&ws.ui)
                    .map(|(t, y)| (t - y).powi(2))
                    .sum();
                let v = local.rwr.mean_sq_residual().max(command_floor);
                se += a.w * e;
                sv += a.w * v * self.n as f64;
            }
            if difference && (dyn_now || check) {
                let c = &local.center;
                f.dynamics_local_difference(&mut ws.phi_d, (q, q0), (u, u0), c, inv_dt);
            } else if dyn_now || check {
                f.dynamics_local(&mut ws.phi_d, q, u, &local.center);
            }
            if check && !by_command && local.dynamics_updates > 0 {
                local.dynamics.mean_into(&ws.phi_d, &mut ws.y)?;
                let x = &ws.xdd_target;
                let e: f64 = x.iter().zip(&ws.y).map(|(x, y)| (x - y).powi(2)).sum();
                let v = local.dynamics.mean_sq_residual().max(floor);
                se += a.w * e;
                sv += a.w * v * self.m as f64;
            }
            if forgetting {
                // At strength 0 the dynamics' factor is 1, which changes nothing.
                let (fd, fc) = self.adapt.decay(ad, a.w);
                local.dynamics.decay(fd);
                local.rwr.decay(fc);
            }
            if dyn_now {
                let w = if dc.weight_power == 1.0 {
                    a.w
                } else {
                    a.w.powf(dc.weight_power)
                };
                local.dynamics.observe(&ws.phi_d, &ws.xdd_target, 0.0, w)?;
            }
            let r = if adapting { self.adapt.cost(r) } else { r };
            match local.observe(&ws.phi, &ws.target, r, a.w, update_every, pace)? {
                Some(MStep::Done) => {
                    self.stats.m_steps += 1;
                    // The learned velocity loop of each joint stays stable (`inertia.rs`).
                    for (j, (l, h)) in lo.iter().zip(hi).enumerate() {
                        local.rwr.clamp_theta(self.m + j, j, *l, *h);
                    }
                }
                Some(MStep::Failed) => self.stats.failed_m_steps += 1,
                None => {}
            }
        }
        if adapting {
            self.adapt.adapting_steps += 1;
            self.adapt.detected = true;
        }
        if check {
            let dt_check = ad.check_every as f64 * self.dt;
            self.adapt.observe(ad, se, sv, dt_check);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use crate::learner::fixture;
    use lwpr::RfId;

    /// Each `Added` event adds exactly one local controller with the field's id, each `Pruned`
    /// event removes exactly that one: the partition and the controllers stay one to one.
    #[test]
    fn partition_events_add_and_remove_exactly_one_controller() {
        let (mut learner, mut sim, _) = fixture::ready(fixture::config(), 200, 50);
        let (fwd, locals) = fixture::ids(&learner);
        assert!(!fwd.is_empty());
        assert_eq!(fwd, locals);
        // Prune one field by hand: the next learning step drops its controller only.
        let gone = fwd[0];
        assert!(fixture::models(&mut learner)
            .forward
            .remove(RfId(gone))
            .unwrap());
        fixture::sweep(&mut learner, &mut sim, 1);
        let (fwd2, locals2) = fixture::ids(&learner);
        assert_eq!(fwd2, locals2);
        assert!(!locals2.contains(&gone));
        assert!(locals2.len() >= locals.len() - 1);
        // More sweeping adds fields; every new one gets exactly one controller.
        fixture::sweep(&mut learner, &mut sim, 3000);
        let (fwd3, locals3) = fixture::ids(&learner);
        assert!(fwd3.len() > fwd2.len(), "{} vs {}", fwd3.len(), fwd2.len());
        assert_eq!(fwd3, locals3);
    }

    /// Every active field gets the sample; an M-step runs after `update_every` of them.
    #[test]
    fn m_steps_run_every_update_every_samples() {
        let mut cfg = fixture::config();
        cfg.controllers.update_every = 10;
        let (learner, _, _) = fixture::ready(cfg, 100, 400);
        let s = learner.stats();
        // No field was pruned in 1 s, so the controllers' M-steps are all there are.
        assert_eq!(s.pruned_untrained, 0);
        let updates: u64 = learner.local_summaries().iter().map(|l| l.updates).sum();
        assert_eq!(s.m_steps, updates);
        assert!(s.m_steps > 0, "{s:?}");
        // A field active in all 501 samples has had at most 501 / 10 M-steps.
        assert!(learner.local_summaries().iter().all(|l| l.updates <= 50));
        assert_eq!(s.samples, 501);
    }

    /// The largest learned velocity gain `|β_{q̇_j, j}|` over the controllers after 400 more
    /// sweep samples (M-steps every 10), with the bounds `±b` (`None`: no bounds).
    fn largest_velocity_gain(b: Option<f64>) -> f64 {
        let mut cfg = fixture::config();
        cfg.controllers.update_every = 10;
        let (mut learner, mut sim, _) = fixture::ready(cfg, 100, 0);
        let models = fixture::models(&mut learner);
        let (lo, hi) = match b {
            Some(b) => (vec![-b; 3], vec![b; 3]),
            None => (Vec::new(), Vec::new()),
        };
        models.velocity_gain_lo = lo;
        models.velocity_gain_hi = hi;
        fixture::sweep(&mut learner, &mut sim, 400);
        let m = 2;
        let models = fixture::models(&mut learner);
        assert!(models.locals.map.values().any(|l| l.updates > 0));
        models
            .locals
            .map
            .values()
            .flat_map(|l| (0..3).map(move |j| l.rwr.theta()[(m + j, j)].abs()))
            .fold(0.0, f64::max)
    }

    /// After every M-step each joint's learned velocity gain is within its bounds; without
    /// them the same samples learn larger gains (so the bound acted).
    #[test]
    fn learned_velocity_gains_stay_within_their_bounds() {
        let free = largest_velocity_gain(None);
        let bounded = largest_velocity_gain(Some(1e-3));
        assert!(free > 1e-2, "{free}");
        assert!(bounded <= 1e-3, "{bounded}");
    }
}
