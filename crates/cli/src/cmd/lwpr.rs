//! `osrl lwpr fit`: train an LWPR model on a CSV file and test it on another.
//!
//! CSV files have a header row; the first K columns are inputs, the rest outputs. The config is
//! TOML with the parameter names of `shared/LWPR.md` in snake case (see `lwpr::LwprConfig`);
//! unknown keys are an error. `norm_in`/`norm_out` may be `"std"`: the training data's
//! standard deviation per column.

use crate::util;
use anyhow::{bail, Context, Result};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use lwpr::{Lwpr, LwprConfig};
use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// LWPR: incremental locally weighted projection regression.
#[derive(clap::Args)]
pub struct Args {
    #[command(subcommand)]
    cmd: Sub,
}

#[derive(clap::Subcommand)]
enum Sub {
    /// Train on a CSV file for some epochs and report test nMSE, model size and timings.
    Fit(FitArgs),
}

#[derive(clap::Args)]
struct FitArgs {
    /// Training data (CSV with a header row).
    #[arg(long)]
    train: PathBuf,
    /// Test data (same columns).
    #[arg(long)]
    test: PathBuf,
    /// Number of input columns K (the first K); the remaining columns are outputs.
    #[arg(long)]
    inputs: usize,
    /// LWPR config (TOML).
    #[arg(long)]
    config: Option<PathBuf>,
    /// Passes over the training data, each in a fresh shuffled order.
    #[arg(long, default_value_t = 20)]
    epochs: usize,
    /// Seed of the shuffling.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Save the trained model here.
    #[arg(long)]
    save: Option<PathBuf>,
    /// Print only one JSON object.
    #[arg(long)]
    json: bool,
}

/// Runs the subcommand.
pub fn run(a: Args) -> Result<()> {
    match a.cmd {
        Sub::Fit(f) => fit(f),
    }
}

/// Rows of a numeric CSV file with a header; every row has the header's column count.
fn read_csv(path: &Path) -> Result<(Vec<String>, Vec<Vec<f64>>)> {
    let text = std::fs::read_to_string(path).with_context(|| format!("{}", path.display()))?;
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty());
    let (_, header) = lines
        .next()
        .with_context(|| format!("{}: empty file", path.display()))?;
    let names: Vec<String> = header.split(',').map(|s| s.trim().to_string()).collect();
    let mut rows = Vec::new();
    for (i, line) in lines {
        let row = line
            .split(',')
            .map(|s| s.trim().parse::<f64>())
            .collect::<Result<Vec<f64>, _>>()
            .with_context(|| format!("{}:{}: not a number", path.display(), i + 1))?;
        if row.len() != names.len() {
            bail!(
                "{}:{}: {} columns, header has {}",
                path.display(),
                i + 1,
                row.len(),
                names.len()
            );
        }
        if row.iter().any(|v| !v.is_finite()) {
            bail!("{}:{}: non-finite value", path.display(), i + 1);
        }
        rows.push(row);
    }
    if rows.is_empty() {
        bail!("{}: no data rows", path.display());
    }
    Ok((names, rows))
}

fn fit(a: FitArgs) -> Result<()> {
    let (names, train) = read_csv(&a.train)?;
    let (test_names, test) = read_csv(&a.test)?;
    if names.len() != test_names.len() {
        bail!(
            "train has {} columns, test has {}",
            names.len(),
            test_names.len()
        );
    }
    let (k, cols) = (a.inputs, names.len());
    if k == 0 || k >= cols {
        bail!("--inputs {k}: need 1 ≤ K < {cols} (the number of columns)");
    }
    if a.epochs == 0 {
        bail!("--epochs must be at least 1");
    }
    let n_out = cols - k;
    let mut cfg: LwprConfig = match &a.config {
        Some(p) => {
            let text = std::fs::read_to_string(p).with_context(|| format!("{}", p.display()))?;
            toml::from_str(&text).with_context(|| format!("{}", p.display()))?
        }
        None => LwprConfig::default(),
    };
    let std_in: Vec<f64> = (0..k).map(|c| util::std_dev(&train, c)).collect();
    let std_out: Vec<f64> = (k..cols).map(|c| util::std_dev(&train, c)).collect();
    cfg.resolve_std(&std_in, &std_out);
    let mut model = Lwpr::new(k, n_out, &cfg)?;

    let mut rng = ChaCha8Rng::seed_from_u64(a.seed);
    let mut order: Vec<usize> = (0..train.len()).collect();
    let total = (a.epochs * train.len()) as u64;
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} updates {msg}")
            .expect("valid template"),
    );
    let mut update_ns = Vec::with_capacity(total as usize);
    let t0 = Instant::now();
    for e in 0..a.epochs {
        order.shuffle(&mut rng);
        for &i in &order {
            let (x, y) = train[i].split_at(k);
            let t = Instant::now();
            model.update(x, y)?;
            update_ns.push(t.elapsed().as_nanos() as f64);
        }
        model.drain_events().for_each(drop);
        bar.set_position(((e + 1) * train.len()) as u64);
        bar.set_message(format!("{} RFs", model.n_rfs_total()));
    }
    let train_seconds = t0.elapsed().as_secs_f64();
    bar.finish_and_clear();

    let mut y = vec![0.0; n_out];
    let mut support = vec![0.0; n_out];
    let mut sq = vec![0.0; n_out];
    let mut unsupported = vec![0usize; n_out];
    let mut predict_ns = Vec::with_capacity(test.len());
    for row in &test {
        let (x, t) = row.split_at(k);
        let s = Instant::now();
        model.predict_with_support(x, &mut y, &mut support)?;
        predict_ns.push(s.elapsed().as_nanos() as f64);
        for o in 0..n_out {
            sq[o] += (y[o] - t[o]).powi(2);
            unsupported[o] += (support[o] == 0.0) as usize;
        }
    }
    let nt = test.len() as f64;
    let nmse: Vec<f64> = (0..n_out)
        .map(|o| (sq[o] / nt) / util::std_dev(&test, k + o).powi(2))
        .collect();
    if let Some(p) = &a.save {
        model
            .save(p)
            .with_context(|| format!("saving {}", p.display()))?;
    }
    let out = serde_json::json!({
        "nmse": nmse,
        "n_rfs": model.n_rfs(),
        "update_us": util::median(update_ns) / 1e3,
        "predict_us": util::median(predict_ns) / 1e3,
        "train_seconds": train_seconds,
        "outputs": &names[k..],
        "unsupported": unsupported,
        "n_train": train.len(),
        "n_test": test.len(),
        "epochs": a.epochs,
    });
    if !a.json {
        println!(
            "{:<12} {:>10} {:>8} {:>12}",
            "output", "nMSE", "RFs", "unsupported"
        );
        let rfs = model.n_rfs();
        for o in 0..n_out {
            let r = rfs[if rfs.len() == 1 { 0 } else { o }];
            println!(
                "{:<12} {:>10.5} {:>8} {:>12}",
                names[k + o],
                nmse[o],
                r,
                unsupported[o]
            );
        }
    }
    println!("{out}");
    Ok(())
}
