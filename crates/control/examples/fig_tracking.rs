//! E2 baseline: the analytical controllers track the default figure-8 (12 s) with the true model
//! on both robots. Prints one markdown row per robot and controller.
//!
//! `cargo run --release -p osrl-control --example fig_tracking`

use osrl_control::{
    check_reachable, run_closed_loop, IkOptions, Law, MetricKind, Osc, OscConfig, TrajectoryConfig,
};
use osrl_dynamics::{robots, SimConfig, SimRobot};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let controllers = [
        ("eq. 7, N = I", Law::Eq7, MetricKind::Identity),
        ("eq. 4", Law::Eq4, MetricKind::Identity),
        ("eq. 7, N = M⁻¹", Law::Eq7, MetricKind::InverseMass),
    ];
    println!("| robot | controller | tracking RMS (mm) | max (mm) | command RMS (N·m) | joint drift (rad/period) | max excursion (rad) | min limit margin (rad) | first limit hit (s) |");
    println!("|---|---|---|---|---|---|---|---|---|");
    for model in [robots::planar3(), robots::sarcos7()] {
        let traj = TrajectoryConfig::default().build(&model)?;
        let reach = check_reachable(&model, &traj, &IkOptions::default())?;
        for (name, law, metric) in controllers {
            let cfg = OscConfig {
                law,
                metric,
                ..OscConfig::default()
            };
            let mut ctrl = Osc::new(model.clone(), cfg)?;
            let mut sim = SimRobot::new(model.clone(), SimConfig::default())?;
            sim.reset(&reach.q_start, &vec![0.0; model.nq()])?;
            let m = run_closed_loop(&mut sim, &mut ctrl, &traj, model.task_axes(), 12.0)?.metrics;
            println!(
                "| {} | {name} | {:.4} | {:.4} | {:.3} | {:.1e} | {:.3} | {:.3} | {} |",
                model.name(),
                m.tracking_rms_mm,
                m.tracking_max_mm,
                m.command_rms,
                m.joint_drift_rad,
                m.max_joint_excursion_rad,
                m.min_limit_margin_rad,
                m.first_limit_s.map_or("–".into(), |t| format!("{t:.2}"))
            );
        }
    }
    Ok(())
}
