//! Task-space trajectories: figure-8, circle and cyclic point-to-point minimum-jerk moves. Each
//! gives the desired world-frame position, velocity and acceleration of the end-effector at any
//! time, starting at rest on the path.

use crate::error::{ControlError, Result};
use crate::warp::TimeWarp;
use nalgebra::Vector3;
use std::f64::consts::TAU;

/// Desired end-effector state at one time, in the world frame (m, m/s, m/s²). A controller reads
/// the rows of its model's task axes.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Target {
    pub x: Vector3<f64>,
    pub xd: Vector3<f64>,
    pub xdd: Vector3<f64>,
}

/// The path of a trajectory.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// `p(φ) = c + a·sin(φ)·e1 + b·sin(2φ)·e2`: a figure-8 lying on its side, `2a` wide along
    /// `e1` and `2b` tall along `e2`, through its centre at `φ = 0`.
    Figure8 {
        centre: Vector3<f64>,
        e1: Vector3<f64>,
        e2: Vector3<f64>,
        a: f64,
        b: f64,
    },
    /// `p(φ) = c + r·(cos(φ)·e1 + sin(φ)·e2)`, starting at `c + r·e1`.
    Circle {
        centre: Vector3<f64>,
        e1: Vector3<f64>,
        e2: Vector3<f64>,
        radius: f64,
    },
    /// Minimum-jerk moves `P_i → P_{i+1}` (and from the last point back to the first), each
    /// taking `move_time` seconds with zero velocity and acceleration at every point:
    /// `x = P_i + (P_{i+1} − P_i)(10τ³ − 15τ⁴ + 6τ⁵)`, `τ` the fraction of the move.
    MinJerk {
        points: Vec<Vector3<f64>>,
        move_time: f64,
    },
}

/// A periodic task-space trajectory: a [`Shape`] traversed once per `period`, with a smooth start
/// ([`TimeWarp`]) for the figure-8 and the circle (minimum-jerk moves start at rest by
/// themselves).
#[derive(Clone, Debug, PartialEq)]
pub struct Trajectory {
    shape: Shape,
    period: f64,
    warp: TimeWarp,
    /// A minimum-jerk lead-in from another point to the path's start, if any
    /// ([`Trajectory::with_approach`]).
    approach: Option<Approach>,
}

/// A minimum-jerk move at rest from `from` to `to` (the path's start) over `seconds`, run before
/// the path.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Approach {
    from: Vector3<f64>,
    to: Vector3<f64>,
    seconds: f64,
}

/// Minimum-jerk move `p0 → p1` over `dur` seconds at time `t` (clamped to the move).
fn min_jerk_move(p0: Vector3<f64>, p1: Vector3<f64>, dur: f64, t: f64) -> Target {
    let tau = (t / dur).clamp(0.0, 1.0);
    let d = p1 - p0;
    let (t2, t3) = (tau * tau, tau * tau * tau);
    Target {
        x: p0 + d * (t3 * (10.0 - 15.0 * tau + 6.0 * t2)),
        xd: d * (30.0 * t2 * (1.0 - 2.0 * tau + t2) / dur),
        xdd: d * (60.0 * tau * (1.0 - 3.0 * tau + 2.0 * t2) / (dur * dur)),
    }
}

fn finite(what: &str, v: &Vector3<f64>) -> Result<()> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(ControlError::InvalidTrajectory(format!(
            "{what} {v:?} is not finite"
        )))
    }
}

/// Normalised plane directions; fails on zero, non-finite or (nearly) parallel vectors.
fn plane(e1: Vector3<f64>, e2: Vector3<f64>) -> Result<(Vector3<f64>, Vector3<f64>)> {
    finite("e1", &e1)?;
    finite("e2", &e2)?;
    let bad = |m: &str| Err(ControlError::InvalidTrajectory(m.into()));
    if e1.norm() < 1e-9 || e2.norm() < 1e-9 {
        return bad("the plane directions e1 and e2 must be non-zero");
    }
    let (u, v) = (e1.normalize(), e2.normalize());
    if u.dot(&v).abs() > 0.99 {
        return bad("the plane directions e1 and e2 are (nearly) parallel");
    }
    Ok((u, v))
}

/// Largest size and farthest point of a path (m, per coordinate): a kilometre, far beyond any
/// arm's reach; the reachability check then names the point in a short line.
pub const MAX_PATH_METRES: f64 = 1e3;

/// A size in `(0, MAX_PATH_METRES]`.
fn size(what: &str, v: f64) -> Result<()> {
    if v > 0.0 && v <= MAX_PATH_METRES {
        Ok(())
    } else {
        Err(ControlError::InvalidTrajectory(format!(
            "{what} must be > 0 and at most {MAX_PATH_METRES:?} m, got {v:?}"
        )))
    }
}

/// A point with every coordinate within `±MAX_PATH_METRES`.
fn point(what: &str, p: &Vector3<f64>) -> Result<()> {
    finite(what, p)?;
    if p.iter().all(|x| x.abs() <= MAX_PATH_METRES) {
        Ok(())
    } else {
        Err(ControlError::InvalidTrajectory(format!(
            "{what} {:?} lies beyond ±{MAX_PATH_METRES:?} m",
            p.as_slice()
        )))
    }
}

/// Longest period, move time or start ramp of a path (s): an hour. Runs and evaluations step
/// through the ramp and sample whole cycles, so absurd durations would never finish.
pub const MAX_PATH_SECONDS: f64 = 3600.0;

/// Shortest period, move time or start ramp of a path (s): a millisecond, far quicker than any
/// arm moves; much shorter ones make the path's accelerations overflow (`a ω²` with
/// `ω = 2π / period`).
pub const MIN_PATH_SECONDS: f64 = 1e-3;

/// `v` is a duration in `[MIN_PATH_SECONDS, MAX_PATH_SECONDS]` (or 0 with `zero_ok`).
fn duration(what: &str, v: f64, zero_ok: bool) -> Result<()> {
    if (MIN_PATH_SECONDS..=MAX_PATH_SECONDS).contains(&v) || (zero_ok && v == 0.0) {
        Ok(())
    } else {
        let zero = if zero_ok { "0 or " } else { "" };
        Err(ControlError::InvalidTrajectory(format!(
            "{what} must be {zero}between {MIN_PATH_SECONDS} and {MAX_PATH_SECONDS} s, got {v:?}"
        )))
    }
}

impl Trajectory {
    /// A figure-8 (see [`Shape::Figure8`]) with period `period` (s) and start ramp `ramp` (s).
    /// `e1`, `e2` are normalised. Fails on non-finite values, a size outside `(0,`
    /// [`MAX_PATH_METRES`]`]` or a centre beyond it, a period outside [[`MIN_PATH_SECONDS`],
    /// [`MAX_PATH_SECONDS`]], a ramp neither 0 nor inside that range, or parallel directions.
    #[allow(clippy::too_many_arguments)]
    pub fn figure8(
        centre: Vector3<f64>,
        e1: Vector3<f64>,
        e2: Vector3<f64>,
        a: f64,
        b: f64,
        period: f64,
        ramp: f64,
    ) -> Result<Self> {
        point("centre", &centre)?;
        let (e1, e2) = plane(e1, e2)?;
        size("figure-8 width a", a)?;
        size("figure-8 height b", b)?;
        let shape = Shape::Figure8 {
            centre,
            e1,
            e2,
            a,
            b,
        };
        Self::periodic(shape, period, ramp)
    }

    /// A circle (see [`Shape::Circle`]); same checks as [`Trajectory::figure8`].
    pub fn circle(
        centre: Vector3<f64>,
        e1: Vector3<f64>,
        e2: Vector3<f64>,
        radius: f64,
        period: f64,
        ramp: f64,
    ) -> Result<Self> {
        point("centre", &centre)?;
        let (e1, e2) = plane(e1, e2)?;
        size("circle radius", radius)?;
        let shape = Shape::Circle {
            centre,
            e1,
            e2,
            radius,
        };
        Self::periodic(shape, period, ramp)
    }

    /// Cyclic minimum-jerk moves through `points` (at least two, finite), `move_time` s each.
    pub fn min_jerk(points: Vec<Vector3<f64>>, move_time: f64) -> Result<Self> {
        if points.len() < 2 {
            return Err(ControlError::InvalidTrajectory(
                "minimum-jerk moves need at least two points".into(),
            ));
        }
        for p in &points {
            point("point", p)?;
        }
        duration("move_time", move_time, false)?;
        let period = move_time * points.len() as f64;
        let shape = Shape::MinJerk { points, move_time };
        Ok(Self {
            shape,
            period,
            warp: TimeWarp { ramp: 0.0 },
            approach: None,
        })
    }

    fn periodic(shape: Shape, period: f64, ramp: f64) -> Result<Self> {
        duration("period", period, false)?;
        duration("ramp", ramp, true)?;
        Ok(Self {
            shape,
            period,
            warp: TimeWarp { ramp },
            approach: None,
        })
    }

    /// This path preceded by a minimum-jerk move at rest from `from` (world, m) to its start,
    /// `seconds` long: `x_d(t)` is the move for `t < seconds`, then the path at `t − seconds`
    /// (which starts at rest, so position, velocity and acceleration are continuous). Replaces
    /// an approach the path already had. Fails on a non-finite `from` or a non-positive
    /// `seconds`.
    pub fn with_approach(mut self, from: Vector3<f64>, seconds: f64) -> Result<Self> {
        point("approach start", &from)?;
        duration("approach seconds", seconds, false)?;
        self.approach = None;
        let to = self.sample(0.0).x;
        self.approach = Some(Approach { from, to, seconds });
        Ok(self)
    }

    /// Seconds of the approach before the path (0 without one).
    pub fn lead(&self) -> f64 {
        self.approach.map_or(0.0, |a| a.seconds)
    }

    /// The path without its approach.
    pub fn without_approach(&self) -> Self {
        Self {
            approach: None,
            ..self.clone()
        }
    }

    pub fn shape(&self) -> &Shape {
        &self.shape
    }
    /// Duration of one cycle (s).
    pub fn period(&self) -> f64 {
        self.period
    }
    /// The start ramp (s); 0 for minimum-jerk moves.
    pub fn ramp(&self) -> f64 {
        self.warp.ramp
    }

    /// Control steps of period `dt` (s) in one period of the path, rounded to the nearest
    /// whole step (0 when `dt` is not finite and > 0, or the count would not fit).
    pub fn steps_per_period(&self, dt: f64) -> usize {
        let k = (self.period() / dt).round();
        if dt > 0.0 && k.is_finite() && k >= 0.0 && k < usize::MAX as f64 {
            k as usize
        } else {
            0
        }
    }

    /// Desired position, velocity and acceleration at time `t` (s; times before 0 give the start).
    pub fn sample(&self, t: f64) -> Target {
        let t = match &self.approach {
            Some(a) if t < a.seconds => return min_jerk_move(a.from, a.to, a.seconds, t),
            Some(a) => t - a.seconds,
            None => t,
        };
        match &self.shape {
            Shape::Figure8 {
                centre,
                e1,
                e2,
                a,
                b,
            } => self.warped(t, |phi| {
                let (s1, c1) = phi.sin_cos();
                let (s2, c2) = (2.0 * phi).sin_cos();
                (
                    centre + e1 * (a * s1) + e2 * (b * s2),
                    e1 * (a * c1) + e2 * (2.0 * b * c2),
                    -e1 * (a * s1) - e2 * (4.0 * b * s2),
                )
            }),
            Shape::Circle {
                centre,
                e1,
                e2,
                radius,
            } => self.warped(t, |phi| {
                let (s, c) = phi.sin_cos();
                let p = (e1 * c + e2 * s) * *radius;
                let dp = (e2 * c - e1 * s) * *radius;
                (centre + p, dp, -p)
            }),
            Shape::MinJerk { points, move_time } => {
                let t = t.max(0.0) % self.period;
                let k = ((t / move_time) as usize).min(points.len() - 1);
                let tau = (t - k as f64 * move_time) / move_time;
                let (p0, p1) = (points[k], points[(k + 1) % points.len()]);
                let d = p1 - p0;
                let (t2, t3) = (tau * tau, tau * tau * tau);
                Target {
                    x: p0 + d * (t3 * (10.0 - 15.0 * tau + 6.0 * t2)),
                    xd: d * (30.0 * t2 * (1.0 - 2.0 * tau + t2) / move_time),
                    xdd: d * (60.0 * tau * (1.0 - 3.0 * tau + 2.0 * t2) / (move_time * move_time)),
                }
            }
        }
    }

    /// Chain rule through `φ = ω s(t)`: `ẋ = p'(φ) ω ṡ`, `ẍ = p''(φ) (ω ṡ)² + p'(φ) ω s̈`.
    #[inline]
    fn warped<F>(&self, t: f64, path: F) -> Target
    where
        F: Fn(f64) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>),
    {
        let w = TAU / self.period;
        let (s, sd, sdd) = self.warp.eval(t);
        let (p, dp, ddp) = path(w * s);
        let rate = w * sd;
        Target {
            x: p,
            xd: dp * rate,
            xdd: ddp * (rate * rate) + dp * (w * sdd),
        }
    }

    /// Start point `x_d(0)`.
    pub fn start(&self) -> Vector3<f64> {
        self.sample(0.0).x
    }
}
