//! `osrl toy`: the Fig. 1 experiment (E1) — adaptive versus fixed reward transformation on the
//! 1-D linear-policy problem of `rwr::toy`, over seeds and a sweep of initial `τ`.
//!
//! Prints a table; writes `fig1_toy.{svg,png}` (policy and transformed reward over iterations,
//! fixed vs adaptive), `toy_iterations.{svg,png}` (iterations to converge vs initial `τ`) and
//! `toy.json` into `--out`; with `--json` the last stdout line is the report object.

use anyhow::Result;
use osrl_experiments::toy;
use osrl_report::figures::toy as figures;
use rwr::toy::{check_claims, Report, ToyConfig, Variant};
use std::path::PathBuf;

/// Arguments of `osrl toy`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Seeds per case (default: the config's, 30).
    #[arg(long)]
    pub seeds: Option<u64>,
    /// Directory for the figures and toy.json.
    #[arg(long, default_value = "out/toy")]
    pub out: PathBuf,
    /// Print the report as one JSON object on the last stdout line.
    #[arg(long)]
    pub json: bool,
    /// TOML file with `rwr::toy::ToyConfig` fields (missing fields keep their defaults).
    #[arg(long)]
    pub config: Option<PathBuf>,
}

fn load(a: &Args) -> Result<ToyConfig> {
    let mut cfg = match &a.config {
        Some(p) => crate::util::read_toml(p)?,
        None => ToyConfig::default(),
    };
    if let Some(s) = a.seeds {
        cfg.seeds = s;
    }
    cfg.validate()?;
    Ok(cfg)
}

/// Runs the sweep (in parallel over cases × seeds), prints, plots, writes JSON.
pub fn run(a: Args) -> Result<()> {
    let cfg = load(&a)?;
    crate::util::check_out_dir("--out", &a.out, &["toy.json"], &[a.config.as_deref()])?;
    let report = toy::sweep(&cfg)?;
    print_table(&cfg, &report);
    let mut written = figures::iterations(&cfg, &report, &a.out)?;
    written.extend(figures::fig1(&toy::fig1(&cfg)?, &a.out)?);
    let json = serde_json::to_string(&report)?;
    let path = a.out.join("toy.json");
    osrl_files::write_atomic(&path, format!("{json}\n").as_bytes())?;
    written.push(path);
    for p in &written {
        println!("wrote {}", p.display());
    }
    if a.json {
        println!("{json}");
    }
    Ok(())
}

fn print_table(cfg: &ToyConfig, report: &Report) {
    let [q1, q2, q3] = cfg.q;
    println!(
        "Fig. 1 toy: r = {q1} a² + {q2} a s + {q3} s², s ~ U[-{s}, {s}], θ0 = {:?}, θ* = {:?}, σ0 = {}, \
         {} samples/iteration, ε = {}, max {} iterations, {} seeds",
        cfg.theta_init,
        cfg.theta_star(),
        cfg.sigma_init,
        cfg.samples_per_iter,
        cfg.epsilon,
        cfg.max_iters,
        cfg.seeds,
        s = cfg.s_max
    );
    println!(
        "{:>7} {:>9} {:>8} {:>8} {:>7} {:>7} {:>7}",
        "tau0", "variant", "sigma", "median", "q25", "q75", "never"
    );
    for r in &report.results {
        let variant = if r.variant == Variant::Adaptive {
            "adaptive"
        } else {
            "fixed"
        };
        let sigma = if r.sigma_update { "updated" } else { "fixed" };
        println!(
            "{:>7} {variant:>9} {sigma:>8} {:>8.1} {:>7.1} {:>7.1} {:>6.0}%",
            r.tau0,
            r.median_iters,
            r.q25_iters,
            r.q75_iters,
            100.0 * r.never_converged
        );
    }
    let claims = check_claims(report);
    for s in &claims.speedups {
        let sigma = if s.sigma_update { "updated" } else { "fixed" };
        println!(
            "tau0 {:>5}, σ {sigma:>7}: fixed/adaptive median = {:.2}",
            s.tau0, s.ratio
        );
    }
    let yes = |b: bool| if b { "holds" } else { "does NOT hold" };
    println!(
        "claim: adaptive ≥ 4× faster for tau0 ≤ 0.1: {}",
        yes(claims.misscaled_4x_faster)
    );
    println!(
        "claim: adaptive never > 20% slower: {}",
        yes(claims.never_20pct_slower)
    );
}
