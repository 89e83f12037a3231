//! The cost of a hindsight sample and the shrinkage of its target (`docs/learner.md`, "Cost"):
//! the paper's `r = ‖u − u0‖²` (`N = I`) or its avoidable part `‖(I − Â⁺Â)(u − u0)‖²`, and the
//! target `u − u0` moved towards the task-space part of itself.

use super::metric::{null_space_cost_in, project_scratch_z, Metric};
use super::stats::Scratch;
use crate::config::{CostKind, LearnerConfig};

/// The cost `r` of the sample in `ws.du = u − u0` (0 without reward weighting); the null-space
/// cost needs `Â` (`known`) in `ws.a_hat` and falls back to the full cost without it.
pub(crate) fn cost(
    cfg: &LearnerConfig,
    known: bool,
    metric: Option<&Metric>,
    ws: &mut Scratch,
) -> f64 {
    let c = &cfg.controllers;
    if !c.reward_weighting {
        return 0.0;
    }
    let full: f64 = match metric {
        None => ws.du.iter().map(|v| v * v).sum(),
        Some(mt) => mt.norm_squared(&ws.du, &mut ws.v_n),
    };
    match c.cost {
        CostKind::Full => full,
        CostKind::NullSpace if known => {
            let m = ws.y.len();
            let (a, du) = (&ws.a_hat, &ws.du);
            null_space_cost_in(
                metric,
                a,
                du,
                m,
                &mut ws.y,
                &mut ws.s,
                &mut ws.a_n,
                &mut ws.v_n,
            )
            .unwrap_or(full)
        }
        CostKind::NullSpace => full,
    }
}

/// Hindsight shrinkage: `target ← target − κ (I − Â⁺Â)(u − u0)` (with `ws.du = u − u0` and `Â`
/// in `ws.a_hat`): the same measured `ẍ` to first order, at a lower cost. `κ = 0`: unchanged.
pub(crate) fn shrink_target(kappa: f64, metric: Option<&Metric>, ws: &mut Scratch) {
    if kappa <= 0.0 {
        return;
    }
    ws.z.copy_from_slice(&ws.du);
    if project_scratch_z(metric, ws) {
        for (t, z) in ws.target.iter_mut().zip(&ws.z) {
            *t -= kappa * z;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{cost, shrink_target};
    use crate::config::{CostKind, LearnerConfig};
    use crate::learner::stats::Scratch;

    /// A scratch for n = 3, m = 2 with `Â` and `du` set.
    fn scratch() -> Scratch {
        let mut ws = Scratch::new(3, 2, 9, 10);
        ws.a_hat.copy_from_slice(&[1.0, -2.0, 0.5, 0.3, 0.7, -1.7]);
        ws.du.copy_from_slice(&[0.4, -1.1, 2.0]);
        ws.target.copy_from_slice(&ws.du.clone());
        ws
    }

    #[test]
    fn a_shrunk_target_keeps_the_task_part() {
        let mut ws = scratch();
        let before: Vec<f64> = (0..2)
            .map(|k| (0..3).map(|j| ws.a_hat[k * 3 + j] * ws.target[j]).sum())
            .collect();
        shrink_target(1.0, None, &mut ws);
        for (k, b) in before.iter().enumerate() {
            let after: f64 = (0..3).map(|j| ws.a_hat[k * 3 + j] * ws.target[j]).sum();
            assert!(
                (after - b).abs() < 1e-12,
                "Â·target changed: {after} vs {b}"
            );
        }
        // And it is cheaper: the null-space part is gone.
        let n2 = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>();
        assert!(n2(&ws.target) < n2(&ws.du));
        // κ = 0 is the paper's plain relabelling.
        let mut ws0 = scratch();
        shrink_target(0.0, None, &mut ws0);
        assert_eq!(ws0.target, ws0.du);
    }

    #[test]
    fn the_null_space_cost_is_the_full_cost_minus_the_task_part() {
        let mut cfg = LearnerConfig::default();
        let mut ws = scratch();
        let full = cost(
            &LearnerConfig {
                controllers: crate::config::ControllerConfig {
                    cost: CostKind::Full,
                    ..cfg.controllers.clone()
                },
                ..cfg.clone()
            },
            true,
            None,
            &mut ws,
        );
        let null = cost(&cfg, true, None, &mut ws);
        assert!((full - (0.16 + 1.21 + 4.0)).abs() < 1e-12);
        assert!(null > 0.0 && null < full, "{null} vs {full}");
        // Without Â the null-space cost is the full one; without reward weighting it is 0.
        assert_eq!(cost(&cfg, false, None, &mut ws), full);
        cfg.controllers.reward_weighting = false;
        assert_eq!(cost(&cfg, true, None, &mut ws), 0.0);
    }
}
