//! `cargo run --release -p osrl-control --example published_arms [-- SECONDS]`: every arm of
//! the committed example-robot-data fixtures with its resolved robot profile
//! (`osrl_control::profile`), eq. 7 (`N = I`, true model) on its default figure-8 for SECONDS
//! (default 12) at 500 Hz: DOF, tip, reach, path size, tracking RMS and max, torque
//! saturations, steps at a joint limit, control periods with implicit (stiff) friction, and the
//! profile's IK checks (smallest limit margin, largest torque share) — or the reason the arm is
//! refused. Prints a Markdown table.

use osrl_control::profile::{load_robot, resolve};
use osrl_control::{check_reachable, run_closed_loop, IkOptions, Osc, OscConfig, TrajectoryConfig};
use osrl_dynamics::{RobotProfile, SimConfig, SimRobot};

/// (file, tip option) of every arm in the fixtures folder.
const ARMS: [(&str, Option<&str>); 15] = [
    ("panda.urdf", None),
    ("ur3_robot.urdf", None),
    ("ur5_robot.urdf", None),
    ("ur10_robot.urdf", None),
    ("kinova.urdf", None),
    ("xarm7.urdf", None),
    ("z1.urdf", None),
    ("so100.urdf", None),
    ("so101.urdf", None),
    ("talos_left_arm.urdf", None),
    ("tiago.urdf", None),
    ("baxter.urdf", Some("right_gripper")),
    ("TwoDofs.urdf", None),
    ("double_pendulum.urdf", None),
    ("finger_edu.urdf", None),
];

fn run(file: &str, tip: Option<&str>, seconds: f64) -> Result<String, String> {
    let dir = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../dynamics/tests/fixtures/example-robot-data"
    );
    let path = format!("{dir}/{file}");
    let given = RobotProfile {
        tip: tip.map(String::from),
        ..RobotProfile::default()
    };
    let e = |e: osrl_control::ControlError| e.to_string();
    let model = load_robot(&path, &given).map_err(e)?;
    let p = resolve(&model, &given).map_err(e)?;
    let traj_cfg = p.trajectory(&TrajectoryConfig::default());
    let traj = traj_cfg.build(&p.model).map_err(e)?;
    let home = check_reachable(&p.model, &traj, &IkOptions::default())
        .map_err(e)?
        .q_start;
    let mut sim =
        SimRobot::new(p.model.clone(), SimConfig::default()).map_err(|x| x.to_string())?;
    sim.reset(&home, &vec![0.0; p.model.nq()])
        .map_err(|x| x.to_string())?;
    let mut osc = Osc::new(p.model.clone(), OscConfig::default()).map_err(e)?;
    let r = run_closed_loop(&mut sim, &mut osc, &traj, p.model.task_axes(), seconds).map_err(e)?;
    let m = &r.metrics;
    let pr = &p.profile;
    Ok(format!(
        "{} | `{}` | {:.3} | {:.0} × {:.0} | {:.4} | {:.4} | {} | {} | {} | {:.2} | {:.2}",
        p.model.nq(),
        pr.tip.clone().unwrap_or_default(),
        pr.reach,
        pr.path.a * 1e3,
        pr.path.b * 1e3,
        m.tracking_rms_mm,
        m.tracking_max_mm,
        m.torque_saturation_steps,
        m.limit_steps,
        sim.stats().implicit_friction,
        pr.min_limit_margin,
        pr.peak_torque_ratio,
    ))
}

fn dir_prefix() -> &'static str {
    concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../dynamics/tests/fixtures/example-robot-data/"
    )
}

fn main() {
    let seconds: f64 = std::env::args()
        .nth(1)
        .map_or(12.0, |s| s.parse().expect("SECONDS is a number"));
    println!("| arm | DOF | tip | reach (m) | path a × b (mm) | eq. 7 RMS (mm) | max (mm) | saturated steps | steps at a joint limit | implicit friction periods | IK min limit margin | IK peak torque share |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (file, tip) in ARMS {
        match run(file, tip, seconds) {
            Ok(row) => println!("| `{file}` | {row} |"),
            Err(why) => {
                let why = why.replace('|', "/").replace(dir_prefix(), "");
                println!("| `{file}` | refused: {why} |")
            }
        }
    }
}
