//! The `<osrl_profile .../>` element (a child of `<robot>`): a robot profile's postures, gains,
//! torque limits and path placement as attributes, so that a profile travels with an exported
//! robot. Vectors are space-separated numbers (`home="0 -0.3 0"`); `path_centre`, `path_e1`,
//! `path_e2` have three, `path_a`, `path_b`, `path_scale`, `null_space_frequency` and
//! `null_space_damping` one. Tip and locks are not written: an exported chain is already reduced.

use super::err;
use crate::error::Result;
use crate::profile::RobotProfile;
use roxmltree::Node;
use std::fmt::Write;

const VECTORS: [&str; 5] = ["home", "rest", "kp", "kd", "torque_limits"];
const POINTS: [&str; 3] = ["path_centre", "path_e1", "path_e2"];
const SCALARS: [&str; 5] = [
    "path_a",
    "path_b",
    "path_scale",
    "null_space_frequency",
    "null_space_damping",
];

fn numbers(attr: &str, text: &str) -> Result<Vec<f64>> {
    text.split_whitespace()
        .map(|s| {
            s.parse::<f64>().map_err(|_| {
                crate::DynamicsError::Urdf(format!(
                    "<osrl_profile {attr}=\"{text}\">: '{s}' is not a number"
                ))
            })
        })
        .collect()
}

/// Reads the element; unknown attributes and malformed numbers are errors naming the
/// attribute (ranges are checked when the profile is resolved for the model).
pub(super) fn read(node: Node) -> Result<RobotProfile> {
    let mut p = RobotProfile::default();
    for a in node.attributes() {
        let (name, text) = (a.name(), a.value());
        let v = numbers(name, text)?;
        let count = |k: usize| -> Result<()> {
            if v.len() == k {
                Ok(())
            } else {
                err(format!(
                    "<osrl_profile {name}=\"{text}\">: {} numbers, expected {k}",
                    v.len()
                ))
            }
        };
        let point = |v: &[f64]| [v[0], v[1], v[2]];
        match name {
            "home" => p.home = Some(v),
            "rest" => p.rest = Some(v),
            "kp" => p.kp = Some(v),
            "kd" => p.kd = Some(v),
            "torque_limits" => p.torque_limits = Some(v),
            _ if POINTS.contains(&name) => {
                count(3)?;
                let x = Some(point(&v));
                match name {
                    "path_centre" => p.path.centre = x,
                    "path_e1" => p.path.e1 = x,
                    _ => p.path.e2 = x,
                }
            }
            _ if SCALARS.contains(&name) => {
                count(1)?;
                let x = Some(v[0]);
                match name {
                    "path_a" => p.path.a = x,
                    "path_b" => p.path.b = x,
                    "path_scale" => p.path.scale = x,
                    "null_space_frequency" => p.null_space_frequency = x,
                    _ => p.null_space_damping = x,
                }
            }
            _ => {
                return err(format!(
                    "<osrl_profile>: unknown attribute '{name}' (known: {}, {}, {})",
                    VECTORS.join(", "),
                    POINTS.join(", "),
                    SCALARS.join(", ")
                ))
            }
        }
    }
    Ok(p)
}

/// The element for `p` (its set postures, gains, limits and placement), one line, or an empty
/// string when none is set.
pub(super) fn write(p: &RobotProfile) -> String {
    let num = |x: f64| format!("{x:?}");
    let list = |v: &[f64]| v.iter().map(|&x| num(x)).collect::<Vec<_>>().join(" ");
    let mut s = String::new();
    let vectors = [&p.home, &p.rest, &p.kp, &p.kd, &p.torque_limits];
    for (name, v) in VECTORS.iter().zip(vectors) {
        if let Some(v) = v {
            let _ = write!(s, " {name}=\"{}\"", list(v));
        }
    }
    let path = &p.path;
    for (name, v) in POINTS.iter().zip([path.centre, path.e1, path.e2]) {
        if let Some(v) = v {
            let _ = write!(s, " {name}=\"{}\"", list(&v));
        }
    }
    let scalars = [
        path.a,
        path.b,
        path.scale,
        p.null_space_frequency,
        p.null_space_damping,
    ];
    for (name, v) in SCALARS.iter().zip(scalars) {
        if let Some(v) = v {
            let _ = write!(s, " {name}=\"{}\"", num(v));
        }
    }
    if s.is_empty() {
        s
    } else {
        format!("  <osrl_profile{s}/>\n")
    }
}
