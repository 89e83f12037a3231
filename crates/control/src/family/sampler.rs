//! The seeded family sampler: draws figure-8s, circles and minimum-jerk paths of random centre,
//! size, in-plane orientation and speed inside the region, and keeps only those the arm can
//! follow — reachable by IK inside the joint limits, and tracked by eq. 7 with the true model
//! from home inside the torque limits — redrawing the others.

use super::region::{path_points, Region};
use super::FamilyConfig;
use crate::error::{ControlError, Result};
use crate::ik::{check_reachable, IkOptions};
use crate::trajectory::Trajectory;
use crate::trajectory_config::{TrajectoryConfig, TrajectoryKind};
use crate::{Osc, OscConfig, TaskController};
use nalgebra::Vector3;
use osrl_dynamics::{Model, Robot, SimConfig, SimRobot};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::TAU;

/// One drawn path.
#[derive(Clone, Debug, PartialEq)]
pub struct FamilyPath {
    /// The path as a `[trajectory]` section (`osrl eval --config` runs it).
    pub config: TrajectoryConfig,
    /// The path itself, starting at rest on its own start.
    pub path: Trajectory,
    /// The path preceded by the minimum-jerk approach from the base's start (home's task
    /// point): what a training episode runs from home.
    pub approached: Trajectory,
    /// The posture at rest on the path's start ([`check_reachable`]): where an evaluation of
    /// the path alone starts.
    pub home: Vec<f64>,
    /// Peak task acceleration along the path (m/s²).
    pub peak_acceleration: f64,
    /// Largest share of a joint's torque limit eq. 7 used along the approached path.
    pub torque_share: f64,
}

/// Why draws were rejected, counted.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Rejections {
    /// Part of the path outside the region.
    pub region: u64,
    /// Faster than `max_acceleration_ratio` allows.
    pub acceleration: u64,
    /// Not reachable by IK inside the joint limits (or no rest posture on its start).
    pub reach: u64,
    /// Eq. 7 from home needed more than `torque_share` of a torque limit, came within 0.05 rad
    /// of a joint limit, or did not track it to 1 mm.
    pub limits: u64,
}

/// Draws paths of a family for one robot, seeded.
pub struct FamilySampler {
    model: Model,
    cfg: FamilyConfig,
    region: Region,
    ramp: f64,
    base_start: Vector3<f64>,
    base_home: Vec<f64>,
    max_acceleration: f64,
    rng: ChaCha8Rng,
    /// The base figure-8 (the `base_every` episodes run it).
    base: Trajectory,
    /// Training paths handed out so far ([`FamilySampler::next_training_path`]).
    episodes: u64,
    /// The rejected draws so far.
    pub rejections: Rejections,
}

impl FamilySampler {
    /// The sampler of the family `cfg` (`kind = "family"`; its `[trajectory.family]`) on
    /// `model`, whose home posture (at rest on the base figure-8's start) is `home`; draws are
    /// seeded with `seed`.
    ///
    /// # Errors
    /// A config that is not a family or is out of range.
    pub fn new(model: &Model, cfg: &TrajectoryConfig, home: &[f64], seed: u64) -> Result<Self> {
        if cfg.kind != TrajectoryKind::Family {
            return Err(ControlError::InvalidConfig(format!(
                "a family sampler needs [trajectory] kind = \"family\", not {:?}",
                cfg.kind
            )));
        }
        cfg.family.validate()?;
        crate::error::check("home", home, model.nq())?;
        let base = cfg.build(model)?;
        let max_acceleration = cfg.family.max_acceleration_ratio * peak_acceleration(&base);
        Ok(Self {
            model: model.clone(),
            cfg: cfg.family.clone(),
            region: Region::of(model, cfg)?,
            ramp: cfg.ramp,
            base_start: base.start(),
            base_home: home.to_vec(),
            max_acceleration,
            rng: ChaCha8Rng::seed_from_u64(seed),
            base,
            episodes: 0,
            rejections: Rejections::default(),
        })
    }

    /// The region the paths are drawn in.
    pub fn region(&self) -> &Region {
        &self.region
    }

    /// The next path: drawn until one passes every check (at most `max_draws` times).
    ///
    /// # Errors
    /// [`ControlError::Unreachable`] after `max_draws` rejected draws (the counts say why), or
    /// a dynamics failure.
    pub fn draw(&mut self) -> Result<FamilyPath> {
        for _ in 0..self.cfg.max_draws {
            if let Some(p) = self.try_one()? {
                return Ok(p);
            }
        }
        Err(ControlError::Unreachable(format!(
            "no path of the family passed the checks in {} draws (rejected so far: {:?}): \
             shrink [trajectory.family] size or the region",
            self.cfg.max_draws, self.rejections
        )))
    }

    /// The path of the next training episode, from home's task point: every `base_every`-th
    /// one (the first included) the base figure-8 itself, otherwise a drawn path behind its
    /// approach ([`FamilySampler::draw`]; the base episodes draw nothing, so the drawn paths
    /// are the same sequence as without them).
    ///
    /// # Errors
    /// As [`FamilySampler::draw`].
    pub fn next_training_path(&mut self) -> Result<Trajectory> {
        let k = self.cfg.base_every as u64;
        let base = k > 0 && self.episodes.is_multiple_of(k);
        self.episodes += 1;
        if base {
            Ok(self.base.clone())
        } else {
            Ok(self.draw()?.approached)
        }
    }

    /// One draw and its checks; `None` when rejected.
    fn try_one(&mut self) -> Result<Option<FamilyPath>> {
        let config = self.propose();
        let path = config.build(&self.model)?;
        if self.region.leaves_by(&path) > 1e-9 {
            self.rejections.region += 1;
            return Ok(None);
        }
        let peak = peak_acceleration(&path);
        if peak > self.max_acceleration {
            self.rejections.acceleration += 1;
            return Ok(None);
        }
        let d = (path.start() - self.base_start).norm();
        let seconds = (1.875 * d / self.cfg.approach_speed).max(1.0);
        let approached = path.clone().with_approach(self.base_start, seconds)?;
        let ik = IkOptions::default();
        let (Ok(reach), Ok(_)) = (
            check_reachable(&self.model, &path, &ik),
            check_reachable(&self.model, &approached, &ik),
        ) else {
            self.rejections.reach += 1;
            return Ok(None);
        };
        if !reach.at_rest {
            self.rejections.reach += 1;
            return Ok(None);
        }
        let Some(torque_share) = self.within_limits(&approached)? else {
            self.rejections.limits += 1;
            return Ok(None);
        };
        Ok(Some(FamilyPath {
            config,
            path,
            approached,
            home: reach.q_start,
            peak_acceleration: peak,
            torque_share,
        }))
    }

    /// A random path description inside the region's box (not yet checked).
    fn propose(&mut self) -> TrajectoryConfig {
        let (r, f) = (&self.region, &self.cfg);
        let rng = &mut self.rng;
        let kind = f.kinds[rng.random_range(0..f.kinds.len())];
        let point = |rng: &mut ChaCha8Rng| {
            let u = r.half[0] * rng.random_range(-1.0..=1.0);
            let v = r.half[1] * rng.random_range(-1.0..=1.0);
            r.centre + r.e1 * u + r.e2 * v
        };
        let centre = point(rng);
        let theta = rng.random_range(0.0..TAU);
        let (s, c) = theta.sin_cos();
        let (e1, e2) = (r.e1 * c + r.e2 * s, r.e2 * c - r.e1 * s);
        let arr = |v: Vector3<f64>| [v[0], v[1], v[2]];
        let mut cfg = TrajectoryConfig {
            kind,
            centre: Some(arr(centre)),
            e1: Some(arr(e1)),
            e2: Some(arr(e2)),
            ramp: self.ramp,
            ..TrajectoryConfig::default()
        };
        let size = |rng: &mut ChaCha8Rng| rng.random_range(f.size[0]..=f.size[1]);
        let period = rng.random_range(f.period[0]..=f.period[1]);
        match kind {
            TrajectoryKind::Figure8 | TrajectoryKind::Family => {
                cfg.kind = TrajectoryKind::Figure8;
                cfg.a = Some(size(rng) * r.half[0]);
                cfg.b = Some(size(rng) * r.half[1]);
                cfg.period = period;
            }
            TrajectoryKind::Circle => {
                cfg.radius = Some(size(rng) * r.half[0].min(r.half[1]));
                cfg.period = period;
            }
            TrajectoryKind::MinJerk => {
                let k = rng.random_range(f.points[0]..=f.points[1]);
                cfg.points = (0..k).map(|_| arr(point(rng))).collect();
                cfg.move_time = rng.random_range(f.move_time[0]..=f.move_time[1]);
                (cfg.centre, cfg.e1, cfg.e2) = (None, None, None);
            }
        }
        cfg
    }

    /// Runs eq. 7 (true model, no noise) from home along `traj` over its approach, ramp and one
    /// cycle; the largest share of a torque limit it needed, or `None` if that exceeds
    /// `torque_share`, a joint came within 0.05 rad of a limit, or the error passed 1 mm.
    fn within_limits(&self, traj: &Trajectory) -> Result<Option<f64>> {
        let model = &self.model;
        let n = model.nq();
        let mut sim = SimRobot::new(model.clone(), SimConfig::default())?;
        sim.reset(&self.base_home, &vec![0.0; n])?;
        let mut osc = Osc::new(model.clone(), OscConfig::default())?;
        let tau_max: Vec<f64> = model.tau_max().collect();
        let (lo, hi): (Vec<f64>, Vec<f64>) = (model.q_min().collect(), model.q_max().collect());
        let dt = sim.control_period();
        let steps = ((traj.lead() + traj.ramp() + traj.period()) / dt).ceil() as usize;
        let mut u = vec![0.0; n];
        let mut share: f64 = 0.0;
        for k in 0..steps {
            let target = traj.sample(k as f64 * dt);
            osc.command(sim.measurement(), &target, &mut u)?;
            for (v, m) in u.iter().zip(&tau_max) {
                share = share.max(v.abs() / m);
            }
            if share > self.cfg.torque_share {
                return Ok(None);
            }
            let meas = sim.step(&u)?;
            let q = meas.q.as_slice();
            if (0..n).any(|i| q[i] < lo[i] + 0.05 || q[i] > hi[i] - 0.05) {
                return Ok(None);
            }
            let after = traj.sample((k + 1) as f64 * dt);
            let e = crate::task_error(&after, model.task_axes(), meas.x.as_slice());
            if e.is_nan() || e >= 1e-3 {
                return Ok(None);
            }
        }
        Ok(Some(share))
    }
}

/// Largest `‖ẍ_d‖` over the path's approach, ramp and one cycle (m/s²).
fn peak_acceleration(traj: &Trajectory) -> f64 {
    let span = traj.lead() + traj.ramp() + traj.period();
    let n = path_points(traj).count().max(2) - 1;
    (0..=n)
        .map(|k| traj.sample(span * k as f64 / n as f64).xdd.norm())
        .fold(0.0, f64::max)
}
