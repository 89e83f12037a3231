//! URDF import: a serial chain of revolute/continuous joints, fixed joints folded in.

use crate::error::{DynamicsError, Result};
use crate::inertia::Inertia;
use crate::model::{Friction, JointLimits, Link, Model, ModelSpec, GRAVITY};
use crate::spatial::{rpy_to_matrix, Pose};
use nalgebra::{Matrix3, Vector3};
use roxmltree::{Document, Node};
use std::collections::HashMap;

fn err<T>(msg: String) -> Result<T> {
    Err(DynamicsError::Urdf(msg))
}

/// Reads and parses a URDF file. Errors name the file and the offending element.
pub fn load_urdf(path: &std::path::Path) -> Result<Model> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| DynamicsError::Urdf(format!("cannot read {}: {e}", path.display())))?;
    parse_urdf(&text).map_err(|e| match e {
        DynamicsError::Urdf(m) => DynamicsError::Urdf(format!("{}: {m}", path.display())),
        other => other,
    })
}

/// `n` numbers from a space-separated attribute (`default` when absent).
fn numbers<const N: usize>(
    node: Node,
    attr: &str,
    default: Option<[f64; N]>,
    ctx: &str,
) -> Result<[f64; N]> {
    let Some(text) = node.attribute(attr) else {
        return default.map_or_else(
            || {
                err(format!(
                    "{ctx}: <{}> lacks the attribute '{attr}'",
                    node.tag_name().name()
                ))
            },
            Ok,
        );
    };
    let vals: Vec<f64> = text
        .split_whitespace()
        .map(str::parse)
        .collect::<std::result::Result<_, _>>()
        .map_err(|_| {
            DynamicsError::Urdf(format!(
                "{ctx}: <{} {attr}=\"{text}\"> is not a list of numbers",
                node.tag_name().name()
            ))
        })?;
    if vals.len() != N || vals.iter().any(|v| !v.is_finite()) {
        return err(format!(
            "{ctx}: <{} {attr}=\"{text}\"> needs {N} finite numbers",
            node.tag_name().name()
        ));
    }
    let mut out = [0.0; N];
    out.copy_from_slice(&vals);
    Ok(out)
}

fn child<'a, 'i>(node: Node<'a, 'i>, tag: &str) -> Option<Node<'a, 'i>> {
    node.children().find(|c| c.has_tag_name(tag))
}

/// An `<origin xyz rpy>` child as a pose (identity when absent).
fn origin(node: Node, ctx: &str) -> Result<Pose> {
    match child(node, "origin") {
        None => Ok(Pose::identity()),
        Some(o) => {
            let [x, y, z] = numbers(o, "xyz", Some([0.0; 3]), ctx)?;
            let [r, p, yaw] = numbers(o, "rpy", Some([0.0; 3]), ctx)?;
            Ok(Pose::new(rpy_to_matrix(r, p, yaw), Vector3::new(x, y, z)))
        }
    }
}

/// A link's `<inertial>` in the link frame (zero when absent).
fn inertial(link: Node, ctx: &str) -> Result<Inertia> {
    let Some(node) = child(link, "inertial") else {
        return Ok(Inertia::zero());
    };
    let pose = origin(node, ctx)?;
    let mass_node = child(node, "mass")
        .ok_or_else(|| DynamicsError::Urdf(format!("{ctx}: <inertial> lacks <mass>")))?;
    let [mass] = numbers(mass_node, "value", None, ctx)?;
    if mass < 0.0 {
        return err(format!("{ctx}: negative mass {mass}"));
    }
    let i = child(node, "inertia")
        .ok_or_else(|| DynamicsError::Urdf(format!("{ctx}: <inertial> lacks <inertia>")))?;
    let mut v = [0.0; 6];
    for (k, name) in ["ixx", "ixy", "ixz", "iyy", "iyz", "izz"]
        .iter()
        .enumerate()
    {
        v[k] = numbers::<1>(i, name, None, ctx)?[0];
    }
    let local = Matrix3::new(v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5]);
    let inertia_com = pose.rot * local * pose.rot.transpose();
    Ok(Inertia::from_com(
        mass,
        pose.trans,
        (inertia_com + inertia_com.transpose()) * 0.5,
    ))
}

struct Joint<'a, 'i> {
    node: Node<'a, 'i>,
    name: String,
    movable: bool,
    parent: String,
    child: String,
}

/// Parses URDF text into a [`Model`] (see the module docs for the conventions).
pub fn parse_urdf(text: &str) -> Result<Model> {
    let doc =
        Document::parse(text).map_err(|e| DynamicsError::Urdf(format!("malformed XML: {e}")))?;
    let robot = doc.root_element();
    if !robot.has_tag_name("robot") {
        return err(format!(
            "the root element is <{}>, expected <robot>",
            robot.tag_name().name()
        ));
    }
    let name = robot.attribute("name").unwrap_or("urdf_robot").to_string();
    let mut links: HashMap<String, Node> = HashMap::new();
    for l in robot.children().filter(|c| c.has_tag_name("link")) {
        let Some(n) = l.attribute("name") else {
            return err("a <link> has no name".into());
        };
        if links.insert(n.to_string(), l).is_some() {
            return err(format!("link '{n}' is defined twice"));
        }
    }
    let mut joints = Vec::new();
    for j in robot.children().filter(|c| c.has_tag_name("joint")) {
        let jname = j
            .attribute("name")
            .ok_or_else(|| DynamicsError::Urdf("a <joint> has no name".into()))?;
        let ctx = format!("joint '{jname}'");
        let kind = j.attribute("type").unwrap_or("");
        let movable = match kind {
            "revolute" | "continuous" => true,
            "fixed" => false,
            other => {
                return err(format!(
                    "{ctx}: type '{other}' is not supported (only revolute, continuous and fixed)"
                ))
            }
        };
        if child(j, "mimic").is_some() {
            return err(format!("{ctx}: <mimic> is not supported"));
        }
        let link_of = |tag: &str| -> Result<String> {
            let n = child(j, tag)
                .and_then(|c| c.attribute("link"))
                .ok_or_else(|| DynamicsError::Urdf(format!("{ctx}: missing <{tag} link=...>")))?;
            if !links.contains_key(n) {
                return err(format!("{ctx}: <{tag}> names the undefined link '{n}'"));
            }
            Ok(n.to_string())
        };
        joints.push(Joint {
            node: j,
            name: jname.to_string(),
            movable,
            parent: link_of("parent")?,
            child: link_of("child")?,
        });
    }
    let roots: Vec<&String> = links
        .keys()
        .filter(|l| !joints.iter().any(|j| &j.child == *l))
        .collect();
    if roots.len() != 1 {
        let mut r: Vec<_> = roots.iter().map(|s| s.as_str()).collect();
        r.sort();
        return err(format!(
            "expected one root link, found {} ({})",
            r.len(),
            r.join(", ")
        ));
    }
    if let Some(j) = joints
        .iter()
        .find(|j| joints.iter().filter(|k| k.child == j.child).count() > 1)
    {
        return err(format!("link '{}' is the child of several joints", j.child));
    }
    build(name, roots[0].clone(), &links, &joints)
}

/// What hangs below one movable frame through fixed joints.
struct Subtree<'j, 'a, 'i> {
    inertia: Inertia,
    movable: Vec<(&'j Joint<'a, 'i>, Pose)>,
    deepest: Option<(usize, Pose)>,
}

/// Walks the fixed-joint subtree of `link` (pose `pose` in the current movable frame).
fn walk<'j, 'a, 'i>(
    link: &str,
    pose: Pose,
    depth: usize,
    links: &HashMap<String, Node>,
    joints: &'j [Joint<'a, 'i>],
    acc: &mut Subtree<'j, 'a, 'i>,
) -> Result<()> {
    let li = inertial(links[link], &format!("link '{link}'"))?;
    acc.inertia = acc.inertia.add(&li.to_parent(&pose));
    if acc.deepest.as_ref().is_none_or(|(d, _)| depth > *d) {
        acc.deepest = Some((depth, pose));
    }
    for j in joints.iter().filter(|j| j.parent == link) {
        let jpose = pose.compose(&origin(j.node, &format!("joint '{}'", j.name))?);
        if j.movable {
            acc.movable.push((j, jpose));
        } else {
            walk(&j.child, jpose, depth + 1, links, joints, acc)?;
        }
    }
    Ok(())
}

fn build(
    name: String,
    root: String,
    links: &HashMap<String, Node>,
    joints: &[Joint],
) -> Result<Model> {
    let mut chain: Vec<Link> = Vec::new();
    let mut link = root;
    let ee_offset = loop {
        let mut sub = Subtree {
            inertia: Inertia::zero(),
            movable: vec![],
            deepest: None,
        };
        walk(&link, Pose::identity(), 0, links, joints, &mut sub)?;
        if let Some(last) = chain.last_mut() {
            last.inertia = sub.inertia;
        }
        match sub.movable.len() {
            0 => break sub.deepest.map_or(Vector3::zeros(), |(_, p)| p.trans),
            1 => {}
            k => {
                let names: Vec<_> = sub.movable.iter().map(|(j, _)| j.name.as_str()).collect();
                return err(format!("link '{link}' branches into {k} movable joints ({}); only serial chains are supported", names.join(", ")));
            }
        }
        let (j, pose) = sub.movable[0];
        chain.push(movable_link(j, pose)?);
        link = j.child.clone();
    };
    if chain.is_empty() {
        return err("no revolute or continuous joint".into());
    }
    let n = chain.len();
    let mid: Vec<f64> = chain
        .iter()
        .map(|l| {
            if l.limits.q_min.is_finite() {
                0.5 * (l.limits.q_min + l.limits.q_max)
            } else {
                0.0
            }
        })
        .collect();
    let mut spec = ModelSpec {
        name,
        links: chain,
        ee_offset,
        gravity: GRAVITY,
        task_axes: vec![0, 1, 2],
        q_start: mid.clone(),
        q_rest: mid,
        kp: vec![10.0; n],
        kd: vec![1.0; n],
    };
    spec.task_axes = reachable_axes(&Model::new(spec.clone())?);
    Model::new(spec)
}

fn movable_link(j: &Joint, pose: Pose) -> Result<Link> {
    let ctx = format!("joint '{}'", j.name);
    let axis = match child(j.node, "axis") {
        Some(a) => Vector3::from(numbers(a, "xyz", Some([1.0, 0.0, 0.0]), &ctx)?),
        None => Vector3::x(),
    };
    if axis.norm() < 1e-12 {
        return err(format!("{ctx}: zero <axis>"));
    }
    let mut limits = JointLimits::default();
    match child(j.node, "limit") {
        Some(l) => {
            let [effort] = numbers(l, "effort", Some([f64::INFINITY]), &ctx)?;
            let [velocity] = numbers(l, "velocity", Some([f64::INFINITY]), &ctx)?;
            limits.tau_max = if effort > 0.0 { effort } else { f64::INFINITY };
            limits.qd_max = if velocity > 0.0 {
                velocity
            } else {
                f64::INFINITY
            };
            if j.node.attribute("type") == Some("revolute") {
                let [lo] = numbers(l, "lower", Some([0.0]), &ctx)?;
                let [hi] = numbers(l, "upper", Some([0.0]), &ctx)?;
                if lo > hi {
                    return err(format!(
                        "{ctx}: <limit lower=\"{lo}\" upper=\"{hi}\"> is not ordered"
                    ));
                }
                (limits.q_min, limits.q_max) = (lo, hi);
            }
        }
        None if j.node.attribute("type") == Some("revolute") => {
            return err(format!("{ctx}: a revolute joint needs a <limit> element"))
        }
        None => {}
    }
    let mut friction = Friction::default();
    if let Some(d) = child(j.node, "dynamics") {
        let [damping] = numbers(d, "damping", Some([0.0]), &ctx)?;
        let [coulomb] = numbers(d, "friction", Some([0.0]), &ctx)?;
        if damping < 0.0 || coulomb < 0.0 {
            return err(format!("{ctx}: negative <dynamics> coefficient"));
        }
        (friction.viscous, friction.coulomb) = (damping, coulomb);
    }
    Ok(Link {
        name: j.child.clone(),
        joint_name: j.name.clone(),
        origin: pose,
        axis,
        inertia: Inertia::zero(),
        friction,
        limits,
    })
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
