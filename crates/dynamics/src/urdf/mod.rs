//! URDF import (revolute, continuous and fixed joints of a serial chain) and export.
//!
//! Import folds fixed joints into their parent link (their inertia is merged), takes the
//! end-effector point as the origin of the deepest link of the chain (a fixed `ee` link after the
//! last revolute joint, if any), and chooses the task axes as the world axes the end-effector can
//! move along (so a planar arm gets a 2-D task). Export writes the same robot back: joint origins
//! as `xyz`/`rpy`, inertias about the centre of mass, `<dynamics damping friction>`, `<limit>`, and
//! a massless `ee_link` on a fixed joint at the end-effector point.

mod export;
mod parse;

pub use export::to_urdf;
pub use parse::{load_urdf, parse_urdf};
