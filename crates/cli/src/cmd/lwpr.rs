//! `osrl lwpr fit`: train an LWPR model on a CSV file and test it on another; `osrl lwpr eval`:
//! test a saved model.
//!
//! CSV files have a header row; the first K columns are inputs, the rest outputs (see
//! `osrl_report::csv::Table`). The config is TOML with the parameter names of `docs/lwpr.md` in
//! snake case (see `lwpr::LwprConfig`); unknown keys are an error. `norm_in`/`norm_out` may be
//! `"std"`: the training data's standard deviation per column.

use crate::util;
use anyhow::{bail, Context, Result};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use lwpr::{Lwpr, LwprConfig};
use osrl_report::csv::Table;
use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::path::PathBuf;
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
    ///
    /// The last stdout line is one JSON object: `nmse` (per output: test MSE / variance of the
    /// test targets; null when undefined, with a warning on stderr), `n_rfs` (per output, one
    /// entry when RFs are shared), `update_us` and `predict_us` (median µs per call of the
    /// whole model), `train_seconds`, `outputs` (column names), `unsupported` (test rows per
    /// output where no trustworthy receptive field is active: predicted as 0, as the
    /// reference library does, and counted in the nMSE), `non_finite` (test rows per output
    /// with a non-finite prediction), `n_train`, `n_test`, `epochs`, and the counts of the
    /// update's numerical guards: `metric_skipped` (metric terms skipped because a sample's
    /// leverage was not below 1; rare) and `removed_non_finite` (receptive fields removed
    /// because their state diverged; a warning on stderr when not 0).
    Fit(FitArgs),
    /// Test a model saved by `fit --save` on a CSV file (the model's inputs, then its outputs).
    ///
    /// The last stdout line is one JSON object with `nmse`, `n_rfs`, `predict_us`, `outputs`,
    /// `unsupported`, `non_finite` and `n_test`, as `fit` reports them.
    Eval(EvalArgs),
}

#[derive(clap::Args)]
struct FitArgs {
    /// Training data: CSV with a header row of column names, then rows of numbers.
    #[arg(long)]
    train: PathBuf,
    /// Test data: the same columns in the same order.
    #[arg(long)]
    test: PathBuf,
    /// Number of input columns K (the first K); the remaining columns are outputs.
    #[arg(long)]
    inputs: usize,
    /// LWPR config (TOML). Keys, each optional (unknown keys are an error): init_d (a number
    /// r for r·I, a list for a diagonal, or a list of rows), init_alpha, diag_only, update_d,
    /// meta, meta_rate, penalty, w_gen, w_prune, prune_rule ("wider"|"narrower"), init_lambda,
    /// final_lambda, tau_lambda, init_s2, add_threshold, kernel ("gaussian"|"bisquare"),
    /// norm_in and norm_out (a number, a list, or "std": the training data's standard
    /// deviation), cutoff, shared_rfs, kernel_dims, regression_dims. Defaults: docs/lwpr.md.
    #[arg(long, verbatim_doc_comment)]
    config: Option<PathBuf>,
    /// Passes over the training data, each in a fresh shuffled order.
    #[arg(long, default_value_t = 20)]
    epochs: usize,
    /// Seed of the shuffling.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Save the trained model here (checked before training; written after the report).
    #[arg(long)]
    save: Option<PathBuf>,
    /// Print only the JSON object (no table).
    #[arg(long)]
    json: bool,
}

#[derive(clap::Args)]
struct EvalArgs {
    /// A model saved by `osrl lwpr fit --save`.
    #[arg(long)]
    model: PathBuf,
    /// Test data: CSV with a header row, the model's inputs then its outputs, in the order of
    /// the training file (taken by position: a saved model keeps no column names).
    #[arg(long)]
    test: PathBuf,
    /// Print only the JSON object (no table).
    #[arg(long)]
    json: bool,
}

/// Runs the subcommand.
pub fn run(a: Args) -> Result<()> {
    match a.cmd {
        Sub::Fit(f) => fit(f),
        Sub::Eval(e) => eval(e),
    }
}

/// Most passes over the training data (`--epochs`).
const MAX_EPOCHS: usize = 100_000;
/// Most updates of one fit (epochs × training rows).
const MAX_UPDATES: usize = 1_000_000_000;

/// At most this many update times are kept for the median (every n-th update beyond).
const MAX_TIMINGS: usize = 1 << 20;

fn fit(a: FitArgs) -> Result<()> {
    let train = Table::read(&a.train)?;
    let test = Table::read(&a.test)?;
    train.check_same_columns(&test)?;
    let (k, cols) = (a.inputs, train.names.len());
    if k == 0 || k >= cols {
        bail!("--inputs {k}: need 1 ≤ K < {cols} (the number of columns)");
    }
    let (e, n) = (a.epochs, train.rows.len());
    let total = e.checked_mul(n).filter(|&t| t <= MAX_UPDATES);
    let Some(total) = total.filter(|_| (1..=MAX_EPOCHS).contains(&e)) else {
        bail!(
            "--epochs {e}: accepted range 1–{MAX_EPOCHS}, and at most {MAX_UPDATES} updates \
             (epochs × {n} training rows)"
        );
    };
    if let Some(p) = &a.save {
        // A missing folder is an error here (as before): it is not created.
        osrl_files::check_output(p).context("--save")?;
        let inputs = [
            Some(a.train.as_path()),
            Some(a.test.as_path()),
            a.config.as_deref(),
        ];
        osrl_files::check_not_input(p, &inputs).context("--save")?;
    }
    let n_out = cols - k;
    let mut cfg: LwprConfig = match &a.config {
        Some(p) => util::read_toml(p)?,
        None => LwprConfig::default(),
    };
    let std_in: Vec<f64> = (0..k).map(|c| util::std_dev(&train.rows, c)).collect();
    let std_out: Vec<f64> = (k..cols).map(|c| util::std_dev(&train.rows, c)).collect();
    let config_name = || match &a.config {
        Some(p) => format!("{}", p.display()),
        None => "the default config".into(),
    };
    cfg.resolve_std(&std_in, &std_out)
        .with_context(|| format!("{}, \"std\" of {}", config_name(), a.train.display()))?;
    let mut model = Lwpr::new(k, n_out, &cfg).with_context(config_name)?;

    let mut rng = ChaCha8Rng::seed_from_u64(a.seed);
    let mut order: Vec<usize> = (0..train.rows.len()).collect();
    let bar = ProgressBar::with_draw_target(Some(total as u64), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} updates {msg}")
            .expect("valid template"),
    );
    // Every `stride`-th update is timed (all of them up to MAX_TIMINGS updates).
    let stride = total.div_ceil(MAX_TIMINGS).max(1);
    let mut update_ns = Vec::with_capacity(total.min(MAX_TIMINGS));
    let t0 = Instant::now();
    let mut done = 0usize;
    for _ in 0..a.epochs {
        order.shuffle(&mut rng);
        for &i in &order {
            let (x, y) = train.rows[i].split_at(k);
            let row = || format!("{}:{}", train.path.display(), train.lines[i]);
            if done.is_multiple_of(stride) {
                let t = Instant::now();
                model.update(x, y).with_context(row)?;
                update_ns.push(t.elapsed().as_nanos() as f64);
            } else {
                model.update(x, y).with_context(row)?;
            }
            done += 1;
            if done.is_multiple_of(1024) {
                bar.set_position(done as u64);
            }
        }
        model.drain_events().for_each(drop);
        bar.set_position(done as u64);
        bar.set_message(format!("{} RFs", model.n_rfs_total()));
    }
    let train_seconds = t0.elapsed().as_secs_f64();
    bar.finish_and_clear();

    let ev = evaluate(&mut model, &test)?;
    let mut out = ev.json();
    out["update_us"] = (util::median(update_ns) / 1e3).into();
    out["train_seconds"] = train_seconds.into();
    out["n_train"] = train.rows.len().into();
    out["epochs"] = a.epochs.into();
    let guards = model.warnings();
    out["metric_skipped"] = guards.metric_skipped.into();
    out["removed_non_finite"] = guards.removed_non_finite.into();
    if guards.removed_non_finite > 0 {
        eprintln!(
            "warning: {} receptive fields diverged (non-finite state) and were removed during \
             training; fast forgetting or meta learning on data that rarely moves can cause this",
            guards.removed_non_finite
        );
    }
    ev.report(&out, a.json);
    if let Some(p) = &a.save {
        util::save_result("LWPR model (the results above stand)", p, &model.to_bytes())?;
    }
    Ok(())
}

fn eval(a: EvalArgs) -> Result<()> {
    let mut model = Lwpr::load(&a.model).map_err(|e| match e {
        // Its message starts with the path already.
        lwpr::LwprError::File(f) => anyhow::Error::from(f),
        e => anyhow::Error::from(e).context(a.model.display().to_string()),
    })?;
    let test = Table::read(&a.test)?;
    let (k, n_out) = (model.n_in(), model.n_out());
    if test.names.len() != k + n_out {
        bail!(
            "{}: {} columns, the model has {k} inputs and {n_out} outputs",
            test.path.display(),
            test.names.len()
        );
    }
    let ev = evaluate(&mut model, &test)?;
    ev.report(&ev.json(), a.json);
    Ok(())
}

/// A model's predictions on a test table (inputs first, then the model's outputs).
struct Evaluation {
    /// Output column names.
    outputs: Vec<String>,
    /// The model's RF counts (one per output, or one when shared).
    n_rfs: Vec<usize>,
    nmse: Vec<f64>,
    /// Test rows per output with no trustworthy RF active (predicted as 0).
    unsupported: Vec<usize>,
    /// Test rows per output whose prediction is not finite.
    non_finite: Vec<usize>,
    /// Whether each output's test targets are all equal.
    constant: Vec<bool>,
    predict_us: f64,
    n_test: usize,
}

fn evaluate(model: &mut Lwpr, test: &Table) -> Result<Evaluation> {
    let (k, n_out) = (model.n_in(), model.n_out());
    let mut y = vec![0.0; n_out];
    let mut support = vec![0.0; n_out];
    let mut sq = vec![0.0; n_out];
    let mut unsupported = vec![0usize; n_out];
    let mut non_finite = vec![0usize; n_out];
    let mut predict_ns = Vec::with_capacity(test.rows.len());
    for row in &test.rows {
        let (x, t) = row.split_at(k);
        let s = Instant::now();
        model.predict_with_support(x, &mut y, &mut support)?;
        predict_ns.push(s.elapsed().as_nanos() as f64);
        for o in 0..n_out {
            sq[o] += (y[o] - t[o]).powi(2);
            unsupported[o] += (support[o] == 0.0) as usize;
            non_finite[o] += !y[o].is_finite() as usize;
        }
    }
    let nt = test.rows.len() as f64;
    // Constant targets have no variance (the computed one may be a rounding residue).
    let constant: Vec<bool> = (k..k + n_out)
        .map(|c| test.rows.iter().all(|r| r[c] == test.rows[0][c]))
        .collect();
    let var: Vec<f64> = (k..k + n_out)
        .map(|c| util::std_dev(&test.rows, c).powi(2))
        .collect();
    Ok(Evaluation {
        outputs: test.names[k..].to_vec(),
        n_rfs: model.n_rfs(),
        nmse: (0..n_out)
            .map(|o| {
                if constant[o] {
                    f64::NAN
                } else {
                    (sq[o] / nt) / var[o]
                }
            })
            .collect(),
        unsupported,
        non_finite,
        constant,
        predict_us: util::median(predict_ns) / 1e3,
        n_test: test.rows.len(),
    })
}

impl Evaluation {
    /// The JSON keys both subcommands report.
    fn json(&self) -> serde_json::Value {
        serde_json::json!({
            "nmse": self.nmse,
            "n_rfs": self.n_rfs,
            "predict_us": self.predict_us,
            "outputs": self.outputs,
            "unsupported": self.unsupported,
            "non_finite": self.non_finite,
            "n_test": self.n_test,
        })
    }

    /// Warnings (stderr) for undefined nMSEs, the table unless `json_only`, then `out` as the
    /// last stdout line.
    fn report(&self, out: &serde_json::Value, json_only: bool) {
        for (o, name) in self.outputs.iter().enumerate() {
            if self.constant[o] {
                eprintln!("warning: the test targets of {name} are constant: its nMSE is undefined (null)");
            }
            if self.non_finite[o] > 0 {
                eprintln!(
                    "warning: {} predictions of {name} are not finite: its nMSE is undefined (null)",
                    self.non_finite[o]
                );
            }
        }
        if !json_only {
            println!(
                "{:<12} {:>10} {:>8} {:>12}",
                "output", "nMSE", "RFs", "unsupported"
            );
            let rfs = &self.n_rfs;
            for (o, name) in self.outputs.iter().enumerate() {
                let r = rfs[if rfs.len() == 1 { 0 } else { o }];
                println!(
                    "{:<12} {:>10.5} {:>8} {:>12}",
                    name, self.nmse[o], r, self.unsupported[o]
                );
            }
        }
        util::print_json(out);
    }
}
