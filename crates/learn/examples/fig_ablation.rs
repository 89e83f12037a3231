//! E6 (paper Sec. II, IV): the ablation ([`osrl_learn::Variant`]) — the default learner against
//! the same architecture with the reward weighting and the hindsight shrinkage off
//! (activation-weighted regression of `u − u0` on the features: direct supervised inverse
//! learning), RWR as in the paper (full cost, no shrinkage), and a global inverse model
//! (supervised, one receptive field that covers the whole state space). Prints the final tracking error, command nMSE
//! against `u*` and command cost ratio of each; writes `<robot>_ablation.csv` (the learning
//! curves, one row per variant and evaluation).
//!
//! `cargo run --release -p osrl-learn --example fig_ablation -- [--robot planar3] [--minutes 3]
//! [--seed 0] [--out target/figures]`

mod common;
use common::{curve_columns, write_csv, Args, Res, Setup, CURVE_HEADER};
use osrl_learn::Variant;

fn main() -> Res<()> {
    let a = Args::parse(3.0, 1)?;
    let s = Setup::new(&a.robot)?;
    println!(
        "{}, {} simulated min per variant, seed {}",
        a.robot, a.minutes, a.seed
    );
    println!(
        "| variant | tracking RMS (mm) | command nMSE | cost ratio | local models | wall (s) |"
    );
    println!("|---|---|---|---|---|---|");
    let mut cols: Vec<Vec<f64>> = vec![Vec::new(); CURVE_HEADER.len() + 1];
    for (i, v) in Variant::ALL.iter().enumerate() {
        let name = v.key();
        let (_, summary) = s.train(a.minutes, a.seed, 1.0, |c| *c = v.config(c.clone()))?;
        let e = summary
            .learning_curve
            .last()
            .map(|p| p.1.clone())
            .unwrap_or_default();
        println!(
            "| {name} | {} | {:.3} | {:.3} | {} | {:.1} |",
            common::mm(&e),
            e.command_nmse,
            e.command_cost_ratio,
            summary.n_local_models,
            summary.wall_seconds
        );
        let c = curve_columns(&summary);
        cols[0].extend(vec![i as f64; c[0].len()]);
        for (j, v) in c.into_iter().enumerate() {
            cols[j + 1].extend(v);
        }
    }
    let names: Vec<&str> = Variant::ALL.iter().map(|v| v.key()).collect();
    println!("variant index in the CSV: {names:?}");
    let mut head = vec!["variant".to_string()];
    head.extend(CURVE_HEADER.iter().map(|h| h.to_string()));
    write_csv(&a.out, &format!("{}_ablation.csv", a.robot), &head, &cols)
}
