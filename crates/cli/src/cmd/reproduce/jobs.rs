//! The training runs of `osrl reproduce` (E3–E7): one job per robot, learner variant, seed and
//! robot (with or without the E7 payload), run in parallel with one progress bar each.

use super::sizes::Sizes;
use crate::learned::{save_model, train_learner, Setup, Sidecar, SIDECAR_VERSION};
use crate::progress;
use anyhow::Result;
use indicatif::{MultiProgress, ProgressBar};
use osrl_control::ModelError;
use osrl_learn::eval::{EvalResult, EvalSeries};
use osrl_learn::train::{BabbleConfig, TrainConfig, TrainSummary};
use osrl_learn::LearnerConfig;
pub use osrl_learn::Variant;
use serde::Serialize;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

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
/// over the ablation seeds, both robots; longest first, so that no long job starts last while the
/// other cores idle. Measured in a full run (2 cores): sarcos7's failing variants 570–890 s
/// (`rwr_paper`, `unweighted`), its RWR and payload runs 230–300 s, its global model 50 s, every
/// planar3 job 13–26 s.
pub fn plan(sizes: &Sizes) -> Vec<Job> {
    let mut jobs = Vec::new();
    for robot in ["sarcos7", "planar3"] {
        let job = |variant, seed, payload| Job {
            robot,
            variant,
            seed,
            payload,
        };
        for v in [Variant::Paper, Variant::Unweighted] {
            jobs.extend((0..sizes.ablation_seeds).map(|s| job(v, s, false)));
        }
        jobs.extend((0..sizes.learned_seeds).map(|s| job(Variant::Rwr, s, false)));
        jobs.extend((0..sizes.ablation_seeds).map(|s| job(Variant::Rwr, s, true)));
        jobs.extend((0..sizes.ablation_seeds).map(|s| job(Variant::Global, s, false)));
    }
    jobs
}

/// Runs every job on the rayon pool's threads, each thread taking the next job of `jobs` in
/// order (a plain `par_iter` would split the list in halves, one per thread, whatever its order);
/// failures are kept as messages. Results are in the order of `jobs`.
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
    let next = AtomicUsize::new(0);
    let slots: Vec<Mutex<Option<JobResult>>> = jobs.iter().map(|_| Mutex::new(None)).collect();
    let run = |job: &Job, bar: &ProgressBar| {
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
    };
    rayon::scope(|scope| {
        for _ in 0..rayon::current_num_threads().min(jobs.len()) {
            scope.spawn(|_| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                let Some(job) = jobs.get(i) else { break };
                let result = run(job, &bars[i]);
                *slots[i]
                    .lock()
                    .expect("no job panics while holding its slot") = Some(result);
            });
        }
    });
    slots
        .into_iter()
        .map(|m| {
            m.into_inner()
                .expect("no job panicked while holding its slot")
                .expect("every job ran")
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
    let lcfg = job.variant.config(LearnerConfig::for_robot(
        &spec.kp,
        &spec.kd,
        &spec.q_rest,
        &model.tau_max().collect::<Vec<_>>(),
    ));
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

#[cfg(test)]
mod tests {
    use super::{plan, Variant};
    use crate::cmd::reproduce::sizes::Sizes;

    #[test]
    fn the_plan_has_every_job_once_longest_first() {
        let sizes = Sizes::full();
        let jobs = plan(&sizes);
        // Per robot: 3 RWR seeds, 3 variants and 1 payload run (one ablation seed each).
        assert_eq!(jobs.len(), 14);
        for (i, a) in jobs.iter().enumerate() {
            assert!(!jobs[i + 1..].contains(a), "{a:?} twice");
        }
        for robot in ["sarcos7", "planar3"] {
            let rwr: Vec<u64> = (jobs.iter())
                .filter(|j| j.robot == robot && j.variant == Variant::Rwr && !j.payload)
                .map(|j| j.seed)
                .collect();
            assert_eq!(rwr, vec![0, 1, 2]);
        }
        // The failing sarcos7 variants (the longest runs) start first, planar3 comes last.
        assert_eq!(jobs[0].robot, "sarcos7");
        assert_eq!(jobs[0].variant, Variant::Paper);
        assert_eq!(jobs[1].variant, Variant::Unweighted);
        assert!(jobs[7..].iter().all(|j| j.robot == "planar3"));
    }
}
