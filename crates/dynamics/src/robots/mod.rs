//! The built-in robots, shared fixtures of tests, benches and experiments.

mod planar3;
mod random;
mod sarcos7;

pub use planar3::planar3;
pub use random::{random_arm, random_mixed_arm, random_unit_vector};
pub use sarcos7::sarcos7;

use crate::{DynamicsError, Model, Result};

/// Names of the built-in robots.
pub const BUILTIN: [&str; 2] = ["planar3", "sarcos7"];

/// A built-in robot by name.
pub fn by_name(name: &str) -> Result<Model> {
    match name {
        "planar3" => Ok(planar3()),
        "sarcos7" => Ok(sarcos7()),
        _ => Err(DynamicsError::InvalidModel(format!(
            "unknown robot '{name}' (built-in: {})",
            BUILTIN.join(", ")
        ))),
    }
}
