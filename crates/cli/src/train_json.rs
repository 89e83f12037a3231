//! The JSON of a training run (`osrl train --json`, `osrl adapt --json`): the final
//! evaluation's metrics, the run's numbers, the learning curve; shared by both commands.

use anyhow::{Context, Result};
use osrl_experiments::stats::{curve_points, EvalSummary};
use osrl_learn::train::TrainSummary;
use serde_json::{json, Value};

/// Above this share of rejected samples a training run warns.
pub const MAX_REJECTED_SHARE: f64 = 0.01;

/// Samples the learner rejected as absurd, and their share of all it saw (0 without any).
pub fn rejected(s: &TrainSummary) -> (u64, f64) {
    let (r, n) = (s.stats.rejected, s.stats.samples + s.stats.rejected);
    (r, if n == 0 { 0.0 } else { r as f64 / n as f64 })
}

/// The JSON of a training run: the final evaluation's metrics, the run's numbers, the curve.
pub fn summary_json(s: &TrainSummary, final_eval: &EvalSummary, robot: &str) -> Result<Value> {
    let mut j = serde_json::to_value(final_eval)?;
    let o = j
        .as_object_mut()
        .context("an evaluation is a JSON object")?;
    let extra = json!({
        "robot": robot,
        "n_local_models": s.n_local_models,
        "sim_training_minutes": s.sim_training_minutes,
        "wall_seconds": s.wall_seconds,
        "realtime_factor": s.realtime_factor,
        "max_command_step": s.max_command_step,
        "max_torque_rate": s.max_torque_rate,
        "rate_limited": s.rate_limited(),
        "clipped_on_policy": s.clipped_on_policy,
        "command_step_curve": s.step_curve,
        "minutes_to_1mm": s.minutes_to(|e| e.tracking_rms_mm <= 1.0),
        "minutes_to_nmse_0.05": s.minutes_to(|e| e.command_nmse <= 0.05),
        "episodes": s.episodes,
        "paths_drawn": s.paths_drawn,
        "aborted_episodes": s.aborted_episodes,
        "braked_episodes": s.braked_episodes,
        "braked_on_step": s.braked_on_step,
        "braked_on_step_by_joint": s.braked_on_step_by_joint,
        "counters": s.stats,
        "rejected_samples": rejected(s).0,
        "rejected_share": rejected(s).1,
        "unsettled_starts": s.unsettled_starts,
        "observer_saturated": s.observer_saturated,
        "rollbacks": s.rollbacks,
        "max_stage": s.episode_log.iter().map(|e| e.stage).max(),
        "episode_log": s.episode_log,
        "learning_curve": curve_points(&s.learning_curve),
        "error_split_curve": error_split_curve(s),
    });
    for (k, v) in extra.as_object().into_iter().flatten() {
        o.insert(k.clone(), v.clone());
    }
    Ok(j)
}

/// The split of the command error at every evaluation of the learning curve (`docs/learner.md`,
/// "Evaluation"): its null-space part, the learned `u0`'s error and its null-space part, the
/// error of `Â`, the cost ratio and the support share; `null` where an evaluation diverged.
fn error_split_curve(s: &TrainSummary) -> Vec<Value> {
    osrl_experiments::stats::dedup_curve(&s.learning_curve)
        .iter()
        .map(|(t, e)| {
            let ok = !e.diverged && e.command_nmse.is_finite();
            let v = |x: f64| if ok { json!(x) } else { Value::Null };
            json!({
                "sim_minutes": t,
                "command_nmse_null": v(e.command_nmse_null),
                "nominal_nmse": v(e.nominal_nmse),
                "nominal_nmse_null": v(e.nominal_nmse_null),
                "gain_error": v(e.gain_error),
                "floor_nmse_null": v(e.floor_nmse_null),
                "command_cost_ratio": v(e.command_cost_ratio),
                "support_share": v(e.support_share),
            })
        })
        .collect()
}
