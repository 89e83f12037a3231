//! Reading a URDF document into plain links and joints, in one linear pass (no physics yet).

use super::{err, MAX_JOINTS, MAX_LINKS, MAX_URDF_BYTES, MAX_XML_NODES};
use crate::error::{DynamicsError, Result};
use crate::inertia::Inertia;
use crate::model::Friction;
use crate::spatial::{rpy_to_matrix, Pose};
use nalgebra::{Matrix3, Vector3};
use roxmltree::{Document, Node, ParsingOptions};
use std::collections::HashMap;

/// A URDF joint type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    Fixed,
    Revolute,
    Continuous,
    Prismatic,
    /// `floating` or `planar`: several degrees of freedom, never part of the chain.
    Multi,
}

/// `<limit>` of a movable joint; absent attributes as in the URDF spec (0 for the position
/// limits, unlimited effort and velocity).
#[derive(Clone, Copy, Debug)]
pub(super) struct Limit {
    pub lower: f64,
    pub upper: f64,
    pub effort: f64,
    pub velocity: f64,
}

/// `<mimic joint multiplier offset>`: this joint's position is `multiplier · q_leader + offset`.
#[derive(Clone, Debug)]
pub(super) struct Mimic {
    pub leader: String,
    pub multiplier: f64,
    pub offset: f64,
}

pub(super) struct RawLink {
    pub name: String,
    /// The `<inertial>` in the link frame (zero when absent).
    pub inertia: Inertia,
    /// The `<inertia>` about the centre of mass as written (for the physical check).
    pub inertia_com: Matrix3<f64>,
}

pub(super) struct RawJoint {
    pub name: String,
    pub kind: Kind,
    pub parent: usize,
    pub child: usize,
    pub origin: Pose,
    pub axis: Vector3<f64>,
    pub limit: Option<Limit>,
    pub friction: Friction,
    pub mimic: Option<Mimic>,
}

/// The links and joints of a file, with maps from names to indices.
pub(super) struct Raw {
    pub name: String,
    pub links: Vec<RawLink>,
    pub joints: Vec<RawJoint>,
    pub joint_index: HashMap<String, usize>,
    pub link_index: HashMap<String, usize>,
    /// The file declares identified inertial parameters (`<osrl identified_inertias="true"/>`).
    pub identified_inertias: bool,
    /// The robot profile of an `<osrl_profile .../>` element, if the file has one.
    pub profile: Option<crate::profile::RobotProfile>,
}

/// Parses the document: every element is read once, names are looked up in hash maps.
pub(super) fn read(text: &str) -> Result<Raw> {
    if text.len() > MAX_URDF_BYTES {
        return err(format!(
            "the file has {} bytes; at most {MAX_URDF_BYTES} are accepted",
            text.len()
        ));
    }
    super::depth::check_depth(text)?;
    let opts = ParsingOptions {
        allow_dtd: false,
        nodes_limit: MAX_XML_NODES,
    };
    let doc = Document::parse_with_options(text, opts)
        .map_err(|e| DynamicsError::Urdf(format!("malformed XML: {e}")))?;
    let robot = doc.root_element();
    if !robot.has_tag_name("robot") {
        return err(format!(
            "the root element is <{}>, expected <robot>",
            robot.tag_name().name()
        ));
    }
    let mut raw = Raw {
        name: robot.attribute("name").unwrap_or("urdf_robot").to_string(),
        links: Vec::new(),
        joints: Vec::new(),
        joint_index: HashMap::new(),
        link_index: HashMap::new(),
        identified_inertias: robot
            .children()
            .any(|c| c.has_tag_name("osrl") && c.attribute("identified_inertias") == Some("true")),
        profile: None,
    };
    let mut profiles = robot.children().filter(|c| c.has_tag_name("osrl_profile"));
    if let Some(node) = profiles.next() {
        if profiles.next().is_some() {
            return err("more than one <osrl_profile> element".into());
        }
        raw.profile = Some(super::profile_xml::read(node)?);
    }
    read_links(robot, &mut raw)?;
    for j in robot.children().filter(|c| c.has_tag_name("joint")) {
        if raw.joints.len() == MAX_JOINTS {
            return err(format!("more than {MAX_JOINTS} joints"));
        }
        let joint = joint(j, &raw.link_index)?;
        if raw
            .joint_index
            .insert(joint.name.clone(), raw.joints.len())
            .is_some()
        {
            return err(format!("joint '{}' is defined twice", joint.name));
        }
        raw.joints.push(joint);
    }
    Ok(raw)
}

/// Every `<link>`: name (unique) and inertial.
fn read_links(robot: Node, raw: &mut Raw) -> Result<()> {
    for l in robot.children().filter(|c| c.has_tag_name("link")) {
        let Some(name) = l.attribute("name") else {
            return err("a <link> has no name".into());
        };
        if raw.links.len() == MAX_LINKS {
            return err(format!("more than {MAX_LINKS} links"));
        }
        if raw
            .link_index
            .insert(name.to_string(), raw.links.len())
            .is_some()
        {
            return err(format!("link '{name}' is defined twice"));
        }
        let (inertia, inertia_com) = inertial(l, &format!("link '{name}'"))?;
        raw.links.push(RawLink {
            name: name.to_string(),
            inertia,
            inertia_com,
        });
    }
    Ok(())
}

/// One `<joint>`: type, links, origin, and for movable joints axis, limit, dynamics and mimic.
fn joint(j: Node, links: &HashMap<String, usize>) -> Result<RawJoint> {
    let name = j
        .attribute("name")
        .ok_or_else(|| DynamicsError::Urdf("a <joint> has no name".into()))?;
    let type_name = j.attribute("type").unwrap_or("");
    let ctx = format!("joint '{name}' ({type_name})");
    let kind = match type_name {
        "fixed" => Kind::Fixed,
        "revolute" => Kind::Revolute,
        "continuous" => Kind::Continuous,
        "prismatic" => Kind::Prismatic,
        "floating" | "planar" => Kind::Multi,
        other => {
            return err(format!(
                "joint '{name}': type '{other}' is not a URDF joint type (revolute, \
                 continuous, prismatic, fixed, floating, planar)"
            ))
        }
    };
    let link_of = |tag: &str| -> Result<usize> {
        let n = child(j, tag)
            .and_then(|c| c.attribute("link"))
            .ok_or_else(|| DynamicsError::Urdf(format!("{ctx}: missing <{tag} link=...>")))?;
        links.get(n).copied().ok_or_else(|| {
            DynamicsError::Urdf(format!("{ctx}: <{tag}> names the undefined link '{n}'"))
        })
    };
    let mut joint = RawJoint {
        name: name.to_string(),
        kind,
        parent: link_of("parent")?,
        child: link_of("child")?,
        origin: origin(j, &ctx)?,
        axis: Vector3::x(),
        limit: None,
        friction: Friction::default(),
        mimic: None,
    };
    if !matches!(kind, Kind::Fixed | Kind::Multi) {
        movable(j, &mut joint, &ctx, type_name)?;
    }
    Ok(joint)
}

/// The axis, `<limit>`, `<dynamics>` and `<mimic>` of a revolute, continuous or prismatic joint.
fn movable(j: Node, joint: &mut RawJoint, ctx: &str, type_name: &str) -> Result<()> {
    if let Some(a) = child(j, "axis") {
        joint.axis = Vector3::from(numbers(a, "xyz", Some([1.0, 0.0, 0.0]), ctx)?);
    }
    if joint.axis.norm() < 1e-12 {
        return err(format!("{ctx}: zero <axis>"));
    }
    joint.limit = child(j, "limit").map(|l| limit(l, ctx)).transpose()?;
    if joint.limit.is_none() && joint.kind != Kind::Continuous {
        return err(format!(
            "{ctx}: a {type_name} joint needs a <limit> element"
        ));
    }
    if let Some(d) = child(j, "dynamics") {
        let [damping] = numbers(d, "damping", Some([0.0]), ctx)?;
        let [coulomb] = numbers(d, "friction", Some([0.0]), ctx)?;
        if damping < 0.0 || coulomb < 0.0 {
            return err(format!("{ctx}: negative <dynamics> coefficient"));
        }
        (joint.friction.viscous, joint.friction.coulomb) = (damping, coulomb);
    }
    if let Some(m) = child(j, "mimic") {
        let leader = m
            .attribute("joint")
            .ok_or_else(|| DynamicsError::Urdf(format!("{ctx}: <mimic> lacks 'joint'")))?;
        let [multiplier] = numbers(m, "multiplier", Some([1.0]), ctx)?;
        let [offset] = numbers(m, "offset", Some([0.0]), ctx)?;
        joint.mimic = Some(Mimic {
            leader: leader.to_string(),
            multiplier,
            offset,
        });
    }
    Ok(())
}

fn limit(l: Node, ctx: &str) -> Result<Limit> {
    let [lower] = numbers(l, "lower", Some([0.0]), ctx)?;
    let [upper] = numbers(l, "upper", Some([0.0]), ctx)?;
    let [effort] = numbers(l, "effort", Some([f64::INFINITY]), ctx)?;
    let [velocity] = numbers(l, "velocity", Some([f64::INFINITY]), ctx)?;
    Ok(Limit {
        lower,
        upper,
        effort,
        velocity,
    })
}

/// `N` numbers from a space-separated attribute (`default` when absent).
pub(super) fn numbers<const N: usize>(
    node: Node,
    attr: &str,
    default: Option<[f64; N]>,
    ctx: &str,
) -> Result<[f64; N]> {
    let tag = node.tag_name().name();
    let Some(text) = node.attribute(attr) else {
        return default.map_or_else(
            || err(format!("{ctx}: <{tag}> lacks the attribute '{attr}'")),
            Ok,
        );
    };
    let mut out = [0.0; N];
    let mut count = 0;
    for word in text.split_whitespace() {
        let v: f64 = word.parse().map_err(|_| {
            DynamicsError::Urdf(format!(
                "{ctx}: <{tag} {attr}=\"{text}\"> is not a list of numbers"
            ))
        })?;
        if count < N {
            out[count] = v;
        }
        count += 1;
    }
    if count != N || out.iter().any(|v| !v.is_finite()) {
        return err(format!(
            "{ctx}: <{tag} {attr}=\"{text}\"> needs {N} finite numbers"
        ));
    }
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

/// A link's `<inertial>` in the link frame (zero when absent), and its `<inertia>` as written.
fn inertial(link: Node, ctx: &str) -> Result<(Inertia, Matrix3<f64>)> {
    let Some(node) = child(link, "inertial") else {
        return Ok((Inertia::zero(), Matrix3::zeros()));
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
    let inertia = Inertia::from_com(
        mass,
        pose.trans,
        (inertia_com + inertia_com.transpose()) * 0.5,
    );
    Ok((inertia, local))
}
