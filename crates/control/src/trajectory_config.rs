//! The trajectory section of the config file, with per-robot defaults.

use crate::error::{ControlError, Result};
use crate::family::FamilyConfig;
use crate::trajectory::Trajectory;
use nalgebra::Vector3;
use osrl_dynamics::Model;
use serde::{Deserialize, Serialize};

/// Which task-space path.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TrajectoryKind {
    /// `x_d = c + a·sin(ωt)·e1 + b·sin(2ωt)·e2`.
    #[default]
    Figure8,
    /// `x_d = c + r·(cos(ωt)·e1 + sin(ωt)·e2)`.
    Circle,
    /// Cyclic point-to-point minimum-jerk moves through `points`.
    MinJerk,
    /// A family of paths over a region ([`crate::family`], `[trajectory.family]`): training
    /// draws one per episode; as one path (evaluation, home) it is its base figure-8.
    Family,
}

/// A trajectory description. Unset (`None`/empty) fields take the robot's default
/// ([`TrajectoryConfig::build`]); positions and directions are in the world frame.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TrajectoryConfig {
    /// `figure8`, `circle`, `min_jerk` or `family`. Default `figure8`.
    pub kind: TrajectoryKind,
    /// Centre `c` (m). Default per robot: planar3 (0.65, 0, 0.25), in the arm's x–z plane;
    /// sarcos7 (0.30, 0.40, 0.05), 0.40 m in front of (+y, where the forearm points at the rest
    /// posture) and 0.23 m below the shoulder; any other arm: the end-effector at `q_start`
    /// (its robot profile, [`crate::profile::Profiled::trajectory`], sets centre, plane and size).
    /// The defaults were checked by IK and by simulating eq. 7 with `N = I` (all joints keep
    /// more than 0.25 rad from their limits).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub centre: Option<[f64; 3]>,
    /// First (horizontal) plane direction `e1`. Default x (for other arms: the first task axis).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub e1: Option<[f64; 3]>,
    /// Second (vertical) plane direction `e2`. Default z (for other arms: the last task axis).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub e2: Option<[f64; 3]>,
    /// Figure-8 half-width along `e1` (m). Default planar3 0.15, sarcos7 0.10, others 0.05.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub a: Option<f64>,
    /// Figure-8 half-height along `e2` (m). Default planar3 0.10, sarcos7 0.10, others 0.05.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub b: Option<f64>,
    /// Circle radius (m). Default `b`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub radius: Option<f64>,
    /// Period of one cycle (s) of the figure-8 and the circle. Default 4.
    pub period: f64,
    /// Start ramp (s) of the time warp ([`crate::TimeWarp`]). Default 1.
    pub ramp: f64,
    /// Points of the minimum-jerk moves (m). Default: the corners of the `2a × 2b` rectangle
    /// around the centre in the `e1`–`e2` plane.
    pub points: Vec<[f64; 3]>,
    /// Duration of each minimum-jerk move (s). Default 1.
    pub move_time: f64,
    /// The family drawn when `kind = "family"` (`[trajectory.family]`).
    #[serde(skip_serializing_if = "FamilyConfig::is_default")]
    pub family: FamilyConfig,
}

impl Default for TrajectoryConfig {
    fn default() -> Self {
        Self {
            kind: TrajectoryKind::Figure8,
            centre: None,
            e1: None,
            e2: None,
            a: None,
            b: None,
            radius: None,
            period: 4.0,
            ramp: 1.0,
            points: Vec::new(),
            move_time: 1.0,
            family: FamilyConfig::default(),
        }
    }
}

/// Default centre, plane and size of a robot's figure-8.
struct RobotDefaults {
    centre: Vector3<f64>,
    e1: Vector3<f64>,
    e2: Vector3<f64>,
    a: f64,
    b: f64,
}

fn robot_defaults(model: &Model) -> Result<RobotDefaults> {
    let name = model.name().split(' ').next().unwrap_or("");
    let axes = model.task_axes();
    match name {
        "planar3" if axes == [0, 2] => Ok(RobotDefaults {
            centre: Vector3::new(0.65, 0.0, 0.25),
            e1: Vector3::x(),
            e2: Vector3::z(),
            a: 0.15,
            b: 0.10,
        }),
        "sarcos7" if axes == [0, 1, 2] => Ok(RobotDefaults {
            centre: Vector3::new(0.30, 0.40, 0.05),
            e1: Vector3::x(),
            e2: Vector3::z(),
            a: 0.10,
            b: 0.10,
        }),
        _ => {
            if axes.len() < 2 {
                return Err(ControlError::InvalidTrajectory(format!(
                    "{} has a {}-D task space; planar paths need at least 2",
                    model.name(),
                    axes.len()
                )));
            }
            // Any other arm: around the end-effector at the start posture, in the plane of its
            // first and last task axes.
            let mut data = model.data();
            osrl_dynamics::forward_kinematics(model, &mut data, &model.spec().q_start)?;
            let mut centre = Vector3::zeros();
            for &a in axes {
                centre[a] = data.ee_pos[a];
            }
            let unit = |a: usize| Vector3::from_fn(|r, _| if r == a { 1.0 } else { 0.0 });
            Ok(RobotDefaults {
                centre,
                e1: unit(axes[0]),
                e2: unit(axes[axes.len() - 1]),
                a: 0.05,
                b: 0.05,
            })
        }
    }
}

/// The data-sheet centre and plane `(c, e1, e2)` of a built-in robot's figure-8 (any other
/// arm: around the end-effector at its start posture, in the plane of its first and last task
/// axes).
pub(crate) fn default_frame(model: &Model) -> Result<(Vector3<f64>, Vector3<f64>, Vector3<f64>)> {
    let d = robot_defaults(model)?;
    Ok((d.centre, d.e1, d.e2))
}

/// The data-sheet half-width and half-height `(a, b)` of a built-in robot's figure-8 (m).
pub(crate) fn default_size(model: &Model) -> Result<(Option<f64>, Option<f64>)> {
    let d = robot_defaults(model)?;
    Ok((Some(d.a), Some(d.b)))
}

impl TrajectoryConfig {
    /// The centre and the orthonormal plane directions `(c, e1, e2)` for `model`, defaults
    /// filled in (`e2` made orthogonal to `e1`).
    ///
    /// # Errors
    /// A robot without a planar task, or parallel directions.
    pub fn frame(&self, model: &Model) -> Result<(Vector3<f64>, Vector3<f64>, Vector3<f64>)> {
        let d = robot_defaults(model)?;
        let v = |o: Option<[f64; 3]>, def: Vector3<f64>| o.map(Vector3::from).unwrap_or(def);
        let (e1, e2) = crate::family::orthonormal(v(self.e1, d.e1), v(self.e2, d.e2))?;
        Ok((v(self.centre, d.centre), e1, e2))
    }

    /// The figure-8 half-width and half-height `[a, b]` (m) for `model`, defaults filled in.
    ///
    /// # Errors
    /// A robot without a planar task.
    pub fn base(&self, model: &Model) -> Result<[f64; 2]> {
        let d = robot_defaults(model)?;
        Ok([self.a.unwrap_or(d.a), self.b.unwrap_or(d.b)])
    }

    /// The trajectory for `model`, defaults filled in. Fails on malformed values (see
    /// [`Trajectory`]), or when the path leaves the model's task space (a centre, direction or
    /// point component along a world axis that is not a task axis). Reachability inside the joint
    /// limits is checked separately by [`crate::check_reachable`].
    pub fn build(&self, model: &Model) -> Result<Trajectory> {
        let d = robot_defaults(model)?;
        let v = |o: Option<[f64; 3]>, def: Vector3<f64>| o.map(Vector3::from).unwrap_or(def);
        let (centre, e1, e2) = (v(self.centre, d.centre), v(self.e1, d.e1), v(self.e2, d.e2));
        let (a, b) = (self.a.unwrap_or(d.a), self.b.unwrap_or(d.b));
        let axes = model.task_axes();
        let names = ["x", "y", "z"];
        let outside = |what: &str, p: &Vector3<f64>| -> Result<()> {
            for k in (0..3).filter(|k| !axes.contains(k)) {
                if p[k].abs() > 1e-12 {
                    return Err(ControlError::InvalidTrajectory(format!(
                        "{what} has a {} component ({}), but {} controls only {}",
                        names[k],
                        p[k],
                        model.name(),
                        axes.iter()
                            .map(|&a| names[a])
                            .collect::<Vec<_>>()
                            .join(", ")
                    )));
                }
            }
            Ok(())
        };
        if self.kind == TrajectoryKind::Family {
            self.family.validate()?;
        }
        match self.kind {
            TrajectoryKind::Figure8 | TrajectoryKind::Circle | TrajectoryKind::Family => {
                outside("centre", &centre)?;
                outside("e1", &e1)?;
                outside("e2", &e2)?;
            }
            TrajectoryKind::MinJerk => {}
        }
        match self.kind {
            TrajectoryKind::Figure8 | TrajectoryKind::Family => {
                Trajectory::figure8(centre, e1, e2, a, b, self.period, self.ramp)
            }
            TrajectoryKind::Circle => {
                let r = self.radius.unwrap_or(b);
                Trajectory::circle(centre, e1, e2, r, self.period, self.ramp)
            }
            TrajectoryKind::MinJerk => {
                let points: Vec<Vector3<f64>> = if self.points.is_empty() {
                    let (u, w) = (e1.normalize() * a, e2.normalize() * b);
                    vec![
                        centre - u - w,
                        centre + u - w,
                        centre + u + w,
                        centre - u + w,
                    ]
                } else {
                    self.points.iter().map(|p| Vector3::from(*p)).collect()
                };
                for p in &points {
                    outside("a min-jerk point", p)?;
                }
                Trajectory::min_jerk(points, self.move_time)
            }
        }
    }
}
