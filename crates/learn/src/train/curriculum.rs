//! The curriculum of the on-policy phase (`docs/learner.md`, "Safe learning"): episodes start on
//! a shrunken, slowed copy of the task path — where the babbling data already reach — and move
//! to the next stage after an episode that tracked well, back after an aborted one. Each episode
//! runs on a path clock that stops smoothly now and then and at the end, holding the target still
//! for a moment: the still samples teach the static gravity model along the path, and the end of
//! an episode is at rest.

use crate::error::{LearnError, Result};
use osrl_control::{Target, Trajectory};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

/// Settings of the curriculum and of the path clock.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CurriculumConfig {
    /// Stages `[amplitude, speed]`, first to last: the path shrunk about its start point by
    /// `amplitude` and run at `speed` times its pace. The last stage should be `[1, 1]` (the task
    /// itself). Empty: the task from the start. Default `[[0.25, 0.5], [0.5, 0.7], [0.75, 0.85],
    /// [1, 1]]`: accelerations from 6 % of the task's up.
    pub stages: Vec<[f64; 2]>,
    /// An episode that was not aborted and whose RMS tracking error stayed below this (m)
    /// advances the curriculum by one stage; an aborted one goes back one. Default 0.002.
    pub advance_error: f64,
    /// Mean time between stops of the path clock (s of episode, each interval drawn uniformly
    /// in [0.5, 1.5] times it); 0: stop only at the end, else at least [`MIN_STOP_EVERY`].
    /// Default 8.
    pub stop_every: f64,
    /// Time to decelerate the path to rest and to accelerate it again (s; at most
    /// [`MAX_STOP_SECONDS`]). Default 0.5.
    pub stop_seconds: f64,
    /// Time the target is held still at a stop (s; at most [`MAX_STOP_SECONDS`]). Default 1:
    /// the arm comes to rest.
    pub hold_seconds: f64,
    /// When the task error exceeds this (m), the episode ends at once and the PD return home
    /// takes over (counted as braked; the curriculum goes back a stage), before the error can
    /// reach `reset_error`. Default 0.01: a controller that leaves its trained region diverges
    /// within a fraction of a second, so the hand-over comes while it still tracks.
    pub brake_error: f64,
    /// A command that would change a joint's torque by more than this from the last command
    /// sent (N·m, every joint) is not sent (the last one is repeated) and the episode brakes the
    /// same way. Default `None`: computed per joint from its torque limit
    /// (`osrl_learn::config::scaled`): 1 N·m up to 100 N·m — well above the exploration's steps
    /// (below 0.5 N·m on the built-in arms), half the torque-rate limit's 2 N·m per 2 ms — and
    /// in proportion above; a controller that starts to oscillate is stopped at its first jump.
    pub brake_step: Option<f64>,
    /// A stage is left backwards after this many failed (braked or aborted) episodes in a row
    /// at it (≥ 1); the failures before retry the same stage. Default 1: back after every
    /// failure, as the curriculum was tuned on the built-in arms.
    pub retreat_after: usize,
}

impl Default for CurriculumConfig {
    fn default() -> Self {
        Self {
            stages: vec![[0.25, 0.5], [0.5, 0.7], [0.75, 0.85], [1.0, 1.0]],
            advance_error: 0.002,
            stop_every: 8.0,
            stop_seconds: 0.5,
            hold_seconds: 1.0,
            brake_error: 0.01,
            brake_step: None,
            retreat_after: 1,
        }
    }
}

/// Shortest mean time between the path clock's stops (s), unless 0 (no stops).
pub const MIN_STOP_EVERY: f64 = 0.5;
/// Longest deceleration or hold of a stop (s).
pub const MAX_STOP_SECONDS: f64 = 60.0;

impl CurriculumConfig {
    /// Checks every field's range.
    ///
    /// # Errors
    /// [`LearnError::InvalidConfig`] naming the field.
    pub fn validate(&self) -> Result<()> {
        let bad = |m: String| Err(LearnError::InvalidConfig(m));
        for (i, [a, s]) in self.stages.iter().enumerate() {
            if !(*a > 0.0 && *a <= 1.0 && *s > 0.0 && *s <= 1.0) {
                return bad(format!(
                    "curriculum.stages[{i}] = [{a}, {s}]: amplitude and speed must be in (0, 1]"
                ));
            }
        }
        // (field, value, whether 0 is accepted, largest value): an episode's path is built
        // ahead, a few segments per stop, so stops are at least `MIN_STOP_EVERY` apart.
        let fields = [
            ("advance_error", self.advance_error, false, f64::MAX),
            ("stop_seconds", self.stop_seconds, false, MAX_STOP_SECONDS),
            ("hold_seconds", self.hold_seconds, true, MAX_STOP_SECONDS),
            ("brake_error", self.brake_error, false, f64::MAX),
            (
                "brake_step",
                self.brake_step.unwrap_or(1.0),
                false,
                f64::MAX,
            ),
        ];
        if self.retreat_after == 0 {
            return bad("curriculum.retreat_after = 0: must be at least 1".into());
        }
        for (what, v, zero_ok, hi) in fields {
            if !(v <= hi && (v > 0.0 || (zero_ok && v == 0.0))) {
                return bad(format!(
                    "curriculum.{what} = {v:?} is out of range ({} and at most {hi:?})",
                    if zero_ok { "≥ 0" } else { "> 0" }
                ));
            }
        }
        let e = self.stop_every;
        if !(e == 0.0 || (MIN_STOP_EVERY..=f64::MAX).contains(&e)) {
            return bad(format!(
                "curriculum.stop_every = {e} is out of range (0: no stops, or at least \
                 {MIN_STOP_EVERY} s, finite)"
            ));
        }
        Ok(())
    }
}

/// A segment of the path clock: the rate `τ̇` goes from `from` to `to` (times the stage's speed)
/// over `seconds`, by a half cosine (constant when equal).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Segment {
    start: f64,
    seconds: f64,
    from: f64,
    to: f64,
    /// Path time at the segment's start.
    tau0: f64,
}

impl Segment {
    /// `(τ, τ̇, τ̈)` at episode time `t` inside the segment (rates relative to the stage speed).
    fn at(&self, t: f64) -> (f64, f64, f64) {
        let s = (t - self.start).clamp(0.0, self.seconds);
        let (a, b, len) = (self.from, self.to, self.seconds);
        let w = std::f64::consts::PI / len;
        // τ̇ = a + (b − a)(1 − cos(w s))/2
        let rate = a + (b - a) * 0.5 * (1.0 - (w * s).cos());
        let acc = (b - a) * 0.5 * w * (w * s).sin();
        let tau = self.tau0 + a * s + (b - a) * 0.5 * (s - (w * s).sin() / w);
        (tau, rate, acc)
    }

    fn end_tau(&self) -> f64 {
        self.at(self.start + self.seconds).0
    }
}

/// Which of the path clock's holds are quiet: the exploration fades out with the clock's rate
/// as it stops and is 0 while it holds, so the hold gives the static gravity model still
/// samples of an arm that is not shaken (`docs/decisions.md`, D20).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum QuietHolds {
    /// Exploration everywhere (the holds give the local dynamics excitation at rest).
    None,
    /// The final stop of each episode only.
    Final,
    /// Every stop.
    All,
}

/// The path of one episode: the task path at a curriculum stage on a clock with stops.
#[derive(Clone, Debug)]
pub(crate) struct EpisodePath {
    amplitude: f64,
    speed: f64,
    x0: nalgebra::Vector3<f64>,
    segments: Vec<Segment>,
    /// Episode length (s), the final stop and hold included.
    pub seconds: f64,
    /// Start of the final stop (s): its deceleration and hold.
    final_stop: f64,
}

impl EpisodePath {
    /// An episode of `cruise` seconds of path at `stage` (`[amplitude, speed]`), stopping
    /// about every `cfg.stop_every` seconds (intervals drawn from `rng`) and at the end.
    pub fn new(
        traj: &Trajectory,
        stage: [f64; 2],
        cruise: f64,
        cfg: &CurriculumConfig,
        rng: &mut ChaCha8Rng,
    ) -> Self {
        let (ts, th) = (cfg.stop_seconds, cfg.hold_seconds);
        let mut segments = Vec::new();
        let (mut t, mut tau) = (0.0, 0.0);
        let push = |segments: &mut Vec<Segment>,
                    t: &mut f64,
                    tau: &mut f64,
                    len: f64,
                    from: f64,
                    to: f64| {
            let seg = Segment {
                start: *t,
                seconds: len,
                from,
                to,
                tau0: *tau,
            };
            *tau = seg.end_tau();
            *t += len;
            segments.push(seg);
        };
        let mut left = cruise;
        loop {
            let run = if cfg.stop_every > 0.0 {
                cfg.stop_every * rng.random_range(0.5..1.5)
            } else {
                f64::INFINITY
            };
            if run >= left {
                push(&mut segments, &mut t, &mut tau, left.max(1e-9), 1.0, 1.0);
                break;
            }
            push(&mut segments, &mut t, &mut tau, run, 1.0, 1.0);
            push(&mut segments, &mut t, &mut tau, ts, 1.0, 0.0);
            if th > 0.0 {
                push(&mut segments, &mut t, &mut tau, th, 0.0, 0.0);
            }
            push(&mut segments, &mut t, &mut tau, ts, 0.0, 1.0);
            left -= run;
        }
        let final_stop = t;
        push(&mut segments, &mut t, &mut tau, ts, 1.0, 0.0);
        if th > 0.0 {
            push(&mut segments, &mut t, &mut tau, th, 0.0, 0.0);
        }
        Self {
            final_stop,
            amplitude: stage[0],
            speed: stage[1],
            x0: traj.sample(0.0).x,
            segments,
            seconds: t,
        }
    }

    fn segment(&self, t: f64) -> usize {
        self.segments
            .partition_point(|s| s.start <= t)
            .saturating_sub(1)
    }

    /// The clock's rate `τ̇` at episode time `t` relative to the stage speed: 1 while cruising,
    /// 0 while holding, a half cosine in between.
    pub fn rate(&self, t: f64) -> f64 {
        self.segments[self.segment(t)].at(t).1
    }

    /// The exploration's gain at episode time `t` under `quiet` (`TrainConfig::quiet_holds`):
    /// `floor + (1 − floor) τ̇` with the clock's rate `τ̇` where the holds are quiet (all of them,
    /// or the final one from its deceleration on), 1 elsewhere.
    pub fn exploration_gain(&self, t: f64, quiet: QuietHolds, floor: f64) -> f64 {
        match quiet {
            QuietHolds::None => 1.0,
            QuietHolds::Final if t < self.final_stop => 1.0,
            QuietHolds::Final | QuietHolds::All => floor + (1.0 - floor) * self.rate(t),
        }
    }

    /// The target at episode time `t`: `x0 + a (x(τ) − x0)` with `τ` the clock's path time
    /// (times the speed), and its derivatives by the chain rule.
    pub fn sample(&self, traj: &Trajectory, t: f64) -> Target {
        let (tau, rate, acc) = self.segments[self.segment(t)].at(t);
        let (v, a) = (self.speed, self.amplitude);
        let base = traj.sample(v * tau);
        let (r, rr) = (v * rate, v * acc);
        Target {
            x: self.x0 + a * (base.x - self.x0),
            xd: a * r * base.xd,
            xdd: a * (r * r * base.xdd + rr * base.xd),
        }
    }
}

/// Where the curriculum stands.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Curriculum {
    stages: Vec<[f64; 2]>,
    pub stage: usize,
    /// Failed episodes in a row at the current stage, and how many make it go back.
    failures: usize,
    retreat_after: usize,
}

impl Curriculum {
    pub fn new(cfg: &CurriculumConfig) -> Self {
        let stages = if cfg.stages.is_empty() {
            vec![[1.0, 1.0]]
        } else {
            cfg.stages.clone()
        };
        Self {
            stages,
            stage: 0,
            failures: 0,
            retreat_after: cfg.retreat_after.max(1),
        }
    }

    /// The current stage `[amplitude, speed]`.
    pub fn current(&self) -> [f64; 2] {
        self.stages[self.stage]
    }

    /// After an episode: forward on a good one, back after `retreat_after` aborted or braked
    /// ones in a row at the stage.
    pub fn after_episode(&mut self, failed: bool, rms_error: f64, advance_error: f64) {
        if failed {
            self.failures += 1;
            if self.failures >= self.retreat_after {
                self.stage = self.stage.saturating_sub(1);
                self.failures = 0;
            }
            return;
        }
        self.failures = 0;
        if rms_error < advance_error && self.stage + 1 < self.stages.len() {
            self.stage += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{CurriculumConfig, EpisodePath};
    use osrl_control::TrajectoryConfig;
    use osrl_dynamics::robots;
    use rand::SeedableRng;

    /// The episode's target is the scaled path, its velocity and acceleration are the
    /// derivatives of its position (finite differences), it stops and is held still, and at
    /// stage [1, 1] between stops it is the task path itself.
    #[test]
    fn the_episode_path_is_smooth_scaled_and_stops() {
        let model = robots::planar3();
        let traj = TrajectoryConfig::default().build(&model).unwrap();
        let cfg = CurriculumConfig::default();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let ep = EpisodePath::new(&traj, [0.5, 0.7], 20.0, &cfg, &mut rng);
        assert!(ep.seconds > 20.0 + 1.5);
        let h = 1e-5;
        let mut still = 0;
        for k in 1..(ep.seconds / 0.01) as usize - 1 {
            let t = k as f64 * 0.01;
            let (a, b, c) = (
                ep.sample(&traj, t - h),
                ep.sample(&traj, t),
                ep.sample(&traj, t + h),
            );
            let v = (c.x - a.x) / (2.0 * h);
            let acc = (c.xd - a.xd) / (2.0 * h);
            assert!((v - b.xd).norm() < 1e-5, "t {t}: {v} vs {}", b.xd);
            assert!((acc - b.xdd).norm() < 1e-3 * (1.0 + b.xdd.norm()), "t {t}");
            still += (b.xd.norm() == 0.0) as usize;
        }
        assert!(still > 100, "held still for {still} samples");
        // The end is at rest.
        let end = ep.sample(&traj, ep.seconds);
        assert_eq!((end.xd.norm(), end.xdd.norm()), (0.0, 0.0));
        // Full stage, before the first stop: the task path.
        let ep1 = EpisodePath::new(&traj, [1.0, 1.0], 20.0, &cfg, &mut rng);
        for t in [0.0, 0.7, 2.0] {
            let (a, b) = (ep1.sample(&traj, t), traj.sample(t));
            assert!((a.x - b.x).norm() < 1e-15 && (a.xdd - b.xdd).norm() < 1e-12);
        }
    }

    /// The exploration's gain under quiet holds: 1 everywhere without them; with all holds
    /// quiet it is `floor` wherever the target is held still and 1 while the path cruises; with
    /// the final one only, 1 before the final stop, `floor` in its hold; it never leaves
    /// [floor, 1] and changes smoothly (by the clock's half cosine).
    #[test]
    fn quiet_holds_fade_the_exploration_out_where_the_target_is_held() {
        use super::QuietHolds;
        let model = robots::planar3();
        let traj = TrajectoryConfig::default().build(&model).unwrap();
        let cfg = CurriculumConfig::default();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let ep = EpisodePath::new(&traj, [1.0, 1.0], 30.0, &cfg, &mut rng);
        let floor = 0.2;
        let (mut held, mut held_before_end, mut prev) = (0, 0, [1.0; 3]);
        for k in 0..(ep.seconds / 0.002) as usize {
            let t = k as f64 * 0.002;
            let g = [QuietHolds::None, QuietHolds::All, QuietHolds::Final]
                .map(|quiet| ep.exploration_gain(t, quiet, floor));
            assert_eq!(g[0], 1.0);
            for (a, b) in g.iter().zip(&prev) {
                assert!(
                    (floor..=1.0).contains(a) && (a - b).abs() < 0.01,
                    "t {t}: {g:?}"
                );
            }
            // The clock holds (the path's own start at rest does not count).
            let still = ep.rate(t) == 0.0;
            assert!(!still || ep.sample(&traj, t).xd.norm() == 0.0);
            if still {
                held += 1;
                assert!((g[1] - floor).abs() < 1e-12, "t {t}: {g:?}");
                if t < ep.final_stop {
                    held_before_end += 1;
                    assert_eq!(g[2], 1.0, "t {t}");
                } else {
                    assert!((g[2] - floor).abs() < 1e-12, "t {t}: {g:?}");
                }
            } else if t < ep.final_stop && ep.rate(t) == 1.0 {
                assert_eq!(g[1], 1.0, "t {t}");
            }
            prev = g;
        }
        assert!(
            held > 1000 && held_before_end > 100,
            "{held} {held_before_end}"
        );
    }

    /// Back a stage after every failure by default; with `retreat_after` 3 the same stage is
    /// retried twice, the third failure in a row goes back, and a good episode resets the count.
    #[test]
    fn the_curriculum_retreats_after_failures_in_a_row() {
        use super::Curriculum;
        let mut one = Curriculum::new(&CurriculumConfig::default());
        one.after_episode(false, 0.001, 0.002);
        one.after_episode(false, 0.001, 0.002);
        assert_eq!(one.stage, 2);
        one.after_episode(true, 0.0, 0.002);
        assert_eq!(one.stage, 1);
        let cfg = CurriculumConfig {
            retreat_after: 3,
            ..CurriculumConfig::default()
        };
        let mut three = Curriculum::new(&cfg);
        three.after_episode(false, 0.001, 0.002);
        three.after_episode(false, 0.001, 0.002);
        assert_eq!(three.stage, 2);
        three.after_episode(true, 0.0, 0.002);
        three.after_episode(true, 0.0, 0.002);
        assert_eq!(three.stage, 2, "two failures retry the stage");
        // A good but slow episode (no advance) resets the count.
        three.after_episode(false, 0.005, 0.002);
        three.after_episode(true, 0.0, 0.002);
        three.after_episode(true, 0.0, 0.002);
        assert_eq!(three.stage, 2);
        three.after_episode(true, 0.0, 0.002);
        assert_eq!(three.stage, 1, "the third failure in a row goes back");
        assert!(CurriculumConfig {
            retreat_after: 0,
            ..CurriculumConfig::default()
        }
        .validate()
        .is_err());
    }
}
