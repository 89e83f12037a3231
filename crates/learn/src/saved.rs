//! A saved learned controller: the [`Learner`] and what running it needs besides — the robot it
//! was trained on, the training trajectory, the home posture, the task gains of eq. 2, the
//! control period, the simulated training minutes and the seed ([`ModelInfo`]) — in one
//! versioned file. Every field is checked on load, and an error names the field.
//!
//! Layout: [`MODEL_MAGIC`], [`MODEL_VERSION`] (u32), the length (u64) and FNV-1a checksum (u64)
//! of the [`ModelInfo`] as JSON, that JSON, then the learner's own bytes
//! ([`Learner::to_bytes`]: magic, version, checksum). All integers little-endian.
//!
//! ```
//! use osrl_control::{TaskGains, TrajectoryConfig};
//! use osrl_learn::{Learner, LearnerConfig, ModelInfo, SavedModel};
//!
//! let model = osrl_dynamics::robots::planar3();
//! let spec = model.spec();
//! let tau: Vec<f64> = model.tau_max().collect();
//! let learner = Learner::new(3, 2, 0.002, LearnerConfig::for_robot(&spec.kp, &spec.kd, &spec.q_rest, &tau))?;
//! let info = ModelInfo {
//!     robot: "planar3".into(),
//!     trajectory: TrajectoryConfig::default(),
//!     home: spec.q_start.clone(),
//!     gains: TaskGains::default(),
//!     control_period: 0.002,
//!     sim_training_minutes: 0.0,
//!     seed: 0,
//!     profile: Default::default(),
//! };
//! let saved = SavedModel::new(info, learner)?;
//! let back = SavedModel::from_bytes(&saved.to_bytes()?)?;
//! assert_eq!(back.info(), saved.info());
//! // A home posture outside the joint limits is refused, naming the field.
//! let mut bad = saved.info().clone();
//! bad.home[1] = 10.0;
//! let err = SavedModel::new(bad, back.into_parts().1).err().unwrap();
//! assert!(err.to_string().contains("home"), "{err}");
//! # Ok::<(), osrl_learn::LearnError>(())
//! ```

use crate::config::CONTROL_PERIOD_RANGE;
use crate::controller::LearnedController;
use crate::error::{LearnError, Result};
use crate::learner::Learner;
use crate::LearnerConfig;
use osrl_control::{TaskGains, TrajectoryConfig};
use osrl_dynamics::{robots, Model, RobotProfile};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// First bytes of a saved model.
pub const MODEL_MAGIC: &[u8; 8] = b"OSRLMDL\0";
/// Version of the saved model's layout; files of another version are refused.
pub const MODEL_VERSION: u32 = 1;
/// First bytes of the learner-only file of the two-file format before [`MODEL_VERSION`] 1
/// (learner file plus a `MODEL.json` sidecar).
/// Largest model file [`SavedModel::load`] reads (1 GiB).
pub const MAX_MODEL_BYTES: u64 = 1 << 30;
const OLD_LEARNER_MAGIC: &[u8] = b"OSRLLC";
const HEADER: usize = 28;

/// What a saved learner needs to run besides itself.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelInfo {
    /// Built-in robot name (`planar3`, `sarcos7`) or URDF path (absolute) the learner was
    /// trained on ([`load_robot`] reads it).
    pub robot: String,
    /// The training trajectory (unset fields take the robot's defaults).
    pub trajectory: TrajectoryConfig,
    /// Home posture (rad): at rest on the start of the training path; one value per joint,
    /// inside the joint limits.
    pub home: Vec<f64>,
    /// Task-space gains of the reference dynamics (eq. 2) used in training: `kp > 0`,
    /// `kd ≥ 0`.
    pub gains: TaskGains,
    /// Control period (s) the learner was trained at, within [`CONTROL_PERIOD_RANGE`].
    pub control_period: f64,
    /// Simulated minutes of training (≥ 0).
    pub sim_training_minutes: f64,
    /// Seed of the training run.
    pub seed: u64,
    /// The robot profile the run was given (`[robot]`, `--profile`, `--tip`, `--lock`,
    /// `--unlock`): the robot is read with its tip and locks, and resolved with it again.
    /// Default none (the robot's own defaults).
    #[serde(default, skip_serializing_if = "RobotProfile::is_empty")]
    pub profile: RobotProfile,
}

/// A learner with its [`ModelInfo`], checked against each other and against the robot.
#[derive(Clone, Debug)]
pub struct SavedModel {
    info: ModelInfo,
    learner: Learner,
    robot: Model,
}

/// A robot by its [`ModelInfo::robot`] spec: a built-in name or a URDF file.
///
/// # Errors
/// [`LearnError::Robot`] for a URDF file that cannot be read or parsed, or a name that is
/// neither.
pub fn load_robot(spec: &str) -> Result<Model> {
    load_robot_with(spec, &RobotProfile::default())
}

/// As [`load_robot`], a URDF file read with the tip and locks of `profile`.
///
/// # Errors
/// As [`load_robot`], or a malformed lock.
pub fn load_robot_with(spec: &str, profile: &RobotProfile) -> Result<Model> {
    if robots::BUILTIN.contains(&spec) {
        return Ok(robots::by_name(spec)?);
    }
    let path = Path::new(spec);
    if spec.ends_with(".urdf") || path.exists() {
        let opts = profile.urdf_options()?;
        return Ok(osrl_dynamics::urdf::load_urdf_with(path, &opts)?);
    }
    Err(LearnError::Robot(
        osrl_dynamics::DynamicsError::InvalidModel(format!(
            "unknown robot '{spec}': use {} or a .urdf file",
            robots::BUILTIN.join(", ")
        )),
    ))
}

fn field(name: &str, why: impl std::fmt::Display) -> LearnError {
    LearnError::Load(format!("{name}: {why}"))
}

/// The home posture: one finite value per joint, inside the joint limits.
fn check_home(home: &[f64], robot: &Model) -> Result<()> {
    let n = robot.nq();
    if home.len() != n {
        return Err(field(
            "home",
            format!("{} values for {n} joints", home.len()),
        ));
    }
    let limits = robot.q_min().zip(robot.q_max());
    for (i, (&q, (lo, hi))) in home.iter().zip(limits).enumerate() {
        if !q.is_finite() || q < lo || q > hi {
            return Err(field(
                "home",
                format!("joint {i} at {q} rad is not inside its limits [{lo}, {hi}] rad"),
            ));
        }
    }
    Ok(())
}

impl ModelInfo {
    /// Checks every field against `learner` and `robot` (the model of [`ModelInfo::robot`]).
    ///
    /// # Errors
    /// [`LearnError::Load`] naming the first field out of range.
    pub fn validate(&self, learner: &Learner, robot: &Model) -> Result<()> {
        let (n, m) = learner.dims();
        if (n, m) != (robot.nq(), robot.task_dim()) {
            return Err(field(
                "robot",
                format!(
                    "{} has {} joints and a {}-D task, the learner {n} and {m}",
                    self.robot,
                    robot.nq(),
                    robot.task_dim()
                ),
            ));
        }
        check_home(&self.home, robot)?;
        let dt = self.control_period;
        if !CONTROL_PERIOD_RANGE.contains(&dt) {
            return Err(field(
                "control_period",
                format!(
                    "{dt} s is not within {}–{} s",
                    CONTROL_PERIOD_RANGE.start(),
                    CONTROL_PERIOD_RANGE.end()
                ),
            ));
        }
        let g = self.gains;
        if !(g.kp > 0.0 && g.kp.is_finite() && g.kd >= 0.0 && g.kd.is_finite()) {
            return Err(field(
                "gains",
                format!(
                    "kp = {}, kd = {}: need a finite kp > 0 and kd ≥ 0",
                    g.kp, g.kd
                ),
            ));
        }
        let t = self.sim_training_minutes;
        if !(t >= 0.0 && t.is_finite()) {
            return Err(field(
                "sim_training_minutes",
                format!("{t}: need a finite number ≥ 0"),
            ));
        }
        self.trajectory
            .build(robot)
            .map_err(|e| field("trajectory", e))?;
        Ok(())
    }
}

impl SavedModel {
    /// `learner` with `info`, checked ([`ModelInfo::validate`] against the robot that
    /// [`load_robot`] reads from `info.robot`). A learner without torque limits gets its
    /// robot's data-sheet limits.
    ///
    /// # Errors
    /// [`LearnError::Load`] naming the field that does not fit (`robot` when it cannot be
    /// read).
    pub fn new(info: ModelInfo, mut learner: Learner) -> Result<Self> {
        if info.robot.trim().is_empty() {
            return Err(field("robot", "empty"));
        }
        let robot = load_robot_with(&info.robot, &info.profile).map_err(|e| field("robot", e))?;
        info.validate(&learner, &robot)?;
        if learner.config().guards.torque_limits.is_empty() {
            let tau: Vec<f64> = robot.tau_max().collect();
            learner
                .set_torque_limits(&LearnerConfig::data_sheet_limits(&tau))
                .map_err(|e| field("learner", e))?;
        }
        Ok(Self {
            info,
            learner,
            robot,
        })
    }

    /// What the learner needs besides itself.
    pub fn info(&self) -> &ModelInfo {
        &self.info
    }

    /// The learner.
    pub fn learner(&self) -> &Learner {
        &self.learner
    }

    /// The robot the learner was trained on (read from [`ModelInfo::robot`]).
    pub fn robot(&self) -> &Model {
        &self.robot
    }

    /// The parts: info, learner, robot.
    pub fn into_parts(self) -> (ModelInfo, Learner, Model) {
        (self.info, self.learner, self.robot)
    }

    /// The learner as a task-space controller with its training gains on its robot's task axes.
    ///
    /// # Errors
    /// As [`LearnedController::new`] (not for a model that passed its checks).
    pub fn controller(self) -> Result<LearnedController> {
        LearnedController::new(self.learner, self.info.gains, self.robot.task_axes())
    }

    /// The model as bytes (layout in the module docs).
    ///
    /// # Errors
    /// As [`Learner::to_bytes`].
    pub fn to_bytes(&self) -> Result<Vec<u8>> {
        let info = serde_json::to_vec(&self.info).map_err(|e| field("info", e))?;
        let learner = self.learner.to_bytes()?;
        let mut out = Vec::with_capacity(HEADER + info.len() + learner.len());
        out.extend_from_slice(MODEL_MAGIC);
        out.extend_from_slice(&MODEL_VERSION.to_le_bytes());
        out.extend_from_slice(&(info.len() as u64).to_le_bytes());
        out.extend_from_slice(&fnv1a(&info).to_le_bytes());
        out.extend_from_slice(&info);
        out.extend_from_slice(&learner);
        Ok(out)
    }

    /// A model from [`SavedModel::to_bytes`], checked as [`SavedModel::new`] checks.
    ///
    /// # Errors
    /// [`LearnError::Load`] for a foreign, older, truncated or corrupted file, or a field out
    /// of range (named).
    pub fn from_bytes(bytes: &[u8]) -> Result<Self> {
        let bad = |m: String| LearnError::Load(m);
        if bytes.starts_with(OLD_LEARNER_MAGIC) {
            return Err(bad(format!(
                "a learner file of the older two-file format (learner plus MODEL.json sidecar); \
                 this build reads model format {MODEL_VERSION}: train it again with `osrl train`"
            )));
        }
        if bytes.len() < HEADER || &bytes[..8] != MODEL_MAGIC {
            return Err(bad("not an osrl model file".into()));
        }
        let word =
            |a: usize, b: usize| u64::from_le_bytes(bytes[a..b].try_into().expect("8 bytes"));
        let version = u32::from_le_bytes(bytes[8..12].try_into().expect("4 bytes"));
        if version != MODEL_VERSION {
            return Err(bad(format!(
                "model format version {version}, this build reads {MODEL_VERSION}"
            )));
        }
        let len = word(12, 20);
        let end = usize::try_from(len)
            .ok()
            .and_then(|l| l.checked_add(HEADER))
            .filter(|&e| e <= bytes.len())
            .ok_or_else(|| bad(format!("truncated: the header says {len} info bytes")))?;
        let info = &bytes[HEADER..end];
        if fnv1a(info) != word(20, 28) {
            return Err(bad(
                "checksum mismatch in the model info: the file is corrupted".into(),
            ));
        }
        let info: ModelInfo =
            serde_json::from_slice(info).map_err(|e| bad(format!("model info: {e}")))?;
        let learner = Learner::from_bytes(&bytes[end..])?;
        Self::new(info, learner)
    }

    /// Writes [`SavedModel::to_bytes`] to `path` through a temporary file and a rename
    /// ([`osrl_files::write_atomic`]: only over a regular file or a missing path; a failure
    /// leaves any old file whole), creating its folder.
    ///
    /// # Errors
    /// [`LearnError::File`] if `path` exists and is not a regular file, or on an I/O error.
    pub fn save(&self, path: &Path) -> Result<()> {
        osrl_files::check_output(path).or_else(|e| match path.parent() {
            // A missing folder is created; anything else is refused before it is.
            Some(dir) if !dir.as_os_str().is_empty() && !dir.exists() => {
                std::fs::create_dir_all(dir).map_err(|_| e)
            }
            _ => Err(e),
        })?;
        Ok(osrl_files::write_atomic(path, &self.to_bytes()?)?)
    }

    /// Reads a model written by [`SavedModel::save`].
    ///
    /// # Errors
    /// As [`SavedModel::from_bytes`], the message starting with the path.
    pub fn load(path: &Path) -> Result<Self> {
        let starts: &[&[u8]] = &[MODEL_MAGIC, OLD_LEARNER_MAGIC];
        let bytes = osrl_files::read_limited_if_starts(path, MAX_MODEL_BYTES, starts)?;
        Self::from_bytes(&bytes).map_err(|e| {
            let why = match e {
                LearnError::Load(why) => why,
                e => e.to_string(),
            };
            LearnError::Load(format!("{}: {why}", path.display()))
        })
    }
}

/// FNV-1a over `bytes`: detects corruption that would still parse.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| {
        (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn saved() -> SavedModel {
        let model = robots::planar3();
        let spec = model.spec();
        let tau: Vec<f64> = model.tau_max().collect();
        let cfg = LearnerConfig::for_robot(&spec.kp, &spec.kd, &spec.q_rest, &tau);
        let learner = Learner::new(3, 2, 0.002, cfg).unwrap();
        let info = ModelInfo {
            robot: "planar3".into(),
            trajectory: TrajectoryConfig::default(),
            home: spec.q_start.clone(),
            gains: TaskGains::default(),
            control_period: 0.002,
            sim_training_minutes: 1.5,
            seed: 4,
            profile: Default::default(),
        };
        SavedModel::new(info, learner).unwrap()
    }

    fn refused(edit: impl Fn(&mut ModelInfo), field: &str) {
        let s = saved();
        let mut info = s.info().clone();
        edit(&mut info);
        let err = SavedModel::new(info, s.into_parts().1)
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with(&format!("cannot load learned controller: {field}:")),
            "{err}"
        );
    }

    #[test]
    fn every_field_is_checked_and_named() {
        refused(|i| i.robot = String::new(), "robot");
        refused(|i| i.robot = "planar4".into(), "robot");
        refused(|i| i.robot = "sarcos7".into(), "robot");
        refused(
            |i| {
                i.home.pop();
            },
            "home",
        );
        refused(|i| i.home[0] = f64::NAN, "home");
        refused(|i| i.home[2] = 4.0, "home");
        refused(|i| i.control_period = 1e-9, "control_period");
        refused(|i| i.control_period = f64::INFINITY, "control_period");
        refused(|i| i.gains.kp = 0.0, "gains");
        refused(|i| i.gains.kd = f64::NAN, "gains");
        refused(|i| i.sim_training_minutes = -1.0, "sim_training_minutes");
        refused(|i| i.trajectory.period = -4.0, "trajectory");
    }

    #[test]
    fn bytes_round_trip_and_damage_is_refused() {
        let s = saved();
        let bytes = s.to_bytes().unwrap();
        let back = SavedModel::from_bytes(&bytes).unwrap();
        assert_eq!(back.info(), s.info());
        assert_eq!(
            back.learner().to_bytes().unwrap(),
            s.learner().to_bytes().unwrap()
        );
        let msg = |b: &[u8]| SavedModel::from_bytes(b).unwrap_err().to_string();
        assert!(msg(&bytes[..20]).contains("not an osrl model"));
        assert!(msg(&bytes[..40]).contains("truncated"));
        let mut v = bytes.clone();
        v[8] = 9;
        assert!(msg(&v).contains("version 9"));
        let mut v = bytes.clone();
        v[HEADER + 3] ^= 1;
        assert!(msg(&v).contains("checksum"));
        let old = s.learner().to_bytes().unwrap();
        assert!(msg(&old).contains("older two-file format"), "{}", msg(&old));
        assert!(msg(&bytes[..bytes.len() - 1]).contains("cannot load"));
        // A well-formed file with a field out of range: its JSON rewritten, checksum fixed.
        let info = serde_json::to_vec(&ModelInfo {
            control_period: 7.0,
            ..s.info().clone()
        })
        .unwrap();
        let mut v = bytes[..12].to_vec();
        v.extend_from_slice(&(info.len() as u64).to_le_bytes());
        v.extend_from_slice(&fnv1a(&info).to_le_bytes());
        v.extend_from_slice(&info);
        v.extend_from_slice(&old);
        assert!(msg(&v).contains("control_period: 7 s"), "{}", msg(&v));
    }

    #[test]
    fn save_refuses_what_is_not_a_regular_file() {
        let dir = std::env::temp_dir().join(format!("osrl-saved-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("taken")).unwrap();
        let s = saved();
        assert!(s
            .save(&dir.join("taken"))
            .unwrap_err()
            .to_string()
            .contains("not a regular file"));
        let p = dir.join("sub").join("m.osrl");
        s.save(&p).unwrap();
        assert_eq!(SavedModel::load(&p).unwrap().info(), s.info());
        assert!(SavedModel::load(&dir.join("none"))
            .unwrap_err()
            .to_string()
            .contains("cannot read"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
