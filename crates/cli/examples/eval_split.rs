//! The error split of saved models on their own (base) figure-8 and, with `--held-out N`, on
//! E9's held-out paths (`N` of each kind; `docs/family.md`): tracking, command nMSE, its
//! null-space part, the nominal behaviour's error, the error of `Â` and the floor of the
//! learner's own `Â` and `û0`.
//!
//! ```sh
//! cargo run --release -p osrl-cli --example eval_split -- [--held-out N] A.osrl B.osrl …
//! ```
//!
//! `--validation N` in place of `--held-out N` evaluates on the validation paths
//! (`osrl_experiments::family::validation`), on which settings are chosen.

use anyhow::{Context, Result};
use osrl_experiments::family::{held_out, label, validation};
use osrl_experiments::Setup;
use osrl_learn::eval::EvalResult;
use osrl_learn::SavedModel;

fn main() -> Result<()> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let mut per_kind = 0;
    let on_validation = args.first().is_some_and(|a| a == "--validation");
    if on_validation || args.first().is_some_and(|a| a == "--held-out") {
        per_kind = (args.get(1))
            .and_then(|n| n.parse().ok())
            .filter(|n| (1..=20).contains(n))
            .context("--held-out N / --validation N: a whole number from 1 to 20")?;
        args.drain(..2);
    }
    for file in &args {
        let saved = SavedModel::load(std::path::Path::new(file))?;
        let setup = Setup::from_saved(&saved)?;
        let (_, mut learner, model) = saved.into_parts();
        let e = setup.evaluator(&model)?.evaluate(&mut learner)?;
        println!("{file}");
        print_split("default figure-8", &e);
        if per_kind > 0 {
            let paths = if on_validation {
                validation(&setup, per_kind)?
            } else {
                held_out(&setup, per_kind)?
            };
            for p in paths {
                let e = setup.evaluate_path(&model, &mut learner, &p)?;
                print_split(&label(&p), &e);
            }
        }
    }
    Ok(())
}

fn print_split(path: &str, e: &EvalResult) {
    println!(
        "  {path}: {:.3} mm, nMSE {:.4} (null {:.4}, floor null {:.4}), nominal nMSE {:.4} \
         (null {:.4}), gain error {:.4}",
        e.tracking_rms_mm,
        e.command_nmse,
        e.command_nmse_null,
        e.floor_nmse_null,
        e.nominal_nmse,
        e.nominal_nmse_null,
        e.gain_error
    );
}
