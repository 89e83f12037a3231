//! E5 (paper Sec. V): learning curves — tracking error, command nMSE against `u*` and command
//! cost ratio against simulated training minutes for `--seeds N` seeds from `--seed S`, mean
//! and min–max over the seeds whose evaluation did not diverge: the table and the figure
//! `<robot>_curves.svg/png`.
//!
//! `cargo run --release -p osrl-report --example fig_learning_curve -- [--robot planar3]
//! [--minutes 5] [--seed 0] [--seeds 2] [--out target/figures]`

mod common;
use common::{wrote, Args, Res};
use osrl_experiments::learned::curves_of;
use osrl_experiments::{learned, Trained};
use osrl_report::figures::learned::curves;
use osrl_report::plot;

fn main() -> Res<()> {
    let a = Args::parse(5.0, 2)?;
    let mut runs = Vec::new();
    for seed in a.seed..a.seed + a.seeds {
        let s = a.setup(seed, 1.0, 1)?;
        let (_, summary) = s.train(s.model(), &mut |_| {})?;
        println!(
            "seed {seed}: {:.1} s wall, {} local models",
            summary.wall_seconds, summary.n_local_models
        );
        let eval = summary
            .learning_curve
            .last()
            .map(|p| p.1.clone())
            .unwrap_or_default();
        runs.push(Trained {
            summary,
            eval,
            series: None,
            on_payload: None,
            model: None,
            held_out: None,
        });
    }
    let c = learned::curves(&runs.iter().collect::<Vec<_>>());
    println!("| sim. minutes | tracking RMS (mm) | command nMSE | cost ratio | seeds evaluated |\n|---|---|---|---|---|");
    let all = curves_of(&runs.iter().collect::<Vec<_>>());
    for (i, t) in c.sim_minutes.iter().enumerate() {
        let ok = all
            .iter()
            .filter(|r| r.iter().any(|p| p.0 == *t && !p.1.diverged))
            .count();
        println!(
            "| {t:.1} | {:.3} | {:.3} | {:.3} | {ok} |",
            c.tracking_rms_mm.mean[i], c.command_nmse.mean[i], c.command_cost_ratio.mean[i]
        );
    }
    let title = format!(
        "{}: learning curves (mean, min–max over {} seeds)",
        a.robot, c.seeds
    );
    let fig = curves(&title, &[("learned (RWR)".into(), c)], None, a.minutes);
    wrote(&plot::save(&fig, &a.out, &format!("{}_curves", a.robot))?);
    Ok(())
}
