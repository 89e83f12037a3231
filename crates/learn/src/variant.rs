//! The learner variants of the ablation (E6): the default learner and what it is compared with.

use crate::config::{CostKind, LearnerConfig};
use lwpr::MetricInit;
use serde::{Deserialize, Serialize};

/// A learner variant, applied to a robot's default [`LearnerConfig`] by [`Variant::config`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Variant {
    /// The default learner: local controllers trained by reward-weighted regression on
    /// hindsight samples with the null-space shrinkage.
    Rwr,
    /// Reward weighting and hindsight shrinkage off: activation-weighted regression of `u − u0`
    /// on the features, i.e. direct supervised inverse learning with the same partition.
    Unweighted,
    /// RWR as in the paper: the full cost `‖u − u0‖²` and no hindsight null-space shrinkage.
    Paper,
    /// Supervised inverse learning with one receptive field covering the whole state space: a
    /// global linear inverse model.
    Global,
}

impl Variant {
    pub const ALL: [Variant; 4] = [
        Variant::Rwr,
        Variant::Unweighted,
        Variant::Paper,
        Variant::Global,
    ];

    /// Short key (file names, JSON).
    pub fn key(self) -> &'static str {
        match self {
            Variant::Rwr => "rwr",
            Variant::Unweighted => "unweighted",
            Variant::Paper => "rwr_paper",
            Variant::Global => "global_unweighted",
        }
    }

    /// Legend text.
    pub fn label(self) -> &'static str {
        match self {
            Variant::Rwr => "RWR (default)",
            Variant::Unweighted => "unweighted regression",
            Variant::Paper => "RWR as in the paper",
            Variant::Global => "global unweighted",
        }
    }

    /// This variant of `base` (a robot's default learner config).
    pub fn config(self, base: LearnerConfig) -> LearnerConfig {
        let mut c = base;
        match self {
            Variant::Rwr => {}
            Variant::Unweighted => {
                c.controllers.reward_weighting = false;
                c.controllers.null_space_shrink = 0.0;
            }
            Variant::Paper => {
                c.controllers.cost = CostKind::Full;
                c.controllers.null_space_shrink = 0.0;
            }
            Variant::Global => {
                c.controllers.reward_weighting = false;
                c.controllers.null_space_shrink = 0.0;
                c.partition.lwpr.init_d = MetricInit::Scalar(1e-8);
                c.partition.lwpr.update_d = false;
            }
        }
        c
    }
}
