//! E9 on saved models: evaluates a figure-8-only and a family-trained controller (`osrl train
//! --trajectory figure8|family`) on the held-out paths of the robot's family as E9 does (from
//! rest at home, behind the approach to each path's start), against issue 27's bounds
//! (`docs/family.md`):
//!
//! ```sh
//! cargo run --release -p osrl-cli --example e9_models -- 2 figure8.osrl family.osrl
//! ```
//!
//! With `--validation` after the models, on validation paths drawn with another seed
//! (`osrl_experiments::family::validation`) instead: settings are chosen on those, and the
//! held-out paths only report them.

use anyhow::{bail, Context, Result};
use osrl_experiments::e9::{within_bounds, E9Point};
use osrl_experiments::family::{held_out, label, validation};
use osrl_experiments::Setup;
use osrl_learn::SavedModel;

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (args, on_validation) = match args.split_last() {
        Some((last, rest)) if last == "--validation" => (rest, true),
        _ => (args.as_slice(), false),
    };
    let [per_kind, f8, fam] = args else {
        bail!("usage: e9_models PATHS_PER_KIND FIGURE8_MODEL FAMILY_MODEL [--validation]");
    };
    let per_kind: usize = per_kind
        .parse()
        .ok()
        .filter(|n| (1..=20).contains(n))
        .context("PATHS_PER_KIND: a whole number from 1 to 20")?;
    let mut runs = Vec::new();
    // The held-out paths of the figure-8-only model's set-up (the robot's default family), for
    // both models: a family model trained on another family is tested on the same paths.
    let mut paths = None;
    for file in [f8, fam] {
        let saved = SavedModel::load(std::path::Path::new(file))?;
        let setup = Setup::from_saved(&saved)?;
        let (_, mut learner, model) = saved.into_parts();
        let own = setup.evaluator(&model)?.evaluate(&mut learner)?;
        let mut rows = vec![("default figure-8".to_string(), E9Point::new(0, &own))];
        if paths.is_none() {
            paths = Some(if on_validation {
                validation(&setup, per_kind)?
            } else {
                held_out(&setup, per_kind)?
            });
        }
        for p in paths.iter().flatten() {
            let e = setup.evaluate_path(&model, &mut learner, p)?;
            rows.push((label(p), E9Point::new(0, &e)));
        }
        runs.push(rows);
    }
    let own = &runs[0][0].1;
    println!(
        "bounds: tracking <= {:.3} mm, nMSE <= {:.4}",
        (1.5 * own.tracking_rms_mm).min(1.0),
        (2.0 * own.command_nmse).min(0.05)
    );
    for ((name, a), (_, b)) in runs[0].iter().zip(&runs[1]) {
        println!(
            "{name:48} figure-8 only {:8.3} mm {:.4} support {:.2} | family {:8.3} mm {:.4} support {:.2} {}",
            a.tracking_rms_mm,
            a.command_nmse,
            a.support_share,
            b.tracking_rms_mm,
            b.command_nmse,
            b.support_share,
            if within_bounds(b, own) { "within" } else { "outside" }
        );
    }
    let paths = &runs[1][1..];
    let geo = |f: &dyn Fn(&E9Point) -> f64| {
        (paths.iter().map(|(_, p)| f(p).ln()).sum::<f64>() / paths.len() as f64).exp()
    };
    println!(
        "family on the {} paths: {} within, geometric means {:.3} mm, nMSE {:.4}",
        paths.len(),
        paths.iter().filter(|(_, p)| within_bounds(p, own)).count(),
        geo(&|p| p.tracking_rms_mm),
        geo(&|p| p.command_nmse)
    );
    Ok(())
}
