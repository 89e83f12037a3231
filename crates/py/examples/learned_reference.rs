//! The Rust side of the Python package's bit-for-bit learned-controller test
//! (`python/tests/test_learned.py`): runs a model saved by `osrl train` as the
//! `osrl_learn::LearnedController` of `osrl simulate --controller learned:MODEL` in a closed loop
//! on osrl's simulator (from rest at the model's home, along its training trajectory) and prints
//! one line per control step: the measured `q, q̇, x, ẋ, ẍ`, the target `x_d, ẋ_d, ẍ_d` on the task
//! axes and the command `u`, each value as its `f64` bit pattern (16 hex digits).
//!
//! `cargo run --release -p osrl-py --example learned_reference -- MODEL STEPS`

use osrl_control::TaskController;
use osrl_dynamics::{Robot, SimConfig, SimRobot};
use osrl_learn::SavedModel;
use std::fmt::Write;

fn hex(out: &mut String, v: impl IntoIterator<Item = f64>) {
    for x in v {
        write!(out, "{:016x} ", x.to_bits()).expect("write to a String");
    }
}

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let [model, steps] = &a[..] else {
        panic!("usage: MODEL STEPS");
    };
    let steps: usize = steps.parse().expect("STEPS: a number");
    let saved = SavedModel::load(model.as_ref()).expect("a saved model");
    let info = saved.info().clone();
    let robot = saved.robot().clone();
    let traj = info
        .trajectory
        .build(&robot)
        .expect("the training trajectory");
    let axes = robot.task_axes().to_vec();
    let sim_cfg = SimConfig {
        control_period: info.control_period,
        ..SimConfig::default()
    };
    let mut sim = SimRobot::new(robot.clone(), sim_cfg).expect("a simulator");
    sim.reset(&info.home, &vec![0.0; robot.nq()]).expect("home");
    let mut ctrl = saved.controller().expect("a controller");
    let mut u = vec![0.0; robot.nq()];
    let mut out = String::new();
    for k in 0..steps {
        let meas = sim.measurement().clone();
        let target = traj.sample(k as f64 * info.control_period);
        ctrl.command(&meas, &target, &mut u).expect("a command");
        for v in [&meas.q, &meas.qd, &meas.x, &meas.xd, &meas.xdd] {
            hex(&mut out, v.iter().copied());
        }
        for v in [&target.x, &target.xd, &target.xdd] {
            hex(&mut out, axes.iter().map(|&i| v[i]));
        }
        hex(&mut out, u.iter().copied());
        out.push('\n');
        sim.step(&u).expect("a step");
    }
    print!("{out}");
}
