//! E5 (paper Sec. V): learning curves — tracking error, command nMSE against `u*` and command
//! cost ratio against simulated training minutes, for `--seeds N` seeds from `--seed S`, with
//! the mean over the seeds whose evaluation did not diverge. Writes
//! `<robot>_learning_curve.csv` (one row per seed and evaluation).
//!
//! `cargo run --release -p osrl-learn --example fig_learning_curve -- [--robot planar3]
//! [--minutes 5] [--seed 0] [--seeds 2] [--out target/figures]`

mod common;
use common::{curve_columns, write_csv, Args, Res, Setup, CURVE_HEADER};

fn main() -> Res<()> {
    let a = Args::parse(5.0, 2)?;
    let s = Setup::new(&a.robot)?;
    let mut all: Vec<Vec<Vec<f64>>> = Vec::new();
    for seed in a.seed..a.seed + a.seeds {
        let (_, summary) = s.train(a.minutes, seed, 1.0, |_| {})?;
        println!(
            "seed {seed}: {:.1} s wall, {} local models",
            summary.wall_seconds, summary.n_local_models
        );
        let mut c = curve_columns(&summary);
        c.insert(0, vec![seed as f64; c[0].len()]);
        all.push(c);
    }
    println!("| sim. minutes | tracking RMS (mm) | command nMSE | cost ratio | diverged seeds |");
    println!("|---|---|---|---|---|");
    let len = all.iter().map(|c| c[0].len()).min().unwrap_or(0);
    for i in 0..len {
        let ok: Vec<&Vec<Vec<f64>>> = all.iter().filter(|c| c[5][i] == 0.0).collect();
        let mean = |col: usize| ok.iter().map(|c| c[col][i]).sum::<f64>() / ok.len().max(1) as f64;
        let (t, nmse, cost) = (mean(2), mean(3), mean(4));
        let show = |v: f64| {
            if ok.is_empty() {
                "–".to_string()
            } else {
                format!("{v:.3}")
            }
        };
        println!(
            "| {:.1} | {} | {} | {} | {} |",
            all[0][1][i],
            show(t),
            show(nmse),
            show(cost),
            all.len() - ok.len()
        );
    }
    let mut head = vec!["seed".to_string()];
    head.extend(CURVE_HEADER.iter().map(|h| h.to_string()));
    let cols: Vec<Vec<f64>> = (0..head.len())
        .map(|j| all.iter().flat_map(|c| c[j].clone()).collect())
        .collect();
    write_csv(
        &a.out,
        &format!("{}_learning_curve.csv", a.robot),
        &head,
        &cols,
    )
}
