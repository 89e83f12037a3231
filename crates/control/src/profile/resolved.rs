//! The checked result of [`super::resolve`]: the profiled model, every value with where it came
//! from, and what the feasibility check measured.

use super::placement::Feasible;
use crate::error::ControlError;
use crate::trajectory_config::TrajectoryConfig;
use osrl_dynamics::{CostMetric, Model, PathPlacement, RobotProfile};
use serde::Serialize;
use std::collections::BTreeMap;

/// Where a resolved value came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Source {
    /// The profile given (config section or `--profile`).
    Given,
    /// The URDF file's `<osrl_profile>` element.
    File,
    /// A built-in robot's data sheet.
    DataSheet,
    /// The URDF's `<limit effort>`.
    Urdf,
    /// Computed from the model ([`super`] docs).
    Computed,
}

/// The default path's frame: `x_d = c + a sin(ωt) e1 + b sin(2ωt) e2` (m, world frame).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PathFrame {
    pub centre: [f64; 3],
    pub e1: [f64; 3],
    pub e2: [f64; 3],
    pub a: f64,
    pub b: f64,
}

/// A resolved profile: every value set and checked.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ResolvedProfile {
    /// The URDF tip link and the rule that chose it (none for a built-in robot).
    pub tip: Option<String>,
    pub tip_rule: Option<String>,
    /// Locked URDF joints as `name=value (reason)`.
    pub locked: Vec<String>,
    /// Home posture (rad or m): the default path is centred at the tip here.
    pub home: Vec<f64>,
    /// Rest posture `q_rest` of `u0` (rad or m).
    pub rest: Vec<f64>,
    /// Joint stiffness `K_P` (N·m/rad or N/m) and damping `K_D` (N·m·s/rad or N·s/m) of `u0`.
    pub kp: Vec<f64>,
    pub kd: Vec<f64>,
    /// Torque limits (N·m or N).
    pub torque_limits: Vec<f64>,
    /// `ω` (rad/s) and `ζ` of computed gains (unused when the gains are given).
    pub null_space_frequency: f64,
    pub null_space_damping: f64,
    /// The default path's placement.
    pub path: PathFrame,
    /// Largest distance of the tip from the first joint (m).
    pub reach: f64,
    /// Smallest distance of a joint to its limits along the IK path (rad or m).
    pub min_limit_margin: f64,
    /// Largest share of a torque limit the IK path's inverse dynamics need.
    pub peak_torque_ratio: f64,
    /// The learner's cost metric `N` (given, or [`super::metric_rule`] of `joint_sweep`).
    pub metric: CostMetric,
    /// Each joint's sweep `max q − min q` (rad or m) under eq. 7 with `N = I` along the default
    /// path for three periods (none when the metric is given and no check simulated it).
    pub joint_sweep: Option<Vec<f64>>,
    /// Where each value came from (keys: `home`, `rest`, `kp`, `kd`, `torque_limits`, `path`,
    /// `metric`;
    /// `path` is `given` or `file` when any of its fields is, the others then computed).
    pub sources: BTreeMap<&'static str, Source>,
}

/// The values the resolution settled on.
pub(super) struct Values {
    pub home: Vec<f64>,
    pub rest: Vec<f64>,
    pub kp: Vec<f64>,
    pub kd: Vec<f64>,
    pub tau: Vec<f64>,
    pub omega: f64,
    pub zeta: f64,
    pub frame: super::PathFrame,
    pub reach: f64,
    pub metric: CostMetric,
    pub sweep: Option<Vec<f64>>,
}

/// A model with its resolved profile applied (postures, gains, torque limits).
#[derive(Clone, Debug)]
pub struct Profiled {
    /// The model with `q_start` = home, `q_rest`, `kp`, `kd` and the torque limits set.
    pub model: Model,
    pub profile: ResolvedProfile,
    /// Path fields a trajectory config takes when it leaves them unset.
    fill: PathPlacement,
}

/// `e` about the profile `field`.
pub(super) fn field(name: &str, e: ControlError) -> ControlError {
    ControlError::Profile {
        field: name.into(),
        reason: e.to_string(),
    }
}

/// An error of the file's embedded profile says so.
pub(super) fn from_file(e: ControlError) -> ControlError {
    match e {
        ControlError::Profile { field, reason } => ControlError::Profile {
            field,
            reason: format!("{reason} (the URDF's <osrl_profile> element)"),
        },
        other => other,
    }
}

impl Profiled {
    pub(super) fn new(
        model: Model,
        v: Values,
        f: Feasible,
        given: &RobotProfile,
        file: &RobotProfile,
    ) -> Self {
        let builtin = model.spec().urdf.is_none();
        let fallback = if builtin {
            Source::DataSheet
        } else {
            Source::Computed
        };
        let src = |g: bool, f: bool, other: Source| match (g, f) {
            (true, _) => Source::Given,
            (false, true) => Source::File,
            _ => other,
        };
        let path_set = |p: &RobotProfile| !p.path.is_empty();
        let mut sources = BTreeMap::new();
        let mut put = |k, g, f, o| {
            sources.insert(k, src(g, f, o));
        };
        put("home", given.home.is_some(), file.home.is_some(), fallback);
        put("rest", given.rest.is_some(), file.rest.is_some(), fallback);
        put("kp", given.kp.is_some(), file.kp.is_some(), fallback);
        put("kd", given.kd.is_some(), file.kd.is_some(), fallback);
        let tau_src = if builtin {
            Source::DataSheet
        } else {
            Source::Urdf
        };
        let (gt, ft) = (given.torque_limits.is_some(), file.torque_limits.is_some());
        put("torque_limits", gt, ft, tau_src);
        put("path", path_set(given), path_set(file), fallback);
        let (gm, fm) = (given.metric.is_some(), file.metric.is_some());
        put("metric", gm, fm, Source::Computed);
        let import = model.spec().urdf.clone();
        let fr = &v.frame;
        let fill = if builtin {
            given.path.clone()
        } else {
            PathPlacement {
                centre: Some(fr.centre),
                e1: Some(fr.e1),
                e2: Some(fr.e2),
                a: Some(fr.a),
                b: Some(fr.b),
                scale: None,
            }
        };
        let profile = ResolvedProfile {
            tip: import.as_ref().map(|u| u.tip.clone()),
            tip_rule: import.as_ref().map(|u| u.tip_rule.clone()),
            locked: import
                .iter()
                .flat_map(|u| &u.locked)
                .map(|l| format!("{}={} ({})", l.name, l.value, l.reason))
                .collect(),
            home: v.home,
            rest: v.rest,
            kp: v.kp,
            kd: v.kd,
            torque_limits: v.tau,
            null_space_frequency: v.omega,
            null_space_damping: v.zeta,
            path: v.frame,
            reach: v.reach,
            min_limit_margin: f.reach.min_margin,
            peak_torque_ratio: f.peak_torque_ratio,
            metric: v.metric,
            joint_sweep: v.sweep,
            sources,
        };
        Self {
            model,
            profile,
            fill,
        }
    }

    /// `cfg` with its unset centre, plane and size taken from the profile (a built-in robot's
    /// data-sheet defaults are left to [`TrajectoryConfig::build`], so its config is unchanged).
    pub fn trajectory(&self, cfg: &TrajectoryConfig) -> TrajectoryConfig {
        let f = &self.fill;
        TrajectoryConfig {
            centre: cfg.centre.or(f.centre),
            e1: cfg.e1.or(f.e1),
            e2: cfg.e2.or(f.e2),
            a: cfg.a.or(f.a),
            b: cfg.b.or(f.b),
            ..cfg.clone()
        }
    }

    /// The resolved values as a profile that gives them all (what an exported URDF carries):
    /// postures, gains and the path's frame (torque limits are the exported `effort`).
    pub fn as_given(&self) -> RobotProfile {
        let p = &self.profile;
        RobotProfile {
            home: Some(p.home.clone()),
            rest: Some(p.rest.clone()),
            kp: Some(p.kp.clone()),
            kd: Some(p.kd.clone()),
            path: PathPlacement {
                centre: Some(p.path.centre),
                e1: Some(p.path.e1),
                e2: Some(p.path.e2),
                a: Some(p.path.a),
                b: Some(p.path.b),
                scale: None,
            },
            ..RobotProfile::default()
        }
    }
}
