//! The loaders and parsers under fuzzing, each a function of one input's bytes: `Ok` with a
//! label of how far it got, or the error's text. A panic, hang or allocation beyond the bound
//! is a finding; an error is the expected answer to a broken input.

use crate::config::Config;
use osrl_learn::SavedModel;
use std::path::Path;

type Outcome = Result<&'static str, String>;
/// The range of an input to mutate alone.
type Part = fn(&[u8]) -> std::ops::Range<usize>;

/// A loader: its name, the folder of its corpus under `fuzz/corpus/`, and the function.
pub struct Target {
    pub name: &'static str,
    pub run: fn(&[u8]) -> Outcome,
    /// Makes a mutated binary input pass its checksums (so the checks behind them are reached).
    pub fix: Option<fn(&mut [u8])>,
    /// The part of an input worth mutating alone half of the time (a saved model's info JSON).
    pub part: Option<Part>,
}

pub const TARGETS: [Target; 9] = [
    Target {
        name: "urdf",
        run: urdf,
        fix: None,
        part: None,
    },
    Target {
        name: "config",
        run: config,
        fix: None,
        part: None,
    },
    Target {
        name: "lwpr_config",
        run: lwpr_config,
        fix: None,
        part: None,
    },
    Target {
        name: "toy_config",
        run: toy_config,
        fix: None,
        part: None,
    },
    Target {
        name: "saved_model",
        run: saved_model,
        fix: Some(fix_saved),
        part: Some(info_part),
    },
    Target {
        name: "lwpr_model",
        run: lwpr_model,
        fix: Some(fix_lwpr),
        part: None,
    },
    Target {
        name: "csv",
        run: csv,
        fix: None,
        part: None,
    },
    Target {
        name: "model_error",
        run: model_error,
        fix: None,
        part: None,
    },
    Target {
        name: "vectors",
        run: vectors,
        fix: None,
        part: None,
    },
];

fn text(bytes: &[u8]) -> Result<&str, String> {
    std::str::from_utf8(bytes).map_err(|_| "not UTF-8".to_string())
}

fn err(e: impl std::fmt::Display) -> String {
    format!("{e:#}")
}

fn urdf(b: &[u8]) -> Outcome {
    let m = osrl_dynamics::urdf::parse_urdf(text(b)?).map_err(err)?;
    let q = vec![0.1; m.nq()];
    let mut d = m.data();
    osrl_dynamics::compute_all(&m, &mut d, &q, &q).map_err(err)?;
    Ok("model")
}

/// The config file of `osrl simulate` and `osrl train`, checked, then the set-up built from it
/// for a built-in robot (a robot path is not followed).
fn config(b: &[u8]) -> Outcome {
    let cfg: Config = crate::util::parse_toml(Path::new("fuzz.toml"), text(b)?).map_err(err)?;
    cfg.validate().map_err(err)?;
    if !osrl_dynamics::robots::BUILTIN.contains(&cfg.robot.name()) {
        return Ok("valid (robot not built in)");
    }
    let setup =
        osrl_experiments::Setup::profiled(cfg.robot.name(), &cfg.robot.0, cfg.trajectory.clone())
            .and_then(|s| s.with_sim(cfg.sim.clone()))
            .and_then(|s| s.with_learner(cfg.learner.clone()))
            .and_then(|s| s.with_train(cfg.train.clone()))
            .map_err(err)?;
    let model = setup.model();
    let (n, m) = (model.nq(), model.task_dim());
    let dt = setup.sim().control_period;
    osrl_learn::Learner::new(n, m, dt, setup.learner_config().clone()).map_err(err)?;
    setup.evaluator(model).map_err(err)?;
    let (_, ctrl) = cfg.model_error.apply(model).map_err(err)?;
    osrl_control::Osc::new(ctrl, cfg.controller.clone()).map_err(err)?;
    Ok("set-up")
}

fn lwpr_config(b: &[u8]) -> Outcome {
    let mut cfg: lwpr::LwprConfig =
        crate::util::parse_toml(Path::new("fuzz.toml"), text(b)?).map_err(err)?;
    cfg.resolve_std(&[0.5, 2.0], &[1.0]).map_err(err)?;
    let mut m = lwpr::Lwpr::new(2, 1, &cfg).map_err(err)?;
    let (mut y, mut s) = ([0.0], [0.0]);
    for i in 0..20 {
        let x = [(i as f64 * 0.37).sin(), (i as f64 * 0.11).cos()];
        m.update(&x, &[x[0] * x[1]]).map_err(err)?;
        m.predict_with_support(&x, &mut y, &mut s).map_err(err)?;
    }
    Ok("trained")
}

fn toy_config(b: &[u8]) -> Outcome {
    let cfg: rwr::toy::ToyConfig =
        crate::util::parse_toml(Path::new("fuzz.toml"), text(b)?).map_err(err)?;
    cfg.validate().map_err(err)?;
    Ok("valid")
}

fn saved_model(b: &[u8]) -> Outcome {
    let saved = SavedModel::from_bytes(b).map_err(err)?;
    let setup = osrl_experiments::Setup::from_saved(&saved).map_err(err)?;
    let mut ctrl = saved.controller().map_err(err)?;
    let target = setup.trajectory().sample(0.0);
    let model = setup.model();
    let mut sim = osrl_dynamics::SimRobot::new(model.clone(), setup.sim().clone()).map_err(err)?;
    sim.reset(setup.home(), &vec![0.0; model.nq()])
        .map_err(err)?;
    let mut u = vec![0.0; model.nq()];
    use osrl_control::TaskController;
    use osrl_dynamics::Robot;
    ctrl.command(sim.measurement(), &target, &mut u)
        .map_err(err)?;
    Ok("commanded")
}

fn lwpr_model(b: &[u8]) -> Outcome {
    let mut m = lwpr::Lwpr::from_bytes(b).map_err(err)?;
    let (mut y, mut s) = (vec![0.0; m.n_out()], vec![0.0; m.n_out()]);
    let x = vec![0.3; m.n_in()];
    m.predict_with_support(&x, &mut y, &mut s).map_err(err)?;
    m.update(&x, &y.iter().map(|v| v + 0.1).collect::<Vec<_>>())
        .map_err(err)?;
    Ok("predicted")
}

fn csv(b: &[u8]) -> Outcome {
    let series = osrl_report::csv::Table::parse(Path::new("fuzz.csv"), b, false).is_ok();
    let t = osrl_report::csv::Table::parse(Path::new("fuzz.csv"), b, true).map_err(err)?;
    // As `osrl lwpr fit --inputs K` with the last column as the output.
    let k = t.names.len() - 1;
    if k == 0 {
        return Ok("table of one column");
    }
    let mut m = lwpr::Lwpr::new(k, 1, &lwpr::LwprConfig::default()).map_err(err)?;
    for row in t.rows.iter().take(3) {
        m.update(&row[..k], &row[k..]).map_err(err)?;
    }
    Ok(if series {
        "fitted"
    } else {
        "fitted, not a series"
    })
}

fn model_error(b: &[u8]) -> Outcome {
    let me: osrl_control::ModelError = text(b)?.parse().map_err(err)?;
    me.validate().map_err(err)?;
    me.apply(&osrl_dynamics::robots::planar3()).map_err(err)?;
    Ok("applied")
}

/// `osrl dynamics` on planar3 with the input's lines as `--q`, `--qd`, `--qdd`, `--u`.
fn vectors(b: &[u8]) -> Outcome {
    let mut lines = text(b)?.lines();
    let q = lines.next().unwrap_or("");
    let (qd, qdd, u) = (lines.next(), lines.next(), lines.next());
    let model = osrl_dynamics::robots::planar3();
    crate::cmd::dynamics::evaluate(&model, q, qd, qdd, u).map_err(err)?;
    Ok("evaluated")
}

fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| {
        (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)
    })
}

/// LWPR file: magic 8, version 4, length 8, payload, checksum 8 (length and checksum redone).
fn fix_lwpr(v: &mut [u8]) {
    if v.len() < 28 {
        return;
    }
    let payload = v[20..v.len() - 8].to_vec();
    v[12..20].copy_from_slice(&(payload.len() as u64).to_le_bytes());
    let n = v.len();
    v[n - 8..].copy_from_slice(&fnv1a(&payload).to_le_bytes());
}

/// Saved model: header 28 with the info's length and checksum, the info JSON, then the
/// learner (magic 8, version 4, length 8, checksum 8, payload). The info's extent is found
/// at the learner's magic; both lengths and checksums are redone.
fn fix_saved(v: &mut [u8]) {
    let Some(at) = v.windows(8).rposition(|w| w == osrl_learn::io::MAGIC) else {
        return;
    };
    if at < 28 || v.len() < at + 28 {
        return;
    }
    let info = v[28..at].to_vec();
    v[12..20].copy_from_slice(&(info.len() as u64).to_le_bytes());
    v[20..28].copy_from_slice(&fnv1a(&info).to_le_bytes());
    let payload = v[at + 28..].to_vec();
    v[at + 12..at + 20].copy_from_slice(&(payload.len() as u64).to_le_bytes());
    v[at + 20..at + 28].copy_from_slice(&fnv1a(&payload).to_le_bytes());
}

/// The info JSON of a saved model (between the header and the learner).
fn info_part(v: &[u8]) -> std::ops::Range<usize> {
    let end = v.windows(8).rposition(|w| w == osrl_learn::io::MAGIC);
    28.min(v.len())..end.unwrap_or(v.len()).max(28.min(v.len()))
}
