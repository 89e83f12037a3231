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
    /// `Unweighted` with the command projection of the default learner: direct supervised
    /// inverse learning whose commands lose half their part in the null space of the learned
    /// `Â` (`docs/decisions.md`, D32).
    UnweightedProjected,
    /// The default learner without the command projection (the default before D32).
    RwrUnprojected,
}

impl Variant {
    pub const ALL: [Variant; 6] = [
        Variant::Rwr,
        Variant::Unweighted,
        Variant::Paper,
        Variant::Global,
        Variant::UnweightedProjected,
        Variant::RwrUnprojected,
    ];

    /// Short key (file names, JSON).
    pub fn key(self) -> &'static str {
        match self {
            Variant::Rwr => "rwr",
            Variant::Unweighted => "unweighted",
            Variant::Paper => "rwr_paper",
            Variant::Global => "global_unweighted",
            Variant::UnweightedProjected => "unweighted_projected",
            Variant::RwrUnprojected => "rwr_unprojected",
        }
    }

    /// Legend text.
    pub fn label(self) -> &'static str {
        match self {
            Variant::Rwr => "RWR (default)",
            Variant::Unweighted => "unweighted regression",
            Variant::Paper => "RWR as in the paper",
            Variant::Global => "global unweighted",
            Variant::UnweightedProjected => "unweighted + command projection",
            Variant::RwrUnprojected => "RWR without command projection",
        }
    }

    /// This variant of `base` (a robot's default learner config). The paper's comparisons
    /// (`Unweighted`, `Paper`, `Global`) command the plain blend, without the command
    /// projection, as the paper's learners do.
    pub fn config(self, base: LearnerConfig) -> LearnerConfig {
        let mut c = base;
        let supervised = |c: &mut LearnerConfig| {
            c.controllers.reward_weighting = false;
            c.controllers.null_space_shrink = 0.0;
        };
        match self {
            Variant::Rwr => {}
            Variant::Unweighted => {
                supervised(&mut c);
                c.controllers.command_projection = 0.0;
            }
            Variant::Paper => {
                c.controllers.cost = CostKind::Full;
                c.controllers.null_space_shrink = 0.0;
                c.controllers.command_projection = 0.0;
            }
            Variant::Global => {
                supervised(&mut c);
                c.controllers.command_projection = 0.0;
                c.partition.lwpr.init_d = MetricInit::Scalar(1e-8);
                c.partition.lwpr.update_d = false;
            }
            Variant::UnweightedProjected => supervised(&mut c),
            Variant::RwrUnprojected => c.controllers.command_projection = 0.0,
        }
        c
    }
}
