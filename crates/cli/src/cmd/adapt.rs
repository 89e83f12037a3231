//! `osrl adapt`: a saved learned controller keeps learning on a changed robot — a payload,
//! heavier links, more friction (`--change`, the grammar of `--model-error` applied to the
//! simulated robot itself). No babbling: on-policy learning along the controller's training path
//! from the first step, with the learner's re-adaptation switched on (`docs/learner.md`,
//! "Re-adaptation"). Saves the adapted controller (its file names the unchanged robot: `osrl
//! eval` on it measures what the adaptation did to the unchanged arm, `osrl eval --change` the
//! same spec measures it on the changed one; its re-adaptation stays
//! on in the file, so that evaluation, `osrl simulate` and the Python `LearnedController` run it
//! with the disturbance observer). With `--json` the last stdout line has every key of `osrl
//! train --json` plus `change`, `tracking_rms_mm_before`, `tracking_rms_mm_before_observer`
//! (the loaded controller with the re-adaptation's task-space disturbance observer and no
//! learning; `null` with the observer off), `tracking_rms_mm_nominal`,
//! `tracking_rms_mm_nominal_observer` (with the observer, on the unchanged robot),
//! `minutes_to_1mm`, `minutes_to_2x_nominal`, `minutes_to_2x_nominal_observer` (to within twice
//! the nominal with the observer), `minutes_to_1mm_stable` and `minutes_to_2x_nominal_stable`
//! (from when every later evaluation stays within the bound: a relapse counts) and the learning
//! curve from minute 0.
//!
//! The config file's `[train]` section sets the run (its gains are replaced by the saved
//! controller's, its babbling is skipped, evaluations come at least every 0.25 minutes) and
//! `[learner.adaptation]` the re-adaptation; the rest of `[learner]` is the saved controller's,
//! and a config that sets another `[learner.*]` table is refused rather than ignored.
//! Without a `[train]` section the episodes run the whole path from the start (no curriculum)
//! and brake at 3 cm of task error.

use crate::config::Config;
use crate::progress;
use crate::train_json::summary_json;
use crate::util::print_json;
use anyhow::{bail, Context, Result};
use osrl_control::RobotChange;
use osrl_experiments::adapt::{adapt, continuation, Adapted};
use osrl_experiments::stats::{curve_points, EvalSummary};
use osrl_experiments::Setup;
use osrl_learn::{ModelInfo, SavedModel};
use serde_json::json;
use std::path::PathBuf;

/// Arguments of `osrl adapt`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// A model saved by `osrl train` (or `osrl adapt`).
    #[arg(long)]
    pub model: PathBuf,
    /// How the robot changes: `payload=0.5`, `mass=1.3`, `friction=2`, `com=0.02,seed=7`, or
    /// several joined by commas.
    #[arg(long)]
    pub change: RobotChange,
    /// Simulated minutes of adaptation (default 10).
    #[arg(long)]
    pub minutes: Option<f64>,
    /// Seed of the exploration noise and the simulator (default: the config's [train] seed, 0).
    #[arg(long)]
    pub seed: Option<u64>,
    /// TOML config file: `[train]` and `[learner.adaptation]` are read.
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// Where to save the adapted controller.
    #[arg(long)]
    pub out: PathBuf,
    /// Print the result as one JSON object on the last stdout line.
    #[arg(long)]
    pub json: bool,
}

/// The brake error of an adaptation run without a `[train]` section (m).
const ADAPT_BRAKE_ERROR: f64 = 0.03;

/// The largest interval between evaluations (simulated minutes): four points per minute.
const EVAL_EVERY_MAX: f64 = 0.25;

/// Loads, checks, adapts, saves, reports.
pub fn run(a: Args) -> Result<()> {
    let (cfg, sections) = Config::load_with_sections(a.config.as_deref())?;
    if let Some(s) = sections.keys().find(|s| *s != "train" && *s != "learner") {
        bail!(
            "{}: [{s}] has no meaning for `osrl adapt` (robot, trajectory and simulator are the \
             saved controller's): remove it",
            a.config
                .as_deref()
                .map_or("config".into(), |p| p.display().to_string())
        );
    }
    refuse_saved_learner_sections(&sections, a.config.as_deref())?;
    cfg.validate()?;
    let saved = SavedModel::load(&a.model)?;
    crate::util::check_out_file("--out", &a.out, &[Some(&a.model), a.config.as_deref()])?;
    let minutes = a.minutes.unwrap_or(10.0);
    if !(minutes > 0.0 && minutes <= crate::config::MAX_TRAIN_MINUTES) {
        bail!(
            "--minutes {minutes}: accepted range (0, {}]",
            crate::config::MAX_TRAIN_MINUTES
        );
    }
    let setup = Setup::from_saved(&saved)?;
    let mut train = continuation(&cfg.train, minutes);
    if !sections.contains_key("train") {
        // Without a [train] section: the whole path from the first episode (the controller was
        // trained to it), braked only at 3 cm (a changed robot starts ~1 cm off).
        train.curriculum.stages.clear();
        train.curriculum.brake_error = ADAPT_BRAKE_ERROR;
    }
    train.gains = saved.info().gains;
    train.seed = a.seed.unwrap_or(cfg.train.seed);
    if !(train.eval_every_minutes > 0.0 && train.eval_every_minutes <= EVAL_EVERY_MAX) {
        train.eval_every_minutes = EVAL_EVERY_MAX;
    }
    let setup = setup.with_train(train).context("[train]")?;
    // The change is checked (range, torque limits along the path) before anything runs.
    osrl_experiments::adapt::checked_change(&setup, &a.change)?;
    let (info, mut learner, model) = saved.into_parts();
    let bar = progress::train_bar(None, &format!("adapt {}", model.name()), minutes);
    let res = adapt(
        &setup,
        &mut learner,
        &a.change,
        cfg.learner.adaptation.clone(),
        setup.train_config(),
        &mut |p| progress::update(&bar, minutes, p),
    )
    .context("adapting")?;
    bar.finish_and_clear();
    let info = ModelInfo {
        sim_training_minutes: info.sim_training_minutes + res.summary.sim_training_minutes,
        ..info
    };
    let bytes = SavedModel::new(info, learner)?.to_bytes()?;
    let saved = crate::util::save_result("adapted model", &a.out, &bytes);
    let text = describe(&res, &a.change);
    if a.json {
        eprintln!("{text}");
    } else {
        println!("{text}");
    }
    if saved.is_ok() && !a.json {
        println!("wrote {}", a.out.display());
    }
    if a.json {
        print_json(&adapt_json(&res, &a.change, model.name())?);
    }
    saved
}

/// The human-readable summary.
fn describe(r: &Adapted, change: &RobotChange) -> String {
    let s = &r.summary;
    let last = s
        .learning_curve
        .last()
        .map(|(_, e)| e.clone())
        .unwrap_or_default();
    let m = |v: Option<f64>| v.map_or("never".into(), |t| format!("{t:.2} min"));
    format!(
        "change {change}: tracking {:.3} mm unchanged, {:.3} mm changed before learning, {:.3} mm \
         after {:.1} min (command nMSE {:.4}) · to 1 mm: {} · to 2× nominal: {} · {} episodes \
         ({} aborted, {} braked) · re-adaptation peak level {:.1}, {} steps",
        r.nominal.tracking_rms_mm,
        r.before.tracking_rms_mm,
        last.tracking_rms_mm,
        s.sim_training_minutes,
        last.command_nmse,
        m(r.minutes_to(|e| e.tracking_rms_mm <= 1.0)),
        m(r.minutes_to(|e| e.tracking_rms_mm <= 2.0 * r.nominal.tracking_rms_mm)),
        s.episodes,
        s.aborted_episodes,
        s.braked_episodes,
        r.peak_level,
        r.adapting_steps
    )
}

/// `osrl train --json`'s keys for the adaptation run, plus the keys of issue 26.
fn adapt_json(r: &Adapted, change: &RobotChange, robot: &str) -> Result<serde_json::Value> {
    let s = &r.summary;
    let last = s
        .learning_curve
        .last()
        .map(|(_, e)| e.clone())
        .unwrap_or_default();
    let mut j = summary_json(s, &EvalSummary::from(&last), robot)?;
    let mut curve = vec![(0.0, r.before.clone())];
    curve.extend(s.learning_curve.iter().cloned());
    let nominal = r.nominal.tracking_rms_mm;
    let nominal_observer = r.nominal_observer.as_ref().map(|e| e.tracking_rms_mm);
    let extra = json!({
        "change": change.to_string(),
        "tracking_rms_mm_before": r.before.tracking_rms_mm,
        "tracking_rms_mm_before_observer": r.before_observer.as_ref().map(|e| e.tracking_rms_mm),
        "tracking_rms_mm_nominal_observer": nominal_observer,
        "tracking_rms_mm_nominal": nominal,
        "minutes_to_1mm": r.minutes_to(|e| e.tracking_rms_mm <= 1.0),
        "minutes_to_2x_nominal": r.minutes_to(|e| e.tracking_rms_mm <= 2.0 * nominal),
        "minutes_to_2x_nominal_observer": nominal_observer
            .and_then(|n| r.minutes_to(|e| e.tracking_rms_mm <= 2.0 * n)),
        "minutes_to_nmse_0.05": r.minutes_to(|e| e.command_nmse <= 0.05),
        "minutes_to_1mm_stable": r.minutes_to_stay(|e| e.tracking_rms_mm <= 1.0),
        "minutes_to_2x_nominal_stable": r
            .minutes_to_stay(|e| e.tracking_rms_mm <= 2.0 * nominal),
        "adaptation_peak_level": r.peak_level,
        "adapting_steps": r.adapting_steps,
        "adaptation_curve": r
            .signal
            .iter()
            .map(|(t, a)| [*t, a.level, a.strength])
            .collect::<Vec<_>>(),
        "learning_curve": curve_points(&curve),
    });
    let o = j.as_object_mut().context("the summary is a JSON object")?;
    for (k, v) in extra.as_object().into_iter().flatten() {
        o.insert(k.clone(), v.clone());
    }
    Ok(j)
}

/// Refuses `[learner.*]` tables other than `[learner.adaptation]` in the config file's `table`
/// (read from `path`): the rest of the learner's configuration is the saved controller's, and a
/// setting that would be ignored silently is an error instead.
fn refuse_saved_learner_sections(
    table: &toml::Table,
    path: Option<&std::path::Path>,
) -> Result<()> {
    let Some(learner) = table.get("learner").and_then(|v| v.as_table()) else {
        return Ok(());
    };
    let ignored: Vec<&str> = learner
        .keys()
        .map(String::as_str)
        .filter(|k| *k != "adaptation")
        .collect();
    if !ignored.is_empty() {
        bail!(
            "{}: [learner] {} would be ignored by `osrl adapt`: the learner's settings are the \
             saved controller's (only [learner.adaptation] is read); remove {}",
            path.map_or("config".into(), |p| p.display().to_string()),
            ignored.join(", "),
            if ignored.len() == 1 { "it" } else { "them" }
        );
    }
    Ok(())
}
