//! E7 (paper Sec. I): the analytical eq. 7 with a wrong model — masses ×0.7 and ×1.3, centres of
//! mass shifted 2 cm, friction unmodelled, an unmodelled 0.5 kg payload — against the learned
//! controller trained on the true robot (and that same controller on the robot carrying the
//! payload, not retrained). Prints the tracking table; writes `<robot>_model_errors.csv` (the
//! tracking error over time of every case) and `<robot>_model_errors_table.csv`.
//!
//! `cargo run --release -p osrl-learn --example fig_model_errors -- [--robot planar3]
//! [--minutes 4] [--seed 0] [--out target/figures]`

mod common;
use common::{errors_mm, write_csv, Args, Res, Setup};
use osrl_control::ModelError;

const ERRORS: [&str; 6] = [
    "none",
    "mass=0.7",
    "mass=1.3",
    "com=0.02",
    "friction=off",
    "payload=0.5",
];

fn main() -> Res<()> {
    let a = Args::parse(4.0, 1)?;
    let s = Setup::new(&a.robot)?;
    let periods = 2;
    let m = s.model.task_dim();
    let (mut head, mut cols) = (vec!["t".to_string()], vec![Vec::new()]);
    let mut table = Vec::new();
    println!("| controller | robot | tracking RMS (mm) | max (mm) |\n|---|---|---|---|");
    for spec in ERRORS {
        let error: ModelError = spec.parse()?;
        let r = s.analytical(&error, periods)?;
        let (rms, max) = (r.metrics.tracking_rms_mm, r.metrics.tracking_max_mm);
        let robot = if error.payload > 0.0 {
            "with payload"
        } else {
            "true"
        };
        println!("| eq. 7, model error {spec} | {robot} | {rms:.3} | {max:.3} |");
        table.push((format!("eq7 {spec}"), rms, max, false));
        cols[0] = r.series.t.clone();
        head.push(format!("eq7 {spec}"));
        cols.push(errors_mm(&r.series.x, &r.series.x_d, m));
    }
    let (mut learner, summary) = s.train(a.minutes, a.seed, 0.0, |_| {})?;
    let payload = ModelError {
        payload: 0.5,
        ..ModelError::default()
    }
    .apply(&s.model)?
    .0;
    for (name, truth) in [
        ("learned", &s.model),
        ("learned (payload, not retrained)", &payload),
    ] {
        let (e, es) = s.evaluate(truth, &mut learner, periods)?;
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
        table.push((
            name.to_string(),
            e.tracking_rms_mm,
            e.tracking_max_mm,
            e.diverged,
        ));
        head.push(name.into());
        cols.push(errors_mm(&es.x, &es.x_d, m));
    }
    println!(
        "learned: seed {}, {:.1} simulated min, {:.1} s wall",
        a.seed, summary.sim_training_minutes, summary.wall_seconds
    );
    write_csv(
        &a.out,
        &format!("{}_model_errors.csv", a.robot),
        &head,
        &cols,
    )?;
    let path = a.out.join(format!("{}_model_errors_table.csv", a.robot));
    let rows: Vec<String> = table
        .iter()
        .map(|(n, r, x, d)| format!("{n},{r},{x},{d}"))
        .collect();
    std::fs::write(
        &path,
        format!(
            "case,tracking_rms_mm,tracking_max_mm,diverged\n{}\n",
            rows.join("\n")
        ),
    )?;
    println!("wrote {}", path.display());
    Ok(())
}
