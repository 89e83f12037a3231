//! The local controllers of a saved model (`docs/decisions.md`, D48): the six with the smallest
//! effective sample size, with their `σ`, `τ` and M-steps; with an `eval.csv` of `osrl eval
//! --out`, the five most active fields every `EVERY` steps between `T0` and `T1` s (`q̇` by
//! central differences of the logged `q`).
//!
//! ```sh
//! cargo run --release -p osrl-cli --example controllers -- MODEL [EVAL.csv T0 T1 EVERY]
//! ```

use anyhow::{bail, Context, Result};
use osrl_learn::SavedModel;

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(file) = args.first() else {
        bail!("usage: controllers MODEL [EVAL.csv T0 T1 EVERY]");
    };
    let (_, learner, model) = SavedModel::load(std::path::Path::new(file))?.into_parts();
    let mut locals = learner.local_summaries();
    locals.sort_by(|a, b| a.ess.total_cmp(&b.ess));
    println!("{file}: {} local controllers; smallest ESS:", locals.len());
    for l in locals.iter().take(6) {
        println!(
            "  field {}: ESS {:.0}, σ {:.3}, τ {:.4}, {} M-steps",
            l.id, l.ess, l.sigma, l.tau, l.updates
        );
    }
    let [csv, t0, t1, every] = match &args[1..] {
        [] => return Ok(()),
        [a, b, c, d] => [a, b, c, d],
        _ => bail!("usage: controllers MODEL [EVAL.csv T0 T1 EVERY]"),
    };
    let (t0, t1, every): (f64, f64, usize) = (t0.parse()?, t1.parse()?, every.parse()?);
    let text = std::fs::read_to_string(csv).with_context(|| csv.clone())?;
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().context("empty csv")?.split(',').collect();
    let col = |name: &str| {
        head.iter()
            .position(|h| *h == name)
            .context(name.to_string())
    };
    let (qi, ei) = (col("q0")?, col("error_mm")?);
    let rows = lines
        .map(|l| {
            l.split(',')
                .map(str::parse)
                .collect::<Result<Vec<f64>, _>>()
        })
        .collect::<Result<Vec<_>, _>>()?;
    let n = model.nq();
    let mut fm = learner
        .forward_model()
        .context("no forward model yet")?
        .clone();
    let mut acts = Vec::new();
    for i in (1..rows.len().saturating_sub(1)).step_by(every.max(1)) {
        let t = rows[i][0];
        if !(t0..=t1).contains(&t) {
            continue;
        }
        let q = &rows[i][qi..qi + n];
        let h = rows[i + 1][0] - rows[i - 1][0];
        let qd: Vec<f64> = (0..n)
            .map(|j| (rows[i + 1][qi + j] - rows[i - 1][qi + j]) / h)
            .collect();
        fm.activations(q, &qd, 1e-3, &mut acts)?;
        acts.sort_by(|a, b| b.w.total_cmp(&a.w));
        let top: Vec<String> = acts
            .iter()
            .take(5)
            .map(|a| match locals.iter().find(|l| l.id == a.id.0) {
                Some(l) => format!(
                    "{}: w {:.2} (ESS {:.0}, τ {:.3})",
                    a.id.0, a.w, l.ess, l.tau
                ),
                None => format!("{}: w {:.2} (no controller)", a.id.0, a.w),
            })
            .collect();
        println!("{t:.3} s, {:.3} mm | {}", rows[i][ei], top.join(", "));
    }
    Ok(())
}
