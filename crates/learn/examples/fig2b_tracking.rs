//! E3 (paper Fig. 2b, 3b): the learned controller tracking the figure-8 after a short training
//! run, next to the analytical eq. 7 with the true model: tracking RMS/max, and the paths and
//! errors over time as CSV (`<robot>_learned.csv`, `<robot>_eq7.csv`: t, x_d, x, error).
//!
//! `cargo run --release -p osrl-learn --example fig2b_tracking -- [--robot planar3] [--minutes 4]
//! [--seed 0] [--out target/figures]`

mod common;
use common::{column, errors_mm, write_csv, Args, Res, Setup};
use osrl_control::ModelError;

fn main() -> Res<()> {
    let a = Args::parse(4.0, 1)?;
    let s = Setup::new(&a.robot)?;
    let (mut learner, summary) = s.train(a.minutes, a.seed, 0.0, |_| {})?;
    let (learned, ls) = s.evaluate(&s.model, &mut learner, 2)?;
    let eq7 = s.analytical(&ModelError::default(), 2)?;
    println!(
        "{} after {:.1} simulated min ({:.1} s wall, {} local models), seed {}",
        a.robot, summary.sim_training_minutes, summary.wall_seconds, summary.n_local_models, a.seed
    );
    println!("| controller | tracking RMS (mm) | max (mm) |\n|---|---|---|");
    println!(
        "| learned | {} | {:.3} |",
        common::mm(&learned),
        learned.tracking_max_mm
    );
    let m = &eq7.metrics;
    println!(
        "| analytical eq. 7 | {:.3} | {:.3} |",
        m.tracking_rms_mm, m.tracking_max_mm
    );
    let names = s.axis_names();
    let mut head = vec!["t".to_string()];
    head.extend(names.iter().map(|n| format!("{n}_d")));
    head.extend(names.iter().map(|n| n.to_string()));
    head.push("error_mm".into());
    let k = names.len();
    for (who, t, x_d, x) in [
        ("learned", &ls.t, &ls.x_d, &ls.x),
        ("eq7", &eq7.series.t, &eq7.series.x_d, &eq7.series.x),
    ] {
        let mut cols = vec![t.clone()];
        cols.extend((0..k).map(|j| column(x_d, k, j)));
        cols.extend((0..k).map(|j| column(x, k, j)));
        cols.push(errors_mm(x, x_d, k));
        write_csv(&a.out, &format!("{}_{who}.csv", a.robot), &head, &cols)?;
    }
    Ok(())
}
