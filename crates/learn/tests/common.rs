//! A small planar3 training setup shared by the tests.

#![allow(dead_code)]

use osrl_control::{check_reachable, IkOptions, Trajectory, TrajectoryConfig};
use osrl_dynamics::{robots, Model, SimConfig, SimRobot};
use osrl_learn::eval::Evaluator;
use osrl_learn::train::{train, BabbleConfig, TrainConfig, TrainSummary};
use osrl_learn::{Learner, LearnerConfig};

pub struct Setup {
    pub model: Model,
    pub traj: Trajectory,
    pub q_start: Vec<f64>,
}

pub fn planar3() -> Setup {
    let model = robots::planar3();
    let traj = TrajectoryConfig::default().build(&model).unwrap();
    let q_start = check_reachable(&model, &traj, &IkOptions::default())
        .unwrap()
        .q_start;
    Setup {
        model,
        traj,
        q_start,
    }
}

/// The default learner config of the set-up's robot (its data sheet's gains and limits).
pub fn config(s: &Setup) -> LearnerConfig {
    let spec = s.model.spec();
    LearnerConfig::for_robot(
        &spec.kp,
        &spec.kd,
        &spec.q_rest,
        &s.model.tau_max().collect::<Vec<_>>(),
    )
}

pub fn learner(s: &Setup) -> Learner {
    Learner::new(3, 2, 0.002, config(s)).unwrap()
}

/// Trains for `minutes` (babbling `babble` of them) and evaluates every `eval_every` minutes.
pub fn run(
    s: &Setup,
    learner: &mut Learner,
    minutes: f64,
    babble: f64,
    eval_every: f64,
    seed: u64,
) -> TrainSummary {
    let mut sim = SimRobot::new(
        s.model.clone(),
        SimConfig {
            seed,
            ..SimConfig::default()
        },
    )
    .unwrap();
    sim.reset(&s.q_start, &[0.0; 3]).unwrap();
    let cfg = TrainConfig {
        minutes,
        seed,
        eval_every_minutes: eval_every,
        babble: BabbleConfig {
            minutes: babble,
            ..BabbleConfig::default()
        },
        ..TrainConfig::default()
    };
    let mut ev = Evaluator::new(
        s.model.clone(),
        SimConfig::default(),
        s.traj.clone(),
        s.q_start.clone(),
        cfg.gains,
        1,
    )
    .unwrap();
    let axes = s.model.task_axes().to_vec();
    train(
        &mut sim,
        learner,
        &s.traj,
        &axes,
        &cfg,
        &mut |l| ev.evaluate(l),
        &mut |_| {},
    )
    .unwrap()
}
