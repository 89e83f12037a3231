//! All experiments at once (`osrl reproduce`): E1, the analytical runs of E2/E7, the training
//! jobs of E3–E7, assembled into [`Results`] with everything the report draws.

use crate::analytical::{self, AnalyticalRun, ROBOTS};
use crate::compare::{e6, e7};
use crate::error::Result;
use crate::jobs::{self, Observer};
use crate::learned::e3_e4_e5;
use crate::results::{ByRobot, Curves, Results, RunConfig};
use crate::setup::Setup;
use crate::sizes::Sizes;
use crate::toy::{self, Fig1};
use osrl_control::{Law, TrajectoryConfig};
use osrl_learn::eval::EvalSeries;
use osrl_learn::train::TrainConfig;
use osrl_learn::{LearnerConfig, SavedModel};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::time::Instant;

/// What the report's figures draw that `results.json` does not hold (its time series aside,
/// which are CSV files): the toy problem's Fig. 1 iterations, each robot's trajectory and the
/// control period, the learning curves of every E6 variant.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FigureInputs {
    pub toy: Fig1,
    pub trajectories: ByRobot<TrajectoryConfig>,
    /// Control period of every run (s).
    pub control_period: f64,
    /// Per robot, each finished variant's legend text and learning curves.
    pub ablation: ByRobot<Vec<(String, Curves)>>,
}

impl FigureInputs {
    /// The set-up of `robot` that the figures need (its trajectory and control period).
    ///
    /// # Errors
    /// As [`Setup::new`].
    pub fn setup(&self, robot: &str) -> Result<Setup> {
        let t = self.trajectories.get(robot).cloned().unwrap_or_default();
        let s = Setup::along(robot, t)?;
        let sim = osrl_dynamics::SimConfig {
            control_period: self.control_period,
            ..osrl_dynamics::SimConfig::default()
        };
        s.with_sim(sim)
    }
}

/// A finished run of every experiment.
pub struct Reproduction {
    /// The numbers (`results.json`).
    pub results: Results,
    pub figures: FigureInputs,
    /// Every analytical run (E2 and E7), with its time series.
    pub analytical: Vec<AnalyticalRun>,
    /// Per robot, seed 0's evaluation series of the learned controller (E3, E4).
    pub learned: ByRobot<EvalSeries>,
    /// Per robot, seed 0's learned controller.
    pub models: ByRobot<SavedModel>,
    /// The training runs that failed: name and error.
    pub failed: Vec<(String, String)>,
}

/// Runs E1–E9 at `sizes` (`quick` records which sizes they are), the training jobs in parallel
/// on the rayon pool; `observer` sees the progress.
///
/// # Errors
/// A failing toy or analytical run (a failed training run is reported in the results instead).
pub fn reproduce(sizes: &Sizes, quick: bool, observer: &dyn Observer) -> Result<Reproduction> {
    let wall = Instant::now();
    let (e1, fig1) = run_e1(sizes, observer)?;
    let setups: Vec<(&str, Setup)> = ROBOTS
        .into_iter()
        .map(|r| Ok((r, Setup::new(r)?)))
        .collect::<Result<_>>()?;
    let runs = run_analytical(sizes, &setups, observer)?;
    let done = run_jobs(sizes, &setups, observer);
    let r = assemble(&done, &runs, &setups);
    let (e8, e8_failed) = crate::e8::run_all(sizes, &setups, &done, observer);
    let results = Results {
        e1,
        e2: e2(&runs),
        e3: r.e3,
        e4: r.e4,
        e5: r.e5,
        e6: r.e6,
        e7: r.e7,
        e8,
        e9: crate::e9::e9(&done),
        config: RunConfig {
            quick,
            sizes: sizes.clone(),
            threads: rayon::current_num_threads(),
            learner_defaults: LearnerConfig::default(),
            train_defaults: TrainConfig::default(),
        },
        seeds: (0..sizes.learned_seeds).collect(),
        wall_seconds: wall.elapsed().as_secs_f64(),
    };
    let figures = FigureInputs {
        toy: fig1,
        trajectories: (setups.iter())
            .map(|(r, s)| (r.to_string(), s.trajectory_config().clone()))
            .collect(),
        control_period: setups[0].1.sim().control_period,
        ablation: r.ablation,
    };
    let failed = (done.iter())
        .filter_map(|j| j.outcome.as_ref().err().map(|e| (j.job.name(), e.clone())))
        .chain(e8_failed)
        .collect();
    let models = (done.into_iter())
        .filter_map(|j| Some((j.job.robot.to_string(), j.outcome.ok()?.model?)))
        .collect();
    Ok(Reproduction {
        results,
        figures,
        analytical: runs,
        learned: r.learned,
        models,
        failed,
    })
}

/// E1: the toy problem's sweep over `sizes.toy_seeds` seeds, and Fig. 1's iterations.
fn run_e1(sizes: &Sizes, observer: &dyn Observer) -> Result<(rwr::toy::Report, Fig1)> {
    let seeds = sizes.toy_seeds;
    observer.note(&format!("E1: RWR toy problem (Fig. 1), {seeds} seeds"));
    let cfg = rwr::toy::ToyConfig {
        seeds,
        ..rwr::toy::ToyConfig::default()
    };
    Ok((toy::sweep(&cfg)?, toy::fig1(&cfg)?))
}

/// The analytical runs of E2 and E7.
fn run_analytical(
    sizes: &Sizes,
    setups: &[(&str, Setup)],
    observer: &dyn Observer,
) -> Result<Vec<AnalyticalRun>> {
    let cases = analytical::cases(sizes.payload_kg, sizes.analytical_seconds)?;
    observer.analytical_started(cases.len());
    analytical::run_all(&cases, setups, &|c| observer.analytical_done(c))
}

/// The training runs of E3–E7.
fn run_jobs(
    sizes: &Sizes,
    setups: &[(&str, Setup)],
    observer: &dyn Observer,
) -> Vec<jobs::JobResult> {
    let plan = jobs::plan(sizes);
    observer.note(&format!(
        "E3–E7, E9: {} training runs (planar3 {} min, sarcos7 {} min simulated) on {} threads",
        plan.len(),
        sizes.planar3.minutes,
        sizes.sarcos7.minutes,
        rayon::current_num_threads()
    ));
    jobs::run_all(&plan, setups, sizes, observer)
}

/// E2: the analytical runs with the true model, keyed `<robot>_<law>`.
fn e2(runs: &[AnalyticalRun]) -> BTreeMap<String, crate::results::AnalyticalRow> {
    (runs.iter())
        .filter(|a| a.case.error_key == "none")
        .map(|a| {
            let key = format!("{}_{}", a.case.robot, a.case.law_name());
            (key, a.row.clone())
        })
        .collect()
}

/// E3–E7 per robot.
#[derive(Default)]
struct Assembled {
    e3: ByRobot<crate::stats::Outcome<crate::results::LearnedRow>>,
    e4: ByRobot<crate::stats::Outcome<crate::results::Commands>>,
    e5: ByRobot<crate::stats::Outcome<Curves>>,
    e6: ByRobot<BTreeMap<String, crate::stats::Outcome<crate::results::AblationRow>>>,
    e7: ByRobot<BTreeMap<String, crate::results::ModelErrorRow>>,
    ablation: ByRobot<Vec<(String, Curves)>>,
    learned: ByRobot<EvalSeries>,
}

fn assemble(
    done: &[jobs::JobResult],
    runs: &[AnalyticalRun],
    setups: &[(&str, Setup)],
) -> Assembled {
    let mut a = Assembled::default();
    for (robot, setup) in setups {
        let key = robot.to_string();
        let eq7 = runs.iter().find(|r| {
            r.case.robot == *robot && r.case.error_key == "none" && r.case.law == Law::Eq7
        });
        let l = e3_e4_e5(
            done,
            robot,
            setup.model().nq(),
            setup.steps_per_period(),
            eq7.map(|r| r.row.tracking_rms_mm),
            eq7.is_some(),
        );
        a.e3.insert(key.clone(), l.e3);
        a.e4.insert(key.clone(), l.e4);
        a.e5.insert(key.clone(), l.e5);
        if let Some(s) = l.series {
            a.learned.insert(key.clone(), s);
        }
        let (rows, plotted) = e6(done, robot);
        a.e6.insert(key.clone(), rows);
        a.ablation.insert(key.clone(), plotted);
        a.e7.insert(key, e7(done, runs, robot));
    }
    a
}
