//! A family of task-space paths over a region of the workspace (`docs/family.md`): its settings
//! ([`FamilyConfig`], the `[trajectory.family]` section), the region ([`Region`]) and the seeded
//! sampler that draws reachable paths inside the joint and torque limits ([`FamilySampler`]).

mod region;
mod sampler;

pub(crate) use region::orthonormal;
pub use region::Region;
pub use sampler::{FamilyPath, FamilySampler};

use crate::error::{ControlError, Result};
use crate::trajectory_config::TrajectoryKind;
use serde::{Deserialize, Serialize};

/// The range of a family's periods and move times (s).
pub const FAMILY_SECONDS: (f64, f64) = (0.2, 600.0);
/// The range of a family's approach speed (m/s).
pub const APPROACH_SPEED: (f64, f64) = (0.01, 10.0);

/// How a family of paths is drawn (`[trajectory.family]`, used when `[trajectory] kind =
/// "family"`). Every path lies in the plane `e1`–`e2` of the `[trajectory]` section, inside the
/// region around its centre; the figure-8 of that section (the robot's default one unless set)
/// is the family's base: home sits on its start and every path is approached from there.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FamilyConfig {
    /// The region is the box around the base figure-8 (half-extents `a`, `b` along `e1`, `e2`)
    /// grown by this fraction. Default 0.5: half as large again as the path the paper trained
    /// on, so the family covers its neighbourhood without reaching for the joint limits.
    pub growth: f64,
    /// The region's half-extents along `e1` and `e2` (m), instead of the grown box. Default
    /// unset.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub half_size: Option<[f64; 2]>,
    /// The kinds drawn, each equally often. Default `["figure8", "circle", "min_jerk"]`: the
    /// paths an operational-space user commands.
    pub kinds: Vec<TrajectoryKind>,
    /// Size of a figure-8 (`a`, `b`) or circle (radius) as a fraction of the region's
    /// half-extents (the circle: of the smaller one), drawn uniformly in this range. Default
    /// [0.3, 0.8]: from a third of the region to nearly all of it.
    pub size: [f64; 2],
    /// Period of a figure-8 or circle (s), drawn uniformly, within [`FAMILY_SECONDS`]. Default
    /// [3, 6] (the base: 4).
    pub period: [f64; 2],
    /// Duration of each minimum-jerk move (s), drawn uniformly, within [`FAMILY_SECONDS`].
    /// Default [0.8, 1.6].
    pub move_time: [f64; 2],
    /// Points of a minimum-jerk path, drawn uniformly in this range (inclusive). Default [2, 4].
    pub points: [usize; 2],
    /// A drawn path's peak task acceleration may be at most this times the base figure-8's
    /// (m/s²). Default 1: the family is as fast as the task the controller is known to learn.
    pub max_acceleration_ratio: f64,
    /// Peak speed of the minimum-jerk approach from home to a path's start (m/s; at least 1 s
    /// long; within [`APPROACH_SPEED`]). Default 0.15: slower than the base figure-8 (peak 0.39
    /// m/s on planar3).
    pub approach_speed: f64,
    /// Eq. 7 with the true model, run along the approached path from home, may need at most
    /// this share of each joint's torque limit. Default 0.8: headroom for exploration and for
    /// the learned controller's errors.
    pub torque_share: f64,
    /// Draws per path before the sampler gives up (an error naming the last rejection). Default
    /// 500.
    pub max_draws: usize,
    /// Every this many training episodes one runs the base figure-8 itself instead of a drawn
    /// path (the 1st, the `(k + 1)`-th, …; 0: never). The drawn paths stay the same sequence,
    /// only interleaved; held-out paths are drawn without it. Default 6: the base figure-8 is
    /// the fastest path of the family, the one the controller is known to learn; without its own
    /// episodes the family's slower data in the same receptive fields let its tracking drift.
    pub base_every: usize,
    /// The learner's static gravity model keeps learning on-policy during family training (as
    /// `[learner.gravity] static_on_policy`, which must also be on). Default false: the family's
    /// rest points (minimum-jerk via points, approach ends, the path clock's stops) are a few
    /// still postures per receptive field scattered over the region, whose fitted slopes shift
    /// `u0` along every other path through those fields.
    pub static_gravity_on_policy: bool,
    /// The learner's command projection during family training: it replaces `[learner.controllers]
    /// command_projection` (the share of the blend's part in the null space of the learned `Â`
    /// that the command removes). Default 1: the whole null-space part. A receptive field
    /// crossed by many different paths sees many different null-space commands for the same
    /// task acceleration; the reward weighting resolves them slowly, the projection at once.
    pub command_projection: f64,
    /// The learner's `neighbour_cutoff` during family training (it replaces `[learner.controllers]
    /// neighbour_cutoff`, 1e-8): the activation at which the nearest trained controllers have
    /// faded into `u0` where the blend's support is thin; 0 or in (0, 1e-3]. Default 1e-40
    /// (about 13.6 kernel widths): a drawn path's stops leave the fields within milliseconds,
    /// faster than a shorter fade hands the arm to `u0`'s pull to rest smoothly.
    pub neighbour_cutoff: f64,
    /// The learner's `[learner.controllers] bilinear` during family training: the local
    /// controllers' features also have `ẍ_j (q_k − c_k)`, the change of the command's slope in
    /// `ẍ` (eq. 7's `M J⁺`) across a field, which a field crossed by many paths sees at every
    /// posture of its support. Default false: on planar3 it lowers the command error of the
    /// held-out paths on most seeds but brakes twice as many episodes and learns slower; on
    /// sarcos7 (21 more features) it is slower and worse (`docs/decisions.md`, D54).
    pub controller_bilinear: bool,
    /// The learner's `[learner.dynamics] weight_power` during family training (it replaces that
    /// key, default 1): a sample's weight in a field's local dynamics is its activation to this
    /// power (at least 1, at most 10). Default 2: the fit of `Â` is more local than the field;
    /// on the validation paths it lowers the command error of sarcos7 on every seed and is
    /// neutral on planar3 (`docs/decisions.md`, D64).
    pub dynamics_weight_power: f64,
}

impl Default for FamilyConfig {
    fn default() -> Self {
        Self {
            growth: 0.5,
            half_size: None,
            kinds: vec![
                TrajectoryKind::Figure8,
                TrajectoryKind::Circle,
                TrajectoryKind::MinJerk,
            ],
            size: [0.3, 0.8],
            period: [3.0, 6.0],
            move_time: [0.8, 1.6],
            points: [2, 4],
            max_acceleration_ratio: 1.0,
            approach_speed: 0.15,
            torque_share: 0.8,
            max_draws: 500,
            base_every: 6,
            static_gravity_on_policy: false,
            command_projection: 1.0,
            neighbour_cutoff: 1e-40,
            controller_bilinear: false,
            dynamics_weight_power: 2.0,
        }
    }
}

impl FamilyConfig {
    /// Whether every field has its default (the section is then not written).
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }

    /// Checks every field's range.
    ///
    /// # Errors
    /// [`ControlError::InvalidConfig`] naming the first field out of range.
    pub fn validate(&self) -> Result<()> {
        let pos = |x: f64| x > 0.0 && x.is_finite();
        let range = |r: [f64; 2]| pos(r[0]) && r[0] <= r[1] && r[1].is_finite();
        // A path's reachability check samples it, and its approach, at a spacing set by the
        // period: absurd durations or speeds would take days or more memory than there is.
        let (t_lo, t_hi) = FAMILY_SECONDS;
        let seconds = |r: [f64; 2]| range(r) && r[0] >= t_lo && r[1] <= t_hi;
        let v = |x: &dyn std::fmt::Debug| format!("{x:?}");
        let lo_hi = format!("[lo, hi] with {t_lo} ≤ lo ≤ hi ≤ {t_hi} (s)");
        let (s_lo, s_hi) = APPROACH_SPEED;
        let speed = format!("within [{s_lo}, {s_hi}] (m/s)");
        // (field, its value, what is accepted, whether it is)
        let checks = [
            (
                "growth",
                v(&self.growth),
                "≥ 0, finite",
                self.growth >= 0.0 && self.growth.is_finite(),
            ),
            (
                "half_size",
                v(&self.half_size),
                "unset or two sizes > 0 m, finite",
                self.half_size.is_none_or(|h| pos(h[0]) && pos(h[1])),
            ),
            (
                "kinds",
                v(&self.kinds),
                "one or more path kinds, not family",
                !self.kinds.is_empty() && !self.kinds.contains(&TrajectoryKind::Family),
            ),
            (
                "size",
                v(&self.size),
                "[lo, hi] with 0 < lo ≤ hi ≤ 1",
                range(self.size) && self.size[1] <= 1.0,
            ),
            (
                "period",
                v(&self.period),
                lo_hi.as_str(),
                seconds(self.period),
            ),
            (
                "move_time",
                v(&self.move_time),
                lo_hi.as_str(),
                seconds(self.move_time),
            ),
            (
                "points",
                v(&self.points),
                "[lo, hi] with 2 ≤ lo ≤ hi ≤ 16",
                self.points[0] >= 2 && self.points[0] <= self.points[1] && self.points[1] <= 16,
            ),
            (
                "max_acceleration_ratio",
                v(&self.max_acceleration_ratio),
                "> 0, finite",
                pos(self.max_acceleration_ratio),
            ),
            (
                "approach_speed",
                v(&self.approach_speed),
                speed.as_str(),
                (s_lo..=s_hi).contains(&self.approach_speed),
            ),
            (
                "torque_share",
                v(&self.torque_share),
                "in (0, 1]",
                pos(self.torque_share) && self.torque_share <= 1.0,
            ),
            (
                "max_draws",
                v(&self.max_draws),
                "in [1, 100000]",
                self.max_draws >= 1 && self.max_draws <= 100_000,
            ),
            (
                "command_projection",
                v(&self.command_projection),
                "in [0, 1]",
                (0.0..=1.0).contains(&self.command_projection),
            ),
            (
                "dynamics_weight_power",
                v(&self.dynamics_weight_power),
                "in [1, 10]",
                (1.0..=10.0).contains(&self.dynamics_weight_power),
            ),
            (
                "neighbour_cutoff",
                v(&self.neighbour_cutoff),
                "0 (off) or in (0, 1e-3]",
                self.neighbour_cutoff == 0.0
                    || (self.neighbour_cutoff > 0.0 && self.neighbour_cutoff <= 1e-3),
            ),
        ];
        match checks.iter().find(|c| !c.3) {
            Some((what, value, accepted, _)) => Err(ControlError::InvalidConfig(format!(
                "[trajectory.family] {what} = {value}: accepted {accepted}"
            ))),
            None => Ok(()),
        }
    }
}
