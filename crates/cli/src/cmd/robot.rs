//! `osrl robot`: show a robot model with its resolved robot profile (`osrl_control::profile`:
//! tip, locked joints, home and rest postures, joint gains, torque limits, the default path's
//! placement, and where each value came from), or export it as URDF with the profile embedded
//! (`<osrl_profile .../>`), so that the exported file loads back with the same profile.

use crate::robot_entry::ProfileArgs;
use anyhow::Result;
use osrl_control::profile::{load_robot, resolve};
use osrl_dynamics::RobotProfile;

#[derive(clap::Args)]
pub struct Args {
    /// Built-in robot (planar3, sarcos7) or a URDF file.
    #[arg(long)]
    pub robot: String,
    #[command(flatten)]
    pub profile: ProfileArgs,
    /// Print the model as URDF, its resolved profile embedded.
    #[arg(long)]
    pub urdf: bool,
    /// Print a JSON summary of the model.
    #[arg(long)]
    pub json: bool,
}

pub fn run(a: Args) -> Result<()> {
    let given = a.profile.apply(&RobotProfile::default())?;
    let loaded = load_robot(&a.robot, &given)?;
    let profiled = resolve(&loaded, &given)?;
    let model = &profiled.model;
    if a.urdf {
        let p = profiled.as_given();
        print!(
            "{}",
            osrl_dynamics::urdf::to_urdf_with_profile(model, Some(&p))
        );
        return Ok(());
    }
    let spec = model.spec();
    let summary = serde_json::json!({
        "name": spec.name,
        "dof": model.nq(),
        "task_axes": spec.task_axes,
        "joints": spec.links.iter().map(|l| l.joint_name.clone()).collect::<Vec<_>>(),
        "q_min": model.q_min().collect::<Vec<_>>(),
        "q_max": model.q_max().collect::<Vec<_>>(),
        "tau_max": model.tau_max().collect::<Vec<_>>(),
        "total_mass": model.total_mass(),
        "q_start": spec.q_start,
        "q_rest": spec.q_rest,
        "kp": spec.kp,
        "kd": spec.kd,
        "profile": profiled.profile,
    });
    if !a.json {
        let p = &profiled.profile;
        let kinds = |k| spec.links.iter().filter(|l| l.kind == k).count();
        println!(
            "{} — {} revolute and {} prismatic joints, {:.3} kg, task axes {:?}",
            spec.name,
            kinds(osrl_dynamics::JointKind::Revolute),
            kinds(osrl_dynamics::JointKind::Prismatic),
            model.total_mass(),
            spec.task_axes
        );
        if let (Some(tip), Some(rule)) = (&p.tip, &p.tip_rule) {
            println!("tip {tip} ({rule}); locked: {}", p.locked.join(", "));
        }
        println!(
            "profile: home {:?}; path centre {:?}, a {:.3} m, b {:.3} m; reach {:.3} m; sources {:?}",
            p.home, p.path.centre, p.path.a, p.path.b, p.reach, p.sources
        );
        let sweep = match &p.joint_sweep {
            Some(s) => format!(
                "; eq. 7 with N = I sweeps the joints {:.3?} rad along the path (bound {} rad)",
                s,
                osrl_control::profile::METRIC_SWEEP_BOUND
            ),
            None => String::new(),
        };
        println!("learner cost metric: {:?}{sweep}", p.metric);
    }
    crate::util::print_json(&summary);
    Ok(())
}
