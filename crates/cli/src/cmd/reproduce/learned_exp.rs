//! E3 (learned tracking, Fig. 2a/2b/3b), E4 (learned vs analytical commands, Fig. 2c) and E5
//! (learning curves over seeds) from the finished training jobs.

use super::figures;
use super::jobs::{JobResult, Trained, Variant};
use super::{Ctx, Fig};
use crate::cmd::eval::figures as evalfig;
use crate::learned::eval_json;
use crate::plot;
use anyhow::Result;
use osrl_learn::eval::EvalResult;
use serde_json::{json, Map, Value};

/// `{mean, min, max}` of `v` (empty: no numbers, so the caller reports a failure instead).
pub fn stats(v: &[f64]) -> Value {
    let mean = v.iter().sum::<f64>() / v.len().max(1) as f64;
    let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    json!({"mean": mean, "min": lo, "max": hi})
}

/// The successful jobs of `robot` and `variant` (payload or not), and the failures' messages.
pub fn select<'a>(
    jobs: &'a [JobResult],
    robot: &str,
    variant: Variant,
    payload: bool,
) -> (Vec<&'a Trained>, Vec<String>) {
    let (mut ok, mut failed) = (Vec::new(), Vec::new());
    for j in jobs
        .iter()
        .filter(|j| j.job.robot == robot && j.job.variant == variant && j.job.payload == payload)
    {
        match &j.outcome {
            Ok(t) => ok.push(t),
            Err(e) => failed.push(format!("seed {}: {e}", j.job.seed)),
        }
    }
    (ok, failed)
}

/// Mean/min/max over runs of the final metrics, plus each run's. Runs whose final evaluation
/// diverged are counted (`diverged_runs`) and left out of the evaluation statistics; if all
/// diverged, those are `{"status": "diverged"}`.
pub fn summarize(runs: &[&Trained]) -> Value {
    let ok: Vec<&&Trained> = runs.iter().filter(|t| !t.eval.diverged).collect();
    let f = |g: &dyn Fn(&Trained) -> f64| {
        if ok.is_empty() {
            json!({"status": "diverged"})
        } else {
            stats(&ok.iter().map(|t| g(t)).collect::<Vec<_>>())
        }
    };
    let all = |g: &dyn Fn(&Trained) -> f64| stats(&runs.iter().map(|t| g(t)).collect::<Vec<_>>());
    json!({
        "runs": runs.len(),
        "tracking_rms_mm": f(&|t| t.eval.tracking_rms_mm),
        "command_nmse": f(&|t| t.eval.command_nmse),
        "command_cost_ratio": f(&|t| t.eval.command_cost_ratio),
        "fallback_share": f(&|t| t.eval.fallback_share),
        "n_local_models": all(&|t| t.summary.n_local_models as f64),
        "sim_training_minutes": all(&|t| t.summary.sim_training_minutes),
        "wall_seconds": all(&|t| t.summary.wall_seconds),
        "realtime_factor": all(&|t| t.summary.realtime_factor),
        "max_command_step": all(&|t| t.summary.max_command_step),
        "max_command_step_analytical": all(&|t| t.eval.max_command_step_analytical),
        "diverged_runs": runs.iter().filter(|t| t.eval.diverged).count(),
        "per_seed": runs.iter().map(|t| eval_json(&t.eval)).collect::<Vec<_>>(),
    })
}

/// Learning curves of runs.
pub fn curves(runs: &[&Trained]) -> Vec<Vec<(f64, EvalResult)>> {
    runs.iter()
        .map(|t| crate::learned::dedup_curve(&t.summary.learning_curve))
        .collect()
}

/// E3, E4, E5 for every robot.
pub fn e3_e4_e5(ctx: &Ctx, figs: &mut Vec<Fig>) -> Result<(Value, Value, Value)> {
    let (mut e3, mut e4, mut e5) = (Map::new(), Map::new(), Map::new());
    for (robot, setup) in ctx.setups {
        let (runs, failed) = select(ctx.jobs, robot, Variant::Rwr, false);
        let analytical = ctx.analytical(robot, "none", osrl_control::Law::Eq7);
        let a_mm = analytical.map(|(v, _)| v["tracking_rms_mm"].clone());
        if runs.is_empty() {
            let f = json!({"status": "failed", "errors": failed});
            for e in [&mut e3, &mut e4, &mut e5] {
                e.insert(robot.to_string(), f.clone());
            }
            continue;
        }
        let mut r3 = summarize(&runs);
        r3["analytical_eq7_tracking_rms_mm"] = a_mm.clone().unwrap_or(Value::Null);
        if !failed.is_empty() {
            r3["failed_seeds"] = json!(failed);
        }
        let dir = ctx.out.join("E3");
        let per = ctx.per_period(setup);
        let n = setup.model.nq();
        if let (Some(s), Some((_, run))) = (runs[0].series.as_ref(), analytical) {
            let names: Vec<&str> = setup
                .model
                .task_axes()
                .iter()
                .map(|&a| ["x", "y", "z"][a])
                .collect();
            evalfig::write_csv(&dir.join(format!("{robot}_learned.csv")), s, n, &names)?;
            plot::save(
                &figures::tracking(setup, s, &run.series),
                &dir,
                &format!("{robot}_tracking"),
            )?;
            figs.push(Fig::new(
                format!("E3/{robot}_tracking.svg"),
                format!("E3 (paper Fig. {}b): {robot} figure-8 with the learned controller (seed 0) and analytical eq. 7 — path and tracking error.", if *robot == "planar3" { 2 } else { 3 }),
            ));
            // The arm drawing needs a whole cycle: the learned run's if it did not diverge.
            let learned_ok = !runs[0].eval.diverged;
            let arm = if learned_ok {
                figures::ArmSeries {
                    t: &s.t,
                    q: &s.q,
                    x_d: &s.x_d,
                    who: "learned",
                }
            } else {
                let a = &run.series;
                figures::ArmSeries {
                    t: &a.t,
                    q: &a.q,
                    x_d: &a.x_d,
                    who: "analytical eq. 7",
                }
            };
            plot::save(
                &figures::arm(setup, &arm, per, ctx.sizes.arm_instants)?,
                &dir,
                &format!("{robot}_arm"),
            )?;
            figs.push(Fig::new(
                format!("E3/{robot}_arm.svg"),
                format!("E3 (paper Fig. {}a): {robot} posture at {} instants of one figure-8 cycle under the {} controller, the first at the path start (links from forward kinematics; large dots: the desired point at the same instant){}.",
                    if *robot == "planar3" { 2 } else { 3 }, ctx.sizes.arm_instants, arm.who,
                    if learned_ok { "" } else { " — the learned controller's evaluation diverged, so the analytical run is drawn" }),
            ));
            // E4: commands over the last cycle.
            let title = format!("{robot}: learned vs analytical optimal commands over one cycle");
            plot::save(
                &evalfig::commands_figure(s, n, per, &title),
                &ctx.out.join("E4"),
                &format!("{robot}_commands"),
            )?;
            figs.push(Fig::new(
                format!("E4/{robot}_commands.svg"),
                format!("E4 (paper Fig. 2c): {robot}, per joint, the learned command and the analytical optimum u* (eq. 7, N = I, true model) at the same states over one cycle."),
            ));
            let pj = evalfig::per_joint_rms(s, n, per);
            e4.insert(
                robot.to_string(),
                json!({
                    "command_nmse": runs[0].eval.command_nmse,
                    "command_cost_ratio": runs[0].eval.command_cost_ratio,
                    "per_joint_rms_difference_nm": pj.iter().map(|p| p.0).collect::<Vec<_>>(),
                    "per_joint_rms_u_star_nm": pj.iter().map(|p| p.1).collect::<Vec<_>>(),
                    "seed": 0,
                }),
            );
        }
        if !e4.contains_key(*robot) {
            e4.insert(
                robot.to_string(),
                json!({"status": "failed", "errors": ["seed 0 has no time series"]}),
            );
        }
        // E5: learning curves.
        let c = curves(&runs);
        let key = |g: fn(&EvalResult) -> f64| {
            let s = figures::spread(&c, g);
            json!({"mean": s.iter().map(|p| p.1).collect::<Vec<_>>(),
                   "min": s.iter().map(|p| p.2).collect::<Vec<_>>(),
                   "max": s.iter().map(|p| p.3).collect::<Vec<_>>()})
        };
        let minutes: Vec<f64> = figures::spread(&c, |e| e.tracking_rms_mm)
            .iter()
            .map(|p| p.0)
            .collect();
        e5.insert(
            robot.to_string(),
            json!({
                "seeds": runs.len(),
                "sim_minutes": minutes,
                "tracking_rms_mm": key(|e| e.tracking_rms_mm),
                "command_nmse": key(|e| e.command_nmse),
                "command_cost_ratio": key(|e| e.command_cost_ratio),
            }),
        );
        let reference = a_mm.and_then(|v| v.as_f64());
        let title = format!(
            "{robot}: learning curves (mean, min–max over {} seeds)",
            runs.len()
        );
        plot::save(
            &figures::curves(&title, &[("learned (RWR)", c)], reference),
            &ctx.out.join("E5"),
            &format!("{robot}_curves"),
        )?;
        figs.push(Fig::new(
            format!("E5/{robot}_curves.svg"),
            format!("E5 (paper Sec. V): {robot} tracking error, command nMSE against u* and command cost vs simulated training minutes, mean with min–max over seeds."),
        ));
        e3.insert(robot.to_string(), r3);
    }
    Ok((Value::Object(e3), Value::Object(e4), Value::Object(e5)))
}
