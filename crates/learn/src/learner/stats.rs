//! The learner's counters (what it did and refused) and its preallocated scratch buffers.

use lwpr::{Activation, RfEvent, RfId};

/// Counters of what the learner did and refused.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LearnerStats {
    /// Transitions learned from.
    pub samples: u64,
    /// Measurements rejected (non-finite or absurd).
    pub rejected: u64,
    /// Commands computed, and those that fell back to `u0`: no trained controller was active,
    /// or the blend was not finite (then also counted in `non_finite`).
    pub commands: u64,
    pub fallbacks: u64,
    /// Commands extrapolated from trained controllers active below the cutoff.
    pub extrapolations: u64,
    /// Receptive fields removed by `partition.prune_untrained_after` (with their controllers).
    pub pruned_untrained: u64,
    /// Commands with at least one joint clipped to its torque limit.
    pub clipped: u64,
    /// Commands with at least one joint held to the torque-rate limit.
    #[serde(default)]
    pub rate_limited: u64,
    /// Commands whose learned blend was not finite and fell back to `u0`.
    pub non_finite: u64,
    /// Local M-steps done and those that failed (too few samples).
    pub m_steps: u64,
    pub failed_m_steps: u64,
}

/// Scratch buffers of the learning step and the command (allocated once, by [`Scratch::new`]).
#[derive(Clone, Debug, Default)]
pub(crate) struct Scratch {
    pub acts: Vec<Activation>,
    /// The activations of the nearest-controller query and its blend (`nearest.rs`).
    pub acts_far: Vec<Activation>,
    pub u_far: Vec<f64>,
    /// A state pulled into a neighbour's support (`nearest.rs`).
    pub q_pull: Vec<f64>,
    pub qd_pull: Vec<f64>,
    pub events: Vec<RfEvent>,
    /// Receptive fields to prune.
    pub stale: Vec<RfId>,
    /// Controller features `φ` and local dynamics features `φ_d`.
    pub phi: Vec<f64>,
    pub phi_d: Vec<f64>,
    /// Per joint: `u0`, `u − u0` (or noise), its null-space part, one controller's mean, the
    /// hindsight target.
    pub u0: Vec<f64>,
    pub du: Vec<f64>,
    pub z: Vec<f64>,
    pub ui: Vec<f64>,
    /// One controller's mean with the `β` before its last M-step (the ramp of `local.rs`).
    pub ui_from: Vec<f64>,
    pub target: Vec<f64>,
    /// The load correction `c` at the last relabelled state, and the policy's command for the
    /// measured `ẍ` (`load.rs`).
    pub load_c: Vec<f64>,
    pub pi: Vec<f64>,
    /// `ĝ(q)` for the null-space correction's global part (`null_scale.rs`).
    pub g_null: Vec<f64>,
    /// The load correction `c(q)` for the same part.
    pub c_null: Vec<f64>,
    /// `Â` (m×n), and the m-vector and m×m matrix of its null-space algebra.
    pub a_hat: Vec<f64>,
    /// Within one command: `Â` of the plain activations (the exploration's), and whether the
    /// command's `Â` (in `a_hat`) and this one are known at its state; `None` until the command
    /// has formed them (`Learner::command_gains`), and again after it.
    pub a_hat_plain: Vec<f64>,
    pub gains: Option<(bool, bool)>,
    pub y: Vec<f64>,
    pub s: Vec<f64>,
    /// `Â` and a joint vector in the cost's metric (`metric.rs`).
    pub a_n: Vec<f64>,
    pub v_n: Vec<f64>,
    /// The local dynamics' regression target: `ẍ`, or `Δẍ/Δt` in the difference form.
    pub xdd_target: Vec<f64>,
}

impl Scratch {
    /// Buffers for `n` joints, `m` task dimensions, `p` controller and `pd` dynamics features.
    pub fn new(n: usize, m: usize, p: usize, pd: usize) -> Self {
        Self {
            acts: Vec::with_capacity(4096),
            acts_far: Vec::with_capacity(4096),
            u_far: vec![0.0; n],
            q_pull: vec![0.0; n],
            qd_pull: vec![0.0; n],
            events: Vec::with_capacity(16),
            stale: Vec::with_capacity(4096),
            phi: vec![0.0; p],
            phi_d: vec![0.0; pd],
            u0: vec![0.0; n],
            du: vec![0.0; n],
            z: vec![0.0; n],
            ui: vec![0.0; n],
            ui_from: vec![0.0; n],
            target: vec![0.0; n],
            load_c: vec![0.0; n],
            pi: vec![0.0; n],
            g_null: vec![0.0; n],
            c_null: vec![0.0; n],
            a_hat: vec![0.0; m * n],
            a_hat_plain: vec![0.0; m * n],
            gains: None,
            y: vec![0.0; m],
            s: vec![0.0; m * m],
            a_n: vec![0.0; m * n],
            v_n: vec![0.0; n],
            xdd_target: vec![0.0; m],
        }
    }
}
