//! The task-space region of a family: a box in the plane of the base path.

use crate::error::{ControlError, Result};
use crate::trajectory::Trajectory;
use crate::trajectory_config::{TrajectoryConfig, TrajectoryKind};
use nalgebra::Vector3;
use osrl_dynamics::Model;

/// A box `|u| ≤ h1`, `|v| ≤ h2` in the plane through `centre` spanned by the orthonormal `e1`,
/// `e2` (world, m), with `u`, `v` the coordinates along them.
#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    pub centre: Vector3<f64>,
    pub e1: Vector3<f64>,
    pub e2: Vector3<f64>,
    pub half: [f64; 2],
}

/// Samples per period at which a path is checked against a region.
const SAMPLES: usize = 400;

impl Region {
    /// The region of `cfg` on `model`: for `kind = "family"` the box around its base figure-8
    /// grown by `family.growth` (or `family.half_size`); for one path the box around it (its
    /// samples' extent along `e1`, `e2`), which is where training on it went.
    ///
    /// # Errors
    /// A malformed trajectory config.
    pub fn of(model: &Model, cfg: &TrajectoryConfig) -> Result<Self> {
        let (centre, e1, e2) = cfg.frame(model)?;
        if cfg.kind == TrajectoryKind::Family {
            let base = cfg.base(model)?;
            let f = &cfg.family;
            let half = f
                .half_size
                .unwrap_or([(1.0 + f.growth) * base[0], (1.0 + f.growth) * base[1]]);
            return Ok(Self {
                centre,
                e1,
                e2,
                half,
            });
        }
        let traj = cfg.build(model)?;
        let mut r = Self {
            centre,
            e1,
            e2,
            half: [0.0; 2],
        };
        for p in path_points(&traj) {
            let (u, v, _) = r.coords(&p);
            r.half = [r.half[0].max(u.abs()), r.half[1].max(v.abs())];
        }
        Ok(r)
    }

    /// `(u, v, w)`: the coordinates along `e1`, `e2` and the distance from the plane (m).
    pub fn coords(&self, p: &Vector3<f64>) -> (f64, f64, f64) {
        let d = p - self.centre;
        let (u, v) = (d.dot(&self.e1), d.dot(&self.e2));
        (u, v, (d - self.e1 * u - self.e2 * v).norm())
    }

    /// How far `p` lies outside the region (m; 0 inside): the distance to the box in the plane
    /// combined with the distance from the plane.
    pub fn outside(&self, p: &Vector3<f64>) -> f64 {
        let (u, v, w) = self.coords(p);
        let du = (u.abs() - self.half[0]).max(0.0);
        let dv = (v.abs() - self.half[1]).max(0.0);
        (du * du + dv * dv + w * w).sqrt()
    }

    /// How far `traj` (its approach, start ramp and one cycle) leaves the region at most (m).
    pub fn leaves_by(&self, traj: &Trajectory) -> f64 {
        path_points(traj)
            .map(|p| self.outside(&p))
            .fold(0.0, f64::max)
    }
}

/// The positions of `traj` over its approach, start ramp and one cycle, [`SAMPLES`] per period.
pub(crate) fn path_points(traj: &Trajectory) -> impl Iterator<Item = Vector3<f64>> + '_ {
    let span = traj.lead() + traj.ramp() + traj.period();
    let n = ((span / traj.period()) * SAMPLES as f64).ceil() as usize;
    (0..=n).map(move |k| traj.sample(span * k as f64 / n as f64).x)
}

/// Orthonormal plane directions from `e1`, `e2` (Gram–Schmidt); fails on parallel ones.
pub(crate) fn orthonormal(
    e1: Vector3<f64>,
    e2: Vector3<f64>,
) -> Result<(Vector3<f64>, Vector3<f64>)> {
    let u = e1.normalize();
    let w = e2 - u * u.dot(&e2);
    if w.norm().is_nan() || w.norm() <= 1e-6 || !u.iter().all(|x| x.is_finite()) {
        return Err(ControlError::InvalidTrajectory(
            "the plane directions e1 and e2 must be non-zero and not parallel".into(),
        ));
    }
    Ok((u, w.normalize()))
}
