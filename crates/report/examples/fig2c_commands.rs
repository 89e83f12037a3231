//! E4 (paper Fig. 2c): the learned command against the analytical optimum `u*` (eq. 7, `N = I`,
//! true model) at the same states, per joint over the last cycle of an evaluation after a short
//! training run: the per-joint RMS of `u − u*` and of `u*`, the command nMSE and cost ratio,
//! and the figure `<robot>_commands.svg/png`.
//!
//! `cargo run --release -p osrl-report --example fig2c_commands -- [--robot planar3]
//! [--minutes 4] [--seed 0] [--out target/figures]`

mod common;
use common::{evaluate, wrote, Args, Res};
use osrl_experiments::learned::per_joint_rms;
use osrl_report::figures::commands::commands_figure;
use osrl_report::plot;

fn main() -> Res<()> {
    let a = Args::parse(4.0, 1)?;
    let s = a.setup(a.seed, 0.0, 1)?;
    let (mut learner, summary) = s.train(s.model(), &mut |_| {})?;
    let (e, es) = evaluate(&s, &mut learner)?;
    let (n, per) = (s.model().nq(), s.steps_per_period());
    println!(
        "{} after {:.1} simulated min ({:.1} s wall), seed {}: command nMSE {:.3}, cost ratio {:.3}, tracking {} mm",
        a.robot, summary.sim_training_minutes, summary.wall_seconds, a.seed,
        e.command_nmse, e.command_cost_ratio, common::mm(&e)
    );
    println!("| joint | RMS(u − u*) (N·m) | RMS(u*) (N·m) |\n|---|---|---|");
    for (j, (d, u)) in per_joint_rms(&es, n, per).iter().enumerate() {
        println!("| {} | {d:.3} | {u:.3} |", j + 1);
    }
    let title = format!(
        "{}: learned vs analytical optimal commands over one cycle",
        a.robot
    );
    wrote(&plot::save(
        &commands_figure(&es, n, per, &title),
        &a.out,
        &format!("{}_commands", a.robot),
    )?);
    Ok(())
}
