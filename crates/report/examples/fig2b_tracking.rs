//! E3 (paper Fig. 2a/2b, 3b): the learned controller tracking the figure-8 after a short
//! training run, next to the analytical eq. 7 with the true model: the tracking table, the path
//! figure (`<robot>_tracking.svg/png`), the arm along the figure-8 (`<robot>_arm.svg/png`) and
//! the learned run's time series (`<robot>_learned.csv`).
//!
//! `cargo run --release -p osrl-report --example fig2b_tracking -- [--robot planar3]
//! [--minutes 4] [--seed 0] [--out target/figures]`

mod common;
use common::{evaluate, wrote, Args, Res};
use osrl_control::{ModelError, OscConfig};
use osrl_report::figures::learned::{arm, tracking, ArmSeries};
use osrl_report::{plot, series};

fn main() -> Res<()> {
    let a = Args::parse(4.0, 1)?;
    let s = a.setup(a.seed, 0.0, 2)?;
    let (mut learner, summary) = s.train(s.model(), &mut |_| {})?;
    let (learned, ls) = evaluate(&s, &mut learner)?;
    let eq7 = s.analytical(&OscConfig::default(), &ModelError::default(), 12.0)?;
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
    let mut files = plot::save(
        &tracking(&s, &ls, &eq7.series),
        &a.out,
        &format!("{}_tracking", a.robot),
    )?;
    let who = ArmSeries {
        t: &ls.t,
        q: &ls.q,
        x_d: &ls.x_d,
        who: "learned",
    };
    files.extend(plot::save(
        &arm(&s, &who, s.steps_per_period(), 6)?,
        &a.out,
        &format!("{}_arm", a.robot),
    )?);
    let csv = a.out.join(format!("{}_learned.csv", a.robot));
    series::write_eval(&csv, &ls, s.model().nq(), s.model().task_axes())?;
    files.push(csv);
    wrote(&files);
    Ok(())
}
