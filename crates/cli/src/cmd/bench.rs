//! `osrl bench lwpr`: the LWPR benchmarks of issue 4, as one JSON object.
//!
//! - `cross_2d`: the reference library's cross test (`docs/lwpr.md`, "The cross tests"): 500 noisy points, 20
//!   epochs (`--cross2-epochs`), tested on the 41×41 grid, over `--seeds` seeds from
//!   `--first-seed` on;
//! - `cross_21d`: the same points embedded in 21-D by a random rotation (or, with
//!   `--cross21-embedding identity`, unrotated), 25 epochs (`--cross21-epochs`), full metric
//!   with meta learning; keys `embedding` and `dim` (`--cross21-dim`: 21 as in issue 4, 25 as
//!   in the reference library's Matlab test `test_lwpr_nD.m`);
//! - `sarcos7_invdyn`: robot inverse dynamics, inputs `[q, q̇, q̈]` (21-D), outputs the 7 joint
//!   torques of the SARCOS master arm by RNEA, diagonal metric, one model per output.
//!
//! Times are wall-clock µs per call of the whole model (mean over a run). With `--repeat R`
//! each run is repeated R times and the smallest update and prediction times are kept (each
//! its own minimum): the repetitions compute the same numbers, so on a shared machine this is
//! the speed without the other jobs' interruptions.

mod c_ref;
mod datasets;
mod markdown;
mod pinocchio;
mod references;
mod samples;
#[cfg(test)]
mod tests;

use crate::util;
use anyhow::{Context, Result};
use lwpr::datasets::{cross21_config, cross_config, cross_nd_run, cross_run, Embedding, RunResult};
use lwpr::{Lwpr, LwprConfig, MetricInit, Norm, NormKeyword, PruneRule};
use osrl_dynamics::{rnea, robots};
use rand::seq::SliceRandom;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde_json::{json, Value};
use std::f64::consts::PI;
use std::time::Instant;

/// Benchmarks.
#[derive(clap::Args)]
pub struct Args {
    #[command(subcommand)]
    cmd: Sub,
}

#[derive(clap::Subcommand)]
enum Sub {
    /// LWPR: the 2-D and 21-D cross tests and robot inverse dynamics.
    Lwpr(LwprArgs),
    /// The crate against the reference LWPR C library and Pinocchio's C++ library (issue 31).
    References(references::RefArgs),
}

#[derive(clap::ValueEnum, Clone, Copy, PartialEq)]
enum Test {
    Cross2,
    Cross21,
    Sarcos7,
}

#[derive(clap::ValueEnum, Clone, Copy)]
enum Prune {
    /// The reference C library's rule (remove the wider of two overlapping RFs).
    Wider,
    /// The written descriptions' rule (remove the narrower; crates/lwpr/README.md, "Choices").
    Narrower,
}

#[derive(clap::ValueEnum, Clone, Copy, PartialEq)]
enum Embed {
    /// One random rotation per seed (the standard test).
    Rotation,
    /// The points in inputs 0 and 1, zeros in the other 19 (what the rotation costs).
    Identity,
}

#[derive(clap::Args)]
struct LwprArgs {
    /// Number of seeds of the cross tests (S..S+N with S = --first-seed); the report gives
    /// medians.
    #[arg(long, default_value_t = 10, value_parser = clap::value_parser!(u64).range(1..=1000))]
    seeds: u64,
    /// First seed of the cross tests.
    #[arg(long, default_value_t = 0)]
    first_seed: u64,
    /// Training epochs of the 2-D cross test (the reference library's test: 20).
    #[arg(long, default_value_t = 20, value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..=10_000))]
    cross2_epochs: usize,
    /// Training epochs of the 21-D cross test (issue 4: 25).
    #[arg(long, default_value_t = 25, value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..=10_000))]
    cross21_epochs: usize,
    /// Runs per seed; the smallest times are kept (the results are identical).
    #[arg(long, default_value_t = 1, value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..=100))]
    repeat: usize,
    /// Only these tests (comma-separated); all by default.
    #[arg(long, value_enum, value_delimiter = ',')]
    only: Vec<Test>,
    /// Prune rule of the 21-D cross test.
    #[arg(long, value_enum, default_value = "wider")]
    prune: Prune,
    /// How the 21-D cross test embeds its 2-D points.
    #[arg(long, value_enum, default_value = "rotation")]
    cross21_embedding: Embed,
    /// Dimension of the "21-D" cross test, 2–1000 (the reference library's Matlab test uses
    /// 25).
    #[arg(long, default_value_t = 21)]
    cross21_dim: usize,
    /// Robot data: number of random trajectories.
    #[arg(long, default_value_t = 10, value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..=10_000))]
    traj: usize,
    /// Robot data: seconds per trajectory, 0.1–3600 (sampled at 100 Hz; a random 10 % is held
    /// out, at least 2 samples).
    #[arg(long, default_value_t = 5.0)]
    seconds: f64,
    /// Robot data: training epochs.
    #[arg(long, default_value_t = 3, value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..=10_000))]
    epochs: usize,
    /// Robot data: initial distance metric `init_D = r·I` (inputs normalised).
    #[arg(long, default_value_t = 0.05)]
    init_d: f64,
    /// Print only one JSON object.
    #[arg(long)]
    json: bool,
}

/// Runs the subcommand.
pub fn run(a: Args) -> Result<()> {
    match a.cmd {
        Sub::Lwpr(b) => lwpr(b),
        Sub::References(b) => references::run(b),
    }
}

/// One seed of a cross test: config, seed, epochs.
type RunFn<'a> = &'a dyn Fn(&LwprConfig, u64, usize) -> Result<RunResult, lwpr::LwprError>;

/// A cross test (`run`: `datasets::cross_run` or `cross_nd_run` with an embedding) with `cfg`
/// for `epochs` over the seeds of `a`, each repeated `a.repeat` times (smallest times kept);
/// medians and per-seed values.
fn cross(a: &LwprArgs, cfg: &LwprConfig, epochs: usize, run: RunFn) -> Result<Value> {
    let (s0, n, repeat) = (a.first_seed, a.seeds, a.repeat);
    let f = |seed| run(cfg, seed, epochs);
    let mut runs = Vec::new();
    // n ≥ 1 and s0 + (n − 1) fits (checked by the caller).
    for seed in s0..=s0 + (n - 1) {
        let mut best = f(seed)?;
        for _ in 1..repeat {
            let r = f(seed)?;
            best.update_us = best.update_us.min(r.update_us);
            best.predict_us = best.predict_us.min(r.predict_us);
        }
        runs.push(best);
    }
    let col = |g: fn(&RunResult) -> f64| util::median(runs.iter().map(g).collect());
    Ok(json!({
        "seeds": n,
        "first_seed": s0,
        "epochs": epochs,
        "nmse": col(|r| r.nmse),
        "n_rfs": col(|r| r.n_rfs as f64),
        "update_us": col(|r| r.update_us),
        "predict_us": col(|r| r.predict_us),
        "nmse_all": runs.iter().map(|r| r.nmse).collect::<Vec<_>>(),
        "n_rfs_all": runs.iter().map(|r| r.n_rfs).collect::<Vec<_>>(),
        // The numerical guards' counts, summed over the seeds (`lwpr::Warnings`).
        "metric_skipped": runs.iter().map(|r| r.warnings.metric_skipped).sum::<u64>(),
        "removed_non_finite": runs.iter().map(|r| r.warnings.removed_non_finite).sum::<u64>(),
    }))
}

fn lwpr(a: LwprArgs) -> Result<()> {
    anyhow::ensure!(
        a.seeds > 0 && a.repeat > 0,
        "--seeds and --repeat must be at least 1"
    );
    anyhow::ensure!(
        a.first_seed.checked_add(a.seeds - 1).is_some(),
        "the last seed, --first-seed + --seeds - 1, must fit in 64 bits (got {} + {} - 1)",
        a.first_seed,
        a.seeds
    );
    anyhow::ensure!(
        a.cross2_epochs > 0 && a.cross21_epochs > 0,
        "--cross2-epochs and --cross21-epochs must be at least 1"
    );
    anyhow::ensure!(
        (2..=1000).contains(&a.cross21_dim),
        "--cross21-dim must be within 2–1000 (got {})",
        a.cross21_dim
    );
    anyhow::ensure!(
        a.traj > 0 && (0.1..=3600.0).contains(&a.seconds) && a.epochs > 0,
        "--traj and --epochs must be at least 1 and --seconds within 0.1–3600 (got {}, {}, {})",
        a.traj,
        a.epochs,
        a.seconds
    );
    let want = |t: Test| a.only.is_empty() || a.only.contains(&t);
    let mut out = serde_json::Map::new();
    let mut say = |name: &str, v: Value| {
        if !a.json {
            eprintln!("{name}: {v}");
        }
        out.insert(name.into(), v);
    };
    if want(Test::Cross2) {
        let v = cross(&a, &cross_config(), a.cross2_epochs, &cross_run)?;
        say("cross_2d", v);
    }
    if want(Test::Cross21) {
        let prune_rule = match a.prune {
            Prune::Wider => PruneRule::Wider,
            Prune::Narrower => PruneRule::Narrower,
        };
        let cfg = LwprConfig {
            prune_rule,
            ..cross21_config()
        };
        let (emb, name) = match a.cross21_embedding {
            Embed::Rotation => (Embedding::Rotation, "rotation"),
            Embed::Identity => (Embedding::Identity, "identity"),
        };
        let d = a.cross21_dim;
        let run = |c: &LwprConfig, s, e| cross_nd_run(c, s, e, d, emb);
        let mut v = cross(&a, &cfg, a.cross21_epochs, &run)?;
        v["embedding"] = json!(name);
        v["dim"] = json!(d);
        say("cross_21d", v);
    }
    if want(Test::Sarcos7) {
        let mut best = sarcos7(&a)?;
        for _ in 1..a.repeat {
            let r = sarcos7(&a)?;
            for k in ["update_us", "predict_us"] {
                best[k] = json!(best[k].as_f64().unwrap().min(r[k].as_f64().unwrap()));
            }
        }
        say("sarcos7_invdyn", best);
    }
    util::print_json(&Value::Object(out));
    Ok(())
}

/// Samples `(x, τ)` along one random trajectory of `seconds` at 100 Hz: per joint a sum of
/// three sinusoids (0.1–0.6 Hz, random phases) within 80 % of the joint range.
fn trajectory(
    rng: &mut ChaCha8Rng,
    seconds: f64,
    xs: &mut Vec<Vec<f64>>,
    ys: &mut Vec<Vec<f64>>,
) -> Result<()> {
    let model = robots::sarcos7();
    let mut data = model.data();
    let n = model.nq();
    let (lo, hi): (Vec<f64>, Vec<f64>) = (model.q_min().collect(), model.q_max().collect());
    let mut waves = Vec::new();
    for i in 0..n {
        let (a, b) = if lo[i].is_finite() && hi[i].is_finite() {
            (lo[i], hi[i])
        } else {
            (-PI, PI)
        };
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        let r: [f64; 3] = std::array::from_fn(|_| rng.random_range(0.2..1.0));
        let sum: f64 = r.iter().sum();
        let w: [(f64, f64, f64); 3] = std::array::from_fn(|k| {
            (
                0.8 * half * r[k] / sum,
                2.0 * PI * rng.random_range(0.1..0.6),
                rng.random_range(0.0..2.0 * PI),
            )
        });
        waves.push((mid, w));
    }
    let (mut q, mut qd, mut qdd) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    for s in 0..(seconds * 100.0) as usize {
        let t = s as f64 * 0.01;
        for (i, (mid, w)) in waves.iter().enumerate() {
            (q[i], qd[i], qdd[i]) = (*mid, 0.0, 0.0);
            for &(amp, om, ph) in w {
                q[i] += amp * (om * t + ph).sin();
                qd[i] += amp * om * (om * t + ph).cos();
                qdd[i] -= amp * om * om * (om * t + ph).sin();
            }
        }
        let tau = rnea(&model, &mut data, &q, &qd, &qdd).context("RNEA on the trajectory")?;
        xs.push([q.as_slice(), &qd, &qdd].concat());
        ys.push(tau.iter().copied().collect());
    }
    Ok(())
}

/// Standard deviation of every column.
fn std_devs(rows: &[Vec<f64>]) -> Vec<f64> {
    (0..rows[0].len()).map(|c| util::std_dev(rows, c)).collect()
}

/// The robot inverse-dynamics benchmark (seed 0): diagonal metric, meta learning, inputs and
/// outputs normalised by the training data's standard deviation.
fn sarcos7(a: &LwprArgs) -> Result<Value> {
    let mut rng = ChaCha8Rng::seed_from_u64(0);
    let (mut xs, mut ys) = (vec![], vec![]);
    for _ in 0..a.traj {
        trajectory(&mut rng, a.seconds, &mut xs, &mut ys)?;
    }
    let mut idx: Vec<usize> = (0..xs.len()).collect();
    idx.shuffle(&mut rng);
    let n_test = xs.len() / 10;
    anyhow::ensure!(
        n_test >= 2,
        "robot data: {} samples give {n_test} test samples; more --traj or --seconds",
        xs.len()
    );
    let pick = |ii: &[usize], v: &[Vec<f64>]| ii.iter().map(|&i| v[i].clone()).collect::<Vec<_>>();
    let (xte, yte) = (pick(&idx[..n_test], &xs), pick(&idx[..n_test], &ys));
    let (xtr, ytr) = (pick(&idx[n_test..], &xs), pick(&idx[n_test..], &ys));
    let mut cfg = LwprConfig {
        init_d: MetricInit::Scalar(a.init_d),
        init_alpha: 250.0,
        w_gen: 0.2,
        meta: true,
        diag_only: true,
        norm_in: Norm::Keyword(NormKeyword::Std),
        norm_out: Norm::Keyword(NormKeyword::Std),
        ..Default::default()
    };
    cfg.resolve_std(&std_devs(&xtr), &std_devs(&ytr))?;
    let mut m = Lwpr::new(21, 7, &cfg)?;
    let mut order: Vec<usize> = (0..xtr.len()).collect();
    let t0 = Instant::now();
    for _ in 0..a.epochs {
        order.shuffle(&mut rng);
        for &i in &order {
            m.update(&xtr[i], &ytr[i])?;
        }
    }
    let update_us = t0.elapsed().as_secs_f64() * 1e6 / (a.epochs * xtr.len()) as f64;
    let (mut yp, mut sup, mut se) = (vec![0.0; 7], vec![0.0; 7], [0.0; 7]);
    let t1 = Instant::now();
    for (x, y) in xte.iter().zip(&yte) {
        m.predict_with_support(x, &mut yp, &mut sup)?;
        for o in 0..7 {
            se[o] += (yp[o] - y[o]).powi(2);
        }
    }
    let predict_us = t1.elapsed().as_secs_f64() * 1e6 / xte.len() as f64;
    let sd = std_devs(&yte);
    let nmse: Vec<f64> = (0..7)
        .map(|o| se[o] / xte.len() as f64 / (sd[o] * sd[o]))
        .collect();
    Ok(json!({
        "train": xtr.len(),
        "test": xte.len(),
        "epochs": a.epochs,
        "n_rfs": m.n_rfs_total(),
        "n_rfs_per_output": m.n_rfs(),
        "update_us": update_us,
        "predict_us": predict_us,
        "nmse_mean": nmse.iter().sum::<f64>() / 7.0,
        "nmse": nmse,
        "metric_skipped": m.warnings().metric_skipped,
        "removed_non_finite": m.warnings().removed_non_finite,
    }))
}
