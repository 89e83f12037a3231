//! The training runs of E3–E7: one job per robot, learner variant, seed and robot (with or
//! without the E7 payload), run in parallel; an [`Observer`] sees them start, progress and end.

use crate::error::Result;
use crate::setup::Setup;
use crate::sizes::Sizes;
use osrl_learn::eval::{EvalResult, EvalSeries};
use osrl_learn::train::{BabbleConfig, Progress, TrainConfig, TrainSummary};
use osrl_learn::{SavedModel, Variant};
use serde::Serialize;
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
    /// Train on the family of paths (E9) instead of the figure-8.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub family: bool,
}

impl Job {
    /// `sarcos7 rwr+payload s0`.
    pub fn name(&self) -> String {
        let payload = match (self.payload, self.family) {
            (true, _) => "+payload",
            (false, true) => "+family",
            (false, false) => "",
        };
        format!(
            "{} {}{payload} s{}",
            self.robot,
            self.variant.key(),
            self.seed
        )
    }

    /// Whether this is the run whose time series, payload evaluation and saved controller the
    /// report keeps: RWR, seed 0, no payload.
    pub fn is_reference(&self) -> bool {
        self.variant == Variant::Rwr && self.seed == 0 && !self.payload && !self.family
    }

    /// Whether this run is evaluated on E9's held-out paths: an RWR run without payload whose
    /// seed is among the robot's E9 seeds (trained on the family or on the figure-8).
    pub fn is_e9(&self, sizes: &Sizes) -> bool {
        self.variant == Variant::Rwr && !self.payload && self.seed < sizes.e9.seeds(self.robot)
    }
}

/// A finished training run.
#[derive(Clone, Debug)]
pub struct Trained {
    pub summary: TrainSummary,
    /// The final evaluation (the last point of the learning curve).
    pub eval: EvalResult,
    /// The reference run's ([`Job::is_reference`]) evaluation time series (E3/E4 figures).
    pub series: Option<EvalSeries>,
    /// The reference run's learner evaluated on the robot with the payload, untrained there
    /// (E7).
    pub on_payload: Option<EvalResult>,
    /// The reference run's learner as a saved model.
    pub model: Option<SavedModel>,
    /// E9 runs ([`Job::is_e9`]): the evaluation on each held-out path, with its label.
    pub held_out: Option<Vec<(String, EvalResult)>>,
}

/// What a job produced: the run, or its error's message.
#[derive(Clone, Debug)]
pub struct JobResult {
    pub job: Job,
    pub outcome: std::result::Result<Trained, String>,
}

/// Sees the experiments run (from the threads that run them): what starts, the analytical
/// runs, the training jobs' progress. Every method does nothing by default.
pub trait Observer: Sync {
    /// A line about what starts next.
    fn note(&self, _text: &str) {}
    /// `count` analytical runs start.
    fn analytical_started(&self, _count: usize) {}
    /// One analytical run finished.
    fn analytical_done(&self, _case: &crate::analytical::Case) {}
    /// The plan of the training jobs, before any starts.
    fn planned(&self, _jobs: &[Job]) {}
    /// Job `index` of the plan reached an evaluation or the end of an episode.
    fn progress(&self, _index: usize, _progress: &Progress) {}
    /// Job `index` finished (or failed).
    fn finished(&self, _index: usize, _result: &JobResult) {}
}

/// An observer that sees nothing.
pub struct Quiet;
impl Observer for Quiet {}

/// The jobs of a run: RWR over the learned seeds, the ablation variants and the payload runs
/// over the ablation seeds, both robots; longest first, so that no long job starts last while the
/// other cores idle. Measured in a full run before D32 (2 cores, 4 variants): sarcos7's failing
/// variants 570–890 s (`rwr_paper`, `unweighted`), its RWR and payload runs 230–300 s, its
/// global model 50 s, every planar3 job 13–26 s.
pub fn plan(sizes: &Sizes) -> Vec<Job> {
    let mut jobs = Vec::new();
    for robot in ["sarcos7", "planar3"] {
        let job = |variant, seed, payload| Job {
            robot,
            variant,
            seed,
            payload,
            family: false,
        };
        let family = |seed| Job {
            family: true,
            ..job(Variant::Rwr, seed, false)
        };
        for v in [Variant::Paper, Variant::Unweighted] {
            jobs.extend((0..sizes.ablation_seeds).map(|s| job(v, s, false)));
        }
        jobs.extend((0..sizes.e9.seeds(robot)).map(family));
        jobs.extend((0..sizes.learned_seeds).map(|s| job(Variant::Rwr, s, false)));
        for v in [Variant::UnweightedProjected, Variant::RwrUnprojected] {
            jobs.extend((0..sizes.ablation_seeds).map(|s| job(v, s, false)));
        }
        jobs.extend((0..sizes.ablation_seeds).map(|s| job(Variant::Rwr, s, true)));
        jobs.extend((0..sizes.ablation_seeds).map(|s| job(Variant::Global, s, false)));
    }
    jobs
}

/// The set-up of one job: the robot's, with the variant's learner and the sizes' training run.
///
/// # Errors
/// A set-up check (see [`Setup`]).
pub fn job_setup(base: &Setup, job: &Job, sizes: &Sizes) -> Result<Setup> {
    let rs = sizes.robot(job.robot);
    let train = TrainConfig {
        minutes: rs.minutes,
        seed: job.seed,
        eval_every_minutes: rs.eval_every_minutes,
        babble: BabbleConfig {
            minutes: rs.babble_minutes.unwrap_or(BabbleConfig::default().minutes),
            ..BabbleConfig::default()
        },
        ..TrainConfig::default()
    };
    let learner = job.variant.config(base.learner_config().clone());
    let base = if job.family {
        base.clone().with_trajectory(base.family_config())?
    } else {
        base.clone()
    };
    base.with_learner(learner)?
        .with_train(train)?
        .with_eval_periods(sizes.eval_periods)
}

/// Runs one job in `setup` ([`job_setup`]); `observe` sees its progress.
///
/// # Errors
/// The training's or the evaluation's error.
pub fn run_one(
    job: &Job,
    setup: &Setup,
    sizes: &Sizes,
    observe: &mut dyn FnMut(&Progress),
) -> Result<Trained> {
    let model = setup.model();
    let payload = setup.with_payload(sizes.payload_kg)?;
    let truth = if job.payload { &payload } else { model };
    let (mut learner, summary) = setup.train(truth, observe)?;
    let eval = summary
        .learning_curve
        .last()
        .map(|(_, e)| e.clone())
        .unwrap_or_default();
    let mut trained = Trained {
        summary,
        eval,
        series: None,
        on_payload: None,
        model: None,
        held_out: None,
    };
    if job.is_e9(sizes) {
        let paths = crate::family::held_out(setup, sizes.e9.paths_per_kind)?;
        let evals = (paths.iter())
            .map(|p| {
                Ok((
                    crate::family::label(p),
                    setup.evaluate_path(model, &mut learner, p)?,
                ))
            })
            .collect::<Result<Vec<_>>>()?;
        trained.held_out = Some(evals);
    }
    if job.is_reference() {
        let mut ev = setup.evaluator(model)?;
        ev.keep_series = true;
        ev.evaluate(&mut learner)?;
        trained.series = Some(std::mem::take(&mut ev.series));
        trained.on_payload = Some(setup.evaluator(&payload)?.evaluate(&mut learner)?);
        trained.model = Some(setup.saved(learner, &trained.summary)?);
    }
    Ok(trained)
}

/// Runs every job on the rayon pool's threads, each thread taking the next job of `jobs` in
/// order (a plain `par_iter` would split the list in halves, one per thread, whatever its order);
/// failures are kept as messages. Results are in the order of `jobs`.
pub fn run_all(
    jobs: &[Job],
    setups: &[(&str, Setup)],
    sizes: &Sizes,
    observer: &dyn Observer,
) -> Vec<JobResult> {
    observer.planned(jobs);
    let next = AtomicUsize::new(0);
    let slots: Vec<Mutex<Option<JobResult>>> = jobs.iter().map(|_| Mutex::new(None)).collect();
    let run = |i: usize, job: &Job| {
        let outcome = crate::setup_of(setups, job.robot)
            .and_then(|base| job_setup(base, job, sizes))
            .and_then(|s| run_one(job, &s, sizes, &mut |p| observer.progress(i, p)))
            .map_err(|e| e.to_string());
        let result = JobResult {
            job: job.clone(),
            outcome,
        };
        observer.finished(i, &result);
        result
    };
    rayon::scope(|scope| {
        for _ in 0..rayon::current_num_threads().min(jobs.len()) {
            scope.spawn(|_| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                let Some(job) = jobs.get(i) else { break };
                let result = run(i, job);
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_plan_has_every_job_once_longest_first() {
        let sizes = Sizes::full();
        let jobs = plan(&sizes);
        // Per robot: 3 RWR seeds, 5 variants and 1 payload run (one ablation seed each), and
        // the family runs of E9 (3 per robot).
        assert_eq!(jobs.len(), 24);
        assert_eq!(jobs.iter().filter(|j| j.family).count(), 6);
        for (i, a) in jobs.iter().enumerate() {
            assert!(!jobs[i + 1..].contains(a), "{a:?} twice");
        }
        for robot in ["sarcos7", "planar3"] {
            let rwr: Vec<u64> = (jobs.iter())
                .filter(|j| {
                    j.robot == robot && j.variant == Variant::Rwr && !j.payload && !j.family
                })
                .map(|j| j.seed)
                .collect();
            assert_eq!(rwr, vec![0, 1, 2]);
        }
        // The failing sarcos7 variants (the longest runs) start first, planar3 comes last.
        assert_eq!(jobs[0].robot, "sarcos7");
        assert_eq!(jobs[0].variant, Variant::Paper);
        assert_eq!(jobs[1].variant, Variant::Unweighted);
        assert!(jobs[12..].iter().all(|j| j.robot == "planar3"));
        assert_eq!(jobs.iter().filter(|j| j.is_reference()).count(), 2);
    }
}
