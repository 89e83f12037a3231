//! `osrl dynamics`: kinematics and dynamics of a robot at one state.

use crate::util::{load_robot, parse_vec, print_json, rows};
use anyhow::{bail, Result};
use osrl_dynamics::{compute_all, forward_dynamics, rnea};

#[derive(clap::Args)]
pub struct Args {
    /// Built-in robot (planar3, sarcos7) or a URDF file.
    #[arg(long)]
    pub robot: String,
    /// Joint positions (rad), comma-separated.
    #[arg(long, allow_hyphen_values = true)]
    pub q: String,
    /// Joint velocities (rad/s); default zeros.
    #[arg(long, allow_hyphen_values = true)]
    pub qd: Option<String>,
    /// Joint accelerations (rad/s²) for `tau`; default zeros.
    #[arg(long, allow_hyphen_values = true)]
    pub qdd: Option<String>,
    /// Joint torques (N·m): adds `qdd_forward`, the forward dynamics with friction.
    #[arg(long, allow_hyphen_values = true)]
    pub u: Option<String>,
    /// Only the JSON line.
    #[arg(long)]
    pub json: bool,
}

/// Every number of the result finite (JSON has no NaN or infinity: they would print as null).
fn check_finite(out: &serde_json::Value) -> Result<()> {
    fn has_null(v: &serde_json::Value) -> bool {
        match v {
            serde_json::Value::Null => true,
            serde_json::Value::Array(a) => a.iter().any(has_null),
            _ => false,
        }
    }
    let bad: Vec<&str> = out
        .as_object()
        .into_iter()
        .flatten()
        .filter(|(_, v)| has_null(v))
        .map(|(k, _)| k.as_str())
        .collect();
    if !bad.is_empty() {
        bail!(
            "{} not finite at this state: --q, --qd, --qdd or --u is too large",
            bad.join(", ")
        );
    }
    Ok(())
}

pub fn run(a: Args) -> Result<()> {
    let model = load_robot(&a.robot)?;
    let (qd, qdd, u) = (a.qd.as_deref(), a.qdd.as_deref(), a.u.as_deref());
    let out = evaluate(&model, &a.q, qd, qdd, u)?;
    if !a.json {
        let x: Vec<f64> = serde_json::from_value(out["x"].clone())?;
        println!("{}: x = {x:?}", model.name());
    }
    print_json(&out);
    Ok(())
}

/// The JSON of `osrl dynamics` for the vector arguments `q`, `qd`, `qdd`, `u` (text).
///
/// # Errors
/// A malformed vector (named), a dynamics error, or a result that is not finite.
pub fn evaluate(
    model: &osrl_dynamics::Model,
    q: &str,
    qd: Option<&str>,
    qdd: Option<&str>,
    u: Option<&str>,
) -> Result<serde_json::Value> {
    let n = model.nq();
    let opt = |flag: &str, v: Option<&str>| v.map_or(Ok(vec![0.0; n]), |t| parse_vec(flag, t, n));
    let q = parse_vec("q", q, n)?;
    let qd = opt("qd", qd)?;
    let qdd = opt("qdd", qdd)?;
    let mut data = model.data();
    compute_all(model, &mut data, &q, &qd)?;
    let mut out = serde_json::json!({
        "robot": model.name(),
        "x": data.ee_pos.as_slice(),
        "xd": data.ee_vel.as_slice(),
        "J": rows(&data.jac),
        "Jdot_qd": data.jdot_qd.as_slice(),
        "task_axes": model.task_axes(),
        "M": rows(&data.mass),
        "g": data.g.as_slice(),
        "h": data.h.as_slice(),
        "friction": data.friction.as_slice(),
    });
    out["tau"] = rnea(model, &mut data, &q, &qd, &qdd)?.as_slice().into();
    if let Some(u) = u {
        let u = parse_vec("u", u, n)?;
        out["qdd_forward"] = forward_dynamics(model, &mut data, &q, &qd, &u)?
            .as_slice()
            .into();
    }
    check_finite(&out)?;
    Ok(out)
}
