//! E6 (paper Sec. II, IV): the ablation ([`osrl_learn::Variant`]) — the default learner against
//! the same architecture with the reward weighting and the hindsight shrinkage off (direct
//! supervised inverse learning), RWR as in the paper (full cost, no shrinkage) and a global
//! inverse model: the final tracking error, command nMSE against `u*` and command cost ratio of
//! each, and their learning curves `<robot>_ablation.svg/png`.
//!
//! `cargo run --release -p osrl-report --example fig_ablation -- [--robot planar3]
//! [--minutes 3] [--seed 0] [--out target/figures]`

mod common;
use common::{wrote, Args, Res};
use osrl_experiments::{learned, Trained};
use osrl_learn::Variant;
use osrl_report::figures::learned::curves;
use osrl_report::plot;

fn main() -> Res<()> {
    let a = Args::parse(3.0, 1)?;
    println!(
        "{}, {} simulated min per variant, seed {}",
        a.robot, a.minutes, a.seed
    );
    println!("| variant | tracking RMS (mm) | command nMSE | cost ratio | local models | wall (s) |\n|---|---|---|---|---|---|");
    let mut plotted = Vec::new();
    for v in Variant::ALL {
        let base = a.setup(a.seed, 1.0, 1)?;
        let s = base
            .clone()
            .with_learner(v.config(base.learner_config().clone()))?;
        let (_, summary) = s.train(s.model(), &mut |_| {})?;
        let e = summary
            .learning_curve
            .last()
            .map(|p| p.1.clone())
            .unwrap_or_default();
        println!(
            "| {} | {} | {:.3} | {:.3} | {} | {:.1} |",
            v.key(),
            common::mm(&e),
            e.command_nmse,
            e.command_cost_ratio,
            summary.n_local_models,
            summary.wall_seconds
        );
        let run = Trained {
            summary,
            eval: e,
            series: None,
            on_payload: None,
            model: None,
            held_out: None,
        };
        plotted.push((v.label().to_string(), learned::curves(&[&run])));
    }
    let title = format!(
        "{}: ablation — reward weighting, cost, localisation",
        a.robot
    );
    wrote(&plot::save(
        &curves(&title, &plotted, None, a.minutes),
        &a.out,
        &format!("{}_ablation", a.robot),
    )?);
    Ok(())
}
