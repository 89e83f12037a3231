//! The analytical runs of `osrl reproduce`: eq. 4 and eq. 7 with the true model (E2) and eq. 7
//! with a wrong model (E7), each written like `osrl simulate --out` (CSV, path figure, metrics).

use crate::cmd::simulate::output::write_outputs;
use crate::config::Config;
use crate::util::load_robot;
use anyhow::{Context, Result};
use osrl_control::{check_reachable, run_closed_loop, IkOptions, Law, ModelError, Osc, Run};
use osrl_dynamics::SimRobot;
use rayon::prelude::*;
use serde_json::Value;
use std::path::{Path, PathBuf};

/// One analytical case.
#[derive(Clone, Debug)]
pub struct Case {
    pub robot: &'static str,
    pub law: Law,
    /// Key of the model error (`none` for the true model) and its spec.
    pub error_key: &'static str,
    pub error: ModelError,
    /// Output directory.
    pub dir: PathBuf,
}

/// The model errors of E7: key and `--model-error` spec.
pub const ERRORS: [(&str, &str); 5] = [
    ("mass_x0.7", "mass=0.7"),
    ("mass_x1.3", "mass=1.3"),
    ("com_2cm", "com=0.02"),
    ("no_friction", "friction=off"),
    ("payload", "payload=0.5"),
];

/// E2 (eq. 7 and eq. 4, true model) and E7 (eq. 7, each wrong model) for both robots;
/// `payload_kg` replaces the payload spec's mass.
pub fn cases(out: &Path, payload_kg: f64) -> Result<Vec<Case>> {
    let mut v = Vec::new();
    for robot in ["planar3", "sarcos7"] {
        for (law, name) in [(Law::Eq7, "eq7"), (Law::Eq4, "eq4")] {
            v.push(Case {
                robot,
                law,
                error_key: "none",
                error: ModelError::default(),
                dir: out.join("E2").join(format!("{robot}_{name}")),
            });
        }
        for (key, spec) in ERRORS {
            let mut error: ModelError = spec.parse()?;
            if key == "payload" {
                error.payload = payload_kg;
            }
            v.push(Case {
                robot,
                law: Law::Eq7,
                error_key: key,
                error,
                dir: out.join("E7").join(format!("{robot}_{key}")),
            });
        }
    }
    Ok(v)
}

/// Runs one case for `seconds`, writes its files, returns the metrics JSON and the run.
pub fn run_case(c: &Case, seconds: f64) -> Result<(Value, Run)> {
    let mut cfg = Config {
        robot: c.robot.into(),
        model_error: c.error.clone(),
        ..Config::default()
    };
    cfg.controller.law = c.law;
    cfg.simulate.seconds = seconds;
    let model = load_robot(c.robot)?;
    let traj = cfg.trajectory.build(&model)?;
    let reach = check_reachable(&model, &traj, &IkOptions::default())?;
    let (sim_model, ctrl_model) = cfg.model_error.apply(&model)?;
    let mut sim = SimRobot::new(sim_model, cfg.sim.clone())?;
    sim.reset(&reach.q_start, &vec![0.0; model.nq()])?;
    let mut osc = Osc::new(ctrl_model, cfg.controller.clone())?;
    let run = run_closed_loop(&mut sim, &mut osc, &traj, model.task_axes(), seconds)
        .with_context(|| format!("{} {:?} with {}", c.robot, c.law, c.error))?;
    let mut json = serde_json::to_value(&run.metrics)?;
    let o = json.as_object_mut().expect("object");
    o.insert("robot".into(), c.robot.into());
    o.insert(
        "controller".into(),
        format!("{:?}", c.law).to_lowercase().into(),
    );
    o.insert("model_error".into(), c.error.to_string().into());
    // `first_limit_s` is null when no joint reached a limit: keep the JSON numeric.
    if o.get("first_limit_s").is_some_and(Value::is_null) {
        o.remove("first_limit_s");
    }
    write_outputs(&c.dir, &cfg, &run, &model, &json)?;
    Ok((json, run))
}

/// Runs all cases in parallel.
pub fn run_all(
    cases: &[Case],
    seconds: f64,
    bar: &indicatif::ProgressBar,
) -> Result<Vec<(Value, Run)>> {
    cases
        .par_iter()
        .map(|c| {
            let r = run_case(c, seconds);
            bar.inc(1);
            r
        })
        .collect()
}
