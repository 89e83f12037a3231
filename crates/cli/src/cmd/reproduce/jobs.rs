//! The training runs of `osrl reproduce` (E3–E7): one job per robot, learner variant, seed and
//! robot (with or without the E7 payload), run in parallel with one progress bar each.

use super::sizes::Sizes;
use crate::learned::{save_model, train_learner, Setup, Sidecar, SIDECAR_VERSION};
use crate::progress;
use anyhow::Result;
use indicatif::{MultiProgress, ProgressBar};
use lwpr::MetricInit;
use osrl_control::ModelError;
use osrl_learn::eval::{EvalResult, EvalSeries};
use osrl_learn::train::{BabbleConfig, TrainConfig, TrainSummary};
use osrl_learn::{CostKind, LearnerConfig};
use rayon::prelude::*;
use serde::Serialize;
use std::path::Path;

/// Which learner.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Variant {
    /// The default learner: local controllers trained by reward-weighted regression.
    Rwr,
    /// Reward weighting off: activation-weighted regression of `u` on the features, i.e.
    /// direct supervised inverse learning with the same partition (E6).
    Unweighted,
    /// RWR with the other cost than the default one: the paper's full `‖u − u0‖²` if the
    /// default is the null-space cost `‖(I − Â⁺Â)(u − u0)‖²`, and vice versa (E6).
    OtherCost,
    /// Reward weighting off and one receptive field covering the whole state space: a global
    /// linear inverse model (E6).
    Global,
}

impl Variant {
    pub const ALL: [Variant; 4] = [
        Variant::Rwr,
        Variant::Unweighted,
        Variant::OtherCost,
        Variant::Global,
    ];

    /// Key in `results.json`.
    pub fn key(self) -> &'static str {
        match self {
            Variant::Rwr => "rwr",
            Variant::Unweighted => "unweighted",
            Variant::OtherCost if default_is_null_space() => "rwr_full_cost",
            Variant::OtherCost => "rwr_null_space_cost",
            Variant::Global => "global_unweighted",
        }
    }

    /// Legend text.
    pub fn label(self) -> &'static str {
        match self {
            Variant::Rwr => "RWR (default)",
            Variant::Unweighted => "unweighted regression",
            Variant::OtherCost if default_is_null_space() => "RWR, full cost (paper)",
            Variant::OtherCost => "RWR, null-space cost",
            Variant::Global => "global unweighted",
        }
    }

    /// The learner config of this variant from the robot's default one.
    pub fn config(self, base: LearnerConfig) -> LearnerConfig {
        let mut c = base;
        match self {
            Variant::Rwr => {}
            Variant::Unweighted => c.reward_weighting = false,
            Variant::OtherCost => {
                c.cost = match c.cost {
                    CostKind::NullSpace => CostKind::Full,
                    _ => CostKind::NullSpace,
                }
            }
            Variant::Global => {
                c.reward_weighting = false;
                c.forward.init_d = MetricInit::Scalar(1e-8);
                c.forward.update_d = false;
            }
        }
        c
    }
}

/// Whether the learner's default cost is the null-space one.
fn default_is_null_space() -> bool {
    LearnerConfig::default().cost == CostKind::NullSpace
}

/// One training run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Job {
    pub robot: &'static str,
    pub variant: Variant,
    pub seed: u64,
    /// Train (and evaluate) on the robot carrying the E7 payload.
    pub payload: bool,
}

/// What a job produced.
pub struct JobResult {
    pub job: Job,
    pub outcome: Result<Trained, String>,
}

/// A finished training run.
pub struct Trained {
    pub summary: TrainSummary,
    /// The final evaluation (the last point of the learning curve).
    pub eval: EvalResult,
    /// Its time series (RWR, seed 0, no payload: E3/E4 figures).
    pub series: Option<EvalSeries>,
    /// The same learner evaluated on the robot with the payload, untrained there (E7).
    pub on_payload: Option<EvalResult>,
}

/// The jobs of a run: RWR over the learned seeds, the ablation variants and the payload runs
/// over the ablation seeds, both robots; longest first.
pub fn plan(sizes: &Sizes) -> Vec<Job> {
    let mut jobs = Vec::new();
    for robot in ["sarcos7", "planar3"] {
        let job = |variant, seed, payload| Job {
            robot,
            variant,
            seed,
            payload,
        };
        jobs.extend((0..sizes.learned_seeds).map(|s| job(Variant::Rwr, s, false)));
        for v in &Variant::ALL[1..] {
            jobs.extend((0..sizes.ablation_seeds).map(|s| job(*v, s, false)));
        }
        jobs.extend((0..sizes.ablation_seeds).map(|s| job(Variant::Rwr, s, true)));
    }
    jobs
}

/// Runs every job in parallel (rayon); failures are kept as messages.
pub fn run_all(
    jobs: &[Job],
    setups: &[(&'static str, Setup)],
    sizes: &Sizes,
    multi: &MultiProgress,
    models_dir: &Path,
) -> Vec<JobResult> {
    let bars: Vec<ProgressBar> = jobs
        .iter()
        .map(|j| {
            let name = format!(
                "{} {}{} s{}",
                j.robot,
                j.variant.key(),
                if j.payload { "+payload" } else { "" },
                j.seed
            );
            progress::train_bar(Some(multi), &name, sizes.robot(j.robot).minutes)
        })
        .collect();
    jobs.par_iter()
        .zip(bars.par_iter())
        .map(|(job, bar)| {
            let setup = &setups
                .iter()
                .find(|(r, _)| *r == job.robot)
                .expect("setup")
                .1;
            let outcome = run_one(job, setup, sizes, bar, models_dir).map_err(|e| format!("{e:#}"));
            if bar.is_hidden() {
                // No terminal (CI, a log file): one line per finished run instead of the bar.
                eprintln!("{}: {}", bar.prefix(), match &outcome {
                    Ok(t) if crate::learned::measured(&t.eval) => format!(
                        "tracking {:.3} mm, command nMSE {:.3}, {} local models, {:.0} s ({:.1}× real time){}",
                        t.eval.tracking_rms_mm, t.eval.command_nmse, t.summary.n_local_models,
                        t.summary.wall_seconds, t.summary.realtime_factor,
                        if t.eval.diverged { ", diverged" } else { "" }),
                    Ok(t) => format!("diverged in the evaluation's warm-up, {:.0} s", t.summary.wall_seconds),
                    Err(e) => format!("failed: {e}"),
                });
            }
            bar.finish();
            JobResult {
                job: job.clone(),
                outcome,
            }
        })
        .collect()
}

fn run_one(
    job: &Job,
    setup: &Setup,
    sizes: &Sizes,
    bar: &ProgressBar,
    models_dir: &Path,
) -> Result<Trained> {
    let rs = sizes.robot(job.robot);
    let model = &setup.model;
    let payload = ModelError {
        payload: sizes.payload_kg,
        ..ModelError::default()
    }
    .apply(model)?
    .0;
    let truth = if job.payload { &payload } else { model };
    let spec = model.spec();
    let lcfg = job
        .variant
        .config(LearnerConfig::for_robot(&spec.kp, &spec.kd, &spec.q_rest));
    let tcfg = TrainConfig {
        minutes: rs.minutes,
        seed: job.seed,
        eval_every_minutes: rs.eval_every_minutes,
        babble: BabbleConfig {
            minutes: rs.babble_minutes.unwrap_or(BabbleConfig::default().minutes),
            ..BabbleConfig::default()
        },
        ..TrainConfig::default()
    };
    let (mut learner, summary) =
        train_learner(setup, truth, lcfg, &tcfg, sizes.eval_periods, &mut |p| {
            progress::update(bar, rs.minutes, p)
        })?;
    let eval = summary
        .learning_curve
        .last()
        .map(|(_, e)| e.clone())
        .unwrap_or_default();
    let (mut series, mut on_payload) = (None, None);
    if job.variant == Variant::Rwr && job.seed == 0 && !job.payload {
        let mut ev = setup.evaluator(model.clone(), tcfg.gains, sizes.eval_periods)?;
        ev.keep_series = true;
        ev.evaluate(&mut learner)?;
        series = Some(std::mem::take(&mut ev.series));
        let mut ev = setup.evaluator(payload.clone(), tcfg.gains, sizes.eval_periods)?;
        on_payload = Some(ev.evaluate(&mut learner)?);
        let side = Sidecar {
            version: SIDECAR_VERSION,
            robot: job.robot.into(),
            trajectory: setup.traj_cfg.clone(),
            home: setup.home.clone(),
            gains: tcfg.gains,
            control_period: osrl_dynamics::SimConfig::default().control_period,
            sim_training_minutes: summary.sim_training_minutes,
            seed: job.seed,
        };
        save_model(
            &models_dir.join(format!("{}.osrl", job.robot)),
            &learner,
            &side,
        )?;
    }
    Ok(Trained {
        summary,
        eval,
        series,
        on_payload,
    })
}
