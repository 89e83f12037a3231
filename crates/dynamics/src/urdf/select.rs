//! The loader's choices: the tip (end-effector link) and, for every movable joint, whether it is a
//! degree of freedom or held rigid at which position (the rules of the module docs).

use super::tree::Tree;
use super::xml::{Kind, Raw, RawJoint};
use super::{err, UrdfOptions};
use crate::error::Result;
use crate::model::LockedJoint;

/// End-effector name patterns, most specific first (lower case). A pattern matches a link name
/// as a whole word: at the name's start or after a character that is not a letter, and at its
/// end or before one (`panda_hand_tcp`, `link_eef`, `arm__ee` match; `knee_link` does not).
pub const TIP_PATTERNS: [&str; 9] = [
    "tcp",
    "end_effector",
    "endeffector",
    "ee_link",
    "eef",
    "tool0",
    "tool",
    "gripper_frame",
    "ee",
];

/// Words that keep a link from being chosen as the tip by name (fingers and sensors).
pub const NOT_A_TIP: [&str; 7] = [
    "finger", "camera", "sensor", "laser", "imu", "optical", "lidar",
];

/// Words that make a joint a gripper joint, locked unless `unlock` names it.
pub const GRIPPER_WORDS: [&str; 3] = ["finger", "gripper", "jaw"];

/// What the loader does with a joint.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Role {
    /// A fixed joint: rigid at its origin.
    Fixed,
    /// A degree of freedom of the model.
    Dof,
    /// Held rigid at `value` (rad or m; 0 for a floating or planar joint: its origin).
    Locked(f64),
}

/// A pattern as written in messages and docs.
fn shown(pattern: &str) -> String {
    format!("*{pattern}*")
}

/// Whether `pattern` occurs in `name` (lower case) as a whole word (see [`TIP_PATTERNS`]).
fn matches_word(name: &str, pattern: &str) -> bool {
    let bytes = name.as_bytes();
    let letter = |i: usize| bytes[i].is_ascii_alphabetic();
    name.match_indices(pattern).any(|(at, _)| {
        let end = at + pattern.len();
        (at == 0 || !letter(at - 1)) && (end == bytes.len() || !letter(end))
    })
}

fn has_word(name: &str, words: &[&str]) -> bool {
    let lower = name.to_lowercase();
    words.iter().any(|w| lower.contains(w))
}

fn is_gripper(j: &RawJoint) -> bool {
    has_word(&j.name, &GRIPPER_WORDS)
}

/// The tip link and the rule that chose it.
pub(super) fn tip(raw: &Raw, tree: &Tree, opts: &UrdfOptions) -> Result<(usize, String)> {
    if let Some(name) = &opts.tip {
        return match raw.link_index.get(name) {
            Some(&l) => Ok((l, "option tip".into())),
            None => err(format!("the tip '{name}' is not a link of the file")),
        };
    }
    for pattern in TIP_PATTERNS {
        let matches: Vec<usize> = tree
            .order
            .iter()
            .copied()
            .filter(|&l| {
                let name = raw.links[l].name.to_lowercase();
                matches_word(&name, pattern) && !has_word(&name, &NOT_A_TIP)
            })
            .collect();
        if matches.is_empty() {
            continue;
        }
        let deepest = *matches
            .iter()
            .max_by_key(|&&l| tree.depth[l])
            .expect("non-empty");
        let on_path = marks(raw, tree, deepest);
        if let Some(&other) = matches.iter().find(|&&l| !on_path[l]) {
            return err(format!(
                "the end-effector is ambiguous: links '{}' and '{}' both match '{}' on \
                 different branches; choose one with the tip option",
                raw.links[deepest].name,
                raw.links[other].name,
                shown(pattern)
            ));
        }
        return Ok((deepest, format!("name matches '{}'", shown(pattern))));
    }
    fallback_tip(raw, tree, opts)
}

/// Without an end-effector name: the link moved by the last arm joint, where the arm joints are the
/// movable joints that are neither gripper joints, mimic joints nor locked by the options.
fn fallback_tip(raw: &Raw, tree: &Tree, opts: &UrdfOptions) -> Result<(usize, String)> {
    let locked = |j: &RawJoint| opts.lock.iter().any(|(n, _)| n == &j.name);
    let unlocked = |j: &RawJoint| opts.unlock.iter().any(|n| n == &j.name);
    let arm: Vec<usize> = (0..raw.joints.len())
        .filter(|&j| {
            let joint = &raw.joints[j];
            matches!(
                joint.kind,
                Kind::Revolute | Kind::Continuous | Kind::Prismatic
            ) && joint.mimic.is_none()
                && !locked(joint)
                && (!is_gripper(joint) || unlocked(joint))
        })
        .collect();
    let Some(&last) = arm.iter().max_by_key(|&&j| tree.depth[raw.joints[j].child]) else {
        return err(format!(
            "no movable joint outside the gripper (joints named with {} are locked, as are \
             mimic joints): choose the tip and unlock the joints that should move",
            GRIPPER_WORDS.join(", ")
        ));
    };
    let tip = raw.joints[last].child;
    let on_path = marks(raw, tree, tip);
    if let Some(&other) = arm.iter().find(|&&j| !on_path[raw.joints[j].child]) {
        return err(format!(
            "no link is named like an end-effector ({}) and the arm branches: joints '{}' and \
             '{}' are on different chains; choose the end-effector link with the tip option",
            TIP_PATTERNS.map(shown).join(", "),
            raw.joints[last].name,
            raw.joints[other].name
        ));
    }
    Ok((
        tip,
        "the link moved by the last arm joint (no end-effector name)".into(),
    ))
}

/// `marks[l]`: link `l` is on the path from the root to `link` (inclusive).
fn marks(raw: &Raw, tree: &Tree, link: usize) -> Vec<bool> {
    let mut on = vec![false; raw.links.len()];
    on[link] = true;
    for j in tree.path_to(raw, link) {
        on[raw.joints[j].parent] = true;
    }
    on
}

/// The role of every joint and the list of locked joints with their reasons.
pub(super) fn roles(
    raw: &Raw,
    tree: &Tree,
    tip: usize,
    opts: &UrdfOptions,
) -> Result<(Vec<Role>, Vec<LockedJoint>)> {
    let on_path = marks(raw, tree, tip);
    let beyond = below(raw, tree, tip);
    check_options(raw, &on_path, opts)?;
    let mut roles = vec![Role::Fixed; raw.joints.len()];
    let mut reasons: Vec<Option<String>> = vec![None; raw.joints.len()];
    // Non-mimic joints first: a mimic joint's position follows its leader's.
    for (j, joint) in raw.joints.iter().enumerate() {
        if joint.kind == Kind::Fixed || joint.mimic.is_some() {
            continue;
        }
        let path = on_path[joint.child];
        let explicit = opts.lock.iter().find(|(n, _)| n == &joint.name);
        let reason = if let Some((_, value)) = explicit {
            roles[j] = Role::Locked(lock_value(joint, *value)?);
            reasons[j] = Some("option lock".into());
            continue;
        } else if beyond[joint.child] {
            "beyond the tip"
        } else if is_gripper(joint) && !opts.unlock.contains(&joint.name) {
            "finger/gripper name"
        } else if !path {
            "not on the chain from the root to the tip"
        } else if joint.kind == Kind::Multi {
            return err(format!(
                "joint '{}': floating and planar joints between the root and the tip are not \
                 supported (fixed-base serial arms only)",
                joint.name
            ));
        } else {
            roles[j] = Role::Dof;
            continue;
        };
        roles[j] = Role::Locked(lock_value(joint, None)?);
        reasons[j] = Some(reason.into());
    }
    for (j, joint) in raw.joints.iter().enumerate() {
        if let Some(m) = &joint.mimic {
            let value = mimic_value(raw, &roles, joint, on_path[joint.child])?;
            roles[j] = Role::Locked(value);
            reasons[j] = Some(format!("mimics '{}'", m.leader));
        }
    }
    let locked = locked_list(raw, &roles, reasons);
    Ok((roles, locked))
}

/// The locked joints, in file order, with their positions and reasons.
fn locked_list(raw: &Raw, roles: &[Role], reasons: Vec<Option<String>>) -> Vec<LockedJoint> {
    raw.joints
        .iter()
        .zip(roles)
        .zip(reasons)
        .filter_map(|((joint, role), reason)| match role {
            Role::Locked(value) => Some(LockedJoint {
                name: joint.name.clone(),
                value: *value,
                reason: reason.unwrap_or_default(),
            }),
            _ => None,
        })
        .collect()
}

/// `below[l]`: link `l` lies strictly beyond `tip` (in its subtree, not the tip itself).
fn below(raw: &Raw, tree: &Tree, tip: usize) -> Vec<bool> {
    let mut out = vec![false; raw.links.len()];
    let mut stack: Vec<usize> = tree.child_joints(tip).to_vec();
    while let Some(j) = stack.pop() {
        let c = raw.joints[j].child;
        out[c] = true;
        stack.extend_from_slice(tree.child_joints(c));
    }
    out
}

/// Every joint named in `lock` and `unlock` exists and can be what it is asked to be.
fn check_options(raw: &Raw, on_path: &[bool], opts: &UrdfOptions) -> Result<()> {
    let find = |name: &str, what: &str| match raw.joint_index.get(name) {
        Some(&j) if raw.joints[j].kind == Kind::Fixed => {
            err(format!("{what} '{name}': the joint is fixed"))
        }
        Some(&j) => Ok(&raw.joints[j]),
        None => err(format!("{what} '{name}': no such joint in the file")),
    };
    for (name, value) in &opts.lock {
        let j = find(name, "lock")?;
        if j.mimic.is_some() && value.is_some() {
            return err(format!(
                "lock '{name}': a mimic joint follows its leader; lock the leader instead"
            ));
        }
        if opts.unlock.contains(name) {
            return err(format!("joint '{name}' is both locked and unlocked"));
        }
    }
    for name in &opts.unlock {
        let j = find(name, "unlock")?;
        if j.mimic.is_some() {
            return err(format!(
                "unlock '{name}': a mimic joint follows its leader and cannot be a degree of \
                 freedom"
            ));
        }
        if !on_path[j.child] {
            return err(format!(
                "unlock '{name}': the joint is not between the root and the tip"
            ));
        }
    }
    Ok(())
}

/// A locked joint's position: `value`, or 0 clamped into its limits; checked against the limits.
fn lock_value(joint: &RawJoint, value: Option<f64>) -> Result<f64> {
    let (lo, hi) = match (joint.kind, joint.limit) {
        (Kind::Revolute | Kind::Prismatic, Some(l)) => (l.lower, l.upper),
        _ => (f64::NEG_INFINITY, f64::INFINITY),
    };
    if joint.kind == Kind::Multi {
        return match value {
            None => Ok(0.0),
            Some(_) => err(format!(
                "lock '{}': a floating or planar joint is locked at its origin; give no value",
                joint.name
            )),
        };
    }
    if lo > hi {
        return err(format!(
            "joint '{}': <limit lower=\"{lo}\" upper=\"{hi}\"> is not ordered",
            joint.name
        ));
    }
    match value {
        None => Ok(0.0f64.clamp(lo, hi)),
        Some(v) if v.is_finite() && v >= lo && v <= hi => Ok(v),
        Some(v) => err(format!(
            "lock '{}={v}': the value must be finite and within the joint's limits [{lo}, {hi}]",
            joint.name
        )),
    }
}

/// A mimic joint's position `multiplier · q_leader + offset`; its leader must be locked.
fn mimic_value(raw: &Raw, roles: &[Role], joint: &RawJoint, on_path: bool) -> Result<f64> {
    let m = joint.mimic.as_ref().expect("a mimic joint");
    let name = &joint.name;
    let Some(&leader) = raw.joint_index.get(&m.leader) else {
        return err(format!(
            "joint '{name}' mimics '{}', which is not a joint",
            m.leader
        ));
    };
    let what = if on_path {
        "a degree of freedom"
    } else {
        "locked"
    };
    match &roles[leader] {
        Role::Locked(v) if raw.joints[leader].mimic.is_none() => Ok(m.multiplier * v + m.offset),
        Role::Dof => err(format!(
            "joint '{name}' mimics '{}', which is a degree of freedom: coupled joints are not \
             supported, so '{name}' cannot be {what}; lock '{}' (or choose another tip)",
            m.leader, m.leader
        )),
        _ => err(format!(
            "joint '{name}' mimics '{}', which is fixed or itself a mimic joint",
            m.leader
        )),
    }
}
