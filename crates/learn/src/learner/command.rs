//! The learned command (eq. 34): the activation-weighted blend of the trained local controllers
//! plus `u0`, extrapolated from the nearest trained ones where none is active, the nominal `u0`
//! where none is near, exploration on top, then the guards (non-finite blend, torque limits).

use super::exploration::explore;
use super::nominal::nominal_into;
use super::null_gravity::null_correction_into_z;
use super::{Learner, State};
use crate::error::{LearnError, Result};
use crate::local::{blend_weight, smoothstep};
use rand::Rng;

/// What produced a command.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CommandSource {
    /// The blend of the trained local controllers (eq. 34).
    Learned,
    /// Thin support (`S < w0`): the blend faded by `κ`, the rest from the nearest trained
    /// controllers (`nearest.rs`) faded into `u0`.
    Extrapolated,
    /// No trained controller active, none above `controllers.neighbour_cutoff`: the nominal
    /// `u0`.
    Fallback,
}

/// Activation cutoff of the neighbour search (initialising a new field from the blend of its
/// trained neighbours).
pub const EXTRAPOLATION_CUTOFF: f64 = 1e-4;

/// A blend's weights: `S = Σ c_i w_i` and `Σ c_i w_i σ_i` of the controllers in it.
struct Blend {
    sum_w: f64,
    sum_sigma: f64,
    source: CommandSource,
    /// The nearest trained controllers' blend is in `ws.u_far`.
    far: bool,
}

impl Learner {
    /// The learned command for the reference acceleration `xdd_ref` at `(q, q̇)` into `u`: the
    /// confidence blend (eq. 34), with exploration noise when `rng` is given, within the torque
    /// and torque-rate limits. Stages: check → blend → nominal → explore → guard → clip → rate.
    /// Does not allocate.
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
        let finished = self.with_fresh_gains(|l| match l.blend(q, qd, xdd_ref, u) {
            Ok(None) => l.fallback(q, qd, u),
            Ok(Some(blend)) => l.finish_blend(q, qd, blend, rng, u),
            Err(e) => Err(e),
        });
        let source = finished?;
        let source = self.guard_non_finite(q, qd, source, u)?;
        self.clip(u);
        if self.rate.apply(u) {
            self.stats.rate_limited += 1;
        }
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

    /// Eq. 34 without `u0`, weighted by confidence: `Σ c_i w̃_i (u^i − u0)` into `u` over the
    /// controllers with any confidence whose activation exceeds `partition.activation_cutoff`
    /// (`w̃ = w − cutoff`, so a field's weight is continuous as it enters). `None` before the
    /// warm-up ends or where no such controller is.
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
        let cut = self.cfg.partition.activation_cutoff;
        let spread = self.cfg.controllers.step_spread;
        models.forward.activations(q, qd, cut, &mut ws.acts)?;
        u.fill(0.0);
        let (mut sum_w, mut sum_sigma) = (0.0, 0.0);
        for a in &ws.acts {
            let Some(local) = models.locals.map.get_mut(&a.id) else {
                continue;
            };
            let w = blend_weight(local.ess, trained_ess, a.w, cut);
            if !(w > 0.0) {
                continue;
            }
            f.controller_local(&mut ws.phi, q, &local.center);
            local.mean_into(&ws.phi, spread, &mut ws.ui, &mut ws.ui_from)?;
            for (o, v) in u.iter_mut().zip(&ws.ui) {
                *o += w * v;
            }
            sum_w += w;
            sum_sigma += w * local.rwr.sigma();
        }
        let far =
            sum_w < self.cfg.controllers.prior_weight && self.nearest_blend(q, qd, xdd_ref)?;
        if !(sum_w > 0.0) && !far {
            return Ok(None);
        }
        let source = if sum_w >= self.cfg.controllers.prior_weight {
            CommandSource::Learned
        } else {
            CommandSource::Extrapolated
        };
        Ok(Some(Blend {
            sum_w,
            sum_sigma,
            source,
            far,
        }))
    }

    /// Scales the blend by its support `κ = smoothstep(S / w0)` (1 from `S = w0` on), adds `u0`
    /// (residual controllers) and the exploration noise (of the blended `σ`, scaled the same).
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
        let kappa = smoothstep(blend.sum_w / self.cfg.controllers.prior_weight);
        // `S = 0` where only the neighbours command: no blend to scale, no exploration.
        let (sigma, scale) = if blend.sum_w > 0.0 {
            let gain = self.noise.gain * self.cfg.exploration.scale;
            (
                gain * kappa * blend.sum_sigma / blend.sum_w,
                kappa / blend.sum_w,
            )
        } else {
            (0.0, 0.0)
        };
        u.iter_mut().for_each(|v| *v *= scale);
        self.project_command(q, u);
        // The neighbours' part after the projection: the projector appears with the first
        // active field, and only the part it multiplies (`κ → 0` there) may meet it.
        if blend.far {
            for (v, f) in u.iter_mut().zip(&self.ws.u_far) {
                *v += (1.0 - kappa) * f;
            }
        }
        if self.cfg.experimental.residual {
            let u0 = &mut self.ws.u0;
            nominal_into(
                &self.cfg.nominal,
                &self.cfg.gravity,
                self.state.models_mut(),
                self.gravity_frozen,
                q,
                qd,
                u0,
            )?;
            self.load.add_into(&self.ws.acts, u0);
            for (v, o) in u.iter_mut().zip(u0.iter()) {
                *v += o;
            }
            self.add_null_correction(q, u)?;
        }
        if let (Some(rng), State::Ready(models)) = (rng, &self.state) {
            explore(
                &self.cfg,
                &self.features,
                models,
                &mut self.ws,
                &mut self.noise,
                q,
                sigma,
                rng,
                u,
            );
        }
        Ok(blend.source)
    }

    /// The null-space correction (`null_gravity.rs`) under the `Â` of the command's blend
    /// (active fields in `ws.acts`), added to `u`; nothing without it or without an `Â`.
    pub(super) fn add_null_correction(&mut self, q: &[f64], u: &mut [f64]) -> Result<()> {
        let State::Ready(models) = &mut self.state else {
            return Ok(());
        };
        if !self.cfg.gravity.null_correction || models.gravity_null.is_none() {
            return Ok(());
        }
        if !self.command_gains(q).0 {
            return Ok(());
        }
        let State::Ready(models) = &mut self.state else {
            return Ok(());
        };
        let ws = &mut self.ws;
        if null_correction_into_z(&self.cfg, models, ws, q, self.gravity_frozen, &self.load)? {
            for (v, z) in u.iter_mut().zip(&ws.z) {
                *v += z;
            }
        }
        Ok(())
    }

    /// Runs `f` with the cache of `Â` at one state (`ws.gains`, filled by
    /// [`Learner::command_gains`]) empty at its start and emptied again at its end, so that
    /// nothing outside `f` reads an `Â` formed at another state.
    pub(super) fn with_fresh_gains<T>(&mut self, f: impl FnOnce(&mut Self) -> T) -> T {
        self.ws.gains = None;
        let out = f(self);
        self.ws.gains = None;
        out
    }

    /// `Â` at the command's state `q` (active fields in `ws.acts`): of the command's blend in
    /// `ws.a_hat` and of the plain activations in `ws.a_hat_plain`, formed once per command
    /// (`Models::command_and_blended_gain`) for the projection, the null-space correction and
    /// the exploration; whether each is known.
    pub(super) fn command_gains(&mut self, q: &[f64]) -> (bool, bool) {
        if let Some(known) = self.ws.gains {
            return known;
        }
        let State::Ready(models) = &self.state else {
            return (false, false);
        };
        let ws = &mut self.ws;
        let weights = (
            self.cfg.partition.activation_cutoff,
            self.cfg.controllers.trained_ess,
        );
        let (acts, a_cmd, a_plain) = (&ws.acts, &mut ws.a_hat, &mut ws.a_hat_plain);
        let known =
            models.command_and_blended_gain(&self.features, acts, q, weights, a_cmd, a_plain);
        ws.gains = Some(known);
        known
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

#[cfg(test)]
mod tests {
    use super::CommandSource;
    use crate::learner::fixture::{self, one_trained_field};
    use nalgebra::DMatrix;
    use rwr::OnlineRwr;

    /// With one trained controller the blend (eq. 34) is that controller's mean plus `u0`, from
    /// any activation; with none, the command is `u0` and counted as a fallback.
    #[test]
    fn a_one_field_blend_equals_that_fields_mean_plus_u0() {
        let mut cfg = fixture::config();
        cfg.controllers.trained_ess = 1e8;
        cfg.controllers.command_projection = 0.0; // eq. 34 as it is (`projection.rs` tests it)
        cfg.controllers.neighbour_cutoff = 0.0; // `u0` alone below w0 (`nearest_tests.rs`)
        let (mut learner, _, last) = fixture::ready(cfg, 200, 0);
        let (q, qd) = (last.q.as_slice().to_vec(), last.qd.as_slice().to_vec());
        let xdd = [0.3, -0.2];
        let (mut u, mut u0) = ([0.0; 3], [0.0; 3]);
        assert_eq!(
            learner
                .command::<rand_chacha::ChaCha8Rng>(&q, &qd, &xdd, None, &mut u)
                .unwrap(),
            CommandSource::Fallback
        );
        learner.nominal(&q, &qd, &mut u0).unwrap();
        assert_eq!(u, u0);
        // Train one field by hand: a known β, and an effective sample size above the threshold.
        let p = learner.features.controller_len();
        let beta = DMatrix::from_fn(p, 3, |r, c| 0.01 * (r as f64 + 1.0) * (c as f64 - 1.0));
        let rwr_cfg = learner.cfg.controllers.rwr.clone();
        let models = fixture::models(&mut learner);
        let (id, local) = models.locals.map.iter_mut().next().unwrap();
        let id = *id;
        local.rwr = OnlineRwr::with_theta(beta.clone(), rwr_cfg).unwrap();
        local.theta_from = None; // set by hand: no update to spread
        local.ess = 1e9;
        let center = local.center.clone();
        // At the field's centre the command is its mean plus u0; where its support is below
        // w0 (extrapolated) the mean is scaled by κ = smoothstep((w − cutoff) / w0).
        let (cut, w0) = (0.05, 0.05);
        for (qq, source) in [
            (center[..3].to_vec(), CommandSource::Learned),
            (
                center[..3].iter().map(|c| c + 0.1665).collect(),
                CommandSource::Extrapolated,
            ),
        ] {
            let vd = center[3..].to_vec();
            learner.start_episode(None).unwrap(); // no rate limit against the previous case
            let src = learner.command::<rand_chacha::ChaCha8Rng>(&qq, &vd, &xdd, None, &mut u);
            assert_eq!(src.unwrap(), source, "field {id:?}");
            let mut acts = Vec::new();
            let fwd = &mut fixture::models(&mut learner).forward;
            fwd.activations(&qq, &vd, 1e-12, &mut acts).unwrap();
            let w = acts.iter().find(|a| a.id == id).unwrap().w;
            let x = ((w - cut) / w0).min(1.0);
            let kappa = x * x * (3.0 - 2.0 * x);
            let mut phi = vec![0.0; p];
            learner.features.controller_common(&mut phi, &xdd, &vd);
            learner.features.controller_local(&mut phi, &qq, &center);
            learner.nominal(&qq, &vd, &mut u0).unwrap();
            for j in 0..3 {
                let mean: f64 = (0..p).map(|r| phi[r] * beta[(r, j)]).sum();
                let want = kappa * mean + u0[j];
                assert!(
                    (u[j] - want).abs() < 1e-12 * (1.0 + want.abs()),
                    "{source:?} w {w} {u:?} vs {want}"
                );
            }
            if source == CommandSource::Extrapolated {
                assert!(kappa > 0.0 && kappa < 1.0, "w = {w}");
            }
        }
        assert_eq!(learner.stats().extrapolations, 1);
    }

    /// The guards: wrong lengths are refused uncounted; commands stay within the torque limits.
    #[test]
    fn wrong_lengths_are_refused_and_limits_hold() {
        let mut cfg = fixture::config();
        cfg.guards.torque_limits = vec![0.1, 0.1, 0.1];
        let (mut learner, _, last) = fixture::ready(cfg, 100, 0);
        let before = learner.stats();
        let mut u = [0.0; 3];
        let q = last.q.as_slice();
        let bad = learner.command::<rand_chacha::ChaCha8Rng>(&q[..2], q, &[0.0; 2], None, &mut u);
        assert!(matches!(bad, Err(crate::LearnError::Dimension { .. })));
        assert_eq!(learner.stats(), before);
        learner
            .command::<rand_chacha::ChaCha8Rng>(q, q, &[0.0; 2], None, &mut u)
            .unwrap();
        assert!(u.iter().all(|v| v.abs() <= 0.1), "{u:?}");
        assert_eq!(learner.stats().clipped, before.clipped + 1);
    }

    /// A `last_sent` beyond the torque limits (a robot that held a larger command) does not
    /// lead the rate limit's commands beyond them; a non-finite or short one is refused.
    #[test]
    fn commands_stay_within_the_limits_after_a_last_sent_beyond_them() {
        let mut cfg = fixture::config();
        cfg.guards.torque_limits = vec![60.0, 40.0, 20.0];
        let (mut learner, _, last) = fixture::ready(cfg, 100, 0);
        let q = last.q.as_slice();
        for far in [100.0, 1e300] {
            learner.start_episode(Some(&[far; 3])).unwrap();
            for _ in 0..30 {
                let mut u = [0.0; 3];
                learner
                    .command::<rand_chacha::ChaCha8Rng>(q, &[0.0; 3], &[0.0; 2], None, &mut u)
                    .unwrap();
                let within = u.iter().zip([60.0, 40.0, 20.0]).all(|(v, l)| v.abs() <= l);
                assert!(within, "last_sent {far}: {u:?}");
            }
        }
        let stats = learner.stats();
        let nan = learner.start_episode(Some(&[0.0, f64::NAN, 0.0]));
        assert!(matches!(
            nan,
            Err(crate::LearnError::NonFinite("last_sent"))
        ));
        let short = learner.start_episode(Some(&[0.0; 2]));
        assert!(matches!(short, Err(crate::LearnError::Dimension { .. })));
        assert_eq!(learner.stats(), stats);
    }

    /// `max_j |a_j − b_j|`.
    fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max)
    }

    /// The largest command change along a straight line in `q` from 2 rad away (beyond the
    /// neighbours' fade also at a family's cutoff, 13.6 kernel widths of 0.125 rad) to the
    /// trained field's centre, in `steps` equal increments (no exploration, no rate limit).
    fn largest_change_into_the_field(steps: usize) -> (f64, Vec<CommandSource>) {
        let mut cfg = fixture::config();
        cfg.guards.torque_rate_limit = Some(f64::MAX);
        cfg.controllers.neighbour_cutoff = 1e-40;
        let (mut learner, c) = one_trained_field(cfg);
        let (q0, vd) = (&c[..3], c[3..].to_vec());
        let (xdd, mut prev, mut u) = ([0.3, -0.2], None::<[f64; 3]>, [0.0; 3]);
        let (mut largest, mut sources) = (0.0f64, Vec::new());
        for k in 0..=steps {
            let s = 2.0 * (1.0 - k as f64 / steps as f64);
            let q: Vec<f64> = q0.iter().map(|v| v + s).collect();
            let src = learner
                .command::<rand_chacha::ChaCha8Rng>(&q, &vd, &xdd, None, &mut u)
                .unwrap();
            if sources.last() != Some(&src) {
                sources.push(src);
            }
            if let Some(p) = prev {
                largest = largest.max(largest_difference(&p, &u));
            }
            prev = Some(u);
        }
        (largest, sources)
    }

    /// An untrained region falls back smoothly: moving into a trained field from where no field
    /// is near, the command goes from `u0` (fallback) through the support-scaled blend
    /// (extrapolated) to the field's own (learned) without a jump — with four times finer
    /// increments, the largest change shrinks about fourfold (a jump would stay).
    #[test]
    fn a_field_joins_the_blend_without_a_step() {
        let (coarse, sources) = largest_change_into_the_field(500);
        let (fine, _) = largest_change_into_the_field(2000);
        assert_eq!(
            sources,
            [
                CommandSource::Fallback,
                CommandSource::Extrapolated,
                CommandSource::Learned
            ]
        );
        assert!(fine < 0.35 * coarse, "{fine} vs {coarse}: a step");
    }

    /// With exploration, consecutive commands never change by more than the torque-rate limit
    /// times the period, and the limiter counts the commands it held.
    #[test]
    fn exploring_commands_stay_within_the_torque_rate_limit() {
        use rand::SeedableRng;
        let mut cfg = fixture::config();
        cfg.guards.torque_rate_limit = Some(50.0);
        cfg.exploration.correlation_time = 0.0; // white noise: the worst case for the limit
        let (mut learner, c) = one_trained_field(cfg);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let (q, vd) = (c[..3].to_vec(), c[3..].to_vec());
        let (mut prev, mut u) = (None::<[f64; 3]>, [0.0; 3]);
        let step = 50.0 * 0.002;
        learner.start_episode(None).unwrap();
        let before = learner.stats().rate_limited;
        for _ in 0..2000 {
            learner
                .command(&q, &vd, &[0.1, 0.0], Some(&mut rng), &mut u)
                .unwrap();
            if let Some(p) = prev {
                let d = largest_difference(&p, &u);
                assert!(d <= step * (1.0 + 1e-12), "{d} > {step}");
            }
            prev = Some(u);
        }
        assert!(
            learner.stats().rate_limited > before,
            "the limit never acted"
        );
    }

    /// The learner's limiter follows the scaling rule: planar3's data sheet keeps 2 N·m per
    /// 2 ms; the same arm with ten times its torque limits gets ten times the step on the
    /// joints above 100 N·m (and the floor on the others); a set rate wins; new torque limits
    /// move the limiter with them.
    #[test]
    fn the_learners_rate_limit_scales_with_its_torque_limits() {
        let dt = 0.002;
        let learner = crate::Learner::new(3, 2, dt, fixture::config()).unwrap();
        assert_eq!(learner.rate.steps(), &[2.0; 3]);
        let mut heavy = fixture::config();
        heavy.guards.torque_limits = vec![600.0, 400.0, 20.0];
        let mut learner = crate::Learner::new(3, 2, dt, heavy.clone()).unwrap();
        let want = [12.0, 8.0, 2.0];
        for (s, w) in learner.rate.steps().iter().zip(want) {
            assert!((s - w).abs() < 1e-12, "{:?}", learner.rate.steps());
        }
        learner.set_torque_limits(&[60.0, 40.0, 20.0]).unwrap();
        assert_eq!(learner.rate.steps(), &[2.0; 3]);
        heavy.guards.torque_rate_limit = Some(50.0);
        let learner = crate::Learner::new(3, 2, dt, heavy).unwrap();
        assert!(learner.rate.steps().iter().all(|s| (s - 0.1).abs() < 1e-12));
    }

    /// An M-step's change is spread over `step_spread` commands: with the field's `β` before
    /// its last update at 0, the learned part of the command at a fixed state rises by equal
    /// steps of 1/25 of the change and then stays at the new controller's.
    #[test]
    fn an_m_steps_change_is_spread_over_step_spread_commands() {
        let mut cfg = fixture::config();
        cfg.guards.torque_rate_limit = Some(f64::MAX);
        cfg.controllers.step_spread = 25;
        let (mut learner, c) = one_trained_field(cfg);
        let (q, vd, xdd) = (c[..3].to_vec(), c[3..].to_vec(), [0.3, -0.2]);
        let mut full = [0.0; 3];
        let cmd = |l: &mut crate::Learner, u: &mut [f64; 3]| {
            l.command::<rand_chacha::ChaCha8Rng>(&q, &vd, &xdd, None, u)
                .unwrap()
        };
        assert_eq!(cmd(&mut learner, &mut full), CommandSource::Learned);
        let mut u0 = [0.0; 3];
        learner.nominal(&q, &vd, &mut u0).unwrap();
        let local = fixture::models(&mut learner)
            .locals
            .map
            .values_mut()
            .next()
            .unwrap();
        local.theta_from = Some(DMatrix::zeros(local.rwr.theta().nrows(), 3));
        local.ramp = 0;
        let mut u = [0.0; 3];
        for k in 1..=30 {
            cmd(&mut learner, &mut u);
            let a = (k as f64 / 25.0).min(1.0);
            for j in 0..3 {
                let want = u0[j] + a * (full[j] - u0[j]);
                assert!((u[j] - want).abs() < 1e-9, "command {k}: {u:?} vs {want}");
            }
        }
        assert!(largest_difference(&full, &u0) > 0.1);
    }
}
