//! From the tree and the joint roles to a [`Model`]: one iterative walk assigns every link to the
//! rigid body of the nearest degree of freedom above it and lumps its inertia there exactly.

use super::err;
use super::select::Role;
use super::tree::Tree;
use super::xml::{Kind, Raw, RawJoint};
use crate::error::Result;
use crate::inertia::Inertia;
use crate::model::{JointKind, JointLimits, Link, Model, ModelSpec, UrdfImport, GRAVITY};
use crate::spatial::{axis_angle, Pose};
use nalgebra::Vector3;

/// The pose of a non-DOF joint's child in its parent link's frame.
fn rigid_pose(joint: &RawJoint, role: &Role) -> Pose {
    let value = match role {
        Role::Locked(v) => *v,
        _ => 0.0,
    };
    match joint.kind {
        Kind::Revolute | Kind::Continuous => joint.origin.compose(&Pose::new(
            axis_angle(&joint.axis.normalize(), value),
            Vector3::zeros(),
        )),
        Kind::Prismatic => joint.origin.compose(&Pose::new(
            nalgebra::Matrix3::identity(),
            joint.axis.normalize() * value,
        )),
        Kind::Fixed | Kind::Multi => joint.origin,
    }
}

/// Builds the model: degrees of freedom are the `Role::Dof` joints (all on the path to `tip`).
pub(super) fn build(
    raw: &Raw,
    tree: &Tree,
    roles: &[Role],
    tip: usize,
    import: UrdfImport,
) -> Result<Model> {
    let dofs = degrees_of_freedom(raw, tree, roles, tip)?;
    let (inertia, origin, ee) = lump(raw, tree, roles, tip, &dofs)?;
    let links = dofs
        .iter()
        .zip(origin)
        .zip(&inertia[1..])
        .map(|((&j, origin), inertia)| dof_link(raw, j, origin, *inertia))
        .collect::<Result<Vec<Link>>>()?;
    let n = links.len();
    let mid: Vec<f64> = links
        .iter()
        .map(|l| {
            if l.limits.q_min.is_finite() && l.limits.q_max.is_finite() {
                0.5 * (l.limits.q_min + l.limits.q_max)
            } else {
                0.0
            }
        })
        .collect();
    let mut spec = ModelSpec {
        name: raw.name.clone(),
        links,
        ee_offset: ee,
        gravity: GRAVITY,
        task_axes: vec![0, 1, 2],
        q_start: mid.clone(),
        q_rest: mid,
        kp: vec![10.0; n],
        kd: vec![1.0; n],
        urdf: Some(import),
    };
    spec.task_axes = reachable_axes(&Model::new(spec.clone())?);
    Model::new(spec)
}

/// The `Role::Dof` joints from the root to the tip: at least one, at most `MAX_DOF`.
fn degrees_of_freedom(raw: &Raw, tree: &Tree, roles: &[Role], tip: usize) -> Result<Vec<usize>> {
    let path = tree.path_to(raw, tip);
    let dofs: Vec<usize> = path
        .iter()
        .copied()
        .filter(|&j| roles[j] == Role::Dof)
        .collect();
    if dofs.is_empty() {
        let locked: Vec<&str> = path
            .iter()
            .filter(|&&j| matches!(roles[j], Role::Locked(_)))
            .map(|&j| raw.joints[j].name.as_str())
            .collect();
        let hint = if locked.is_empty() {
            String::new()
        } else {
            format!(
                " (locked on the way: {}; see the unlock option)",
                locked.join(", ")
            )
        };
        return err(format!(
            "no degree of freedom between the root link '{}' and the tip '{}'{hint}",
            raw.links[tree.root].name, raw.links[tip].name
        ));
    }
    if dofs.len() > crate::model::MAX_DOF {
        return err(format!(
            "{} degrees of freedom: at most {} are supported",
            dofs.len(),
            crate::model::MAX_DOF
        ));
    }
    Ok(dofs)
}

/// One iterative walk over the tree: the lumped inertia of every body (body 0 is the fixed base,
/// body k + 1 moves with DOF k), each DOF's joint origin in the previous body's frame, and the
/// tip's position in the last body's frame.
fn lump(
    raw: &Raw,
    tree: &Tree,
    roles: &[Role],
    tip: usize,
    dofs: &[usize],
) -> Result<(Vec<Inertia>, Vec<Pose>, Vector3<f64>)> {
    let mut body_of_dof = vec![usize::MAX; raw.joints.len()];
    for (k, &j) in dofs.iter().enumerate() {
        body_of_dof[j] = k + 1;
    }
    let mut inertia = vec![Inertia::zero(); dofs.len() + 1];
    let mut origin = vec![Pose::identity(); dofs.len()];
    let mut ee = Vector3::zeros();
    let mut stack = vec![(tree.root, 0usize, Pose::identity())];
    while let Some((l, body, pose)) = stack.pop() {
        if body > 0 {
            let link = &raw.links[l];
            if !raw.identified_inertias {
                check_inertia(&link.name, &link.inertia_com)?;
            }
            inertia[body] = inertia[body].add(&link.inertia.to_parent(&pose));
        }
        if l == tip {
            ee = pose.trans;
        }
        for &j in tree.child_joints(l) {
            let joint = &raw.joints[j];
            if roles[j] == Role::Dof {
                let k = body_of_dof[j];
                origin[k - 1] = pose.compose(&joint.origin);
                stack.push((joint.child, k, Pose::identity()));
            } else {
                let child = pose.compose(&rigid_pose(joint, &roles[j]));
                stack.push((joint.child, body, child));
            }
        }
    }
    Ok((inertia, origin, ee))
}

/// A degree of freedom as a model link: kind, axis, limits (a positive effort required) and
/// friction.
fn dof_link(raw: &Raw, j: usize, origin: Pose, inertia: Inertia) -> Result<Link> {
    let joint = &raw.joints[j];
    let ctx = format!("joint '{}'", joint.name);
    let mut limits = JointLimits::default();
    if let Some(l) = joint.limit {
        if !(l.effort > 0.0) {
            return err(format!(
                "{ctx}: <limit effort=\"{}\"> must be positive (N·m or N)",
                l.effort
            ));
        }
        limits.tau_max = l.effort;
        limits.qd_max = if l.velocity > 0.0 {
            l.velocity
        } else {
            f64::INFINITY
        };
        if joint.kind != Kind::Continuous {
            if l.lower > l.upper {
                return err(format!(
                    "{ctx}: <limit lower=\"{}\" upper=\"{}\"> is not ordered",
                    l.lower, l.upper
                ));
            }
            (limits.q_min, limits.q_max) = (l.lower, l.upper);
        }
    }
    Ok(Link {
        name: raw.links[joint.child].name.clone(),
        joint_name: joint.name.clone(),
        origin,
        axis: joint.axis,
        kind: if joint.kind == Kind::Prismatic {
            JointKind::Prismatic
        } else {
            JointKind::Revolute
        },
        inertia,
        friction: joint.friction,
        limits,
    })
}

/// Refuses an inertia no rigid body can have ([`Inertia::unphysical`]), naming the link.
fn check_inertia(link: &str, ic: &nalgebra::Matrix3<f64>) -> Result<()> {
    match Inertia::unphysical(ic, ic.trace().abs()) {
        Some(why) => err(format!("link '{link}': {why}")),
        None => Ok(()),
    }
}

/// World axes along which the end-effector can move: rows of `J` that are non-zero at some of a
/// few fixed test postures (a planar arm gets its plane's two axes).
fn reachable_axes(model: &Model) -> Vec<usize> {
    let mut data = model.data();
    let n = model.nq();
    let mut moves = [false; 3];
    for k in 0..5 {
        let q: Vec<f64> = (0..n)
            .map(|i| (0.7 * (i + 1) as f64 + 1.3 * k as f64).sin())
            .collect();
        if crate::jacobian(model, &mut data, &q).is_ok() {
            for (a, m) in moves.iter_mut().enumerate() {
                *m |= data.jac.row(a).amax() > 1e-9;
            }
        }
    }
    let axes: Vec<usize> = (0..3).filter(|&a| moves[a]).collect();
    if axes.is_empty() {
        vec![0, 1, 2]
    } else {
        axes
    }
}
