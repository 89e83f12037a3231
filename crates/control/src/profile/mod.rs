//! Robot profiles: the values an arm needs beyond its dynamics (home and rest postures, joint PD
//! gains of the nominal behaviour `u0 = g − K_D q̇ − K_P (q − q_rest)`, torque limits, the task
//! path's placement), resolved for a model and checked once ([`resolve`] → [`Profiled`]).
//!
//! Precedence, per field: the profile given (config `[robot]` section or `--profile F`), then
//! the one a URDF file carries (`<osrl_profile .../>`, written by `osrl robot --urdf`), then a
//! built-in robot's data sheet, then values computed from the model:
//! - **home**: the best admissible posture of [`home`]'s search (well conditioned, inside the
//!   limits, tip in front of the base at 40–75 % of the reach, gravity within half the torque
//!   limits) whose default path is feasible; the next ones are tried if it is not.
//! - **rest** = home; **kp** = `m_i ω²`, **kd** = `2 ζ ω √(m_i M_ii)` with `ω` =
//!   [`DEFAULT_FREQUENCY`] rad/s, `ζ` = [`DEFAULT_DAMPING`], `m_i = 1 / (M⁻¹(home))_ii` the
//!   inertia joint `i` moves when every other joint is free and `M_ii(home)` the one it moves
//!   when every other joint is locked: the same null-space time scale on every joint whatever
//!   its inertia, and `M⁻¹K` has eigenvalues at most `n ω²` (its scaled form has a unit
//!   diagonal), so the 500 Hz loop stays far from its stability bound. (Stiffness from `M_ii`
//!   made the Panda chatter: two nearly parallel joints form a light mode that `M_ii` does not
//!   see. Damping from `m_i` alone left the heavy mode of the same joints, 25 times `m_i`,
//!   at damping ratio 0.14 (0.25 under the training's 3× PD): the return home between training
//!   episodes never settled. The geometric mean damps it at 0.68 (1.0 under 3×), and the light
//!   mode's damping pole stays at `2 ω √(M_ii/m_i)` ≈ 100 rad/s, 0.2 of the 500 Hz bound.)
//!   **torque limits**: the URDF's `effort`.
//! - **path**: a figure-8 centred at the tip at home, in the vertical plane facing the arm
//!   ([`placement`]), half-width and half-height [`DEFAULT_SCALE`] × the reach, halved up to
//!   twice until it is reachable by IK over a whole cycle inside the joint limits and within
//!   [`TORQUE_SHARE`] of the torque limits, and until eq. 7 (`N = I`, default task gains, true
//!   model, 500 Hz) tracks it for three periods within [`TRACKING_BOUND_MM`] RMS without a
//!   saturated torque. An arm for which no candidate works is refused
//!   with the last reason.
//! - **metric** (the learner's cost metric `N`, [`CostMetric`]): eq. 7 with `N = I` (default
//!   task gains, true model, 500 Hz) run along the resolved default path for three periods
//!   from rest (the check above's run when there is one); if some joint's sweep
//!   `max q_j − min q_j` over it exceeds [`METRIC_SWEEP_BOUND`], `inverse_inertia`, else
//!   `identity` ([`metric_rule`]). `N = I` puts the cheapest torque on the lightest joints, and
//!   on an arm with light wrists the optimum the learner chases turns them far beyond the
//!   region its fields were trained in (`docs/decisions.md`, D27, D29).

mod apply;
mod check;
mod home;
mod placement;
mod resolved;
mod verify;

pub use osrl_dynamics::CostMetric;
pub use placement::TORQUE_SHARE;
pub use resolved::{PathFrame, Profiled, ResolvedProfile, Source};
pub use verify::TRACKING_BOUND_MM;

use crate::error::Result;
use apply::{apply, figure8, joint_inertias};
use check::{bad, check_given};
use osrl_dynamics::{robots, Model, RobotProfile};

/// Default null-space natural frequency `ω` of the computed joint gains (rad/s).
pub const DEFAULT_FREQUENCY: f64 = 10.0;
/// Default damping ratio `ζ` of the computed joint gains.
pub const DEFAULT_DAMPING: f64 = 1.0;
/// Largest `null_space_frequency` (rad/s): a joint time constant of 1 ms, a hundred times the
/// default's bandwidth and beyond what a joint position loop realises.
pub const MAX_FREQUENCY: f64 = 1e3;
/// Largest `null_space_damping` (damping ratio `ζ`).
pub const MAX_DAMPING: f64 = 1e3;

/// Default size of the path as a fraction of the reach.
pub const DEFAULT_SCALE: f64 = 0.1;
/// Home candidates tried before an arm is refused.
const HOME_CANDIDATES: usize = 6;
/// Largest joint sweep (rad) of eq. 7 with `N = I` along the default path for which the
/// profile keeps the learner's metric `N = I` ([`metric_rule`]). Measured largest sweeps: planar3
/// 0.72, sarcos7 0.44 (both learn with `N = I`, and sarcos7 diverges with `M⁻¹`); UR5 1.63,
/// 1.74, 6.12 (joints 3–5), Panda 2.25 and 3.61 (joints 4 and 6), which brake with `N = I` and
/// learn with `M⁻¹` (`docs/decisions.md`, D27): 1 rad lies between the two groups.
pub const METRIC_SWEEP_BOUND: f64 = 1.0;

/// The metric the profile chooses from the joint sweeps (rad) of eq. 7 with `N = I` along the
/// default path: `inverse_inertia` when one exceeds [`METRIC_SWEEP_BOUND`], else `identity`.
pub fn metric_rule(sweep: &[f64]) -> CostMetric {
    if sweep.iter().any(|&s| s.is_nan() || s > METRIC_SWEEP_BOUND) {
        CostMetric::InverseInertia
    } else {
        CostMetric::Identity
    }
}

/// A built-in robot by name, or a URDF file read with the profile's tip and locks.
///
/// # Errors
/// A tip or lock for a built-in robot (they have no URDF to reduce), a malformed lock, an
/// unreadable or refused URDF, an unknown name.
pub fn load_robot(robot: &str, profile: &RobotProfile) -> Result<Model> {
    if robots::BUILTIN.contains(&robot) {
        if profile.changes_structure() {
            return bad(
                "tip",
                format!("{robot} is built in: tip, lock and unlock apply to URDF files"),
            );
        }
        return Ok(robots::by_name(robot)?);
    }
    let path = std::path::Path::new(robot);
    if robot.ends_with(".urdf") || path.exists() {
        return Ok(osrl_dynamics::urdf::load_urdf_with(
            path,
            &profile.urdf_options()?,
        )?);
    }
    Ok(robots::by_name(robot)?)
}

/// Resolves `given` for `model` (module docs): every missing value computed or taken from the
/// file or the data sheet, every value checked, the default path checked feasible.
///
/// # Errors
/// [`crate::ControlError::Profile`] naming the field: a wrong length, a non-finite value, a
/// posture outside the joint limits, a non-positive torque limit or scalar; a path that is not
/// reachable or feasible; an arm for which no home posture and path work (with the reason);
/// [`crate::ControlError::Dynamics`] for a model the simulator refuses (a gimbal
/// inside the joint limits, `osrl_dynamics::gimbal`).
pub fn resolve(model: &Model, given: &RobotProfile) -> Result<Profiled> {
    // Before the home search: its eq. 7 runs would refuse the model for every candidate.
    osrl_dynamics::gimbal::check(model)?;
    let file = model
        .spec()
        .urdf
        .as_ref()
        .and_then(|u| u.profile.clone())
        .unwrap_or_default();
    check_given(model, &file).map_err(resolved::from_file)?;
    check_given(model, given)?;
    let p = file.overlaid(given);
    let builtin = model.spec().urdf.is_none();
    let tau: Vec<f64> = p
        .torque_limits
        .clone()
        .unwrap_or_else(|| model.tau_max().collect());
    let omega = p.null_space_frequency.unwrap_or(DEFAULT_FREQUENCY);
    let zeta = p.null_space_damping.unwrap_or(DEFAULT_DAMPING);
    let limited = apply(
        model,
        &model.spec().q_start,
        &model.spec().q_rest,
        &model.spec().kp,
        &model.spec().kd,
        &tau,
    )?;
    let reach = home::reach(&limited)?;
    let (homes, rejected) = match (&p.home, builtin) {
        (Some(h), _) => (vec![h.clone()], String::new()),
        (None, true) => (vec![model.spec().q_start.clone()], String::new()),
        (None, false) => {
            let found = home::search(&limited, &tau, HOME_CANDIDATES)?;
            (found.candidates, found.rejected)
        }
    };
    if homes.is_empty() {
        return bad(
            "home",
            format!(
                "no posture of {} inside its joint limits has the tip in front of the base at \
                 40–75 % of its {reach:.3} m reach with gravity within half the torque limits \
                 (samples rejected: {rejected})",
                model.name()
            ),
        );
    }
    let scales: Vec<f64> = match (p.path.scale, p.path.a.is_some() && p.path.b.is_some()) {
        (Some(s), _) => vec![s],
        (None, true) => vec![DEFAULT_SCALE],
        (None, false) => vec![DEFAULT_SCALE, DEFAULT_SCALE / 2.0, DEFAULT_SCALE / 4.0],
    };
    // Computed defaults are verified by simulating eq. 7; given and data-sheet ones are not.
    let computed = !builtin && (p.home.is_none() || p.path.is_empty());
    let mut last = None;
    for home in &homes {
        let rest = p.rest.clone().unwrap_or_else(|| match builtin {
            true => model.spec().q_rest.clone(),
            false => home.clone(),
        });
        let (kp, kd) = match builtin {
            true => (model.spec().kp.clone(), model.spec().kd.clone()),
            false => {
                let (free, locked) = joint_inertias(model, home)?;
                let kp = free.iter().map(|m| m * omega * omega).collect();
                let kd = free
                    .iter()
                    .zip(&locked)
                    .map(|(m, ml)| 2.0 * zeta * (m * ml).sqrt() * omega)
                    .collect();
                (kp, kd)
            }
        };
        let (kp, kd) = (p.kp.clone().unwrap_or(kp), p.kd.clone().unwrap_or(kd));
        let profiled = apply(model, home, &rest, &kp, &kd, &tau)?;
        let (centre, e1, e2) = match builtin {
            true => crate::trajectory_config::default_frame(&profiled)?,
            false => placement::default_frame(&profiled, home)?,
        };
        let (a0, b0) = match builtin {
            true => crate::trajectory_config::default_size(&profiled)?,
            false => (None, None),
        };
        for &s in &scales {
            let frame = PathFrame {
                centre: p.path.centre.unwrap_or(centre.into()),
                e1: p.path.e1.unwrap_or(e1.into()),
                e2: p.path.e2.unwrap_or(e2.into()),
                a: p.path.a.or(a0).unwrap_or(s * reach),
                b: p.path.b.or(b0).unwrap_or(s * reach),
            };
            let traj = figure8(&frame).map_err(|e| resolved::field("path", e))?;
            let checked = placement::feasible(&profiled, &traj).and_then(|f| {
                let sweep = match computed {
                    true => Some(verify::eq7_sweep(&profiled, &traj, &f.reach.q_start, true)?),
                    false => None,
                };
                Ok((f, sweep))
            });
            match checked {
                Ok((f, sweep)) => {
                    let (metric, sweep) = match (p.metric, sweep) {
                        (Some(m), s) => (m, s),
                        (None, Some(s)) => (metric_rule(&s), Some(s)),
                        (None, None) => {
                            let s = verify::eq7_sweep(&profiled, &traj, &f.reach.q_start, false)
                                .map_err(|e| resolved::field("metric", e))?;
                            (metric_rule(&s), Some(s))
                        }
                    };
                    let values = resolved::Values {
                        home: home.clone(),
                        rest,
                        kp,
                        kd,
                        tau,
                        omega,
                        zeta,
                        frame,
                        reach,
                        metric,
                        sweep,
                    };
                    return Ok(Profiled::new(profiled, values, f, given, &file));
                }
                Err(e) => last = Some(e),
            }
        }
    }
    let why = last.map(|e| e.to_string()).unwrap_or_default();
    let field = if p.home.is_some() || builtin {
        "path"
    } else {
        "home"
    };
    bad(
        field,
        format!(
            "{} cannot follow its default path from {} home posture(s) tried: {why}",
            model.name(),
            homes.len()
        ),
    )
}
