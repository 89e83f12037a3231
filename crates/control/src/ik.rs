//! Damped-least-squares inverse kinematics on the task axes, and the reachability check of a
//! trajectory (start posture on the path, whole path inside the reach and the joint limits).

use crate::error::{ControlError, Result};
use crate::trajectory::Trajectory;
use nalgebra::{DMatrix, DVector, Vector3};
use osrl_dynamics::{jacobian, Data, Model};

/// Settings of [`solve_ik`] and [`check_reachable`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IkOptions {
    /// Damping `λ` of `Jᵀ(J Jᵀ + λ²I)⁻¹` (m). Default 1e-3.
    pub damping: f64,
    /// Position tolerance (m). Default 1e-6.
    pub tol: f64,
    /// Iteration limit. Default 500.
    pub max_iter: usize,
    /// Joints are kept this far inside their limits (rad). Default 0.05.
    pub margin: f64,
    /// Gain of the null-space pull toward `q_rest` per iteration (0..1). Default 0.1.
    pub null_gain: f64,
    /// Path samples per cycle checked by [`check_reachable`]. Default 400.
    pub samples: usize,
}

impl Default for IkOptions {
    fn default() -> Self {
        Self {
            damping: 1e-3,
            tol: 1e-6,
            max_iter: 500,
            margin: 0.05,
            null_gain: 0.1,
            samples: 400,
        }
    }
}

/// Moves `q` (rad, in place) so that the end-effector's task coordinates reach those of `target`
/// (world, m), by damped least squares `Δq = J⁺e + (I − J⁺J)·k·(q_rest − q)` with steps of at
/// most 0.2 rad, keeping every joint `margin` inside its limits. Returns the remaining task
/// distance (m) — the caller decides whether it is small enough. Allocates (not for hot paths).
pub fn solve_ik(
    model: &Model,
    data: &mut Data,
    target: &Vector3<f64>,
    q: &mut [f64],
    opts: &IkOptions,
) -> Result<f64> {
    crate::error::check("q", q, model.nq())?;
    let (n, axes) = (model.nq(), model.task_axes());
    let m = axes.len();
    let q_rest = &model.spec().q_rest;
    let (lo, hi): (Vec<f64>, Vec<f64>) = model
        .q_min()
        .zip(model.q_max())
        .map(|(a, b)| {
            let mid = 0.5 * (a + b);
            ((a + opts.margin).min(mid), (b - opts.margin).max(mid))
        })
        .unzip();
    let clamp = |q: &mut [f64]| {
        q.iter_mut()
            .enumerate()
            .for_each(|(i, v)| *v = v.clamp(lo[i], hi[i]))
    };
    clamp(q);
    for _ in 0..opts.max_iter {
        jacobian(model, data, q)?;
        let j = DMatrix::from_fn(m, n, |r, c| data.jac[(axes[r], c)]);
        let e = DVector::from_fn(m, |r, _| target[axes[r]] - data.ee_pos[axes[r]]);
        let err = e.norm();
        let jjt = &j * j.transpose() + DMatrix::identity(m, m) * opts.damping.powi(2);
        let Some(inv) = jjt.try_inverse() else {
            return Err(ControlError::Singular("IK: J Jᵀ + λ²I is singular".into()));
        };
        let pinv = j.transpose() * inv;
        let pull = DVector::from_fn(n, |i, _| opts.null_gain * (q_rest[i] - q[i]));
        let null = &pull - &pinv * (&j * &pull);
        let mut dq = &pinv * e + null;
        let big = dq.amax();
        if big > 0.2 {
            dq *= 0.2 / big;
        }
        for i in 0..n {
            q[i] += dq[i];
        }
        clamp(q);
        if err < opts.tol && big < 1e-9 {
            break;
        }
    }
    jacobian(model, data, q)?;
    let e: f64 = axes
        .iter()
        .map(|&a| (target[a] - data.ee_pos[a]).powi(2))
        .sum();
    Ok(e.sqrt())
}

/// What [`check_reachable`] found.
#[derive(Clone, Debug, PartialEq)]
pub struct Reach {
    /// Home: the posture in which eq. 7 holds the start point `x_d(0)` at rest (rad), found by
    /// [`crate::settle_at_start`] from `q_ik`; start the robot here, at rest. `q_ik` itself if
    /// the arm does not come to rest there (`at_rest` false).
    pub q_start: Vec<f64>,
    /// The posture at the start point by IK from `q_rest` (rad).
    pub q_ik: Vec<f64>,
    /// Whether `q_start` is the settled posture.
    pub at_rest: bool,
    /// Largest IK residual along the path (m).
    pub max_residual: f64,
    /// Smallest distance of any joint to its limits along the IK path (rad).
    pub min_margin: f64,
}

/// Checks that `traj` lies within `model`'s reach and can be followed inside its joint limits.
///
/// 1. Every sampled point's task coordinates must lie within the arm's reach (the sum of its link
///    lengths and end-effector offset) of the first joint; otherwise the error names the point.
/// 2. IK solves the start point from `q_rest`, then follows the approach ([`Trajectory::lead`];
///    at the same spacing) and `opts.samples` points of one cycle, each from the previous solution, keeping joints `opts.margin` inside their limits; a point
///    left more than 0.1 mm away is unreachable (error naming the time and the residual).
/// 3. The home posture is where eq. 7 holds the start point at rest, from the IK posture
///    ([`crate::settle_at_start`]): there the nominal pull of `u0` is balanced, so a run from
///    home does not begin by swinging the redundant joints.
pub fn check_reachable(model: &Model, traj: &Trajectory, opts: &IkOptions) -> Result<Reach> {
    let axes = model.task_axes();
    let links = model.links();
    let base = links[0].origin.trans;
    let reach: f64 = links[1..]
        .iter()
        .map(|l| l.origin.trans.norm())
        .sum::<f64>()
        + model.spec().ee_offset.norm();
    let samples = opts.samples.max(8);
    // The approach (if any) at the cycle's sample spacing, then one cycle after the ramp.
    let lead = traj.lead();
    let spacing = traj.period() / samples as f64;
    let approach = (lead / spacing).ceil() as usize;
    let times: Vec<f64> = (1..approach)
        .map(|k| k as f64 * lead / approach as f64)
        .chain(
            (0..=samples).map(|k| lead + traj.ramp() + traj.period() * k as f64 / samples as f64),
        )
        .collect();
    for &t in std::iter::once(&0.0).chain(&times) {
        let p = traj.sample(t).x;
        let d: f64 = axes
            .iter()
            .map(|&a| (p[a] - base[a]).powi(2))
            .sum::<f64>()
            .sqrt();
        if d > reach {
            return Err(ControlError::Unreachable(format!(
                "x_d(t = {t:.3} s) = ({:.3}, {:.3}, {:.3}) m is {d:.3} m from the first joint; \
                 {} reaches at most {reach:.3} m",
                p[0],
                p[1],
                p[2],
                model.name()
            )));
        }
    }
    let mut data = model.data();
    let mut q = model.spec().q_rest.clone();
    let tol = 1e-4;
    let start = traj.start();
    let r0 = solve_ik(model, &mut data, &start, &mut q, opts)?;
    if r0 > tol {
        return Err(ControlError::Unreachable(format!(
            "the start point ({:.3}, {:.3}, {:.3}) m is {:.1} mm away from the closest posture \
             of {} inside its joint limits (margin {} rad)",
            start[0],
            start[1],
            start[2],
            r0 * 1e3,
            model.name(),
            opts.margin
        )));
    }
    let q_start = q.clone();
    let (mut max_residual, mut min_margin) = (r0, f64::INFINITY);
    let limits: Vec<(f64, f64)> = model.q_min().zip(model.q_max()).collect();
    for &t in &times {
        let p = traj.sample(t).x;
        let r = solve_ik(model, &mut data, &p, &mut q, opts)?;
        if r > tol {
            return Err(ControlError::Unreachable(format!(
                "x_d(t = {t:.3} s) = ({:.3}, {:.3}, {:.3}) m stays {:.1} mm away from {} inside \
                 its joint limits (margin {} rad)",
                p[0],
                p[1],
                p[2],
                r * 1e3,
                model.name(),
                opts.margin
            )));
        }
        max_residual = max_residual.max(r);
        for (v, (lo, hi)) in q.iter().zip(&limits) {
            min_margin = min_margin.min(v - lo).min(hi - v);
        }
    }
    let (home, at_rest) = match crate::settle_at_start(model, traj, &q_start) {
        Ok(home) => (home, true),
        Err(_) => (q_start.clone(), false),
    };
    Ok(Reach {
        q_start: home,
        q_ik: q_start,
        at_rest,
        max_residual,
        min_margin,
    })
}
