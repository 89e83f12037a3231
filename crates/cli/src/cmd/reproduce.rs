//! `osrl reproduce`: runs experiments E1–E7 (`osrl_experiments::reproduce`) and writes one
//! report folder (`osrl_report`): `index.html` (self-contained, inline SVG), `results.json`,
//! `figures.json`, every figure as SVG and PNG, the time series as CSV, and the seed-0 learned
//! controllers in `models/` (for `osrl eval`). Sizes come from `osrl_experiments::Sizes` (full
//! or `--quick`); training runs go in parallel on all cores, one progress bar each.

use crate::progress::Bars;
use anyhow::{bail, Context, Result};
use osrl_experiments::Sizes;
use std::path::PathBuf;
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
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=100))]
    pub seeds: Option<u64>,
}

pub fn run(a: Args) -> Result<()> {
    let wall = Instant::now();
    let out = &a.out;
    // Check the output before the long work.
    crate::util::check_out_dir(
        "--out",
        out,
        &["index.html", "results.json", "figures.json"],
        &[],
    )?;
    crate::util::check_out_dir(
        "--out",
        &out.join("models"),
        &["planar3.osrl", "sarcos7.osrl"],
        &[],
    )?;
    // The page's figures and tables go in folders per experiment: nothing already there may
    // be a file that cannot be replaced.
    osrl_files::check_output_tree(out, &crate::util::PAGE_EXTENSIONS).context("--out")?;
    let mut sizes = if a.quick {
        Sizes::quick()
    } else {
        Sizes::full()
    };
    if let Some(s) = a.seeds {
        sizes.learned_seeds = s;
    }
    let bars = Bars::new(&sizes);
    let rep = osrl_experiments::reproduce(&sizes, a.quick, &bars)?;
    for (job, e) in &rep.failed {
        eprintln!("training run {job} failed: {e}");
    }
    // A model that cannot be saved where asked is saved next to it; the report is written
    // all the same, and the command fails at the end saying where the model went.
    let mut unsaved = Vec::new();
    for (robot, model) in &rep.models {
        let path = out.join("models").join(format!("{robot}.osrl"));
        if let Err(e) = crate::util::save_result("trained model", &path, &model.to_bytes()?) {
            eprintln!("error: {e:#}");
            unsaved.push(robot.to_string());
        }
    }
    osrl_report::write_report(out, &rep)?;
    eprintln!(
        "report: {} ({:.0} s)",
        out.join("index.html").display(),
        wall.elapsed().as_secs_f64()
    );
    if !unsaved.is_empty() {
        bail!(
            "the models of {} were not saved in models/ (see above)",
            unsaved.join(", ")
        );
    }
    Ok(())
}
