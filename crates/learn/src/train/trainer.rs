//! The training driver's state (argmin style: state + driver + observer): the robot, the learner,
//! the clock, the evaluation schedule and the run's counters. Its phases are in `babble.rs` and
//! `on_policy.rs`; [`Trainer::run`] reads as the list of them.

use super::curriculum::Curriculum;
use super::observer::{EpisodeRecord, Observer, Phase, Progress};
use super::paths::{check_start, PathSource};
use super::safety::{StepMonitor, StepPoint};
use super::TrainConfig;
use crate::config::scaled;
use crate::error::{LearnError, Result};
use crate::eval::EvalResult;
use crate::learner::{Learner, LearnerStats, RateLimiter};
use osrl_control::Trajectory;
use osrl_dynamics::{Measurement, Robot};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
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
    /// Episodes ended early by braking the path clock on a growing task error.
    #[serde(default)]
    pub braked_episodes: u64,
    /// Of the braked episodes, those braked on a command jump (`curriculum.brake_step`); the
    /// others braked on the task error (`curriculum.brake_error`).
    #[serde(default)]
    pub braked_on_step: u64,
    /// Of those, per joint: the episodes whose refused command jumped first on that joint.
    #[serde(default)]
    pub braked_on_step_by_joint: Vec<u64>,
    /// `(simulated minutes, evaluation)` pairs.
    pub learning_curve: Vec<(f64, EvalResult)>,
    /// Largest change of a joint's command between consecutive on-policy commands (N·m),
    /// exploration and the switches to and from the returns home included.
    pub max_command_step: f64,
    /// The same as a rate: `max_command_step / dt` (N·m/s).
    #[serde(default)]
    pub max_torque_rate: f64,
    /// Commands the training driver held to the torque-rate limit (it applies the limit to
    /// every command it sends; the learner's own count is in `stats.rate_limited`).
    #[serde(default)]
    pub driver_rate_limited: u64,
    /// On-policy commands held to `TrainConfig::command_step_limit`.
    #[serde(default)]
    pub step_limited: u64,
    /// The largest on-policy command step per bin of simulated time.
    #[serde(default)]
    pub step_curve: Vec<StepPoint>,
    /// Commands clipped to the torque limits in the on-policy phase (the learner's and the
    /// driver's: every command sent is clipped).
    #[serde(default)]
    pub clipped_on_policy: u64,
    pub stats: LearnerStats,
    pub n_local_models: usize,
    /// On-policy episodes that started although the return home before them had not settled
    /// within `home_hold_seconds` (`home_tolerance`).
    #[serde(default)]
    pub unsettled_starts: u64,
    /// On-policy periods in which the task-space disturbance observer's estimate was held to
    /// `adaptation.observer_max` (0 with the observer off).
    #[serde(default)]
    pub observer_saturated: u64,
    /// Times the re-adapting learner was restored to its state after the last completed
    /// episode, after `adaptation.rollback_after` failed episodes in a row (`rollback.rs`).
    #[serde(default)]
    pub rollbacks: u64,
    /// Episode paths drawn from a path source (0 when every episode ran the task path).
    #[serde(default)]
    pub paths_drawn: u64,
    /// Every on-policy episode: start, curriculum stage, length, error, outcome.
    #[serde(default)]
    pub episode_log: Vec<EpisodeRecord>,
}

impl TrainSummary {
    /// The simulated minute of the first evaluation that did not diverge and meets `pred`
    /// (`None` if none did).
    pub fn minutes_to(&self, pred: impl Fn(&EvalResult) -> bool) -> Option<f64> {
        self.learning_curve
            .iter()
            .find(|(_, e)| !e.diverged && pred(e))
            .map(|(t, _)| *t)
    }

    /// The simulated minute from which every evaluation on (it included) did not diverge and
    /// meets `pred` (`None` if the last one does not): unlike [`Self::minutes_to`], a relapse
    /// after a first success counts.
    pub fn minutes_to_stay(&self, pred: impl Fn(&EvalResult) -> bool) -> Option<f64> {
        let ok = |e: &EvalResult| !e.diverged && pred(e);
        let bad = self.learning_curve.iter().rposition(|(_, e)| !ok(e));
        let from = bad.map_or(0, |i| i + 1);
        self.learning_curve.get(from).map(|(t, _)| *t)
    }

    /// Commands held to the torque-rate limit, by the learner or by the driver, or to the
    /// on-policy step limit (`TrainConfig::command_step_limit`).
    pub fn rate_limited(&self) -> u64 {
        self.stats.rate_limited + self.driver_rate_limited + self.step_limited
    }
}

/// Evaluates the learner (without exploration or learning) and returns the metrics.
pub type Evaluate<'a> = dyn FnMut(&mut Learner) -> Result<EvalResult> + 'a;

/// A training run in progress.
pub struct Trainer<'a, R: Robot + ?Sized> {
    pub(super) robot: &'a mut R,
    pub(super) learner: &'a mut Learner,
    pub(super) traj: &'a Trajectory,
    /// The source of the episodes' paths (`None`: every episode runs `traj`) and the current
    /// episode's path.
    paths: Option<&'a mut dyn PathSource>,
    pub(super) episode_path: Trajectory,
    pub(super) axes: &'a [usize],
    pub(super) cfg: &'a TrainConfig,
    evaluate: &'a mut Evaluate<'a>,
    observer: &'a mut dyn Observer,
    /// Home posture (at rest on the path start) and joint limits (rad).
    pub(super) home: Vec<f64>,
    pub(super) q_min: Vec<f64>,
    pub(super) q_max: Vec<f64>,
    /// The last measurement and the command being sent.
    pub(super) prev: Measurement,
    /// The buffer the next measurement is copied into (swapped with `prev` after each step, so
    /// that a step does not allocate).
    cur: Measurement,
    pub(super) u: Vec<f64>,
    pub(super) rng: ChaCha8Rng,
    /// Control period (s), control steps per simulated minute, steps done and in all.
    pub(super) dt: f64,
    pub(super) per_min: u64,
    pub(super) steps: u64,
    pub(super) total_steps: u64,
    next_eval: u64,
    eval_steps: u64,
    /// Whether the transitions are learned from.
    pub(super) learning: bool,
    curve: Vec<(f64, EvalResult)>,
    pub(super) progress: Progress,
    /// The on-policy command steps, and the learner's clipped count when on-policy began.
    pub(super) steps_seen: StepMonitor,
    pub(super) clipped_before: u64,
    /// On-policy commands of the driver (fades, returns home) clipped to the torque limits.
    driver_clipped: u64,
    /// Whether a command that jumps by more than `curriculum.brake_step` from the last one is
    /// refused (during episodes), and whether one was since the flag was last cleared.
    pub(super) jump_guard: bool,
    /// The per-joint jump (N·m) that brakes an episode (`curriculum.brake_step`, or computed).
    brake_steps: Vec<f64>,
    /// Refused jumps per joint (the first joint over its step).
    jumps_by_joint: Vec<u64>,
    pub(super) jumped: bool,
    /// The joint of the first refused jump since `jumped` was last cleared.
    pub(super) jump_joint: Option<usize>,
    /// The on-policy episodes so far.
    pub(super) episode_log: Vec<EpisodeRecord>,
    /// The torque-rate limit on the driver's own (PD) commands, and how often it acted.
    pub(super) rate: RateLimiter,
    pub(super) rate_limited: u64,
    /// On-policy commands held to `command_step_limit`.
    step_limited: u64,
    /// The babbling noise process (unit variance per joint).
    pub(super) babble_noise: Vec<f64>,
    /// The integral of the joint error while holding home (rad·s), and the returns home that
    /// did not settle within the hold (the episode started anyway).
    pub(super) integral: Vec<f64>,
    pub(super) unsettled_starts: u64,
    /// The curriculum's current stage.
    pub(super) curriculum: Curriculum,
    /// The fade between command sources: the command it starts from and the steps left.
    fade_from: Vec<f64>,
    fade_left: u64,
    fade_len: u64,
    /// The next PD move starts its reference at this velocity (rad/s; then cleared), set on
    /// the way home after a braked episode (`brake_return_from_velocity`).
    pub(super) move_v0: Option<Vec<f64>>,
    /// The task-space disturbance observer of the episodes (`adaptation.observer_seconds`).
    pub(super) dob: crate::Dob,
    /// Whether the last command sent differed from the learner's: faded, clipped, refused by
    /// the jump guard, step or rate limited (the observer does not learn from its response).
    pub(super) sent_modified: bool,
    /// Paths drawn from the source.
    paths_drawn: u64,
    /// The recorded path postures of `posture_holds`, and whether the transitions teach the
    /// static gravity model alone (while `learning` is false: the holds at those postures).
    pub(super) postures: super::posture_holds::PosturePool,
    pub(super) static_only: bool,
    /// The checkpoint of the re-adapting learner and the rollbacks to it (`rollback.rs`).
    pub(super) rollback: super::rollback::Rollback,
    /// Whether the on-policy phase continues a trained learner (no babbling before it).
    pub(super) continuation: bool,
    wall: Instant,
}

impl<'a, R: Robot + ?Sized> Trainer<'a, R> {
    /// A run of `learner` on `robot` (at rest at its home posture on the path start) along
    /// `traj`, whose world axes `axes` are the task; `evaluate` is called every
    /// `cfg.eval_every_minutes` and at the end, `observer` sees the progress.
    ///
    /// # Errors
    /// An invalid `cfg`, or a robot, learner and task axes that do not match.
    pub fn new(
        robot: &'a mut R,
        learner: &'a mut Learner,
        traj: &'a Trajectory,
        axes: &'a [usize],
        cfg: &'a TrainConfig,
        evaluate: &'a mut Evaluate<'a>,
        observer: &'a mut dyn Observer,
    ) -> Result<Self> {
        let wall = Instant::now();
        cfg.validate()?;
        let dt = robot.control_period();
        let (n, m) = learner.dims();
        if robot.dof() != n || robot.task_dim() != m || axes.len() != m {
            return Err(LearnError::InvalidConfig(format!(
                "robot ({} joints, {}-D task), learner ({n}, {m}) and task axes {axes:?} do not \
                 match",
                robot.dof(),
                robot.task_dim()
            )));
        }
        let g = &learner.config().guards;
        let rates = scaled::torque_rate_limits(g.torque_rate_limit, &g.torque_limits, n);
        let dob = learner.observer();
        let rate = RateLimiter::new(&rates, dt);
        let brake_steps = scaled::brake_steps(cfg.curriculum.brake_step, &g.torque_limits, n);
        let prev = robot.measurement().clone();
        let (q_min, q_max) = robot.joint_limits();
        let (q_min, q_max) = (q_min.to_vec(), q_max.to_vec());
        let per_min = (60.0 / dt).round() as u64;
        let eval_steps = (cfg.eval_every_minutes * per_min as f64).round() as u64;
        Ok(Self {
            home: prev.q.as_slice().to_vec(),
            cur: prev.clone(),
            prev,
            robot,
            learner,
            traj,
            paths: None,
            episode_path: traj.clone(),
            axes,
            cfg,
            evaluate,
            observer,
            q_min,
            q_max,
            u: vec![0.0; n],
            rng: ChaCha8Rng::seed_from_u64(cfg.seed),
            dt,
            per_min,
            steps: 0,
            total_steps: (cfg.minutes * per_min as f64).round() as u64,
            next_eval: eval_steps,
            eval_steps,
            learning: true,
            curve: Vec::new(),
            progress: Progress::start(),
            steps_seen: StepMonitor::new(n, dt),
            clipped_before: 0,
            driver_clipped: 0,
            jump_guard: false,
            brake_steps,
            jumps_by_joint: vec![0; n],
            jumped: false,
            jump_joint: None,
            episode_log: Vec::new(),
            rate,
            rate_limited: 0,
            step_limited: 0,
            babble_noise: vec![0.0; n],
            integral: vec![0.0; n],
            unsettled_starts: 0,
            curriculum: Curriculum::new(&cfg.curriculum),
            fade_from: vec![0.0; n],
            fade_left: 0,
            dob,
            sent_modified: false,
            fade_len: 1,
            move_v0: None,
            paths_drawn: 0,
            postures: Default::default(),
            static_only: false,
            rollback: Default::default(),
            continuation: false,
            wall,
        })
    }

    /// This run with one path per on-policy episode drawn from `paths` (each starting where
    /// `traj` starts) instead of `traj` every time; evaluations are the caller's as before.
    pub fn with_paths(mut self, paths: &'a mut dyn PathSource) -> Self {
        self.paths = Some(paths);
        self
    }

    /// The next episode's path into `episode_path` (a new one from the source, if any).
    pub(super) fn next_path(&mut self) -> Result<()> {
        if let Some(src) = self.paths.as_mut() {
            let p = src.next_path()?;
            check_start(&p, self.traj, self.axes)?;
            self.episode_path = p;
            self.paths_drawn += 1;
        }
        Ok(())
    }

    /// The run: babbling, on-policy learning, the final evaluation.
    ///
    /// # Errors
    /// The first robot, learner or evaluation error.
    pub fn run(mut self) -> Result<TrainSummary> {
        // Only a continuation freezes the static gravity model (`on_policy`); a learner that
        // ran one before learns again here.
        self.learner.freeze_static_gravity(false);
        self.babble()?;
        self.on_policy()?;
        self.final_evaluation()?;
        Ok(self.summary())
    }

    pub(super) fn minutes(&self) -> f64 {
        self.steps as f64 * self.dt / 60.0
    }

    pub(super) fn done(&self) -> bool {
        self.steps >= self.total_steps
    }

    /// Starts a fade from the command last sent to whatever comes next (a switch of source).
    pub(super) fn begin_fade(&mut self, seconds: f64) {
        self.fade_from.copy_from_slice(&self.u);
        self.fade_left = (seconds / self.dt).round() as u64;
        self.fade_len = self.fade_left.max(1);
    }

    /// Blends `self.u` with the command the fade started from, `smoothstep` over its length.
    fn fade(&mut self) {
        if self.fade_left == 0 {
            return;
        }
        let a = crate::local::smoothstep(1.0 - self.fade_left as f64 / self.fade_len as f64);
        for (u, f) in self.u.iter_mut().zip(&self.fade_from) {
            *u = (1.0 - a) * f + a * *u;
        }
        self.fade_left -= 1;
    }

    /// Applies `self.u` (faded, if a fade is on) for one period, learns from the transition,
    /// evaluates when due; in the on-policy phase also measures the command step.
    pub(super) fn step(&mut self) -> Result<()> {
        let faded = self.fade_left > 0;
        self.fade();
        let limits = &self.learner.config().guards.torque_limits;
        let mut clipped = false;
        for (u, lim) in self.u.iter_mut().zip(limits) {
            clipped |= u.abs() > *lim;
            *u = u.clamp(-lim, *lim);
        }
        if clipped && self.progress.phase == Phase::OnPolicy {
            self.driver_clipped += 1;
        }
        let (mut refused, mut step_limited) = (false, false);
        if let Some(j) = self
            .jump_guard
            .then(|| self.steps_seen.jump(&self.u, &self.brake_steps))
            .flatten()
        {
            // Refused: the previous command again, and the episode brakes.
            self.steps_seen.repeat_last(&mut self.u);
            refused = true;
            self.jumped = true;
            self.jump_joint.get_or_insert(j);
            self.jumps_by_joint[j] += 1;
        }
        if let Some(limit) = self.cfg.command_step_limit {
            if self.progress.phase == Phase::OnPolicy
                && self.steps_seen.limit_step(&mut self.u, limit)
            {
                self.step_limited += 1;
                step_limited = true;
            }
        }
        let rate_limited = self.rate.apply(&mut self.u);
        if rate_limited {
            self.rate_limited += 1;
        }
        self.sent_modified = faded || clipped || refused || step_limited || rate_limited;
        if self.progress.phase == Phase::OnPolicy {
            self.steps_seen.sent(&self.u);
        }
        self.cur.copy_from(self.robot.step(&self.u)?);
        self.steps += 1;
        self.steps_seen.tick(self.steps, self.per_min);
        if self.learning && self.steps.is_multiple_of(self.cfg.learn_every as u64) {
            match self.learner.learn(&self.prev, &self.cur) {
                Ok(()) | Err(LearnError::BadMeasurement(_)) => {}
                Err(e) => return Err(e),
            }
        } else if self.static_only {
            match self.learner.learn_static_gravity(&self.prev, &self.cur) {
                Ok(()) | Err(LearnError::BadMeasurement(_)) => {}
                Err(e) => return Err(e),
            }
        }
        std::mem::swap(&mut self.prev, &mut self.cur);
        if self.eval_steps > 0 && self.steps >= self.next_eval {
            self.next_eval += self.eval_steps;
            self.evaluate_now()?;
        }
        Ok(())
    }

    /// One evaluation, recorded on the learning curve and shown to the observer.
    fn evaluate_now(&mut self) -> Result<()> {
        let e = (self.evaluate)(self.learner)?;
        self.curve.push((self.minutes(), e.clone()));
        self.progress.sim_minutes = self.minutes();
        self.progress.eval = Some(e);
        self.progress.n_local_models = self.learner.n_local_models();
        self.progress.n_trained = self.learner.n_trained();
        self.observer.evaluated(&self.progress);
        Ok(())
    }

    /// Shows the end of an episode to the observer.
    pub(super) fn episode_ended(&mut self) {
        self.progress.sim_minutes = self.minutes();
        self.progress.max_command_step = self.steps_seen.max_step;
        self.observer.episode_ended(&self.progress);
    }

    /// The final evaluation, unless the schedule just made one at this very step.
    fn final_evaluation(&mut self) -> Result<()> {
        let now = self.minutes();
        if self
            .curve
            .last()
            .is_none_or(|(t, _)| (*t - now).abs() > 1e-12)
        {
            self.evaluate_now()?;
        }
        Ok(())
    }

    fn summary(mut self) -> TrainSummary {
        self.steps_seen.close(self.steps, self.per_min);
        let wall_seconds = self.wall.elapsed().as_secs_f64();
        let minutes = self.minutes();
        TrainSummary {
            sim_training_minutes: minutes,
            wall_seconds,
            realtime_factor: minutes * 60.0 / wall_seconds.max(1e-9),
            episodes: self.progress.episodes,
            aborted_episodes: self.progress.aborted_episodes,
            braked_episodes: self.progress.braked_episodes,
            braked_on_step: self.progress.braked_on_step,
            braked_on_step_by_joint: std::mem::take(&mut self.jumps_by_joint),
            learning_curve: self.curve,
            max_command_step: self.steps_seen.max_step,
            max_torque_rate: self.steps_seen.max_step / self.dt,
            step_curve: std::mem::take(&mut self.steps_seen.curve),
            clipped_on_policy: self.learner.stats().clipped - self.clipped_before
                + self.driver_clipped,
            driver_rate_limited: self.rate_limited,
            step_limited: self.step_limited,
            stats: self.learner.stats(),
            n_local_models: self.learner.n_local_models(),
            unsettled_starts: self.unsettled_starts,
            observer_saturated: self.dob.saturated(),
            rollbacks: self.rollback.count,
            paths_drawn: self.paths_drawn,
            episode_log: std::mem::take(&mut self.episode_log),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Trainer;
    use crate::learner::fixture;
    use crate::train::{Observer, Phase, Progress, TrainConfig};
    use crate::Learner;
    use osrl_control::TrajectoryConfig;
    use osrl_dynamics::robots;

    #[derive(Default)]
    struct Log {
        evaluations: Vec<(f64, Phase)>,
        episodes: u64,
    }
    impl Observer for Log {
        fn evaluated(&mut self, p: &Progress) {
            self.evaluations.push((p.sim_minutes, p.phase));
        }
        fn episode_ended(&mut self, _: &Progress) {
            self.episodes += 1;
        }
    }

    /// The evaluations follow the schedule (and one at the end, not twice), the observer sees
    /// both phases, and an episode whose error exceeds `reset_error` is counted as aborted.
    #[test]
    fn the_schedule_phases_and_aborts_are_reported() {
        let model = robots::planar3();
        let traj = TrajectoryConfig::default().build(&model).unwrap();
        let mut sim = fixture::robot();
        let mut learner = Learner::new(3, 2, 0.002, fixture::config()).unwrap();
        let cfg = TrainConfig {
            eval_every_minutes: 0.15,
            // Tiny: every on-policy episode from rest aborts at once (the path starts elsewhere).
            reset_error: 1e-9,
            ..fixture::short_training(0.7)
        };
        let axes = model.task_axes().to_vec();
        let mut evaluate = |_: &mut Learner| Ok(Default::default());
        let mut log = Log::default();
        let summary = Trainer::new(
            &mut sim,
            &mut learner,
            &traj,
            &axes,
            &cfg,
            &mut evaluate,
            &mut log,
        )
        .unwrap()
        .run()
        .unwrap();
        let minutes: Vec<f64> = log.evaluations.iter().map(|e| e.0).collect();
        assert_eq!(minutes.len(), 5, "{minutes:?}");
        assert!((minutes[0] - 0.15).abs() < 1e-9 && (minutes[4] - 0.7).abs() < 1e-9);
        assert_eq!(log.evaluations[0].1, Phase::Babbling);
        assert_eq!(log.evaluations[4].1, Phase::OnPolicy);
        assert!(summary.episodes > 0, "{summary:?}");
        assert_eq!(summary.aborted_episodes, summary.episodes);
        // The log has every episode, each aborted, in order of its start, at stage 0.
        assert_eq!(summary.episode_log.len() as u64, summary.episodes);
        assert!(summary
            .episode_log
            .iter()
            .all(|e| e.outcome == crate::train::EpisodeOutcome::Aborted
                && e.stage == 0
                && e.jump_joint.is_none()));
        assert!(summary
            .episode_log
            .windows(2)
            .all(|w| w[0].start_minute < w[1].start_minute));
        assert!(summary.episode_log[0].start_minute >= 0.4 - 1e-9);
        assert_eq!(log.episodes, summary.episodes);
        assert_eq!(summary.learning_curve.len(), 5);
        // The fixture's evaluations are all the default (0 mm, not diverged): met from the
        // first one on; a predicate the last one misses is never met for good.
        let first = summary.learning_curve[0].0;
        assert_eq!(summary.minutes_to_stay(|_| true), Some(first));
        assert_eq!(summary.minutes_to_stay(|_| false), None);
        let mut relapse = summary.clone();
        let diverged = crate::eval::EvalResult {
            diverged: true,
            ..Default::default()
        };
        relapse.learning_curve = vec![
            (0.25, Default::default()),
            (0.5, diverged),
            (0.75, Default::default()),
        ];
        assert_eq!(relapse.minutes_to(|_| true), Some(0.25));
        assert_eq!(relapse.minutes_to_stay(|_| true), Some(0.75));
        // The learner's ĝ is frozen once on-policy learning starts.
        assert!(learner.gravity_frozen());
    }
}
