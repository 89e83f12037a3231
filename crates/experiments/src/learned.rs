//! E3 (learned tracking, Fig. 2a/2b/3b), E4 (learned vs analytical commands, Fig. 2c) and E5
//! (learning curves over seeds) from the finished training jobs.

use crate::jobs::{JobResult, Trained};
use crate::results::{Commands, Curves, LearnedRow, RunsSummary, SafetyRow};
use crate::stats::{EvalSummary, Missing, Outcome, Spread, SpreadSeries, Stat, Status};
use osrl_learn::eval::{EvalResult, EvalSeries};
use osrl_learn::Variant;

/// The successful jobs of `robot` and `variant` (payload or not), and the failures' messages.
pub fn select<'a>(
    jobs: &'a [JobResult],
    robot: &str,
    variant: Variant,
    payload: bool,
) -> (Vec<&'a Trained>, Vec<String>) {
    let (mut ok, mut failed) = (Vec::new(), Vec::new());
    for j in jobs.iter().filter(|j| {
        j.job.robot == robot
            && j.job.variant == variant
            && j.job.payload == payload
            && !j.job.family
    }) {
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
pub fn summarize(runs: &[&Trained]) -> RunsSummary {
    let ok: Vec<&&Trained> = runs.iter().filter(|t| !t.eval.diverged).collect();
    let f = |g: &dyn Fn(&Trained) -> f64| {
        if ok.is_empty() {
            Stat::Missing(Missing {
                status: Status::Diverged,
                errors: Vec::new(),
            })
        } else {
            Stat::Spread(Spread::of(&ok.iter().map(|t| g(t)).collect::<Vec<_>>()))
        }
    };
    let all =
        |g: &dyn Fn(&Trained) -> f64| Spread::of(&runs.iter().map(|t| g(t)).collect::<Vec<_>>());
    RunsSummary {
        runs: runs.len(),
        tracking_rms_mm: f(&|t| t.eval.tracking_rms_mm),
        command_nmse: f(&|t| t.eval.command_nmse),
        command_cost_ratio: f(&|t| t.eval.command_cost_ratio),
        fallback_share: f(&|t| t.eval.fallback_share),
        n_local_models: all(&|t| t.summary.n_local_models as f64),
        sim_training_minutes: all(&|t| t.summary.sim_training_minutes),
        wall_seconds: all(&|t| t.summary.wall_seconds),
        realtime_factor: all(&|t| t.summary.realtime_factor),
        max_command_step: all(&|t| t.summary.max_command_step),
        max_command_step_analytical: all(&|t| t.eval.max_command_step_analytical),
        diverged_runs: runs.iter().filter(|t| t.eval.diverged).count(),
        per_seed: runs.iter().map(|t| EvalSummary::from(&t.eval)).collect(),
        safety: runs.iter().map(|t| safety(t)).collect(),
    }
}

/// A run's learning safety.
pub fn safety(t: &Trained) -> SafetyRow {
    let s = &t.summary;
    SafetyRow {
        aborted_episodes: s.aborted_episodes,
        braked_episodes: s.braked_episodes,
        clipped_on_policy: s.clipped_on_policy,
        fallbacks: s.stats.fallbacks,
        rate_limited: s.rate_limited(),
        max_command_step: s.max_command_step,
        max_torque_rate: s.max_torque_rate,
        max_command_step_analytical: t.eval.max_command_step_analytical,
        minutes_to_1mm: s.minutes_to(|e| e.tracking_rms_mm <= 1.0),
        minutes_to_nmse_0_05: s.minutes_to(|e| e.command_nmse <= 0.05),
        step_curve: s.step_curve.clone(),
    }
}

/// Each run's learning curve (repeated evaluations at one minute listed once).
pub fn curves_of(runs: &[&Trained]) -> Vec<Vec<(f64, EvalResult)>> {
    runs.iter()
        .map(|t| crate::stats::dedup_curve(&t.summary.learning_curve))
        .collect()
}

/// Mean and (min, max) over seeds of `f` at each evaluation of the learning curves, over the
/// seeds whose evaluation there did not diverge (points where all diverged are left out):
/// `(minutes, mean, min, max)`.
pub fn spread(
    curves: &[Vec<(f64, EvalResult)>],
    f: impl Fn(&EvalResult) -> f64,
) -> Vec<(f64, f64, f64, f64)> {
    let len = curves.iter().map(Vec::len).min().unwrap_or(0);
    (0..len)
        .filter(|&i| curves.iter().any(|c| !c[i].1.diverged))
        .map(|i| {
            let v: Vec<f64> = curves
                .iter()
                .filter(|c| !c[i].1.diverged)
                .map(|c| f(&c[i].1))
                .collect();
            let s = Spread::of(&v);
            (curves[0][i].0, s.mean, s.min, s.max)
        })
        .collect()
}

/// The learning curves of `runs` over their seeds.
pub fn curves(runs: &[&Trained]) -> Curves {
    let c = curves_of(runs);
    let series = |g: fn(&EvalResult) -> f64| {
        let s = spread(&c, g);
        SpreadSeries {
            mean: s.iter().map(|p| p.1).collect(),
            min: s.iter().map(|p| p.2).collect(),
            max: s.iter().map(|p| p.3).collect(),
        }
    };
    Curves {
        seeds: runs.len(),
        sim_minutes: spread(&c, |e| e.tracking_rms_mm)
            .iter()
            .map(|p| p.0)
            .collect(),
        tracking_rms_mm: series(|e| e.tracking_rms_mm),
        command_nmse: series(|e| e.command_nmse),
        command_cost_ratio: series(|e| e.command_cost_ratio),
    }
}

/// Rows `[start, end)` of the last whole period of a series of `len` rows (`per_period` rows
/// per period).
pub fn last_cycle(len: usize, per_period: usize) -> (usize, usize) {
    let per = per_period.max(1).min(len);
    (len - per, len)
}

/// Per-joint RMS of `u − u*` and RMS of `u*` over the last cycle (N·m).
pub fn per_joint_rms(es: &EvalSeries, n: usize, per_period: usize) -> Vec<(f64, f64)> {
    let (a, b) = last_cycle(es.t.len(), per_period);
    let c = (b - a).max(1) as f64;
    (0..n)
        .map(|j| {
            let (mut d2, mut s2) = (0.0, 0.0);
            for k in a..b {
                d2 += (es.u[k * n + j] - es.u_star[k * n + j]).powi(2);
                s2 += es.u_star[k * n + j].powi(2);
            }
            ((d2 / c).sqrt(), (s2 / c).sqrt())
        })
        .collect()
}

/// E3, E4 and E5 of one robot with `n` joints and `per_period` steps per period, from its RWR
/// runs; `eq7_mm` is eq. 7's tracking with the true model (E2); `with_series` says whether the
/// analytical time series exists (E4 needs it beside the learned one).
pub struct LearnedExperiments {
    pub e3: Outcome<LearnedRow>,
    pub e4: Outcome<Commands>,
    pub e5: Outcome<Curves>,
    /// Seed 0's evaluation series (if the run and the analytical series exist).
    pub series: Option<EvalSeries>,
}

/// See [`LearnedExperiments`].
pub fn e3_e4_e5(
    jobs: &[JobResult],
    robot: &str,
    n: usize,
    per_period: usize,
    eq7_mm: Option<f64>,
    with_series: bool,
) -> LearnedExperiments {
    let (runs, failed) = select(jobs, robot, Variant::Rwr, false);
    if runs.is_empty() {
        let f = Missing::failed(failed);
        return LearnedExperiments {
            e3: Outcome::Failed(f.clone()),
            e4: Outcome::Failed(f.clone()),
            e5: Outcome::Failed(f),
            series: None,
        };
    }
    let e3 = Outcome::Done(LearnedRow {
        summary: summarize(&runs),
        analytical_eq7_tracking_rms_mm: eq7_mm,
        failed_seeds: failed,
    });
    let series = runs[0].series.clone().filter(|_| with_series);
    let e4 = match &series {
        Some(s) => {
            let pj = per_joint_rms(s, n, per_period);
            Outcome::Done(Commands {
                command_nmse: runs[0].eval.command_nmse,
                command_cost_ratio: runs[0].eval.command_cost_ratio,
                per_joint_rms_difference_nm: pj.iter().map(|p| p.0).collect(),
                per_joint_rms_u_star_nm: pj.iter().map(|p| p.1).collect(),
                seed: 0,
            })
        }
        None => Outcome::Failed(Missing::failed(vec!["seed 0 has no time series".into()])),
    };
    LearnedExperiments {
        e3,
        e4,
        e5: Outcome::Done(curves(&runs)),
        series,
    }
}
