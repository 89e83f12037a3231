//! The driver loop of [`train`](super::train).

use super::{min_jerk, pd_command, reference, rng, uniform, Progress, TrainConfig};
use crate::error::{LearnError, Result};
use crate::eval::EvalResult;
use crate::learner::{Learner, LearnerStats};
use osrl_control::Trajectory;
use osrl_dynamics::{Measurement, Robot};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// The outcome of a training run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TrainSummary {
    pub sim_training_minutes: f64,
    pub wall_seconds: f64,
    /// Simulated training time over wall time (evaluations included in the wall time).
    pub realtime_factor: f64,
    pub episodes: u64,
    pub aborted_episodes: u64,
    /// `(simulated minutes, evaluation)` pairs.
    pub learning_curve: Vec<(f64, EvalResult)>,
    /// Largest change of the commanded torque between consecutive on-policy steps (N·m).
    pub max_command_step: f64,
    pub stats: LearnerStats,
    pub n_local_models: usize,
}

/// Loop state shared by the phases.
struct Run<'a, R: Robot + ?Sized> {
    robot: &'a mut R,
    learner: &'a mut Learner,
    cfg: &'a TrainConfig,
    prev: Measurement,
    steps: u64,
    total_steps: u64,
    next_eval: u64,
    eval_steps: u64,
    curve: Vec<(f64, EvalResult)>,
    u: Vec<f64>,
    rng: ChaCha8Rng,
    dt: f64,
    learning: bool,
}

impl<R: Robot + ?Sized> Run<'_, R> {
    fn minutes(&self) -> f64 {
        self.steps as f64 * self.dt / 60.0
    }
    fn done(&self) -> bool {
        self.steps >= self.total_steps
    }
    /// A minimum-jerk joint move from the current posture to `target` over `total` seconds,
    /// then `settle` seconds holding it, under PD control with the learned gravity compensation;
    /// stops early when the step count reaches `limit`.
    #[allow(clippy::too_many_arguments)]
    fn pd_move(
        &mut self,
        target: &[f64],
        total: f64,
        settle: f64,
        noise: f64,
        limit: u64,
        evaluate: &mut dyn FnMut(&mut Learner) -> Result<EvalResult>,
        observe: &mut dyn FnMut(&Progress),
        progress: &mut Progress,
    ) -> Result<()> {
        let n = target.len();
        let start: Vec<f64> = self.prev.q.as_slice().to_vec();
        let (mut q_t, mut v_t) = (vec![0.0; n], vec![0.0; n]);
        for k in 0..((total + settle) / self.dt).round() as u64 {
            if self.steps >= limit {
                break;
            }
            for i in 0..n {
                (q_t[i], v_t[i]) = min_jerk(start[i], target[i], k as f64 * self.dt, total);
            }
            let prev = self.prev.clone();
            pd_command(
                self.learner,
                &prev,
                &q_t,
                &v_t,
                self.cfg.babble.gain_scale,
                &mut self.u,
            )?;
            // Babbling noise: the torque of a `noise`-radian PD error, per joint; none while
            // holding the target, so the arm comes to rest (the static gravity model's samples).
            if noise > 0.0 && (k as f64) * self.dt < total {
                let kp = &self.learner.config().nominal.kp;
                for (u, k) in self.u.iter_mut().zip(kp) {
                    let z: f64 = StandardNormal.sample(&mut self.rng);
                    *u += noise * k * z;
                }
            }
            self.step(evaluate, observe, progress)?;
        }
        Ok(())
    }

    /// Applies `self.u` for one period, learns from the transition, evaluates when due.
    fn step(
        &mut self,
        evaluate: &mut dyn FnMut(&mut Learner) -> Result<EvalResult>,
        observe: &mut dyn FnMut(&Progress),
        progress: &mut Progress,
    ) -> Result<()> {
        let cur = self.robot.step(&self.u)?.clone();
        self.steps += 1;
        if self.learning && self.steps.is_multiple_of(self.cfg.learn_every as u64) {
            match self.learner.learn(&self.prev, &cur) {
                Ok(()) | Err(LearnError::BadMeasurement(_)) => {}
                Err(e) => return Err(e),
            }
        }
        self.prev = cur;
        if self.eval_steps > 0 && self.steps >= self.next_eval {
            self.next_eval += self.eval_steps;
            let e = evaluate(self.learner)?;
            self.curve.push((self.minutes(), e.clone()));
            progress.sim_minutes = self.minutes();
            progress.eval = Some(e);
            progress.n_local_models = self.learner.n_local_models();
            progress.n_trained = self.learner.n_trained();
            observe(progress);
        }
        Ok(())
    }
}

/// Trains `learner` on `robot` (at rest at its home posture on the path start): motor babbling,
/// then on-policy learning along `traj` (world axes `axes` are the task), calling `evaluate`
/// every `cfg.eval_every_minutes` and at the end, and `observe` with the progress.
pub fn train<R: Robot + ?Sized>(
    robot: &mut R,
    learner: &mut Learner,
    traj: &Trajectory,
    axes: &[usize],
    cfg: &TrainConfig,
    evaluate: &mut dyn FnMut(&mut Learner) -> Result<EvalResult>,
    observe: &mut dyn FnMut(&Progress),
) -> Result<TrainSummary> {
    let wall = Instant::now();
    cfg.validate()?;
    let dt = robot.control_period();
    let (n, m) = learner.dims();
    if robot.dof() != n || robot.task_dim() != m || axes.len() != m || cfg.learn_every == 0 {
        return Err(LearnError::InvalidConfig(format!(
            "robot ({} joints, {}-D task), learner ({n}, {m}) and task axes {axes:?} do not match",
            robot.dof(),
            robot.task_dim()
        )));
    }
    let home: Vec<f64> = robot.measurement().q.as_slice().to_vec();
    let (q_min, q_max) = robot.joint_limits();
    let (q_min, q_max) = (q_min.to_vec(), q_max.to_vec());
    let per_min = (60.0 / dt).round() as u64;
    let eval_steps = (cfg.eval_every_minutes * per_min as f64).round() as u64;
    let mut run = Run {
        prev: robot.measurement().clone(),
        robot,
        learner,
        cfg,
        steps: 0,
        total_steps: (cfg.minutes * per_min as f64).round() as u64,
        next_eval: eval_steps,
        eval_steps,
        curve: Vec::new(),
        u: vec![0.0; n],
        rng: rng(cfg.seed),
        dt,
        learning: true,
    };
    let mut progress = Progress {
        sim_minutes: 0.0,
        phase: "babbling",
        n_local_models: 0,
        n_trained: 0,
        episodes: 0,
        aborted_episodes: 0,
        eval: None,
        max_command_step: 0.0,
    };
    // Phase 1: motor babbling, random point-to-point moves around home.
    let babble_steps = (cfg.babble.minutes * per_min as f64).round() as u64;
    let mut target = vec![0.0; n];
    let babble_end = babble_steps.min(run.total_steps);
    let spread = cfg.babble.spread_for(n);
    while run.steps < babble_end {
        for i in 0..n {
            let (lo, hi) = (
                (q_min[i] + 0.05).max(home[i] - spread),
                (q_max[i] - 0.05).min(home[i] + spread),
            );
            target[i] = uniform(&mut run.rng, lo, hi);
        }
        let total = uniform(
            &mut run.rng,
            cfg.babble.move_time[0],
            cfg.babble.move_time[1],
        );
        run.pd_move(
            &target,
            total,
            cfg.babble.settle,
            cfg.babble.noise,
            babble_end,
            evaluate,
            observe,
            &mut progress,
        )?;
    }
    // Phase 2: on-policy learning along the task, episodes from home.
    progress.phase = "on-policy";
    run.learning = cfg.learn_on_policy;
    let gravity_on = run.learner.config().experimental.gravity_on_policy;
    run.learner.freeze_gravity(!gravity_on);
    let mut xdd_ref = vec![0.0; m];
    // The previous command of this episode (for the largest command step), if any.
    let mut last_u = run.u.clone();
    let mut have_last = false;
    let mut max_step: f64 = 0.0;
    while !run.done() {
        // Return home (and settle) when not at rest there.
        let off = run
            .prev
            .q
            .iter()
            .zip(&home)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        if off > 0.01 || run.prev.qd.amax() > 0.01 {
            let limit = run.total_steps;
            run.learning = cfg.learn_on_policy && cfg.learn_returning_home;
            run.pd_move(
                &home,
                2.0,
                1.0,
                0.0,
                limit,
                evaluate,
                observe,
                &mut progress,
            )?;
            have_last = false;
            continue;
        }
        run.learning = cfg.learn_on_policy;
        progress.episodes += 1;
        let k_ep = (cfg.episode_seconds / dt).round() as u64;
        for k in 0..k_ep {
            if run.done() {
                break;
            }
            let t = k as f64 * dt;
            let prev = run.prev.clone();
            reference(traj, &cfg.gains, axes, &prev, t, &mut xdd_ref);
            let rng = if cfg.explore {
                Some(&mut run.rng)
            } else {
                None
            };
            run.learner.command(
                prev.q.as_slice(),
                prev.qd.as_slice(),
                &xdd_ref,
                rng,
                &mut run.u,
            )?;
            if have_last {
                max_step = max_step.max(crate::eval::max_abs_diff(&last_u, &run.u));
            }
            last_u.copy_from_slice(&run.u);
            have_last = true;
            run.step(evaluate, observe, &mut progress)?;
            let target = traj.sample(t + dt);
            let err = axes
                .iter()
                .enumerate()
                .map(|(k, &a)| (run.prev.x[k] - target.x[a]).powi(2))
                .sum::<f64>()
                .sqrt();
            if err > cfg.reset_error {
                progress.aborted_episodes += 1;
                break;
            }
        }
        have_last = false;
        progress.max_command_step = max_step;
    }
    // Final evaluation, unless the schedule just made one at this very step.
    if run
        .curve
        .last()
        .is_none_or(|(t, _)| (*t - run.minutes()).abs() > 1e-12)
    {
        let e = evaluate(run.learner)?;
        run.curve.push((run.minutes(), e.clone()));
        progress.sim_minutes = run.minutes();
        progress.eval = Some(e);
        progress.n_local_models = run.learner.n_local_models();
        progress.n_trained = run.learner.n_trained();
        observe(&progress);
    }
    let wall_seconds = wall.elapsed().as_secs_f64();
    Ok(TrainSummary {
        sim_training_minutes: run.minutes(),
        wall_seconds,
        realtime_factor: run.minutes() * 60.0 / wall_seconds.max(1e-9),
        episodes: progress.episodes,
        aborted_episodes: progress.aborted_episodes,
        learning_curve: run.curve,
        max_command_step: max_step,
        stats: run.learner.stats(),
        n_local_models: run.learner.n_local_models(),
    })
}
