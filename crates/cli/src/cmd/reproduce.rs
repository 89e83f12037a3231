//! `osrl reproduce`: runs experiments E1–E7 of DESIGN.md §5 and writes one report folder:
//! `index.html` (self-contained, inline SVG), `results.json`, every figure as SVG and PNG, time
//! series as CSV, and the seed-0 learned controllers in `models/` (for `osrl eval`). Sizes come
//! from [`sizes::Sizes`] (full or `--quick`); training runs go in parallel on all cores.

mod analytical;
mod compare;
mod figures;
mod jobs;
mod learned_exp;
mod report;
mod sizes;

use crate::cmd::toy;
use crate::learned::Setup;
use crate::progress;
use anyhow::{bail, Context, Result};
use indicatif::MultiProgress;
use osrl_control::{Law, Run, TrajectoryConfig};
use serde_json::{json, Map, Value};
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Report directory.
    #[arg(long, default_value = "report")]
    pub out: PathBuf,
    /// Small sizes (for CI: a few simulated minutes of training, under 3 minutes on 2 cores).
    #[arg(long)]
    pub quick: bool,
    /// Training seeds of the learned controller per robot (default 3, 2 with --quick).
    #[arg(long)]
    pub seeds: Option<u64>,
}

/// A figure of the report: SVG path relative to the report folder and its caption.
pub struct Fig {
    pub file: String,
    pub caption: String,
}

impl Fig {
    pub fn new(file: String, caption: String) -> Self {
        Self { file, caption }
    }
}

/// Everything the experiments' assembly reads.
pub struct Ctx<'a> {
    pub out: &'a Path,
    pub sizes: &'a sizes::Sizes,
    pub setups: &'a [(&'static str, Setup)],
    pub jobs: &'a [jobs::JobResult],
    pub cases: &'a [analytical::Case],
    pub runs: &'a [(Value, Run)],
}

impl Ctx<'_> {
    /// The analytical run of `robot` with the model error `error_key` and `law`.
    pub fn analytical(&self, robot: &str, error_key: &str, law: Law) -> Option<(&Value, &Run)> {
        self.cases
            .iter()
            .zip(self.runs)
            .find(|(c, _)| c.robot == robot && c.error_key == error_key && c.law == law)
            .map(|(_, (v, r))| (v, r))
    }
    /// Control steps per trajectory period.
    pub fn per_period(&self, setup: &Setup) -> usize {
        (setup.traj.period() / osrl_dynamics::SimConfig::default().control_period).round() as usize
    }
}

fn read_json(p: &Path) -> Result<Value> {
    let text = std::fs::read_to_string(p).with_context(|| format!("reading {}", p.display()))?;
    serde_json::from_str(&text).with_context(|| format!("parsing {}", p.display()))
}

pub fn run(a: Args) -> Result<()> {
    let wall = Instant::now();
    let out = &a.out;
    std::fs::create_dir_all(out).with_context(|| format!("creating {}", out.display()))?;
    let mut sizes = if a.quick {
        sizes::Sizes::quick()
    } else {
        sizes::Sizes::full()
    };
    if let Some(s) = a.seeds {
        if s == 0 {
            bail!("--seeds must be at least 1");
        }
        sizes.learned_seeds = s;
    }
    let multi = MultiProgress::new();
    let mut figs = Vec::new();
    // E1: Fig. 1, adaptive vs fixed reward transformation.
    let _ = multi.println(format!(
        "E1: RWR toy problem (Fig. 1), {} seeds",
        sizes.toy_seeds
    ));
    let e1_dir = out.join("E1");
    toy::run(toy::Args {
        seeds: Some(sizes.toy_seeds),
        out: e1_dir.clone(),
        json: false,
        config: None,
    })?;
    let e1 = read_json(&e1_dir.join("toy.json"))?;
    figs.push(Fig::new("E1/fig1_toy.svg".into(), "E1 (paper Fig. 1): transformed reward and policy mean over EM iterations, fixed vs adaptive τ.".into()));
    figs.push(Fig::new("E1/toy_iterations.svg".into(), "E1 (paper Fig. 1): EM iterations to converge vs initial τ (median, quartiles), adaptive vs fixed.".into()));
    // E2 and the analytical half of E7.
    let cases = analytical::cases(out, sizes.payload_kg)?;
    let bar = progress::job_bar(Some(&multi), "analytical E2/E7", cases.len() as u64);
    let runs = analytical::run_all(&cases, sizes.analytical_seconds, &bar)?;
    bar.finish();
    let mut e2 = Map::new();
    for (c, (v, _)) in cases
        .iter()
        .zip(&runs)
        .filter(|(c, _)| c.error_key == "none")
    {
        let law = format!("{:?}", c.law).to_lowercase();
        e2.insert(format!("{}_{law}", c.robot), v.clone());
        figs.push(Fig::new(
            format!("E2/{}_{law}/path.svg", c.robot),
            format!("E2 (baseline): {}, analytical {law} with the true model — desired vs actual figure-8 and the error over time.", c.robot),
        ));
    }
    // E3–E7: the training runs, all in parallel.
    let setups: Vec<(&'static str, Setup)> = ["planar3", "sarcos7"]
        .into_iter()
        .map(|r| Ok((r, Setup::for_robot(r, TrajectoryConfig::default())?)))
        .collect::<Result<_>>()?;
    let plan = jobs::plan(&sizes);
    let _ = multi.println(format!(
        "E3–E7: {} training runs (planar3 {} min, sarcos7 {} min simulated) on {} threads",
        plan.len(),
        sizes.planar3.minutes,
        sizes.sarcos7.minutes,
        rayon::current_num_threads()
    ));
    let results = jobs::run_all(&plan, &setups, &sizes, &multi, &out.join("models"));
    for r in &results {
        if let Err(e) = &r.outcome {
            eprintln!("training run {:?} failed: {e}", r.job);
        }
    }
    let ctx = Ctx {
        out,
        sizes: &sizes,
        setups: &setups,
        jobs: &results,
        cases: &cases,
        runs: &runs,
    };
    let (e3, e4, e5) = learned_exp::e3_e4_e5(&ctx, &mut figs)?;
    let e6 = compare::e6(&ctx, &mut figs)?;
    let e7 = compare::e7(&ctx)?;
    let results = json!({
        "E1": e1, "E2": Value::Object(e2), "E3": e3, "E4": e4, "E5": e5, "E6": e6, "E7": e7,
        "config": {
            "quick": a.quick,
            "sizes": sizes,
            "threads": rayon::current_num_threads(),
            "learner_defaults": osrl_learn::LearnerConfig::default(),
            "train_defaults": osrl_learn::train::TrainConfig::default(),
        },
        "seeds": (0..sizes.learned_seeds).collect::<Vec<_>>(),
        "wall_seconds": wall.elapsed().as_secs_f64(),
    });
    std::fs::write(
        out.join("results.json"),
        serde_json::to_string_pretty(&results)?,
    )?;
    report::write(out, &results, &figs)?;
    eprintln!(
        "report: {} ({:.0} s)",
        out.join("index.html").display(),
        wall.elapsed().as_secs_f64()
    );
    Ok(())
}
