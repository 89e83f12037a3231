//! The Rust side of `examples/python/bench_learned_step.py`: the wall time of one
//! `LearnedController::command` of a saved model (µs, best of 5 repeats over `STEPS` commands
//! on states recorded in a closed loop holding the home posture on osrl's simulator), printed
//! as one JSON line `{"command_us": …}`.
//!
//! `cargo run --release -p osrl-py --example learned_timing -- MODEL STEPS`

use osrl_control::{Target, TaskController};
use osrl_dynamics::{Robot, SimConfig, SimRobot};
use osrl_learn::SavedModel;
use std::time::Instant;

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let [model, steps] = &a[..] else {
        panic!("usage: MODEL STEPS");
    };
    let steps: usize = steps.parse().expect("STEPS: a number");
    let saved = SavedModel::load(model.as_ref()).expect("a saved model");
    let info = saved.info().clone();
    let robot = saved.robot().clone();
    let sim_cfg = SimConfig {
        control_period: info.control_period,
        ..SimConfig::default()
    };
    let mut sim = SimRobot::new(robot.clone(), sim_cfg).expect("a simulator");
    sim.reset(&info.home, &vec![0.0; robot.nq()]).expect("home");
    let mut ctrl = saved.controller().expect("a controller");
    let mut target = Target::default();
    let x0 = sim.measurement().x.clone();
    for (i, &ax) in robot.task_axes().iter().enumerate() {
        target.x[ax] = x0[i];
    }
    let mut u = vec![0.0; robot.nq()];
    let mut states = Vec::new();
    for _ in 0..steps.min(2000) {
        states.push(sim.measurement().clone());
        ctrl.command(sim.measurement(), &target, &mut u)
            .expect("a command");
        sim.step(&u).expect("a step");
    }
    let reps = (steps / states.len()).max(1);
    let mut best = f64::INFINITY;
    for _ in 0..5 {
        let t0 = Instant::now();
        for _ in 0..reps {
            for s in &states {
                ctrl.command(s, &target, &mut u).expect("a command");
            }
        }
        best = best.min(t0.elapsed().as_secs_f64() / (reps * states.len()) as f64);
    }
    println!("{{\"command_us\": {:.3}}}", best * 1e6);
}
