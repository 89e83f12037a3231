//! E4 (paper Fig. 2c): the learned command against the analytical optimum `u*` (eq. 7, `N = I`,
//! true model) at the same states, per joint over the last cycle of an evaluation after a short
//! training run. Prints the per-joint RMS of `u − u*` and of `u*`, the command nMSE and cost
//! ratio; writes `<robot>_commands.csv` (time in the cycle, `u_i`, `u_star_i`).
//!
//! `cargo run --release -p osrl-learn --example fig2c_commands -- [--robot planar3] [--minutes 4]
//! [--seed 0] [--out target/figures]`

mod common;
use common::{column, write_csv, Args, Res, Setup};

fn main() -> Res<()> {
    let a = Args::parse(4.0, 1)?;
    let s = Setup::new(&a.robot)?;
    let (mut learner, summary) = s.train(a.minutes, a.seed, 0.0, |_| {})?;
    let (e, es) = s.evaluate(&s.model, &mut learner, 1)?;
    let n = s.model.nq();
    // The last whole cycle (the evaluation may have stopped early if it diverged).
    let end = es.t.len();
    let start = end.saturating_sub(s.per_period);
    let cycle = |v: &[f64]| v[start * n..end * n].to_vec();
    let (u, u_star) = (cycle(&es.u), cycle(&es.u_star));
    println!(
        "{} after {:.1} simulated min ({:.1} s wall), seed {}: command nMSE {:.3}, cost ratio {:.3}, tracking {} mm",
        a.robot, summary.sim_training_minutes, summary.wall_seconds, a.seed,
        e.command_nmse, e.command_cost_ratio, common::mm(&e)
    );
    println!("| joint | RMS(u − u*) (N·m) | RMS(u*) (N·m) |\n|---|---|---|");
    let rms = |v: &[f64]| (v.iter().map(|x| x * x).sum::<f64>() / v.len().max(1) as f64).sqrt();
    let mut cols = vec![es.t[start..end]
        .iter()
        .map(|t| t - es.t[start])
        .collect::<Vec<_>>()];
    let mut head = vec!["t_in_cycle".to_string()];
    for j in 0..n {
        let (uj, sj) = (column(&u, n, j), column(&u_star, n, j));
        let d: Vec<f64> = uj.iter().zip(&sj).map(|(p, q)| p - q).collect();
        println!("| {} | {:.3} | {:.3} |", j + 1, rms(&d), rms(&sj));
        head.push(format!("u{j}"));
        cols.push(uj);
    }
    for j in 0..n {
        head.push(format!("u_star{j}"));
        cols.push(column(&u_star, n, j));
    }
    write_csv(&a.out, &format!("{}_commands.csv", a.robot), &head, &cols)
}
