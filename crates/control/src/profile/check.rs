//! Checks of the values a profile gives, each error naming the field and the joint.

use super::{MAX_DAMPING, MAX_FREQUENCY};
use crate::error::{ControlError, Result};
use osrl_dynamics::{Model, RobotProfile};

/// An error naming the profile `field`.
pub(super) fn bad<T>(field: &str, reason: String) -> Result<T> {
    Err(ControlError::Profile {
        field: field.into(),
        reason,
    })
}

fn joint(model: &Model, i: usize) -> String {
    format!("joint {i} ('{}')", model.links()[i].joint_name)
}

/// One finite value per degree of freedom.
pub(super) fn per_joint(field: &str, v: &[f64], model: &Model) -> Result<()> {
    let n = model.nq();
    if v.len() != n {
        return bad(
            field,
            format!(
                "{} values for the {n} degrees of freedom of {}",
                v.len(),
                model.name()
            ),
        );
    }
    if let Some(i) = v.iter().position(|x| !x.is_finite()) {
        return bad(
            field,
            format!("{} is {} (not finite)", joint(model, i), v[i]),
        );
    }
    Ok(())
}

/// A posture: one finite value per joint, each inside the joint's limits.
pub(super) fn posture(field: &str, v: &[f64], model: &Model) -> Result<()> {
    per_joint(field, v, model)?;
    for (i, ((&q, lo), hi)) in v.iter().zip(model.q_min()).zip(model.q_max()).enumerate() {
        if q < lo || q > hi {
            return bad(
                field,
                format!(
                    "{} at {q} is outside its limits [{lo}, {hi}]",
                    joint(model, i)
                ),
            );
        }
    }
    Ok(())
}

/// Gains or limits: one finite value per joint, each ≥ 0 (or > 0 with `strict`).
pub(super) fn non_negative(field: &str, v: &[f64], model: &Model, strict: bool) -> Result<()> {
    per_joint(field, v, model)?;
    for (i, &x) in v.iter().enumerate() {
        if x < 0.0 || (strict && x == 0.0) {
            let need = if strict { "> 0" } else { "≥ 0" };
            return bad(field, format!("{} is {x}; need {need}", joint(model, i)));
        }
    }
    Ok(())
}

/// A positive finite scalar.
pub(super) fn positive(field: &str, x: f64) -> Result<()> {
    if x > 0.0 && x.is_finite() {
        Ok(())
    } else {
        bad(field, format!("{x} must be a positive finite number"))
    }
}

/// A finite point or direction (a direction also non-zero).
pub(super) fn point(field: &str, p: &[f64; 3], direction: bool) -> Result<()> {
    if p.iter().any(|x| !x.is_finite()) {
        return bad(field, format!("{p:?} is not finite"));
    }
    if direction && p.iter().all(|&x| x == 0.0) {
        return bad(field, "the zero vector is not a direction".into());
    }
    Ok(())
}

/// Checks every value `p` sets, naming the field.
pub(super) fn check_given(model: &Model, p: &RobotProfile) -> Result<()> {
    for (field, v) in [("home", &p.home), ("rest", &p.rest)] {
        if let Some(v) = v {
            posture(field, v, model)?;
        }
    }
    let gains = [
        ("kp", &p.kp, osrl_dynamics::MAX_JOINT_KP),
        ("kd", &p.kd, osrl_dynamics::MAX_JOINT_KD),
    ];
    for (field, v, hi) in gains {
        if let Some(v) = v {
            non_negative(field, v, model, false)?;
            if let Some(i) = v.iter().position(|&x| x > hi) {
                return bad(
                    field,
                    format!("{} is {:?}; at most {hi:?}", joint(model, i), v[i]),
                );
            }
        }
    }
    if let Some(v) = &p.torque_limits {
        non_negative("torque_limits", v, model, true)?;
    }
    let scalars = [
        ("null_space_frequency", p.null_space_frequency),
        ("null_space_damping", p.null_space_damping),
        ("path.a", p.path.a),
        ("path.b", p.path.b),
        ("path.scale", p.path.scale),
    ];
    for (field, x) in scalars {
        if let Some(x) = x {
            positive(field, x)?;
        }
    }
    let bounded = [
        (
            "null_space_frequency",
            p.null_space_frequency,
            MAX_FREQUENCY,
        ),
        ("null_space_damping", p.null_space_damping, MAX_DAMPING),
    ];
    for (field, x, hi) in bounded {
        if let Some(x) = x.filter(|&x| x > hi) {
            return bad(field, format!("{x:?} is more than {hi:?}"));
        }
    }
    if let Some(s) = p.path.scale.filter(|&s| s > 1.0) {
        return bad(
            "path.scale",
            format!("{s} is more than the whole reach (≤ 1)"),
        );
    }
    for (field, x, dir) in [
        ("path.centre", p.path.centre, false),
        ("path.e1", p.path.e1, true),
        ("path.e2", p.path.e2, true),
    ] {
        if let Some(x) = x {
            point(field, &x, dir)?;
        }
    }
    Ok(())
}
