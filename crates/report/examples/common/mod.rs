//! What the figure examples share: the command line and a small training set-up.
//!
//! Flags: `--robot planar3|sarcos7` (default planar3), `--minutes M` (simulated training
//! minutes, babbling included; default per example), `--seed S` (0), `--seeds N` (examples over
//! seeds; default per example), `--out DIR` (target/figures).
#![allow(dead_code)] // each example uses its part

use osrl_experiments::Setup;
use osrl_learn::eval::{EvalResult, EvalSeries};
use osrl_learn::train::{BabbleConfig, TrainConfig};
use osrl_learn::Learner;
use std::path::PathBuf;

pub type Res<T> = Result<T, Box<dyn std::error::Error>>;

/// The command line.
pub struct Args {
    pub robot: String,
    pub minutes: f64,
    pub seed: u64,
    pub seeds: u64,
    pub out: PathBuf,
}

impl Args {
    /// Parses `--key value` pairs; `minutes` and `seeds` are the example's defaults.
    pub fn parse(minutes: f64, seeds: u64) -> Res<Self> {
        let mut a = Args {
            robot: "planar3".into(),
            minutes,
            seed: 0,
            seeds,
            out: "target/figures".into(),
        };
        let argv: Vec<String> = std::env::args().skip(1).collect();
        for pair in argv.chunks(2) {
            let v = pair.get(1).ok_or(format!("{} needs a value", pair[0]))?;
            match pair[0].as_str() {
                "--robot" => a.robot = v.clone(),
                "--minutes" => a.minutes = v.parse()?,
                "--seed" => a.seed = v.parse()?,
                "--seeds" => a.seeds = v.parse()?,
                "--out" => a.out = v.into(),
                f => {
                    return Err(format!(
                        "unknown flag {f} (--robot --minutes --seed --seeds --out)"
                    )
                    .into())
                }
            }
        }
        std::fs::create_dir_all(&a.out)?;
        Ok(a)
    }

    /// The robot's set-up training for `--minutes` with `seed`, evaluating every `eval_every`
    /// simulated minutes (0: at the end) over `periods` periods; small runs babble for at most
    /// 40 % of their time (as `osrl reproduce --quick`).
    pub fn setup(&self, seed: u64, eval_every: f64, periods: usize) -> Res<Setup> {
        let babble = BabbleConfig::default();
        let train = TrainConfig {
            minutes: self.minutes,
            seed,
            eval_every_minutes: eval_every,
            babble: BabbleConfig {
                minutes: babble.minutes.min(0.4 * self.minutes),
                ..babble
            },
            ..TrainConfig::default()
        };
        Ok(Setup::new(&self.robot)?
            .with_train(train)?
            .with_eval_periods(periods)?)
    }
}

/// `learner` evaluated on the set-up's robot, with its time series.
pub fn evaluate(setup: &Setup, learner: &mut Learner) -> Res<(EvalResult, EvalSeries)> {
    let mut ev = setup.evaluator(setup.model())?;
    ev.keep_series = true;
    let r = ev.evaluate(learner)?;
    Ok((r, ev.series))
}

/// `12.345` or `diverged (12.345)`.
pub fn mm(e: &EvalResult) -> String {
    if e.diverged {
        format!("diverged ({:.3})", e.tracking_rms_mm)
    } else {
        format!("{:.3}", e.tracking_rms_mm)
    }
}

/// Prints the files written.
pub fn wrote(files: &[PathBuf]) {
    for f in files {
        println!("wrote {}", f.display());
    }
}
