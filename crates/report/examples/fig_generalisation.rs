//! E9 (issue 27): one controller for the workspace. Per seed, a controller trained on the
//! default figure-8 only and one trained on the family of paths around it (`osrl train
//! --trajectory family`), for the same time, each evaluated on held-out paths (two figure-8s,
//! two circles and two minimum-jerk paths drawn with a seed no training uses) and on the
//! default figure-8: the table of tracking and command nMSE per path, whether the
//! family-trained controller meets issue 27's bounds there, and the figure
//! `<robot>_held_out.svg/png`. `osrl reproduce` trains 30 (planar3) and 60 (sarcos7) minutes.
//!
//! `cargo run --release -p osrl-report --example fig_generalisation -- [--robot planar3]
//! [--minutes 10] [--seed 0] [--seeds 1] [--out target/figures]`

mod common;
use common::{wrote, Args, Res};
use osrl_experiments::analytical::ROBOTS;
use osrl_experiments::e9::{e9, E9Point};
use osrl_experiments::jobs::{job_setup, run_one};
use osrl_experiments::{Job, JobResult, RobotSizes, Setup, Sizes};
use osrl_learn::train::BabbleConfig;
use osrl_learn::Variant;
use osrl_report::figures::held_out;
use osrl_report::plot;

/// `tracking mm / nMSE` of one evaluation.
fn cell(p: &E9Point) -> String {
    let diverged = if p.diverged { " (diverged)" } else { "" };
    format!("{:.3} / {:.4}{diverged}", p.tracking_rms_mm, p.command_nmse)
}

fn main() -> Res<()> {
    let a = Args::parse(10.0, 1)?;
    let robot = *(ROBOTS.iter())
        .find(|r| **r == a.robot)
        .ok_or(format!("E9 runs on {ROBOTS:?}, not {}", a.robot))?;
    let base = Setup::new(robot)?;
    let mut sizes = Sizes::full();
    let rs = RobotSizes {
        minutes: a.minutes,
        babble_minutes: Some(BabbleConfig::default().minutes.min(0.4 * a.minutes)),
        eval_every_minutes: 0.0,
    };
    sizes.planar3 = rs.clone();
    sizes.sarcos7 = rs;
    sizes.e9.planar3_seeds = a.seed + a.seeds;
    sizes.e9.sarcos7_seeds = a.seed + a.seeds;
    let mut done = Vec::new();
    for seed in a.seed..a.seed + a.seeds {
        for family in [false, true] {
            let job = Job {
                robot,
                variant: Variant::Rwr,
                seed,
                payload: false,
                family,
            };
            let s = job_setup(&base, &job, &sizes)?;
            let outcome = run_one(&job, &s, &sizes, &mut |_| {});
            match &outcome {
                Ok(t) => println!(
                    "{}: {:.1} simulated min, {:.1} s wall",
                    job.name(),
                    t.summary.sim_training_minutes,
                    t.summary.wall_seconds
                ),
                Err(e) => println!("{}: failed: {e}", job.name()),
            }
            done.push(JobResult {
                job,
                outcome: outcome.map_err(|e| e.to_string()),
            });
        }
    }
    let rows = e9(&done);
    let row = rows.get(robot).ok_or("no seed finished both trainings")?;
    println!(
        "| path | seed | figure-8 only: mm / nMSE | family: mm / nMSE | family's support share \
         | within issue 27's bounds |\n|---|---|---|---|---|---|"
    );
    for (k, seed) in row.seeds.iter().enumerate() {
        println!(
            "| default figure-8 (trained on by both) | {seed} | {} | {} | — | — |",
            cell(&row.figure8_only_on_figure8[k]),
            cell(&row.family_on_figure8[k])
        );
    }
    for p in &row.paths {
        for k in 0..p.family.len() {
            println!(
                "| {} | {} | {} | {} | {:.2} | {} |",
                p.label,
                p.family[k].seed,
                cell(&p.figure8_only[k]),
                cell(&p.family[k]),
                p.family[k].support_share,
                if p.family_within_bounds[k] {
                    "yes"
                } else {
                    "no"
                }
            );
        }
    }
    let met: usize = (row.paths.iter())
        .map(|p| p.family_within_bounds.iter().filter(|b| **b).count())
        .sum();
    let pairs: usize = row.paths.iter().map(|p| p.family.len()).sum();
    println!("within the bounds: {met} of {pairs} held-out pairs");
    wrote(&plot::save(
        &held_out(robot, row),
        &a.out,
        &format!("{robot}_held_out"),
    )?);
    Ok(())
}
