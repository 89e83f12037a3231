//! E7 baseline: how the analytical controllers degrade with a wrong model (default figure-8,
//! 12 s). Prints a markdown table: true model vs masses ×1.3, centres of mass shifted 2 cm
//! (random directions, seed 0), friction unmodelled, all three, and an unmodelled 0.5 kg payload.
//!
//! `cargo run --release -p osrl-control --example model_errors`

use osrl_control::{
    check_reachable, run_closed_loop, IkOptions, Law, MetricKind, ModelError, Osc, OscConfig,
    TrajectoryConfig,
};
use osrl_dynamics::{robots, SimConfig, SimRobot};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let errors = [
        ("true model", "none"),
        ("masses ×1.3", "mass=1.3"),
        ("COM shifted 2 cm", "com=0.02"),
        ("friction unmodelled", "friction=off"),
        ("all three", "mass=1.3,com=0.02,friction=off"),
        ("payload 0.5 kg", "payload=0.5"),
    ];
    let controllers = [
        ("eq. 7, N = I", Law::Eq7, MetricKind::Identity),
        ("eq. 4", Law::Eq4, MetricKind::Identity),
    ];
    println!(
        "| robot | controller | model | tracking RMS (mm) | max (mm) | steps at a joint limit |"
    );
    println!("|---|---|---|---|---|---|");
    for model in [robots::planar3(), robots::sarcos7()] {
        let traj = TrajectoryConfig::default().build(&model)?;
        let reach = check_reachable(&model, &traj, &IkOptions::default())?;
        for (cname, law, metric) in controllers {
            for (ename, spec) in errors {
                let err: ModelError = spec.parse()?;
                let (sim_model, ctrl_model) = err.apply(&model)?;
                let cfg = OscConfig {
                    law,
                    metric,
                    ..OscConfig::default()
                };
                let mut ctrl = Osc::new(ctrl_model, cfg)?;
                let mut sim = SimRobot::new(sim_model, SimConfig::default())?;
                sim.reset(&reach.q_start, &vec![0.0; model.nq()])?;
                let m = run_closed_loop(&mut sim, &mut ctrl, &traj, model.task_axes(), 12.0)?;
                let m = m.metrics;
                println!(
                    "| {} | {cname} | {ename} | {:.3} | {:.3} | {} |",
                    model.name(),
                    m.tracking_rms_mm,
                    m.tracking_max_mm,
                    m.limit_steps
                );
            }
        }
    }
    Ok(())
}
