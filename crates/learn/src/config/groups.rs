//! The groups of [`LearnerConfig`](super::LearnerConfig), one per part of the learned controller
//! (paper section IV; `docs/learner.md`). Each field's doc gives its unit, its default and why;
//! the measurements behind the defaults are in `docs/decisions.md`.

use crate::gravity::StaticGate;
use lwpr::{LwprConfig, MetricInit};
use rwr::RwrConfig;
use serde::{Deserialize, Serialize};

/// The cost whose transformed value weights the hindsight samples of the local controllers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CostKind {
    /// The paper's `r = ‖u − u0‖²` (`N = I`).
    Full,
    /// Only its avoidable part `r_null = ‖(I − Â⁺Â)(u − u0)‖²`, with `Â = ∂ẍ/∂u` from the local
    /// dynamics: the same optimum, with a `τ` set by the part the controller can change.
    #[default]
    NullSpace,
}

/// The metric `N` of the local controllers' cost (`learner/metric.rs`); defined with the robot
/// profile, which chooses it.
pub use osrl_dynamics::CostMetric;

/// The nominal behaviour `u0 = ĝ(q) − K_Dq q̇ − K_Pq (q − q_rest)` (eq. 6 plus learned gravity).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct NominalConfig {
    /// Joint stiffness `K_Pq` (N·m/rad), one per joint. Default: the robot's data sheet, whose
    /// gains keep the arm near its rest posture.
    pub kp: Vec<f64>,
    /// Joint damping `K_Dq` (N·m·s/rad), one per joint. Default: the robot's data sheet.
    pub kd: Vec<f64>,
    /// Rest posture `q_rest` (rad). Default: the robot's data sheet.
    pub q_rest: Vec<f64>,
}

/// The learned gravity compensation `ĝ(q)` of `u0`: LWPR on `[q, q̇, q̈] → u`, kernel on `q`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GravityConfig {
    /// The LWPR model (its input, kernel and regression dimensions are set by the learner).
    /// Default: fixed kernels of width 0.25 rad (`init_d` 16, `update_d` false), `w_gen` 0.2,
    /// `init_alpha` 10: metric learning collapsed the model to a few fields for the whole arm.
    pub lwpr: LwprConfig,
    /// A second model learnt from still samples only (see [`StaticGate`]), regressing on `q`;
    /// once on-policy learning starts, `u0` uses it wherever it has support. `None`: the dynamic
    /// model only. Default `Some(StaticGate::default())`: along a path the dynamic model cannot
    /// separate gravity from inertia.
    pub static_gate: Option<StaticGate>,
    /// The static model keeps learning on-policy (from the still samples of the stops; the
    /// dynamic model is frozen there). Default true: at rest `u = g(q)` whatever the
    /// controller, so these samples are exact along the path.
    pub static_on_policy: bool,
    /// `ĝ` is continuous in `q` and defined everywhere (`docs/decisions.md`, D21): each model
    /// predicts from all its fields without LWPR's cutoff (`GravityModel::predict_everywhere`),
    /// and once `ĝ` is frozen the static and the dynamic model are blended by their total
    /// activations, `ĝ = (S_s ĝ_s + λ S_d ĝ_d) / (S_s + λ S_d)` (`λ`: `dynamic_weight`). false:
    /// the switch of before — the static model where a field is above the cutoff, else the
    /// dynamic one, else 0 (on the Panda `u0` lost 38–42 N·m in one period there). Default true.
    pub continuous: bool,
    /// `λ` of `continuous` (≥ 0): the dynamic model's weight per unit of its total activation,
    /// relative to the static model's. Default 0.01: the static model (exact samples, D8)
    /// decides wherever it has a field within about 3 kernel widths; the dynamic one takes
    /// over where the static model's support is a hundred times weaker.
    pub dynamic_weight: f64,
    /// A correction of `u0` in the null space of `Â` (`learner/null_gravity.rs`): a third
    /// LWPR model on `q` learns, from the still samples of the holds at path postures
    /// (`TrainConfig::posture_holds`, which then teach it instead of the static model), what `ĝ`
    /// and the load correction miss there, and the command adds its part in the null space of
    /// the blended `Â`. Default true. Why: the null-space part of `û0`'s error is what
    /// task-space measurements never teach (most of sarcos7's command error, D25), and a change
    /// of `ĝ` in the task directions would move the task acceleration under the trained
    /// controllers.
    pub null_correction: bool,
    /// Support `S0` of the correction's fade `S / (S + S0)`, `S` its model's total activation at
    /// `q` (> 0). Default 0.1: a field about two kernel widths away adds a tenth of its value,
    /// so a new field enters the command gradually.
    pub null_support: f64,
    /// The correction's ridge: its fields' `init_s2` (LWPR's initial `SSs2` of a projection) at
    /// least this (≥ 0). Default 0.1: a field fitted at one posture has no information on its
    /// slopes, and the ridge keeps them near 0 until its samples spread.
    pub null_ridge: f64,
    /// A hold teaches the correction only if it gave at least this many still samples (≥ 1),
    /// all at its end. Default 100 (0.2 s at 2 ms): a hold cut short, or a field fitted to a
    /// few samples of an arm still settling, would move the command on a guess.
    pub null_min_samples: usize,
    /// The correction's global part (`learner/null_scale.rs`; needs `null_correction`), learned
    /// at every hold, also in training: one scale `k` fitted to the holds' gravity errors
    /// `u − ĝ` adds `a k ĝ(q)` everywhere and the load correction keeps `1 − a` of its null-space
    /// part, `a` the share from the fit's `R²` (`null_scale_explained`); the LWPR model learns
    /// what they leave. Default false (`adaptation.null_scale` learns it while a change is
    /// re-adapted). Why: a change of the masses moves the gravity torques in proportion to `ĝ`
    /// at every posture, where the model's fields know only the held ones.
    pub null_scale: bool,
    /// How many holds the scale remembers (≥ 1): each hold's sums are forgotten by
    /// `1 − 1 / null_scale_memory`. Default 10 holds, one return home while re-adapting, so an
    /// undone change is forgotten within a few returns.
    pub null_scale_memory: f64,
    /// The scale's ridge `ρ` (≥ 0), per joint in units of its squared torque scale. Default
    /// 0.001: holds that barely load the arm leave the scale near 0.
    pub null_scale_ridge: f64,
    /// The global part's share `a` in the correction (`k ĝ` in, and the load correction's
    /// null-space part out, by `a`): 0 while the scale explains less than the first value of the
    /// holds' gravity errors (`R²`), 1 above the second, linear between (0 ≤ lo < hi ≤ 1).
    /// Default `[0.8, 0.95]`: heavier links measured `R²` 0.95–0.995, a payload at the hand
    /// 0.2–0.7, and where the errors are not proportional to `ĝ` the load correction's
    /// null-space part covers the path better than the holds alone (D43).
    pub null_scale_explained: [f64; 2],
}

/// The partition: the forward model `ẍ = f(q, q̇, u)` (eqs. 32–33) whose receptive fields carry
/// the local controllers.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PartitionConfig {
    /// The LWPR forward model (kernel on `(q, q̇)`, fields shared by the task dimensions; set by
    /// the learner). Default: fixed kernels of width 0.125 rad and 1.25 rad/s (`init_d` 64,
    /// `update_d` false), `w_gen` 0.2, `init_alpha` 10: it places fields, `Â` comes from the
    /// local dynamics, and metric learning only made the step slower.
    pub lwpr: LwprConfig,
    /// A receptive field learns from (and joins the blend at) activations above this (0–1).
    /// Default 0.05: LWPR's own pruning scale; below it a field's samples are noise.
    pub activation_cutoff: f64,
    /// The forward model learns from every this many transitions (≥ 1). Default 8: it only
    /// places fields, and its update was the largest cost of a learning step.
    pub learn_every: usize,
    /// Receptive fields whose controller is untrained and that were not active for this long
    /// (s of learning) are removed with their controller; `None`: never (in TOML, where a
    /// missing key is the default, a huge value such as 1e300 switches it off). Default 60:
    /// failing early episodes leave thousands of idle fields that every step scans.
    pub prune_untrained_after: Option<f64>,
    /// Scale of joint velocities in the models' inputs (rad/s): kernel widths in `q̇` are this
    /// many times those in `q`; within [`lwpr::NORM_RANGE`]. Default 10: joint speeds along the
    /// tasks are about ten times the joint excursions of a field.
    pub velocity_scale: f64,
}

/// The local controllers `u^i = u0 + [ẍ_refᵀ, q̇ᵀ, (q − c_i)ᵀ, 1] β^i` (eq. 31) and their
/// reward-weighted regression on hindsight samples.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ControllerConfig {
    /// Reward-weighted regression of each local controller (own `τ_i`, `σ_i`). Default `τ0`
    /// 0.1, `σ0` 0.5 N·m, `σ_min` 0.05, forgetting 1 (hindsight targets are stationary), ridge
    /// 1e-4, `min_ess` 10 (the M-step's own floor on the weights' effective sample size),
    /// `min_ess_share` 0.1 (once a controller's statistics forget, while re-adapting, the next
    /// `τ` is pulled down whenever its weights keep less than a tenth of the effective sample
    /// size the activations alone give: eq. 28's `τ` diverges there otherwise),
    /// trust region 0.05 N·m (one M-step moves a controller's commands by at most that, RMS).
    pub rwr: RwrConfig,
    /// Effective sample size of a local controller's last M-step at which it counts as trained
    /// (samples): its confidence in the blend ramps from 0 at half of this to 1 at 1.5 times
    /// it. Default 50: a controller fitted on fewer samples extrapolates.
    pub trained_ess: f64,
    /// M-step of a local controller after this many new samples (≥ 1). Default 25: often enough
    /// to follow the policy, rarely enough to be cheap.
    pub update_every: usize,
    /// Weight the hindsight samples by the transformed reward (true: RWR) or not (false:
    /// activation-weighted regression, the supervised-inverse ablation). Default true.
    pub reward_weighting: bool,
    /// Cost of the reward weighting. Default `null_space` (see [`CostKind`]).
    pub cost: CostKind,
    /// Support `w0` at which the learned part of the command is fully trusted (activation
    /// units): the command is `u0 + κ Σ c_i w̃_i (u^i − u0) / S` with `S = Σ c_i w̃_i` and
    /// `κ = smoothstep(S / w0)`, so the learned part fades into `u0` where no trained field is
    /// near instead of switching. Default 0.05: one field at its own cutoff scale.
    pub prior_weight: f64,
    /// Activation down to which the trained controllers nearest to a thinly supported state
    /// still command (`learner/nearest.rs`; `docs/learner.md`, "Thin support"): where `κ < 1`
    /// the share `1 − κ` goes to their blend, each evaluated at the state pulled into its
    /// field's support, faded into `u0` as the nearest trained field's activation falls from
    /// `partition.activation_cutoff` to this value. Default 1e-8 (about 6 kernel widths):
    /// `u0`'s pull to rest would take the arm out of the trained region for good. 0: off (the
    /// learned part fades into `u0` alone). Training on a family of paths uses
    /// `[trajectory.family] neighbour_cutoff` instead.
    pub neighbour_cutoff: f64,
    /// Hindsight shrinkage `κ ∈ [0, 1]`: a sample's target `u − u0` loses the share `κ` of its
    /// part in the null space of `Â` — the same `ẍ` at a lower cost. 0 is the paper's plain
    /// relabelling. Default 1.
    pub null_space_shrink: f64,
    /// Projection of the command `κ_c ∈ [0, 1]`: the blended learned part `ū` of the command
    /// loses the share `κ_c` of its part in the null space of the blended `Â` (computed at the
    /// command), `ū ← ū − κ_c (I − Â⁺Â) ū`: the same task acceleration to first order, the
    /// minimum-norm form eq. 7's `u* − u0` has. The hindsight targets already have that form
    /// (shrunk with the `Â` of the plain activations);
    /// what the blend of several fields, targets shrunk with an older `Â`, and the regression's
    /// own error add in the null space is removed (`docs/decisions.md`, D20). `Â` is blended
    /// with the command's own weights, so the projector moves continuously as fields join.
    /// 0: the plain blend (eq. 34). Default 0.5: half the projection, the share at which the
    /// built-in arms' command error falls; the full projection brakes more episodes (D31, D32).
    /// Training on a family of paths uses `[trajectory.family] command_projection` instead.
    pub command_projection: f64,
    /// Bound on each local controller's learned velocity gain on its own joint
    /// (`docs/decisions.md`, D21): the net damping `K_D,j − β_{q̇_j, j}` stays within
    /// `[0, share · 2 / (Δt (M⁻¹)_jj)]`, `(M⁻¹)_jj` measured in the warm-up and `2 / (Δt
    /// (M⁻¹)_jj)` the discrete-time stability limit of a velocity loop under a held command;
    /// this is `share`. Applied after every M-step (residual controllers only). 0 (default): no
    /// bound — it made planar3's tracking and the Panda's braking worse (D21).
    pub damping_bound: f64,
    /// An M-step's change of a controller's command is spread over this many commands (≥ 1):
    /// the controller commands `(1 − α) β_oldᵀφ + α β_newᵀφ` with `α` rising linearly from 0
    /// to 1, so one update cannot make a command jump (D21). 1 (default): at once — spreading
    /// made planar3 and the UR5 worse (D21).
    pub step_spread: usize,
    /// The metric `N` of the cost, of the null space of `Â` and of the hindsight shrinkage (see
    /// [`CostMetric`]). Default: unset, the robot profile's choice (`osrl robot` prints it;
    /// `identity`, the paper's, for the built-in arms; `inverse_inertia` keeps the Panda's and
    /// the UR5's wrists near home, where `N = I` spins them through 1.6–6 rad along the path,
    /// `docs/decisions.md` D27, D29); `identity` for a learner built without a
    /// robot profile. Set, it wins over the profile. The estimated `N` is saved with the model.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub metric: Option<CostMetric>,
    /// The features of eq. 31 also have the products `ẍ_j (q_k − c_i,k)` (`m n` more, after the
    /// constant; needs the position features): the command's slope in `ẍ`, `M J⁺` in eq. 7,
    /// changes across a field. Default false: along one path `ẍ_ref` is nearly a function of
    /// `q` within a field, so the products add parameters and nothing to fit. Training on a
    /// family of paths uses `[trajectory.family] controller_bilinear` instead.
    pub bilinear: bool,
}

/// The local dynamics `ẍ ≈ [uᵀ, q̇ᵀ, (q − c)ᵀ, 1, u_j (q_k − c_k)] Θ` of each receptive field, by
/// weighted least squares; its `u` rows give `Â = ∂ẍ/∂u`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DynamicsConfig {
    /// Forgetting factor per sample, in (0, 1]. Default 0.99995: the on-path `Â` follows the
    /// policy's states.
    pub forgetting: f64,
    /// Learn from every this many transitions (≥ 1). Default 1.
    pub learn_every: usize,
    /// Re-solve at every this many M-steps of the field's controller (≥ 1). Default 4: a solve
    /// factors a 71×71 system on sarcos7.
    pub solve_every: usize,
    /// What the regression fits: the levels `ẍ` on `φ_d`, or the changes between consecutive
    /// transitions (see [`DynamicsRegression`]). Default `difference`: `Â`'s error on the path
    /// is about 10× smaller than with the levels, on both robots (`docs/decisions.md`, D23).
    pub regression: DynamicsRegression,
    /// Trust region of a solve (weighted RMS change of the fitted target over the field's
    /// samples: m/s² for `level`, m/s³ for `difference`; 0 = none): a larger change is shrunk
    /// towards the previous solution. Default 0 (none): in the difference form the target is
    /// `1/Δt` larger, and the levels' 0.05 m/s² (inherited from the controllers) held `Â` near
    /// its start for minutes (D23).
    pub trust_region: f64,
    /// A sample's weight in a field is its activation raised to this power (≥ 1): above 1 the
    /// fit is more local than the field. Default 1. Training on a family of paths uses
    /// `[trajectory.family] dynamics_weight_power` (2) instead.
    pub weight_power: f64,
}

/// What the local dynamics regression of a field fits (`docs/decisions.md`, D23).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DynamicsRegression {
    /// `ẍ` on `φ_d = [u, q̇, q − c, 1, u_j (q_k − c_k)]` (the learner until D23).
    Level,
    /// The change between two consecutive transitions, divided by their time step:
    /// `Δẍ/Δt` on `Δφ_d/Δt`. The state moves by `O(Δt)` in one control period while the
    /// exploration's innovation moves `u` by `O(√Δt)`, so `Δu` is nearly independent of the
    /// state, and whatever `φ_d` leaves unmodelled in `ẍ(q, q̇)` (quadratic velocity terms,
    /// curvature of gravity and of `M⁻¹` inside the field) cancels to second order instead of
    /// biasing `Θ_u` through the policy's correlation of `u` with the state. The constant is
    /// not identified (its change is 0; the ridge keeps it at 0), so the fit predicts changes,
    /// not levels. Only consecutive transitions (one control period apart) are learned.
    #[default]
    Difference,
}

/// The random process of the exploration noise.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum NoiseProcess {
    /// Ornstein–Uhlenbeck: `z ← a z + sqrt(1 − a²) e`, `a = exp(−dt/T)`, unit variance.
    #[default]
    OrnsteinUhlenbeck,
    /// The same process with uniform innovations `e ∈ [−√3, √3]` (unit variance): the same
    /// covariance, and a per-period change bounded by construction (at most `2√3 sqrt(1 − a²)`,
    /// in practice `√3 sqrt(1 − a²)` plus a small drift term).
    OrnsteinUhlenbeckBounded,
    /// Standard normal knots (clipped at 3) `T` apart, joined by half-cosines: the per-period
    /// change is at most `3π dt / T` by construction.
    Smooth,
}

/// Exploration noise of the on-policy commands.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ExplorationConfig {
    /// Scale of the noise relative to the blended `σ` of the local controllers (≥ 0). Default 1:
    /// RWR's own `σ` (eq. 24).
    pub scale: f64,
    /// The noise process. Default `ornstein_uhlenbeck`: its fine-grained variation identifies
    /// the local dynamics `Â` fast; `smooth` bounds the torque rate by construction but learns
    /// slower (`docs/decisions.md`).
    pub process: NoiseProcess,
    /// Correlation time of the noise (s): the Ornstein–Uhlenbeck time constant, or the spacing
    /// of the smooth process's knots (its torque rate is then at most `3π σ / T`). 0: white
    /// noise. Default 0.1: many independent draws per second, ten times smoother than white
    /// noise at 500 Hz.
    pub correlation_time: f64,
    /// Cap per joint, as a share of the standard deviation of that joint's torques during the
    /// warm-up (≥ 0). Default 0.15: light distal joints are not shaken by the noise that suits
    /// heavy proximal ones.
    pub cap: f64,
    /// Largest rate of change of each joint's exploration torque (N·m/s): the noise's change
    /// from one command to the next is clipped to `max_rate · dt`, whatever the process, the
    /// blended `σ` (which jumps at an M-step) or the null-space projector (which moves with
    /// `Â`) do. `None` (default): not bounded (`docs/decisions.md`, D24).
    #[serde(default)]
    pub max_rate: Option<f64>,
}

/// Guards on what the learner accepts and sends.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GuardConfig {
    /// Torque limits (N·m), one per joint: every command, exploration included, is clipped to
    /// `±limit` (counted). Empty: none. Default empty; [`LearnerConfig::for_robot`] fills it from
    /// the data sheet.
    ///
    /// [`LearnerConfig::for_robot`]: super::LearnerConfig::for_robot
    pub torque_limits: Vec<f64>,
    /// Largest change of a joint's command per second (N·m/s), for every joint: every command
    /// is moved towards its value by at most `limit · dt` from the previous one (counted).
    /// Default `None`: computed per joint from its torque limit ([`super::scaled`]): 1000 N·m/s
    /// (the rate at which a Franka arm's controller stops the robot) up to 100 N·m, in
    /// proportion above (a 330 N·m joint: 3300 N·m/s).
    pub torque_rate_limit: Option<f64>,
    /// Measurements with `|ẍ|` above this (m/s²) are rejected as absurd (counted). Default 1000:
    /// far above any arm's task acceleration, so only sensor faults trip it.
    pub max_abs_acceleration: f64,
    /// Measurements with `|q̇|` above this (rad/s) are rejected as absurd (counted). Default 100.
    pub max_abs_velocity: f64,
    /// Transitions collected before the models are created; their standard deviations set the
    /// models' torque and acceleration scales (10 to 1,000,000: each is kept until then).
    /// Default 1000 (2 s at 500 Hz).
    pub warmup_samples: usize,
}

/// Switches of the model structure that only experiments flip; the defaults are the learner.
/// Not part of the documented configuration.
#[doc(hidden)]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Experimental {
    /// Local controllers learn `u − u0` (true) or `u` (false, eq. 31 as printed).
    pub residual: bool,
    /// The features of eq. 31 also have `q − c_i`.
    pub position_features: bool,
    /// The forward model's local regression also uses `q` (eq. 32 uses `[q̇, u, 1]`).
    pub forward_uses_q: bool,
    /// Exploration adds noise projected onto the null space of `Â` (true) or isotropic only.
    pub null_space_exploration: bool,
    /// Cap on the null-space noise of joint `j`, as a share of its warm-up torque deviation.
    pub null_space_cap: Option<f64>,
    /// `ĝ` keeps learning on-policy.
    pub gravity_on_policy: bool,
    /// The gravity model's regressors include `q̇ᵢq̇ⱼ`.
    pub gravity_velocity_products: bool,
    /// The local dynamics have the bilinear features `u_j (q_k − c_k)`.
    pub dynamics_bilinear: bool,
}

impl Default for GravityConfig {
    fn default() -> Self {
        Self {
            lwpr: LwprConfig {
                init_d: MetricInit::Scalar(16.0),
                update_d: false,
                w_gen: 0.2,
                init_alpha: 10.0,
                ..LwprConfig::default()
            },
            static_gate: Some(StaticGate::default()),
            static_on_policy: true,
            continuous: true,
            dynamic_weight: 0.01,
            null_correction: true,
            null_support: 0.1,
            null_ridge: 0.1,
            null_min_samples: 100,
            null_scale: false,
            null_scale_memory: 10.0,
            null_scale_ridge: 1e-3,
            null_scale_explained: [0.8, 0.95],
        }
    }
}

impl Default for PartitionConfig {
    fn default() -> Self {
        Self {
            lwpr: LwprConfig {
                init_d: MetricInit::Scalar(64.0),
                update_d: false,
                w_gen: 0.2,
                init_alpha: 10.0,
                ..LwprConfig::default()
            },
            activation_cutoff: 0.05,
            learn_every: 8,
            prune_untrained_after: Some(60.0),
            velocity_scale: 10.0,
        }
    }
}

impl ControllerConfig {
    /// The metric the learner uses: `metric`, `identity` when unset.
    pub fn cost_metric(&self) -> CostMetric {
        self.metric.unwrap_or_default()
    }
}

impl Default for ControllerConfig {
    fn default() -> Self {
        Self {
            rwr: RwrConfig {
                tau_init: 0.1,
                sigma_init: 0.5,
                sigma_min: 0.05,
                forgetting: 1.0,
                ridge: 1e-4,
                min_ess: 10.0,
                min_ess_share: 0.1,
                trust_region: Some(0.05),
                ..RwrConfig::default()
            },
            trained_ess: 50.0,
            update_every: 25,
            prior_weight: 0.05,
            neighbour_cutoff: 1e-8,
            reward_weighting: true,
            cost: CostKind::NullSpace,
            null_space_shrink: 1.0,
            command_projection: 0.5,
            damping_bound: 0.0,
            step_spread: 1,
            metric: None,
            bilinear: false,
        }
    }
}

impl Default for DynamicsConfig {
    fn default() -> Self {
        Self {
            forgetting: 0.99995,
            learn_every: 1,
            solve_every: 4,
            regression: DynamicsRegression::Difference,
            trust_region: 0.0,
            weight_power: 1.0,
        }
    }
}

impl Default for ExplorationConfig {
    fn default() -> Self {
        Self {
            scale: 1.0,
            process: NoiseProcess::OrnsteinUhlenbeck,
            correlation_time: 0.1,
            cap: 0.15,
            max_rate: None,
        }
    }
}

impl Default for GuardConfig {
    fn default() -> Self {
        Self {
            torque_limits: Vec::new(),
            torque_rate_limit: None,
            max_abs_acceleration: 1000.0,
            max_abs_velocity: 100.0,
            warmup_samples: 1000,
        }
    }
}

impl Default for Experimental {
    fn default() -> Self {
        Self {
            residual: true,
            position_features: true,
            forward_uses_q: true,
            null_space_exploration: true,
            null_space_cap: None,
            gravity_on_policy: false,
            gravity_velocity_products: true,
            dynamics_bilinear: true,
        }
    }
}
