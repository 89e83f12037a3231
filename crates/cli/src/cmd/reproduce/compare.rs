//! E6 (ablation: the learner's variants side by side) and E7 (analytical eq. 7 with a wrong
//! model vs the learned controller trained on the true robot).

use super::analytical::ERRORS;
use super::figures;
use super::jobs::Variant;
use super::learned_exp::{curves, select, summarize};
use super::{Ctx, Fig};
use crate::learned::eval_json;
use crate::plot;
use anyhow::Result;
use osrl_control::Law;
use serde_json::{json, Map, Value};

/// E6: per robot and variant, the final metrics over its seeds, and one figure of the curves.
pub fn e6(ctx: &Ctx, figs: &mut Vec<Fig>) -> Result<Value> {
    let mut out = Map::new();
    for (robot, _) in ctx.setups {
        let mut rows = Map::new();
        let mut plotted = Vec::new();
        for v in Variant::ALL {
            let (runs, failed) = select(ctx.jobs, robot, v, false);
            let row = if runs.is_empty() {
                json!({"status": "failed", "errors": failed})
            } else {
                let mut r = summarize(&runs);
                r["label"] = v.label().into();
                r["seeds"] = runs.len().into();
                if !failed.is_empty() {
                    r["failed_seeds"] = json!(failed);
                }
                plotted.push((v.label(), curves(&runs)));
                r
            };
            rows.insert(v.key().into(), row);
        }
        let a = ctx.analytical(robot, "none", Law::Eq7);
        let reference = a.and_then(|(v, _)| v["tracking_rms_mm"].as_f64());
        let title = format!("{robot}: ablation — reward weighting, cost, localisation");
        plot::save(
            &figures::curves(&title, &plotted, reference),
            &ctx.out.join("E6"),
            &format!("{robot}_ablation"),
        )?;
        figs.push(Fig::new(
            format!("E6/{robot}_ablation.svg"),
            format!("E6 (paper Sec. II, IV): {robot}, RWR vs unweighted (supervised) inverse learning, RWR as in the paper (full cost, no shrinkage), and a global unweighted inverse model — tracking, command error against u*, command cost over training."),
        ));
        out.insert(robot.to_string(), Value::Object(rows));
    }
    Ok(Value::Object(out))
}

/// E7: per robot and model error, the analytical eq. 7 with that wrong model against the learned
/// controller on the true robot.
pub fn e7(ctx: &Ctx) -> Result<Value> {
    let mut out = Map::new();
    for (robot, _) in ctx.setups {
        let mut rows = Map::new();
        let (rwr, _) = select(ctx.jobs, robot, Variant::Rwr, false);
        let learned_true = summarize_or_null(&rwr);
        let seed0 = ctx
            .jobs
            .iter()
            .find(|j| {
                j.job.robot == *robot
                    && j.job.variant == Variant::Rwr
                    && j.job.seed == 0
                    && !j.job.payload
            })
            .and_then(|j| j.outcome.as_ref().ok());
        let (pay, pay_failed) = select(ctx.jobs, robot, Variant::Rwr, true);
        let mut keys = vec!["none"];
        keys.extend(ERRORS.iter().map(|e| e.0));
        for key in keys {
            let a = ctx.analytical(robot, key, Law::Eq7);
            let mut row = json!({
                "analytical_eq7_tracking_rms_mm": a.map_or(Value::Null, |(v, _)| v["tracking_rms_mm"].clone()),
                "analytical_eq7_tracking_max_mm": a.map_or(Value::Null, |(v, _)| v["tracking_max_mm"].clone()),
                "model_error": a.map_or(Value::Null, |(v, _)| v["model_error"].clone()),
            });
            if key == "payload" {
                // The robot carries the payload: the learned controller trained on it, and the
                // one trained without it (not retrained).
                row["learned_tracking_rms_mm"] = if pay.is_empty() {
                    json!({"status": "failed", "errors": pay_failed})
                } else {
                    summarize(&pay)["tracking_rms_mm"].clone()
                };
                row["learned_trained_with_payload"] = if pay.is_empty() {
                    Value::Null
                } else {
                    summarize(&pay)
                };
                row["learned_trained_without_payload"] = seed0
                    .and_then(|t| t.on_payload.as_ref())
                    .map_or(Value::Null, eval_json);
            } else {
                // The robot is the true one: the learned controller has no model to be wrong.
                row["learned_tracking_rms_mm"] = learned_true["tracking_rms_mm"].clone();
            }
            rows.insert(key.into(), row);
        }
        out.insert(robot.to_string(), Value::Object(rows));
    }
    Ok(Value::Object(out))
}

fn summarize_or_null(runs: &[&super::jobs::Trained]) -> Value {
    if runs.is_empty() {
        json!({"tracking_rms_mm": {"status": "failed"}})
    } else {
        summarize(runs)
    }
}
