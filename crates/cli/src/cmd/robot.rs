//! `osrl robot`: show a robot model.

use crate::util::load_robot;
use anyhow::Result;

#[derive(clap::Args)]
pub struct Args {
    /// Built-in robot (planar3, sarcos7) or a URDF file.
    #[arg(long)]
    pub robot: String,
    /// Print the model as URDF.
    #[arg(long)]
    pub urdf: bool,
    /// Print a JSON summary of the model.
    #[arg(long)]
    pub json: bool,
}

pub fn run(a: Args) -> Result<()> {
    let model = load_robot(&a.robot)?;
    if a.urdf {
        print!("{}", osrl_dynamics::urdf::to_urdf(&model));
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
    });
    if !a.json {
        println!(
            "{} — {} revolute joints, {:.3} kg, task axes {:?}",
            spec.name,
            model.nq(),
            model.total_mass(),
            spec.task_axes
        );
    }
    crate::util::print_json(&summary);
    Ok(())
}
