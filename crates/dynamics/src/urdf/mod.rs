//! URDF import (any tree of revolute, continuous, prismatic and fixed joints, reduced to the serial
//! chain from the root to a tip) and export.
//!
//! # How a file becomes a model
//! 1. **Tip** (the end-effector link; the model's end-effector point is its origin):
//!    [`UrdfOptions::tip`] if given; otherwise the first of the name patterns
//!    [`TIP_PATTERNS`] (`*tcp*`, `*end_effector*`, `*endeffector*`, `*ee_link*`, `*eef*`,
//!    `*tool0*`, `*tool*`, `*gripper_frame*`, `*ee*`, case-insensitive, each as a whole word) that some link matches, never a link
//!    whose name contains one of [`NOT_A_TIP`] (finger, camera, sensor, …); several matches on one
//!    branch give the deepest, matches on different branches are an error. Without any match:
//!    the link moved by the last arm joint (movable joints that are not gripper joints, see 3.),
//!    an error if those joints branch. The choice and its rule are in
//!    [`crate::ModelSpec::urdf`].
//! 2. **Degrees of freedom**: the revolute, continuous and prismatic joints on the path from the
//!    root to the tip, except the locked ones (3.). Continuous joints are revolute joints without
//!    position limits.
//! 3. **Locked joints** are held rigid: joints beyond the tip, joints off the path to the tip (a
//!    second arm, a head), gripper joints (names containing [`GRIPPER_WORDS`]: finger, gripper,
//!    jaw) unless [`UrdfOptions::unlock`] names them, and the joints of [`UrdfOptions::lock`].
//!    Each is held at the value given in `lock`, otherwise at 0 clamped into its limits (a
//!    floating or planar joint off the path: at its origin).
//! 4. **Mimic joints** follow their leader: a mimic joint is locked at
//!    `multiplier · q_leader + offset`, with its leader's locked value. A mimic joint whose leader
//!    is a degree of freedom is an error (coupled joints are not modelled), as is a mimic joint on
//!    the path to the tip with a moving leader.
//! 5. **Lumping**: every link is part of the rigid body of the nearest degree of freedom above it;
//!    fixed and locked joints compose its pose, and its inertia is added exactly (mass, first
//!    moment, rotational inertia about the body's frame). Links above the first degree of freedom
//!    form the fixed base and do not enter the dynamics.
//! 6. **Checks** (errors name the link or joint): every link that moves must have a physical
//!    inertia — principal moments about the centre of mass non-negative and obeying the triangle
//!    inequality, each within [`crate::inertia::INERTIA_TOLERANCE`] of the trace plus
//!    [`crate::inertia::INERTIA_FLOOR`] (round-off in a point mass's products; point masses and
//!    massless frames are fine); a degree of freedom's `<limit effort>` must be positive;
//!    `revolute` and `prismatic` joints need a `<limit>`. `<dynamics damping friction>` become the
//!    viscous and Coulomb friction. A file that declares `<osrl identified_inertias="true"/>` (a
//!    child of `<robot>`) skips the inertia check: identified base parameters (sarcos7's) are
//!    consistent for the arm as a whole, not link by link; the export writes it for such models.
//! 7. **Sizes**: at most [`MAX_URDF_BYTES`] bytes, [`MAX_XML_NODES`] XML nodes nested at most
//!    [`MAX_XML_DEPTH`] deep, [`MAX_LINKS`] links, [`MAX_JOINTS`] joints and
//!    [`crate::model::MAX_DOF`] degrees of freedom. Loading takes time linear in the file's
//!    size (names are looked up in hash maps, every walk over the tree is iterative, each link
//!    is visited once), so a chain of any depth within these limits loads.
//!
//! Gravity is the URDF convention (9.81 m/s² along −z); the task axes are the world axes the
//! end-effector can move along (a planar arm gets a 2-D task); start and rest postures are the
//! middle of the joint limits (0 without limits), PD gains 10 and 1 — placeholders that
//! `osrl_control::profile` replaces (computed from the model, or given). A `<osrl_profile .../>`
//! child of `<robot>` carries a robot profile ([`crate::RobotProfile`]), read into
//! [`crate::UrdfImport::profile`].
//!
//! Export writes the model back: joint origins as `xyz`/`rpy`, inertias about the centre of mass,
//! `<dynamics damping friction>`, `<limit>`, and a massless `ee_link` on a fixed joint at the
//! end-effector point.
//!
//! ```
//! use osrl_dynamics::urdf::{parse_urdf_with, UrdfOptions};
//! let text = r#"<robot name="r">
//!   <link name="base"/>
//!   <link name="arm"><inertial><mass value="1"/>
//!     <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
//!   <link name="tool0"/>
//!   <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/>
//!     <axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="10" velocity="1"/></joint>
//!   <joint name="flange" type="fixed"><parent link="arm"/><child link="tool0"/>
//!     <origin xyz="0.3 0 0"/></joint>
//! </robot>"#;
//! let model = parse_urdf_with(text, &UrdfOptions::default()).unwrap();
//! let import = model.spec().urdf.as_ref().unwrap();
//! assert_eq!((model.nq(), import.tip.as_str()), (1, "tool0"));
//! assert_eq!(import.tip_rule, "name matches '*tool0*'");
//! ```

mod build;
mod depth;
mod export;
mod profile_xml;
mod select;
mod tree;
mod xml;

pub use export::{to_urdf, to_urdf_with_profile};
pub use select::{GRIPPER_WORDS, NOT_A_TIP, TIP_PATTERNS};

use crate::error::{DynamicsError, Result};
use crate::model::{Model, UrdfImport};
use serde::{Deserialize, Serialize};

/// Largest URDF file accepted (bytes): 16 MiB, far above published robots (the largest in
/// `example-robot-data` is below 1 MB) and small enough to parse in well under a second.
pub const MAX_URDF_BYTES: usize = 16 << 20;
/// Largest number of XML nodes (elements and text) accepted, bounding the parser's memory.
pub const MAX_XML_NODES: u32 = 2_000_000;
/// Deepest nesting of XML elements accepted: URDF elements nest about five deep, and the
/// parser descends recursively, so a deeper file is refused before it is parsed.
pub const MAX_XML_DEPTH: usize = 256;
/// Largest number of `<link>` elements accepted.
pub const MAX_LINKS: usize = 100_000;
/// Largest number of `<joint>` elements accepted.
pub const MAX_JOINTS: usize = 100_000;

/// What the loader should choose differently from its rules (module docs).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct UrdfOptions {
    /// The end-effector link. Default: none, the naming rule of the module docs chooses it, so
    /// that a finger or a camera is never taken silently.
    pub tip: Option<String>,
    /// Joints to hold rigid, each at a position (rad or m; must lie within its limits) or, with
    /// `None`, at 0 clamped into its limits. Default: none beyond the rule's.
    pub lock: Vec<(String, Option<f64>)>,
    /// Gripper joints (finger/gripper/jaw names) on the path to the tip that should move instead
    /// of being locked. Default: none.
    pub unlock: Vec<String>,
}

impl UrdfOptions {
    /// Adds a lock from the command-line form `JOINT` or `JOINT=VALUE`.
    ///
    /// # Errors
    /// An empty joint name or a value that is not a finite number.
    pub fn push_lock(&mut self, spec: &str) -> Result<()> {
        let (name, value) = match spec.split_once('=') {
            None => (spec, None),
            Some((name, v)) => {
                let value: f64 = v.trim().parse().map_err(|_| {
                    DynamicsError::Urdf(format!("lock '{spec}': '{v}' is not a number"))
                })?;
                if !value.is_finite() {
                    return err(format!("lock '{spec}': the value must be finite"));
                }
                (name, Some(value))
            }
        };
        let name = name.trim();
        if name.is_empty() {
            return err(format!(
                "lock '{spec}': no joint name (JOINT or JOINT=VALUE)"
            ));
        }
        self.lock.push((name.to_string(), value));
        Ok(())
    }
}

pub(crate) fn err<T>(msg: String) -> Result<T> {
    Err(DynamicsError::Urdf(msg))
}

/// Reads and parses a URDF file with the default options. Errors name the file and the offending
/// element.
pub fn load_urdf(path: &std::path::Path) -> Result<Model> {
    load_urdf_with(path, &UrdfOptions::default())
}

/// Reads and parses a URDF file.
///
/// # Errors
/// A file that cannot be read, is larger than [`MAX_URDF_BYTES`] (checked before reading) or
/// that [`parse_urdf_with`] refuses; the message starts with the path.
pub fn load_urdf_with(path: &std::path::Path, opts: &UrdfOptions) -> Result<Model> {
    let at = |m: String| DynamicsError::Urdf(format!("{}: {m}", path.display()));
    let meta = std::fs::metadata(path).map_err(|e| at(format!("cannot read: {e}")))?;
    if !meta.is_file() {
        return Err(at("not a regular file".into()));
    }
    if meta.len() > MAX_URDF_BYTES as u64 {
        return Err(at(format!(
            "the file has {} bytes; at most {MAX_URDF_BYTES} are accepted",
            meta.len()
        )));
    }
    let text = std::fs::read_to_string(path).map_err(|e| at(format!("cannot read: {e}")))?;
    parse_urdf_with(&text, opts).map_err(|e| match e {
        DynamicsError::Urdf(m) => at(m),
        other => other,
    })
}

/// Parses URDF text with the default options (module docs).
pub fn parse_urdf(text: &str) -> Result<Model> {
    parse_urdf_with(text, &UrdfOptions::default())
}

/// Parses URDF text into a [`Model`] following the rules of the module docs.
///
/// # Errors
/// Malformed XML, a size beyond the limits, a joint type or structure that cannot be reduced to
/// a serial chain, an unphysical inertia, a non-positive effort, or options naming joints and
/// links that do not exist or cannot be what they ask; the message names the element.
pub fn parse_urdf_with(text: &str, opts: &UrdfOptions) -> Result<Model> {
    let raw = xml::read(text)?;
    let tree = tree::Tree::new(&raw)?;
    let (tip, tip_rule) = select::tip(&raw, &tree, opts)?;
    let (roles, locked) = select::roles(&raw, &tree, tip, opts)?;
    let import = UrdfImport {
        tip: raw.links[tip].name.clone(),
        tip_rule,
        locked,
        identified_inertias: raw.identified_inertias,
        profile: raw.profile.clone(),
    };
    build::build(&raw, &tree, &roles, tip, import)
}
