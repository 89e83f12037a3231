//! Test fixture: a planar3 learner past its warm-up, fed by a simulator under a slow joint PD
//! sweep (no trained controller yet), and helpers to inspect it.

use super::{Learner, Models, State};
use crate::config::LearnerConfig;
use osrl_dynamics::{robots, Measurement, Robot, SimConfig, SimRobot};

/// The default learner config of planar3's data sheet.
pub fn config() -> LearnerConfig {
    let model = robots::planar3();
    let spec = model.spec();
    let tau: Vec<f64> = model.tau_max().collect();
    LearnerConfig::for_robot(&spec.kp, &spec.kd, &spec.q_rest, &tau)
}

/// A simulated planar3 at rest at its rest posture.
pub fn robot() -> SimRobot {
    let model = robots::planar3();
    let q = model.spec().q_rest.clone();
    let mut sim = SimRobot::new(model, SimConfig::default()).unwrap();
    sim.reset(&q, &[0.0; 3]).unwrap();
    sim
}

/// Feeds `k` transitions of a sinusoidal PD sweep around rest (with `ĝ`) to `learner`.
pub fn sweep(learner: &mut Learner, sim: &mut SimRobot, k: usize) -> Measurement {
    let spec = robots::planar3().spec().clone();
    let mut prev = sim.measurement().clone();
    let mut u = [0.0; 3];
    for s in 0..k {
        let t = prev.t;
        learner.gravity(prev.q.as_slice(), &mut u).unwrap();
        #[allow(clippy::needless_range_loop)]
        for i in 0..3 {
            let target = spec.q_rest[i] + 0.3 * (1.3 * t + i as f64).sin();
            u[i] += 3.0 * spec.kp[i] * (target - prev.q[i]) - 3.0 * spec.kd[i] * prev.qd[i];
            u[i] += 0.5 * ((s * 7 + i * 3) % 11) as f64 - 2.5;
        }
        let cur = sim.step(&u).unwrap().clone();
        learner.learn(&prev, &cur).unwrap();
        prev = cur;
    }
    prev
}

/// A learner just past its warm-up (`warmup` transitions, then `extra` more).
pub fn ready(cfg: LearnerConfig, warmup: usize, extra: usize) -> (Learner, SimRobot, Measurement) {
    let mut cfg = cfg;
    cfg.guards.warmup_samples = warmup;
    let mut learner = Learner::new(3, 2, 0.002, cfg).unwrap();
    let mut sim = robot();
    let last = sweep(&mut learner, &mut sim, warmup + 1 + extra);
    assert!(learner.ready());
    (learner, sim, last)
}

/// The learner's models (it must be ready).
pub fn models(learner: &mut Learner) -> &mut Models {
    match &mut learner.state {
        State::Ready(m) => m,
        State::WarmUp(_) => panic!("the fixture's learner is ready"),
    }
}

/// Sorted ids of the forward model's receptive fields and of the local controllers.
pub fn ids(learner: &Learner) -> (Vec<u64>, Vec<u64>) {
    let fwd = learner.forward_model().unwrap().lwpr();
    let mut a: Vec<u64> = fwd.rfs(0).unwrap().map(|v| v.id().0).collect();
    a.sort_unstable();
    let b: Vec<u64> = learner.local_summaries().iter().map(|s| s.id).collect();
    (a, b)
}

/// `k + 1` measurements of planar3 under the sweep's PD law and torque pattern (no learner,
/// no gravity compensation), and the true `(M⁻¹)_jj` at their mean posture: the reference of
/// the test of the measured inertia (the learner never reads it).
pub fn warm_up_with_inverse_inertia(k: usize) -> (Vec<Measurement>, Vec<f64>) {
    let model = robots::planar3();
    let spec = model.spec().clone();
    let mut sim = robot();
    let mut out = vec![sim.measurement().clone()];
    let mut u = [0.0; 3];
    for s in 0..k {
        let prev = out.last().unwrap();
        let t = prev.t;
        for (i, ui) in u.iter_mut().enumerate() {
            let target = spec.q_rest[i] + 0.3 * (1.3 * t + i as f64).sin();
            *ui = 3.0 * spec.kp[i] * (target - prev.q[i]) - 3.0 * spec.kd[i] * prev.qd[i];
            *ui += 0.5 * ((s * 7 + i * 3) % 11) as f64 - 2.5;
        }
        out.push(sim.step(&u).unwrap().clone());
    }
    let mean: Vec<f64> = (0..3)
        .map(|i| out.iter().map(|m| m.q[i]).sum::<f64>() / out.len() as f64)
        .collect();
    let mut data = model.data();
    let m = osrl_dynamics::crba(&model, &mut data, &mean)
        .unwrap()
        .clone();
    let inv = m.try_inverse().unwrap();
    (out, (0..3).map(|j| inv[(j, j)]).collect())
}

/// One field trained by hand (a known `β`, confident) in a fixture learner with `cfg`, and
/// its centre in `(q, q̇)`.
pub fn one_trained_field(mut cfg: LearnerConfig) -> (Learner, Vec<f64>) {
    cfg.controllers.trained_ess = 1e8;
    let (mut learner, _, _) = ready(cfg, 200, 0);
    let p = learner.features.controller_len();
    let beta = nalgebra::DMatrix::from_fn(p, 3, |r, c| 0.02 * (r as f64 + 1.0) * (c as f64 - 1.0));
    let rwr_cfg = learner.cfg.controllers.rwr.clone();
    let local = models(&mut learner).locals.map.values_mut().next().unwrap();
    local.rwr = rwr::OnlineRwr::with_theta(beta, rwr_cfg).unwrap();
    local.theta_from = None; // set by hand: no update to spread
    local.ess = 1e9;
    let center = local.center.clone();
    (learner, center)
}

/// A short training run of `minutes` for the driver's tests: 0.4 simulated minutes of babbling
/// first, no evaluations.
pub fn short_training(minutes: f64) -> crate::train::TrainConfig {
    use crate::train::{BabbleConfig, TrainConfig};
    TrainConfig {
        minutes,
        eval_every_minutes: 0.0,
        babble: BabbleConfig {
            minutes: 0.4,
            ..BabbleConfig::default()
        },
        ..TrainConfig::default()
    }
}
