//! E8 (issue 26): the robot changes under a learned controller trained on the unchanged arm —
//! a 0.5 kg payload (removed again), links 30 % heavier, twice the friction. Per change, the
//! controller re-adapting on-policy, the same controller frozen and eq. 7 with the stale model:
//! the table of recovery times and the figure `<robot>_adaptation.svg/png` (tracking over the
//! timeline, the change marked). The timelines have `osrl reproduce --quick`'s sizes (half a
//! minute unchanged, 1.5 minutes with the change, 1 minute after its removal); the full run's
//! are 1 / 10 / 3 minutes.
//!
//! `cargo run --release -p osrl-report --example fig_adaptation -- [--robot planar3]
//! [--minutes 10] [--seed 0] [--out target/figures]`

mod common;
use common::{wrote, Args, Res};
use osrl_experiments::{e8, Sizes};
use osrl_report::e8::{minutes, or_diverged as mm};
use osrl_report::figures::change::timelines;
use osrl_report::plot;
use std::collections::BTreeMap;

fn main() -> Res<()> {
    let a = Args::parse(10.0, 1)?;
    let sizes = Sizes::quick();
    let s = a.setup(a.seed, 0.0, sizes.eval_periods)?;
    let (learner, summary) = s.train(s.model(), &mut |_| {})?;
    println!(
        "trained on the unchanged arm: seed {}, {:.1} simulated min, {:.1} s wall",
        a.seed, summary.sim_training_minutes, summary.wall_seconds
    );
    println!(
        "| change | learned, unchanged arm (mm) | frozen, changed (mm) | eq. 7 stale (mm) \
         | re-adapting: minutes to 1 mm | to 2× nominal | at the end (mm / nMSE) \
         | largest step (N·m) | braked |\n|---|---|---|---|---|---|---|---|---|"
    );
    let mut rows = BTreeMap::new();
    for (key, _, _) in e8::CHANGES {
        let r = e8::run(&s, &learner, key, &sizes)?;
        println!(
            "| {key} ({}) | {} | {} | {} | {} | {} | {} / {} | {:.3} | {} |",
            r.change,
            mm(r.nominal_tracking_rms_mm),
            mm(r.frozen_tracking_rms_mm),
            mm(r.eq7_stale_tracking_rms_mm),
            minutes(r.minutes_to_1mm),
            minutes(r.minutes_to_2x_nominal),
            mm(r.adapted_tracking_rms_mm),
            r.adapted_command_nmse
                .map_or("—".into(), |x| format!("{x:.4}")),
            r.max_command_step,
            r.braked_episodes,
        );
        rows.insert(key.to_string(), r);
    }
    let fig = timelines(&a.robot, &rows);
    wrote(&plot::save(
        &fig,
        &a.out,
        &format!("{}_adaptation", a.robot),
    )?);
    Ok(())
}
