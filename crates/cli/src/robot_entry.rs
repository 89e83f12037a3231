//! The config file's `robot` entry: a name (`robot = "sarcos7"`, as before) or a `[robot]`
//! section — a robot profile (`osrl_dynamics::RobotProfile`) with the robot's `name`:
//!
//! ```toml
//! [robot]
//! name = "crates/dynamics/tests/fixtures/example-robot-data/panda.urdf"
//! tip = "panda_hand_tcp"
//! lock = ["panda_finger_joint1=0.02"]
//! kp = [100.0, 100.0, 50.0, 50.0, 5.0, 5.0, 1.0]
//! path = { scale = 0.05 }
//! ```
//!
//! The same fields (without `name`, or with it: `--robot` wins) make a `--profile F` file.

use anyhow::Result;
use osrl_dynamics::RobotProfile;
use serde::de::{self, MapAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// Built-in robot when the config names none.
pub const DEFAULT_ROBOT: &str = "planar3";

/// A robot name with its profile (empty by default).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RobotEntry(pub RobotProfile);

impl RobotEntry {
    /// The robot: a built-in name or a URDF file (default planar3).
    pub fn name(&self) -> &str {
        self.0.name.as_deref().unwrap_or(DEFAULT_ROBOT)
    }
    pub fn set_name(&mut self, name: &str) {
        self.0.name = Some(name.to_string());
    }
}

impl From<&str> for RobotEntry {
    fn from(name: &str) -> Self {
        RobotEntry(RobotProfile {
            name: Some(name.into()),
            ..RobotProfile::default()
        })
    }
}

impl Serialize for RobotEntry {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        if self.0.is_empty() {
            s.serialize_str(self.name())
        } else {
            self.0.serialize(s)
        }
    }
}

impl<'de> Deserialize<'de> for RobotEntry {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = RobotEntry;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a robot name or a [robot] section (a robot profile with `name`)")
            }
            fn visit_str<E: de::Error>(self, v: &str) -> std::result::Result<RobotEntry, E> {
                Ok(RobotEntry::from(v))
            }
            fn visit_map<A: MapAccess<'de>>(
                self,
                map: A,
            ) -> std::result::Result<RobotEntry, A::Error> {
                RobotProfile::deserialize(de::value::MapAccessDeserializer::new(map))
                    .map(RobotEntry)
            }
        }
        d.deserialize_any(V)
    }
}

/// Flags that set the robot profile (over the config's `[robot]` section).
#[derive(clap::Args, Debug, Default, Clone)]
pub struct ProfileArgs {
    /// Robot profile file (TOML, the fields of a `[robot]` section: tip, lock, home, rest, kp,
    /// kd, torque_limits, null_space_frequency, null_space_damping, path); its values replace
    /// the config's.
    #[arg(long)]
    pub profile: Option<std::path::PathBuf>,
    /// End-effector link of a URDF (default: the loader's name rule, printed by `osrl robot`).
    #[arg(long)]
    pub tip: Option<String>,
    /// Hold a URDF joint rigid: JOINT or JOINT=VALUE (rad or m); repeatable.
    #[arg(long)]
    pub lock: Vec<String>,
    /// Let a gripper joint (finger/gripper/jaw name) move instead of being locked; repeatable.
    #[arg(long)]
    pub unlock: Vec<String>,
}

impl ProfileArgs {
    /// `base` (the config's profile) overlaid by the `--profile` file, then by the flags.
    pub fn apply(&self, base: &RobotProfile) -> Result<RobotProfile> {
        let mut p = base.clone();
        if let Some(f) = &self.profile {
            let file: RobotProfile = crate::util::read_toml(f)?;
            p = p.overlaid(&file);
        }
        let flags = RobotProfile {
            tip: self.tip.clone(),
            lock: self.lock.clone(),
            unlock: self.unlock.clone(),
            ..RobotProfile::default()
        };
        Ok(p.overlaid(&flags))
    }
}
