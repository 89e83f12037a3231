//! What an evaluation returns: its metrics ([`EvalResult`]) and, on request, its time series
//! ([`EvalSeries`]) (`docs/learner.md`, "Evaluation").

use serde::{Deserialize, Serialize};

/// Metrics of one evaluation run (definitions of issue 6).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct EvalResult {
    /// RMS of `‖x − x_d‖` over whole periods after the first (mm).
    pub tracking_rms_mm: f64,
    pub tracking_max_mm: f64,
    /// Mean `‖u − u*‖²` over the summed per-joint variance of `u*`.
    pub command_nmse: f64,
    /// Mean `‖u − u0‖²` of the learned commands over that of `u*`.
    pub command_cost_ratio: f64,
    /// The part of `command_nmse` in the null space of the true `A = J M⁻¹` (`‖(I − A⁺A)(u −
    /// u*)‖²`, same normalisation): the redundancy resolution's share of the error.
    #[serde(default)]
    pub command_nmse_null: f64,
    /// The learned nominal behaviour's error, `‖û0 − u0‖²` (`û0` as the command adds it: learned
    /// `ĝ`, the load correction and the null-space correction, against the true `g`), with the
    /// same normalisation: a floor of `command_nmse` set by the gravity model.
    #[serde(default)]
    pub nominal_nmse: f64,
    /// Its part in the null space of the true `A` (the part the task cannot correct).
    #[serde(default)]
    pub nominal_nmse_null: f64,
    /// Mean relative error `‖Â − A‖_F / ‖A‖_F` of the learner's blended input gain `Â = ∂ẍ/∂u`
    /// against the true `A = J M⁻¹` (steps where the learner has one).
    #[serde(default)]
    pub gain_error: f64,
    /// The null-space error (same normalisation) of the command that would be optimal for the
    /// learner's own `Â` and `û0` — `û0 + Â⁺Â (u* − û0)` — over the steps where it has an `Â`:
    /// the floor that `Â` and the learned `u0` set for `command_nmse_null`; the rest of it is the
    /// local controllers' own error.
    #[serde(default)]
    pub floor_nmse_null: f64,
    /// The scales behind the ratios: summed per-joint variance of `u*` (N²·m²) and mean
    /// `‖u* − u0‖²` (N²·m²).
    #[serde(default)]
    pub u_star_variance: f64,
    #[serde(default)]
    pub u_star_cost: f64,
    /// Share of steps where no trained local controller was active (fallback to `u0`).
    pub fallback_share: f64,
    /// Share of steps inside trained receptive fields: the command was the blend of trained
    /// local controllers whose confidence-weighted activation `S = Σ c_i w_i` reached
    /// `controllers.prior_weight` (`CommandSource::Learned`), not an extrapolation or `u0`.
    #[serde(default)]
    pub support_share: f64,
    /// Largest change of the command between consecutive steps (N·m), learned and analytical.
    pub max_command_step: f64,
    pub max_command_step_analytical: f64,
    /// Whether the run was cut short by a tracking error above 0.2 m, or never reached the
    /// evaluated window; the metrics then cover the steps before (all steps if the window was
    /// never reached).
    pub diverged: bool,
}

/// The time series of one evaluation (for plots).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct EvalSeries {
    pub t: Vec<f64>,
    /// Task position, desired and actual (row-major, `m` per step).
    pub x_d: Vec<f64>,
    pub x: Vec<f64>,
    /// Learned and optimal commands (row-major, `n` per step).
    pub u: Vec<f64>,
    pub u_star: Vec<f64>,
    pub q: Vec<f64>,
    /// Wall time of each learned command (s): what a controller command costs on this model.
    pub command_seconds: Vec<f64>,
}

impl EvalSeries {
    /// The `p`-quantile (0–1, nearest rank) of the command wall times in µs; `None` if none.
    pub fn command_us_quantile(&self, p: f64) -> Option<f64> {
        let mut v = self.command_seconds.clone();
        if v.is_empty() {
            return None;
        }
        v.sort_by(f64::total_cmp);
        let k = ((v.len() - 1) as f64 * p.clamp(0.0, 1.0)).round() as usize;
        Some(v[k] * 1e6)
    }
}
