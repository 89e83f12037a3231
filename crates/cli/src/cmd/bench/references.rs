//! `osrl bench references`: the crate against the reference implementations in one run (issue
//! 31). LWPR: the C library built at `-O2` and `-O3 -march=native` (`c_ref`), run on exactly
//! the samples the crate gets (`datasets`), C and Rust interleaved per seed. Dynamics:
//! Pinocchio's C++ library where the `pin` wheel is importable. A missing reference is
//! reported as `{"skipped": why}`, never as a number.

use super::c_ref::{self, Harness};
use super::datasets::{self, Set};
use super::samples::Measured;
use super::{markdown, pinocchio};
use crate::util;
use anyhow::{bail, Context, Result};
use serde_json::{json, Value};
use std::path::PathBuf;
use std::process::Command;

/// The crate against the reference C library and Pinocchio.
#[derive(clap::Args)]
pub struct RefArgs {
    /// Permutation seeds per data set (S..S+N with S = --first-seed).
    #[arg(long, default_value_t = 10, value_parser = clap::value_parser!(u64).range(1..=1000))]
    seeds: u64,
    /// First seed.
    #[arg(long, default_value_t = 0, value_parser = clap::value_parser!(u64).range(0..=1_000_000))]
    first_seed: u64,
    /// Permutation seeds on the SARCOS split (from --first-seed; its runs are the long ones).
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u64).range(1..=1000))]
    sarcos_seeds: u64,
    /// Only these parts (comma-separated): cross2, cross21, sarcos7, dynamics; all by default.
    #[arg(long, value_delimiter = ',')]
    only: Vec<String>,
    /// Epochs of the 2-D cross (the reference library's test: 20).
    #[arg(long, default_value_t = 20, value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..=10_000))]
    cross2_epochs: usize,
    /// Epochs of the 21-D cross (issue 4: 25).
    #[arg(long, default_value_t = 25, value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..=10_000))]
    cross21_epochs: usize,
    /// Epochs on the SARCOS split.
    #[arg(long, default_value_t = 3, value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..=10_000))]
    sarcos_epochs: usize,
    /// The reference LWPR C library's folder (with its build.sh).
    #[arg(long, default_value = "../shared/reference/lwpr-c")]
    reference: PathBuf,
    /// The SARCOS split's folder.
    #[arg(long, default_value = "../shared/data/sarcos")]
    sarcos: PathBuf,
    /// Where the C library, the harness and the sample files are built and written.
    #[arg(long, default_value = "target/bench-references")]
    build_dir: PathBuf,
    /// Fail unless the crate's median nMSE lies within the reference's (-O2) range over the
    /// same seeds, widened by this relative margin (e.g. 0.1: 10 %).
    #[arg(long)]
    check: Option<f64>,
    /// Print the JSON object only.
    #[arg(long)]
    json: bool,
    /// Print the tables as Markdown (from the same JSON object) instead of JSON.
    #[arg(long, conflicts_with = "json")]
    markdown: bool,
    /// Measure nothing: print the Markdown tables of a saved `--json` output.
    #[arg(long, requires = "markdown")]
    from: Option<PathBuf>,
}

/// Median, range and all values of `v`.
fn spread(v: Vec<f64>) -> Value {
    let (lo, hi) = v
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    json!({"median": util::median(v.clone()), "min": lo, "max": hi, "all": v})
}

/// One implementation's runs over the seeds.
fn summary(runs: &[Measured]) -> Value {
    let col = |f: fn(&Measured) -> f64| util::median(runs.iter().map(f).collect());
    json!({
        "nmse": spread(runs.iter().map(Measured::nmse_mean).collect()),
        "n_rfs": col(|m| m.n_rfs as f64),
        "update_us": col(|m| m.update_us),
        "predict_us": col(|m| m.predict_us),
        "update_us_batch": col(|m| m.update_us_batch),
        "predict_us_batch": col(|m| m.predict_us_batch),
    })
}

/// One data set over the seeds, C variants and the crate interleaved per seed.
fn lwpr_set(a: &RefArgs, set: Set, cs: &[Harness]) -> Result<Value> {
    let epochs = match set {
        Set::Cross2 => a.cross2_epochs,
        Set::Cross21 => a.cross21_epochs,
        Set::Sarcos7 => a.sarcos_epochs,
    };
    let seeds = if set == Set::Sarcos7 {
        a.sarcos_seeds
    } else {
        a.seeds
    };
    let mut runs: Vec<Vec<Measured>> = vec![vec![]; cs.len() + 1];
    let mut updates = 0;
    for seed in a.first_seed..a.first_seed + seeds {
        let (s, cfg) = datasets::samples(set, seed, epochs, &a.sarcos)?;
        let file = a
            .build_dir
            .join(format!("samples-{}-{seed}.txt", set.key()));
        c_ref::write_samples(&s, &file)?;
        updates = s.train.len();
        // C -O2, the crate, C -O3 native: each timed between the others.
        runs[0].push(cs[0].measure(&file)?);
        runs[cs.len()].push(s.run_rust(&cfg)?);
        for (i, c) in cs.iter().enumerate().skip(1) {
            runs[i].push(c.measure(&file)?);
        }
    }
    let rust = summary(&runs[cs.len()]);
    let mut v = json!({"seeds": seeds, "first_seed": a.first_seed, "epochs": epochs,
        "updates": updates, "rust": rust});
    for (i, c) in cs.iter().enumerate() {
        let sum = summary(&runs[i]);
        for k in [
            "update_us",
            "predict_us",
            "update_us_batch",
            "predict_us_batch",
        ] {
            v[format!("ratio_{k}_{}", c.key)] =
                json!(sum[k].as_f64().unwrap() / rust[k].as_f64().unwrap());
        }
        v[c.key] = sum;
    }
    Ok(v)
}

/// Date, CPU model and load of this machine now.
fn machine() -> Value {
    let read = |p: &str| std::fs::read_to_string(p).unwrap_or_default();
    let cpu = read("/proc/cpuinfo")
        .lines()
        .find(|l| l.starts_with("model name"))
        .and_then(|l| l.split(':').nth(1))
        .map(|s| s.trim().to_string());
    let date = Command::new("date")
        .args(["-u", "+%Y-%m-%d %H:%M UTC"])
        .output()
        .ok()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string());
    json!({"date": date, "cpu": cpu, "cores": std::thread::available_parallelism().map(|n| n.get()).ok(),
        "loadavg": read("/proc/loadavg").split_whitespace().take(3).collect::<Vec<_>>().join(" ")})
}

/// Runs the comparison.
pub fn run(a: RefArgs) -> Result<()> {
    let want = |k: &str| a.only.is_empty() || a.only.iter().any(|o| o == k);
    let known = ["cross2", "cross21", "sarcos7", "dynamics"];
    if let Some(bad) = a.only.iter().find(|o| !known.contains(&o.as_str())) {
        bail!("--only: unknown part {bad:?} (known: {})", known.join(", "));
    }
    if let Some(path) = &a.from {
        let text =
            std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
        let out: Value = serde_json::from_str(&text).with_context(|| {
            format!("{}: not the JSON of osrl bench references", path.display())
        })?;
        print!("{}", markdown::render(&out));
        return Ok(());
    }
    let mut out = json!({"machine": machine(), "lwpr": {}});
    let missing = c_ref::missing(&a.reference);
    let cs = match &missing {
        None => c_ref::build(&a.reference, &a.build_dir)?,
        Some(_) => vec![],
    };
    for set in [Set::Cross2, Set::Cross21, Set::Sarcos7]
        .into_iter()
        .filter(|s| want(s.key()))
    {
        let skip = match (&missing, set) {
            (Some(why), _) => Some(why.clone()),
            (None, Set::Sarcos7) if !a.sarcos.join("parity_train.csv").is_file() => {
                Some(format!("no SARCOS split at {}", a.sarcos.display()))
            }
            _ => None,
        };
        let v = match skip {
            Some(why) => json!({"skipped": why}),
            None => lwpr_set(&a, set, &cs)?,
        };
        if !a.json && !a.markdown {
            eprintln!("{}: {v}", set.key());
        }
        out["lwpr"][set.key()] = v;
    }
    if want("dynamics") {
        out["dynamics"] = pinocchio::dynamics();
    }
    if a.markdown {
        print!("{}", markdown::render(&out));
    } else {
        util::print_json(&out);
    }
    match a.check {
        Some(margin) => check(&out["lwpr"], margin),
        None => Ok(()),
    }
}

/// Fails unless, for every data set measured, the crate's median nMSE lies within
/// `[min·(1 − margin), max·(1 + margin)]` of the reference (-O2) over the same seeds.
pub fn check(lwpr: &Value, margin: f64) -> Result<()> {
    let mut bad = vec![];
    for (k, v) in lwpr.as_object().into_iter().flatten() {
        if let Some(why) = v.get("skipped") {
            eprintln!("check {k}: skipped ({})", why.as_str().unwrap_or("?"));
            continue;
        }
        let f = |p: &str| v.pointer(p).and_then(Value::as_f64).unwrap_or(f64::NAN);
        let (r, lo, hi) = (
            f("/rust/nmse/median"),
            f("/c_o2/nmse/min"),
            f("/c_o2/nmse/max"),
        );
        let (lo, hi) = (lo * (1.0 - margin), hi * (1.0 + margin));
        let ok = r >= lo && r <= hi;
        eprintln!(
            "check {k}: crate nMSE {r:.4}, reference range with margin [{lo:.4}, {hi:.4}]: {}",
            if ok { "ok" } else { "OUTSIDE" }
        );
        if !ok {
            bad.push(k.clone());
        }
    }
    match bad.is_empty() {
        true => Ok(()),
        false => bail!(
            "the crate's nMSE lies outside the reference's range on {}",
            bad.join(", ")
        ),
    }
}
