//! The learner's state: its configuration, dimensions, feature layouts, the warm-up or its
//! models, counters, and the memory of the command (noise processes, rate limiter).

use super::exploration::Noise;
use super::stats::Scratch;
use super::{AdaptationSignal, Features, LearnerStats, LoadCorrection, Models, RateLimiter};
use crate::config::{scaled, LearnerConfig};
use crate::error::{LearnError, Result};
use crate::forward::ForwardModel;
use crate::gravity::GravityModel;
use osrl_dynamics::Measurement;

/// What the learner has: measurements of the warm-up, or its models.
#[derive(Clone, Debug)]
pub(crate) enum State {
    /// Transitions collected until `guards.warmup_samples`; their scales size the models.
    WarmUp(Vec<Measurement>),
    /// The models, made from the warm-up and trained since.
    Ready(Box<Models>),
}

impl State {
    pub fn models(&self) -> Option<&Models> {
        match self {
            State::Ready(m) => Some(m),
            State::WarmUp(_) => None,
        }
    }
    pub fn models_mut(&mut self) -> Option<&mut Models> {
        match self {
            State::Ready(m) => Some(m),
            State::WarmUp(_) => None,
        }
    }
}

/// The learned operational space controller's state (paper section IV).
#[derive(Clone, Debug)]
pub struct Learner {
    pub(crate) cfg: LearnerConfig,
    pub(crate) n: usize,
    pub(crate) m: usize,
    /// Control period (s).
    pub(crate) dt: f64,
    pub(crate) features: Features,
    pub(crate) state: State,
    pub(crate) stats: LearnerStats,
    /// `ĝ` no longer learns (see [`Learner::freeze_gravity`]).
    pub(crate) gravity_frozen: bool,
    /// The static gravity model learns nothing either (see [`Learner::freeze_static_gravity`];
    /// not saved: the training driver sets it for each run).
    pub(crate) static_frozen: bool,
    pub(crate) ws: Scratch,
    /// The exploration noise processes and the torque-rate limiter: the memory of the command
    /// from one control period to the next (reset by [`Learner::start_episode`]).
    pub(crate) noise: Noise,
    pub(crate) rate: RateLimiter,
    /// The re-adaptation's running level (not saved; see [`Learner::reset_adaptation`]).
    pub(crate) adapt: AdaptationSignal,
    /// The load correction of `u0` learned while re-adapting (saved; empty until then).
    pub(crate) load: LoadCorrection,
    /// The still samples of the current hold at a path posture, for the null-space correction
    /// (`null_gravity.rs`; not saved).
    pub(crate) hold: super::hold::HoldBatch,
}

impl Learner {
    /// A learner for a robot with `n` joints and an `m`-dimensional task, controlled every `dt`
    /// seconds (within [`crate::CONTROL_PERIOD_RANGE`]).
    ///
    /// # Errors
    /// [`LearnError::InvalidConfig`] on an invalid config or dimensions.
    pub fn new(n: usize, m: usize, dt: f64, cfg: LearnerConfig) -> Result<Self> {
        cfg.validate(n)?;
        let periods = crate::config::CONTROL_PERIOD_RANGE;
        if m == 0 || m > n || !periods.contains(&dt) {
            return Err(LearnError::InvalidConfig(format!(
                "need 0 < m ≤ n and a control period dt within [{:?}, {:?}] s, the range a \
                 saved model accepts (n = {n}, m = {m}, dt = {dt:?})",
                periods.start(),
                periods.end()
            )));
        }
        Models::check_config(&cfg, n, m)?;
        let x = &cfg.experimental;
        let features = Features::new(n, m, x.position_features, x.dynamics_bilinear)
            .with_controller_bilinear(cfg.controllers.bilinear);
        let ws = Scratch::new(n, m, features.controller_len(), features.dynamics_len());
        let noise = Noise::with_rate(
            n,
            cfg.exploration.process,
            cfg.exploration.correlation_time,
            dt,
            cfg.exploration.max_rate,
        );
        let g = &cfg.guards;
        let rates = scaled::torque_rate_limits(g.torque_rate_limit, &g.torque_limits, n);
        let rate = RateLimiter::new(&rates, dt);
        Ok(Self {
            noise,
            rate,
            state: State::WarmUp(Vec::with_capacity(cfg.guards.warmup_samples + 1)),
            cfg,
            n,
            m,
            dt,
            features,
            stats: LearnerStats::default(),
            gravity_frozen: false,
            static_frozen: false,
            ws,
            adapt: AdaptationSignal::default(),
            load: LoadCorrection::default(),
            hold: Default::default(),
        })
    }

    /// The re-adaptation's state (`adaptation.enabled`; all 0 while it is off).
    pub fn adaptation(&self) -> AdaptationSignal {
        self.adapt
    }

    /// The load correction of `u0` (`learner/load.rs`; empty unless the learner re-adapted).
    pub fn load_correction(&self) -> &LoadCorrection {
        &self.load
    }

    /// Starts the re-adaptation's running level afresh (it is not saved with the learner, so a
    /// run that continues a saved or an in-memory learner calls this to behave the same), for a
    /// continuing learner (`AdaptationSignal::continuation`).
    pub fn reset_adaptation(&mut self) {
        self.adapt = AdaptationSignal {
            continuation: true,
            ..AdaptationSignal::default()
        };
    }

    /// Sets the re-adaptation settings (e.g. on a loaded controller).
    ///
    /// # Errors
    /// A setting out of range; nothing is changed.
    pub fn set_adaptation(&mut self, cfg: crate::config::AdaptationConfig) -> Result<()> {
        cfg.validate()?;
        if cfg.enabled && cfg.null_correction {
            self.cfg.gravity.null_correction = true;
        }
        self.cfg.adaptation = cfg;
        Ok(())
    }

    /// Scales the exploration noise of the next commands by `gain` (clamped to [0, 1]; 1 until
    /// set): the driver fades exploration out where it wants still samples (the path clock's
    /// holds, `TrainConfig::explore_with_clock`). Not saved.
    pub fn set_exploration_gain(&mut self, gain: f64) {
        self.noise.gain = if gain.is_nan() {
            1.0
        } else {
            gain.clamp(0.0, 1.0)
        };
    }

    /// Starts a new sequence of commands: the command last sent to the robot (`None`: unknown,
    /// the next command is not rate limited) and the exploration noise back at 0. A
    /// `last_sent` beyond the torque limits (`guards.torque_limits`) counts as sent at the
    /// limit: the learner's commands stay within its limits, also while the rate limit leads
    /// them away from a command it did not send.
    ///
    /// # Errors
    /// [`LearnError::Dimension`] for a `last_sent` without one value per joint,
    /// [`LearnError::NonFinite`] for a value that is not finite; the learner is unchanged.
    pub fn start_episode(&mut self, last_sent: Option<&[f64]>) -> Result<()> {
        match last_sent {
            None => self.rate.reset(None),
            Some(u) => {
                if u.len() != self.n {
                    return Err(LearnError::Dimension {
                        what: "last_sent",
                        expected: self.n,
                        got: u.len(),
                    });
                }
                if u.iter().any(|v| !v.is_finite()) {
                    return Err(LearnError::NonFinite("last_sent"));
                }
                self.rate.reset_within(u, &self.cfg.guards.torque_limits);
            }
        }
        self.noise.reset();
        Ok(())
    }

    pub fn config(&self) -> &LearnerConfig {
        &self.cfg
    }

    /// A task-space disturbance observer with this learner's settings for the drivers that
    /// compute `ẍ_ref`: `adaptation.observer_seconds` while re-adapting (or with
    /// `observer_always`), off otherwise.
    pub fn observer(&self) -> crate::Dob {
        let a = &self.cfg.adaptation;
        let on = a.enabled || a.observer_always;
        let seconds = if on { a.observer_seconds } else { 0.0 };
        crate::Dob::new(self.m, self.dt, seconds, a.observer_max)
    }

    /// Sets the torque limits of the commands (N·m, one per joint; empty: none), e.g. on a
    /// controller saved without them.
    ///
    /// # Errors
    /// A wrong count or a limit that is not finite and > 0; nothing is changed.
    pub fn set_torque_limits(&mut self, tau_max: &[f64]) -> Result<()> {
        let mut cfg = self.cfg.clone();
        cfg.guards.torque_limits = tau_max.to_vec();
        cfg.validate(self.n)?;
        let g = &cfg.guards;
        let rates = scaled::torque_rate_limits(g.torque_rate_limit, &g.torque_limits, self.n);
        self.rate.set_rates(&rates, self.dt);
        self.cfg = cfg;
        Ok(())
    }

    pub fn stats(&self) -> LearnerStats {
        self.stats
    }

    /// Number of joints and task dimensions.
    pub fn dims(&self) -> (usize, usize) {
        (self.n, self.m)
    }

    /// The control period the learner was made for (s).
    pub fn control_period(&self) -> f64 {
        self.dt
    }

    /// Number of local controllers (= receptive fields of the forward model).
    pub fn n_local_models(&self) -> usize {
        self.state.models().map_or(0, |m| m.locals.len())
    }

    /// Summaries of the local controllers (effective sample size, σ, τ).
    pub fn local_summaries(&self) -> Vec<crate::local::LocalSummary> {
        self.state
            .models()
            .map_or_else(Vec::new, |m| m.locals.summaries())
    }

    /// The forward model (the partition), once the warm-up is over.
    pub fn forward_model(&self) -> Option<&ForwardModel> {
        self.state.models().map(|m| &m.forward)
    }

    /// `Â = ∂ẍ/∂u` at `(q, q̇)` from the local dynamics of the active receptive fields (m×n
    /// row-major into `a`); `false` without support or before the warm-up ends.
    pub fn input_gain(&mut self, q: &[f64], qd: &[f64], a: &mut [f64]) -> Result<bool> {
        let State::Ready(models) = &mut self.state else {
            return Ok(false);
        };
        let cutoff = self.cfg.partition.activation_cutoff;
        models
            .forward
            .activations(q, qd, cutoff, &mut self.ws.acts)?;
        Ok(models.blended_gain(&self.features, &self.ws.acts, q, a))
    }

    /// Stops (or resumes) the learning of the gravity model `ĝ`. The training driver freezes it
    /// when on-policy learning starts: along a single path `q̇` and `q̈` are functions of `q`, so
    /// the inverse-dynamics regression cannot separate them and its value at `q̇ = q̈ = 0` drifts.
    pub fn freeze_gravity(&mut self, frozen: bool) {
        self.gravity_frozen = frozen;
    }

    /// Stops (or resumes) the learning of the static gravity model too, which otherwise keeps
    /// learning from the still samples while `ĝ` is frozen (`gravity.static_on_policy`). The
    /// training driver freezes it for a continuation of a trained controller (`osrl adapt`,
    /// `TrainConfig::freeze_static_in_continuation`).
    pub fn freeze_static_gravity(&mut self, frozen: bool) {
        self.static_frozen = frozen;
    }

    /// The cost metric `N` (n×n, row-major) the local controllers use, estimated in the
    /// warm-up (`controllers.metric = "inverse_inertia"`); `None` for `N = I` or before the
    /// warm-up ends.
    pub fn cost_metric(&self) -> Option<Vec<f64>> {
        self.state.models()?.metric.as_ref().map(|m| m.matrix())
    }

    /// Whether `ĝ` is frozen.
    pub fn gravity_frozen(&self) -> bool {
        self.gravity_frozen
    }

    /// Local controllers with enough data to act.
    pub fn n_trained(&self) -> usize {
        let ess = self.cfg.controllers.trained_ess;
        self.state.models().map_or(0, |m| m.locals.n_trained(ess))
    }

    /// The gravity model `ĝ`, once the warm-up is over.
    pub fn gravity_model(&self) -> Option<&GravityModel> {
        self.state.models().map(|m| &m.gravity)
    }

    /// The static gravity model, if configured and past the warm-up.
    pub fn gravity_static_model(&self) -> Option<&GravityModel> {
        self.state.models().and_then(|m| m.gravity_static.as_ref())
    }

    /// Receptive fields of the gravity model.
    pub fn n_gravity_rfs(&self) -> usize {
        self.gravity_model().map_or(0, |g| g.n_rfs())
    }

    /// Whether the warm-up is over and the models exist.
    pub fn ready(&self) -> bool {
        matches!(self.state, State::Ready(_))
    }
}
