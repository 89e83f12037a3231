//! E7 (paper Sec. I): the analytical eq. 7 with a wrong model — masses ×0.7 and ×1.3, centres of
//! mass shifted 2 cm, friction unmodelled, an unmodelled 0.5 kg payload — against the learned
//! controller trained on the true robot (and that same controller on the robot carrying the
//! payload, not retrained): the tracking table and `<robot>_model_errors.csv`.
//!
//! `cargo run --release -p osrl-report --example fig_model_errors -- [--robot planar3]
//! [--minutes 4] [--seed 0] [--out target/figures]`

mod common;
use common::{wrote, Args, Res};
use osrl_experiments::analytical::{cases, run_case};
use osrl_report::csv;

fn main() -> Res<()> {
    let a = Args::parse(4.0, 1)?;
    let s = a.setup(a.seed, 0.0, 2)?;
    println!("| controller | robot | tracking RMS (mm) | max (mm) |\n|---|---|---|---|");
    let mut rows = Vec::new();
    for c in cases(0.5, 12.0)?
        .iter()
        .filter(|c| c.robot == a.robot && c.law_name() == "eq7")
    {
        let r = run_case(&s, c)?.row;
        let robot = if c.error.payload > 0.0 {
            "with payload"
        } else {
            "true"
        };
        println!(
            "| eq. 7, model error {} | {robot} | {:.3} | {:.3} |",
            c.error_key, r.tracking_rms_mm, r.tracking_max_mm
        );
        rows.push((
            format!("eq7 {}", c.error_key),
            r.tracking_rms_mm,
            r.tracking_max_mm,
            false,
        ));
    }
    let (mut learner, summary) = s.train(s.model(), &mut |_| {})?;
    let payload = s.with_payload(0.5)?;
    for (name, truth) in [
        ("learned", s.model()),
        ("learned (payload, not retrained)", &payload),
    ] {
        let e = s.evaluator(truth)?.evaluate(&mut learner)?;
        let robot = if name == "learned" {
            "true"
        } else {
            "with payload"
        };
        println!(
            "| {name} | {robot} | {} | {:.3} |",
            common::mm(&e),
            e.tracking_max_mm
        );
        rows.push((
            name.into(),
            e.tracking_rms_mm,
            e.tracking_max_mm,
            e.diverged,
        ));
    }
    println!(
        "learned: seed {}, {:.1} simulated min, {:.1} s wall",
        a.seed, summary.sim_training_minutes, summary.wall_seconds
    );
    let path = a.out.join(format!("{}_model_errors.csv", a.robot));
    let head: Vec<String> = ["case", "tracking_rms_mm", "tracking_max_mm", "diverged"]
        .map(String::from)
        .into();
    let names: Vec<&str> = rows.iter().map(|r| r.0.as_str()).collect();
    // Numeric columns only: the case is its row's index in the table printed above.
    let numeric = rows
        .iter()
        .enumerate()
        .map(|(i, r)| vec![i as f64, r.1, r.2, r.3 as u8 as f64]);
    csv::write(&path, &head, numeric)?;
    println!("cases in the CSV, by index: {names:?}");
    wrote(&[path]);
    Ok(())
}
