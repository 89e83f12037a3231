//! Settings of the learned controller (the learner) — every field with its unit and default.

use crate::error::{LearnError, Result};
use lwpr::{LwprConfig, MetricInit};
use rwr::RwrConfig;
use serde::{Deserialize, Serialize};

/// The cost whose transformed value weights the hindsight samples of the local controllers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CostKind {
    /// The paper's `r = ‖u − u0‖²` (`N = I`).
    Full,
    /// Only its avoidable part `r_null = ‖(I − Â⁺Â)(u − u0)‖²`, with `Â = ∂ẍ/∂u` from the
    /// receptive fields' local dynamics regressions (DESIGN.md §3): the same optimum, a
    /// better-scaled `τ`. The default: with `full`, `τ` is set by the unavoidable part of the cost
    /// and the null space barely improves (measured on planar3: command nMSE ≈ 0.9–1.6 after
    /// 10–20 simulated minutes, and the runs become unstable).
    #[default]
    NullSpace,
}

/// How exploration noise is shaped.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ExplorationKind {
    /// Isotropic Gaussian actuator noise of the blended `σ`, capped per joint by
    /// `exploration_cap` (the paper's exploration).
    Isotropic,
    /// The same capped isotropic noise plus Gaussian noise of the blended `σ` projected onto the
    /// null space of `Â = ∂ẍ/∂u` (local dynamics regressions): it explores the redundancy that RWR
    /// must resolve without disturbing the task (to first order). The default: capped isotropic
    /// noise alone is too small to discriminate null-space commands, uncapped it shakes the task.
    #[default]
    NullSpace,
}

/// The nominal behaviour `u0 = ĝ(q) − K_Dq q̇ − K_Pq (q − q_rest)` (eq. 6 plus learned gravity).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct NominalConfig {
    /// Joint stiffness `K_Pq` (N·m/rad), one per joint. Default: the robot's PD gains.
    pub kp: Vec<f64>,
    /// Joint damping `K_Dq` (N·m·s/rad). Default: the robot's PD gains.
    pub kd: Vec<f64>,
    /// Rest posture (rad). Default: the robot's rest posture.
    pub q_rest: Vec<f64>,
}

/// All settings of the learner (models and local controllers).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LearnerConfig {
    /// Nominal behaviour; filled from the robot's data sheet by [`LearnerConfig::for_robot`].
    pub nominal: NominalConfig,
    /// Gravity model `ĝ`: LWPR on `[q, q̇, q̈] → u`, kernel on `q` (the input and kernel
    /// dimensions are set by the learner). Default: fixed kernels of width 0.25 rad (`init_d` 16,
    /// `update_d` false), `w_gen` 0.2. (Measured on planar3, seed 1: `u0` error 0.023 of the
    /// command variance vs 0.13–0.16 with `init_d` 4 and metric learning, which left 5–8
    /// receptive fields for the whole arm.)
    pub gravity: LwprConfig,
    /// Forward model: LWPR on `[q, q̇, u] → ẍ`, kernel on `(q, q̇)` (eq. 33), regression on
    /// `(q̇, u)` (eq. 32), receptive fields shared by the task dimensions (set by the learner).
    /// Default: fixed kernels of width 0.125 rad and 1.25 rad/s (`init_d` 64, `update_d`
    /// false), `w_gen` 0.2. Without the distance-metric learning a sarcos7 learning step is
    /// cheaper and the results did not suffer (`learn_figure8`, 20 simulated minutes, seeds
    /// 0/1: nMSE 0.070/0.052 and 8.1–8.8× real time with two runs on 2 cores, against
    /// 0.071/0.131 and 5.6–5.8× with it; planar3 seed 0 after 30 minutes: 0.0100 against
    /// 0.0116).
    pub forward: LwprConfig,
    /// Reward-weighted regression of each local controller (its own `τ_i`, `σ_i`). Default
    /// forgetting 1: with the hindsight shrinkage the regression targets are stationary, and
    /// forgetting the babbling data left on-path regressions whose features are collinear
    /// (measured on planar3: tracking drifting from 0.22 to ~1 mm between minutes 10 and 30 with
    /// forgetting 0.99995; 0.15–0.16 mm and still improving with 1).
    pub rwr: RwrConfig,
    /// Cost of the reward weighting. Default `null_space` (see [`CostKind`]).
    pub cost: CostKind,
    /// The forward model's local regression also uses `q` (eq. 32 uses `[q̇, u, 1]` only). Without
    /// it the learned `Â = ∂ẍ/∂u` is biased towards zero (measured: 90 % error on `planar3`),
    /// since `u` carries the gravity compensation of the `q` it was applied at. Default true.
    pub forward_uses_q: bool,
    /// Local controllers learn the deviation from the nominal behaviour, `u = u0(q, q̇) +
    /// [ẍ_refᵀ, q̇ᵀ, 1] β^i`, instead of `u` itself (eq. 31): the learned gravity and the PD pull,
    /// which vary inside a receptive field, are then exact rather than averaged. Default true.
    pub residual: bool,
    /// Add the offset from the receptive field's centre, `q − c_i`, to the features of eq. 31, so
    /// each local controller is linear in `q` too. Default true (false: the paper's features).
    pub position_features: bool,
    /// Weight the hindsight samples by the transformed reward (`true`, RWR) or not (`false`:
    /// plain activation-weighted regression, the supervised-inverse ablation of E6). Default true.
    pub reward_weighting: bool,
    /// A receptive field learns from (and joins the blend at) activations above this. Default 0.05.
    pub activation_cutoff: f64,
    /// A local controller joins the blend once its effective sample size reaches this. Default 50.
    pub min_ess: f64,
    /// M-step of a local controller after this many new samples. Default 25.
    pub update_every: usize,
    /// The forward model (the partition) learns from every this many transitions; the local
    /// controllers still learn from every one (their dynamics from every `dynamics_every`).
    /// With fixed kernels its regression serves no one (`Â` comes from the local dynamics, its
    /// PLS slopes were 87–96 % off): it places the receptive fields, and a new field needs a
    /// state visited for longer than this many control periods. Its update was the largest cost
    /// of a sarcos7 learning step (41 % of the time with 2). Default 8 (`learn_figure8` sarcos7,
    /// 20 simulated minutes, seeds 0/1: nMSE 0.071/0.057, steady 3.5–4 s of wall time per
    /// simulated minute, against 0.070/0.052 and about 6 s with 2).
    pub forward_every: usize,
    /// The local dynamics regressions (`Â`) learn from every this many transitions: consecutive
    /// transitions (2 ms apart) carry nearly the same information, and on sarcos7 (71 features
    /// with `dynamics_bilinear`) these regressions were over half of a learning step. Default 1.
    pub dynamics_every: usize,
    /// The local dynamics regressions are re-solved at every this many M-steps of their
    /// controller (each re-solve factors a 71×71 system on sarcos7): at its 1st, 5th, 9th, …
    /// M-step with 4. Before this switch existed, `dynamics_every` also set this. Default 4
    /// (measured together with `forward_every` 2 against 1 and 1 on sarcos7 seed 2, two runs
    /// side by side: 30 simulated minutes reached while the other reached 22–23, nMSE 0.089 at
    /// minute 30 for both; planar3 seed 0 after 30 minutes 0.012 vs 0.009).
    pub dynamics_solve_every: usize,
    /// Scale of the exploration noise relative to each local controller's `σ_i`. Default 1.
    pub exploration_scale: f64,
    /// Shape of the exploration noise. Default `null_space`.
    pub exploration: ExplorationKind,
    /// Optional cap on the null-space exploration noise of joint `j` (before the projection), as
    /// a share of the standard deviation of its torques during the warm-up. Default none.
    /// (Measured on planar3, 20 simulated minutes, seeds 0/1/2: with 0.25 all three seeds track,
    /// 2.9/0.65/0.87 mm at command nMSE 0.93/0.77/1.05; without it seed 2 fails while seed 0 gets
    /// further, 1.06 mm at nMSE 0.49 after 30 minutes.)
    pub null_space_cap: Option<f64>,
    /// Forgetting factor of each receptive field's local dynamics regression (`Â`), per sample.
    /// Default 0.99995 (the on-path `Â` error is 7 % with it, 18–25 % with 1).
    pub dynamics_forgetting: f64,
    /// The gravity model's regressors include the velocity products `q̇ᵢq̇ⱼ` (inverse dynamics is
    /// quadratic in `q̇`; without them each local model's intercept, and so `ĝ`, carries the mean
    /// centripetal torque of its samples). Default true. (Not a clear win yet: on planar3, seed 1,
    /// babbling without noise, the `u0` error was 0.078 of the command variance with the products
    /// and 0.023 without; every later measurement, with babbling noise, used them. With metric
    /// learning on, the products let `ĝ` collapse to one receptive field, hence the fixed
    /// kernels.)
    pub gravity_velocity_products: bool,
    /// The local dynamics regressions also have the bilinear features `u_j (q_k − c_k)`, so `Â`
    /// varies linearly with `q` inside a receptive field (`Â(q) = Θ_u + Σ_k (q_k − c_k) Θ_{u q_k}`).
    /// Default true: on planar3 (seeds 1/2, 20 simulated minutes) the on-path `Â` error fell from
    /// 6.7–7.1 % to 2.4–2.7 % and the command nMSE from 0.17/0.16 to 0.047/0.051.
    pub dynamics_bilinear: bool,
    /// The gravity model `ĝ` keeps learning during on-policy training (false: it learns from the
    /// babbling only; see [`crate::Learner::freeze_gravity`]). Default false.
    pub gravity_on_policy: bool,
    /// A second gravity model learnt from still samples only (see [`StaticGate`]), regressing on
    /// `q` alone; once `ĝ` is frozen (on-policy), `u0` uses it wherever it has support (the
    /// dynamic model drives the babbling and fills in elsewhere). `None`: the dynamic model only.
    /// Default `Some(StaticGate::default())`. Measured on sarcos7 after 4 minutes of babbling
    /// (seeds 0/1/2): RMS `ĝ` error 0.08–0.10 N·m inside the babbling region and 0.15–0.21 along
    /// the figure-8 (static) against 0.47–0.50 and 0.77–0.90 (dynamic). Feeding the static model back into the babbling instead
    /// made the babbling unstable on 3 of 5 settings (a few still postures per receptive field
    /// give wild slopes).
    pub gravity_static: Option<crate::gravity::StaticGate>,
    /// Hindsight null-space shrinkage `κ ∈ [0, 1]`: the regression target `u − u0` of each
    /// hindsight sample loses the share `κ` of its part in the null space of the blended `Â`,
    /// `(u − u0) − κ (I − Â⁺Â)(u − u0)` — the same measured `ẍ` (to first order) at a lower
    /// cost. 0 is the paper's plain relabelling. Default 1.
    pub null_space_shrink: f64,
    /// Cap on the exploration noise of joint `j`, as a share of the standard deviation of its
    /// torques during the warm-up (so light distal joints are not shaken by the noise that
    /// suits heavy proximal ones). Default 0.15. With 0.05, every sarcos7 run that reached
    /// command nMSE 0.1–0.2 drifted afterwards (cost ratio falling to 0.70–0.88, the task
    /// under-actuated); with 0.15, seeds 0/1/2 held 0.09–0.14 (cost ratio 0.98–0.99) up to
    /// minute 30 (`learn_figure8`, 30 simulated minutes). planar3 after 30 minutes, seeds 0/1:
    /// nMSE 0.009/0.016 (0.007/0.017 with 0.05).
    pub exploration_cap: f64,
    /// Torque limits (N·m), one per joint, from the robot's data sheet: every command of the
    /// learned controller, exploration noise included, is clipped to `±limit` (counted in
    /// [`crate::LearnerStats::clipped`]). Empty: no limits. Default empty;
    /// [`LearnerConfig::for_robot`] fills it (and `osrl train` fills it when left empty).
    pub torque_limits: Vec<f64>,
    /// Receptive fields whose controller is not trained at present (effective sample size
    /// after its last M-step below `min_ess`, so not in the blend) and that were not active
    /// above `activation_cutoff` for this many seconds of learning are removed from the
    /// partition, with their controller; a later visit creates a new one. `None`: never (in a
    /// TOML file, where a missing key means the default, a huge value such as `1e300` switches
    /// it off). Default 60. Such fields come from the failing early episodes of sarcos7
    /// (1,600–4,500 fields, of which 150–440 ever trained, in 60-minute runs without this rule)
    /// and every command and learning step scans all fields.
    pub prune_untrained_after: Option<f64>,
    /// Measurements with `|ẍ|` above this (m/s²) or `|q̇|` above 100·this are rejected as absurd.
    /// Default 1000.
    pub max_abs_acceleration: f64,
    /// Transitions collected before the models are created; their standard deviations set the
    /// scales of torques and accelerations inside the models. Default 1000.
    pub warmup_samples: usize,
    /// Scale of joint velocities in the kernels (rad/s): kernel widths in `q̇` are this many
    /// times those in `q`, within [`lwpr::NORM_RANGE`]. Default 10.
    pub velocity_scale: f64,
}

impl Default for LearnerConfig {
    fn default() -> Self {
        Self {
            nominal: NominalConfig::default(),
            gravity: LwprConfig {
                init_d: MetricInit::Scalar(16.0),
                update_d: false,
                w_gen: 0.2,
                init_alpha: 10.0,
                ..LwprConfig::default()
            },
            forward: LwprConfig {
                init_d: MetricInit::Scalar(64.0),
                update_d: false,
                w_gen: 0.2,
                init_alpha: 10.0,
                ..LwprConfig::default()
            },
            rwr: RwrConfig {
                tau_init: 0.1,
                sigma_init: 0.5,
                sigma_min: 0.05,
                forgetting: 1.0,
                ridge: 1e-4,
                min_ess: 10.0,
                ..RwrConfig::default()
            },
            cost: CostKind::NullSpace,
            forward_uses_q: true,
            residual: true,
            position_features: true,
            reward_weighting: true,
            activation_cutoff: 0.05,
            min_ess: 50.0,
            update_every: 25,
            forward_every: 8,
            dynamics_every: 1,
            dynamics_solve_every: 4,
            exploration_scale: 1.0,
            exploration: ExplorationKind::NullSpace,
            null_space_cap: None,
            null_space_shrink: 1.0,
            gravity_on_policy: false,
            gravity_static: Some(Default::default()),
            gravity_velocity_products: true,
            dynamics_forgetting: 0.99995,
            dynamics_bilinear: true,
            exploration_cap: 0.15,
            torque_limits: Vec::new(),
            prune_untrained_after: Some(60.0),
            max_abs_acceleration: 1000.0,
            warmup_samples: 1000,
            velocity_scale: 10.0,
        }
    }
}

impl LearnerConfig {
    /// The defaults with the nominal behaviour and torque limits of a robot's data sheet: its
    /// joint PD gains, rest posture and torque limits (N·m; an infinite limit is stored as
    /// `f64::MAX`, no limit, so the config stays plain JSON). No dynamics parameters.
    pub fn for_robot(kp: &[f64], kd: &[f64], q_rest: &[f64], tau_max: &[f64]) -> Self {
        let mut c = Self::default();
        c.fill_data_sheet(kp, kd, q_rest, tau_max);
        c
    }

    /// Fills the data-sheet fields left empty — `nominal.kp`, `nominal.kd`, `nominal.q_rest`
    /// and `torque_limits` — from a robot's data sheet (as [`LearnerConfig::for_robot`]); fields
    /// already set are kept.
    pub fn fill_data_sheet(&mut self, kp: &[f64], kd: &[f64], q_rest: &[f64], tau_max: &[f64]) {
        let nom = &mut self.nominal;
        for (v, def) in [
            (&mut nom.kp, kp),
            (&mut nom.kd, kd),
            (&mut nom.q_rest, q_rest),
        ] {
            if v.is_empty() {
                *v = def.to_vec();
            }
        }
        if self.torque_limits.is_empty() {
            self.torque_limits = Self::data_sheet_limits(tau_max);
        }
    }

    /// A data sheet's torque limits (N·m) as `torque_limits`: an infinite limit (none) becomes
    /// `f64::MAX`, so the config stays plain JSON.
    pub fn data_sheet_limits(tau_max: &[f64]) -> Vec<f64> {
        tau_max.iter().map(|t| t.min(f64::MAX)).collect()
    }

    /// Checks ranges and that the nominal behaviour has `n` joints.
    pub fn validate(&self, n: usize) -> Result<()> {
        let bad = |m: String| Err(LearnError::InvalidConfig(m));
        let nom = &self.nominal;
        for (what, v) in [
            ("nominal.kp", &nom.kp),
            ("nominal.kd", &nom.kd),
            ("nominal.q_rest", &nom.q_rest),
        ] {
            if v.len() != n || v.iter().any(|x| !x.is_finite()) {
                return bad(format!("{what} needs {n} finite values, got {v:?}"));
            }
        }
        if !(self.activation_cutoff > 0.0 && self.activation_cutoff < 1.0) {
            return bad(format!(
                "activation_cutoff {} must be in (0, 1)",
                self.activation_cutoff
            ));
        }
        if !(self.min_ess >= 1.0 && self.min_ess.is_finite()) {
            return bad(format!("min_ess {} must be ≥ 1", self.min_ess));
        }
        if self.update_every == 0 {
            return bad("update_every must be ≥ 1".into());
        }
        if self.forward_every == 0 || self.dynamics_every == 0 || self.dynamics_solve_every == 0 {
            return bad(
                "forward_every, dynamics_every and dynamics_solve_every must be ≥ 1".into(),
            );
        }
        if let Some(t) = self.prune_untrained_after {
            if !(t > 0.0 && t.is_finite()) {
                return bad(format!(
                    "prune_untrained_after {t} must be finite and > 0 (s)"
                ));
            }
        }
        if let Some(cap) = self.null_space_cap {
            if !(cap >= 0.0 && cap.is_finite()) {
                return bad(format!("null_space_cap {cap} must be finite and ≥ 0"));
            }
        }
        if !(0.0..=1.0).contains(&self.null_space_shrink) {
            return bad(format!(
                "null_space_shrink {} must be in [0, 1]",
                self.null_space_shrink
            ));
        }
        if !(self.dynamics_forgetting > 0.0 && self.dynamics_forgetting <= 1.0) {
            return bad(format!(
                "dynamics_forgetting {} must be in (0, 1]",
                self.dynamics_forgetting
            ));
        }
        if !(self.exploration_cap >= 0.0 && self.exploration_cap.is_finite()) {
            return bad(format!(
                "exploration_cap {} must be finite and ≥ 0",
                self.exploration_cap
            ));
        }
        if !(self.exploration_scale >= 0.0 && self.exploration_scale.is_finite()) {
            return bad(format!(
                "exploration_scale {} must be finite and ≥ 0",
                self.exploration_scale
            ));
        }
        if let Some(g) = &self.gravity_static {
            if !(g.max_velocity > 0.0 && g.max_acceleration > 0.0) {
                return bad(format!(
                    "gravity_static limits must be > 0, got {} rad/s and {} rad/s²",
                    g.max_velocity, g.max_acceleration
                ));
            }
        }
        let tl = &self.torque_limits;
        if !(tl.is_empty() || tl.len() == n) || tl.iter().any(|t| !(*t > 0.0 && t.is_finite())) {
            return bad(format!(
                "torque_limits needs {n} finite values > 0 (N·m) or none (a huge value for a \
                 joint without a limit), got {tl:?}"
            ));
        }
        if self.warmup_samples < 10 {
            return bad("warmup_samples must be ≥ 10".into());
        }
        // It normalises the models' velocity inputs: LWPR's range for a normalisation.
        let (lo, hi) = lwpr::NORM_RANGE;
        if !(lo..=hi).contains(&self.velocity_scale) {
            return bad(format!(
                "velocity_scale {:e} must be within [{lo:e}, {hi:e}] (rad/s)",
                self.velocity_scale
            ));
        }
        if !(self.max_abs_acceleration > 0.0) {
            return bad("max_abs_acceleration must be > 0".into());
        }
        self.rwr.validate()?;
        Ok(())
    }
}
