//! E8 (issue 26): the robot changes under a learned controller trained on the unchanged arm.
//! One timeline per robot and change — tracking on the unchanged arm, the change made at
//! [`ChangeSizes::nominal_minutes`], the payload removed again after
//! [`ChangeSizes::changed_minutes`] — and three controllers on it: the learner re-adapting
//! on-policy (`[learner.adaptation]` on, as `osrl adapt` runs it), the same learner frozen, and
//! eq. 7 with the stale (unchanged) model. The learner sees only measurements; each evaluation
//! scores it on the robot as it is at that moment.

use crate::adapt::{checked_change, continuation, run_changing, ChangeSchedule};
use crate::error::Result;
use crate::setup::Setup;
use crate::sizes::Sizes;
use osrl_control::{Law, Osc, OscConfig, RobotChange};
use osrl_dynamics::Model;
use osrl_learn::eval::EvalResult;
use osrl_learn::{AdaptationConfig, Learner};
use serde::{Deserialize, Serialize};

/// The changes of E8: key in `results.json`, spec (`payload`'s mass is the sizes'), whether
/// it is removed again.
pub const CHANGES: [(&str, &str, bool); 3] = [
    ("payload", "payload=0.5", true),
    ("mass_x1.3", "mass=1.3", false),
    ("friction_x2", "friction=2", false),
];

/// The brake error of the re-adapting runs (m), as `osrl adapt`'s: a changed robot starts
/// ~1 cm off its path.
const BRAKE_ERROR: f64 = 0.03;

/// The three controllers' tracking at each evaluation of the timeline (mm; `null` where the
/// evaluation diverged).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Timeline {
    pub sim_minutes: Vec<f64>,
    /// The learner re-adapting on-policy.
    pub adapting_mm: Vec<Option<f64>>,
    /// The same learner, frozen (no learning): its evaluation on the robot as it is.
    pub frozen_mm: Vec<Option<f64>>,
    /// Eq. 7 with the model of the unchanged arm.
    pub eq7_stale_mm: Vec<Option<f64>>,
}

/// E8 for one robot and change. Minutes are counted from the change (or from its removal);
/// `null` = never within the timeline.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ChangeRow {
    /// The change's spec (`RobotChange`'s grammar).
    pub change: String,
    /// Training seed of the controller (and of the re-adapting run).
    pub seed: u64,
    /// Simulated minutes of the timeline at which the change is made and removed.
    pub change_at_minutes: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub revert_at_minutes: Option<f64>,
    /// The learned controller on the unchanged arm before the change (its nominal tracking).
    pub nominal_tracking_rms_mm: Option<f64>,
    /// The learned controller, frozen, on the changed arm.
    pub frozen_tracking_rms_mm: Option<f64>,
    /// The same with the re-adaptation's task-space disturbance observer and no learning: what
    /// the observer does alone (`None` with the observer off, or diverged: then listed in
    /// `diverged`).
    #[serde(default)]
    pub observer_frozen_tracking_rms_mm: Option<f64>,
    /// Eq. 7 with the true model on the unchanged arm, and with that (stale) model on the
    /// changed arm.
    pub eq7_nominal_tracking_rms_mm: Option<f64>,
    pub eq7_stale_tracking_rms_mm: Option<f64>,
    /// Re-adapting: first evaluation after the change at ≤ 1 mm, at ≤ 2× nominal.
    pub minutes_to_1mm: Option<f64>,
    pub minutes_to_2x_nominal: Option<f64>,
    /// The same, from when every later evaluation of the change stays within the bound (a
    /// relapse counts; `null` if the last one does not).
    #[serde(default)]
    pub minutes_to_1mm_stable: Option<f64>,
    #[serde(default)]
    pub minutes_to_2x_nominal_stable: Option<f64>,
    /// Re-adapting: the last evaluation with the change, its tracking and command nMSE
    /// against eq. 7 on the changed true model.
    pub adapted_tracking_rms_mm: Option<f64>,
    pub adapted_command_nmse: Option<f64>,
    /// Payload only: re-adapting after the removal.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub after_removal: Option<AfterRemoval>,
    /// The re-adapting run's safety.
    pub aborted_episodes: u64,
    pub braked_episodes: u64,
    /// Times the re-adapting learner was rolled back to its last checkpoint
    /// (`adaptation.rollback_after`).
    #[serde(default)]
    pub rollbacks: u64,
    pub max_command_step: f64,
    pub max_torque_rate: f64,
    /// The re-adaptation's largest level.
    pub adaptation_peak_level: f64,
    /// The fields above that are `null` because their evaluation diverged (an error above
    /// 0.2 m: `osrl_learn::eval::EvalResult::diverged`), e.g. `frozen_tracking_rms_mm`.
    pub diverged: Vec<String>,
    pub timeline: Timeline,
}

impl ChangeRow {
    /// Lists in [`ChangeRow::diverged`] every tracking or nMSE field that is `null`
    /// (`observer_frozen_tracking_rms_mm` only when the observer ran: without it, it is `null`
    /// too).
    fn note_diverged(mut self, observer_on: bool) -> Self {
        let mut d = Vec::new();
        let mut note = |name: &str, v: Option<f64>| {
            if v.is_none() {
                d.push(name.to_string());
            }
        };
        note("nominal_tracking_rms_mm", self.nominal_tracking_rms_mm);
        note("frozen_tracking_rms_mm", self.frozen_tracking_rms_mm);
        if observer_on {
            note(
                "observer_frozen_tracking_rms_mm",
                self.observer_frozen_tracking_rms_mm,
            );
        }
        note(
            "eq7_nominal_tracking_rms_mm",
            self.eq7_nominal_tracking_rms_mm,
        );
        note("eq7_stale_tracking_rms_mm", self.eq7_stale_tracking_rms_mm);
        note("adapted_tracking_rms_mm", self.adapted_tracking_rms_mm);
        note("adapted_command_nmse", self.adapted_command_nmse);
        if let Some(a) = &self.after_removal {
            note("after_removal.tracking_rms_mm", a.tracking_rms_mm);
        }
        self.diverged = d;
        self
    }
}

/// The re-adapting controller after the change is removed (minutes from the removal; `null` =
/// never within the timeline).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AfterRemoval {
    /// First evaluation at ≤ 1 mm, at ≤ 2× nominal.
    pub minutes_to_1mm: Option<f64>,
    pub minutes_to_2x_nominal: Option<f64>,
    /// The last evaluation: the adapted controller on the unchanged arm.
    pub tracking_rms_mm: Option<f64>,
}

/// A finite number, or `None`.
fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

/// An evaluation's tracking, `None` if it diverged (then its number covers only the steps
/// before the error passed 0.2 m).
fn mm(e: &EvalResult) -> Option<f64> {
    if e.diverged {
        None
    } else {
        finite(e.tracking_rms_mm)
    }
}

/// Eq. 7 with `setup`'s model on the `truth` robot for `seconds`: its tracking (mm; `None` if
/// not finite).
///
/// # Errors
/// As [`Setup::closed_loop`].
fn eq7_on(setup: &Setup, truth: Model, seconds: f64) -> Result<Option<f64>> {
    let cfg = OscConfig {
        law: Law::Eq7,
        ..OscConfig::default()
    };
    let mut ctrl = Osc::new(setup.model().clone(), cfg)?;
    let run = setup.closed_loop(truth, &mut ctrl, seconds)?;
    Ok(finite(run.metrics.tracking_rms_mm))
}

/// The first time in `(from, to]` of `curve` whose tracking meets `pred`, minus `from`.
fn first(
    curve: &[(f64, Option<f64>)],
    from: f64,
    to: f64,
    pred: &dyn Fn(f64) -> bool,
) -> Option<f64> {
    (curve.iter())
        .filter(|(t, _)| *t > from && *t <= to + 1e-9)
        .find(|(_, v)| v.is_some_and(&pred))
        .map(|(t, _)| t - from)
}

/// Minutes after `from` of the first point of `curve` in `(from, to]` from which every point
/// up to `to` is a number meeting `pred` (`None` if the last one is not): a relapse after a
/// first success counts.
fn stays(
    curve: &[(f64, Option<f64>)],
    from: f64,
    to: f64,
    pred: &dyn Fn(f64) -> bool,
) -> Option<f64> {
    let window: Vec<&(f64, Option<f64>)> = (curve.iter())
        .filter(|(t, _)| *t > from && *t <= to + 1e-9)
        .collect();
    let bad = window.iter().rposition(|(_, v)| !v.is_some_and(pred));
    window.get(bad.map_or(0, |i| i + 1)).map(|(t, _)| t - from)
}

/// Runs one E8 timeline: `learner` (trained on `setup`'s unchanged robot with `setup`'s
/// training gains; `setup`'s training seed, evaluation periods) under the change `key`.
///
/// # Errors
/// A change the arm cannot hold, a simulation, learning or evaluation error.
pub fn run(setup: &Setup, learner: &Learner, key: &str, sizes: &Sizes) -> Result<ChangeRow> {
    let (_, spec, reverts) = CHANGES
        .into_iter()
        .find(|(k, _, _)| *k == key)
        .ok_or_else(|| crate::ExperimentError::Invalid(format!("E8: no change {key}")))?;
    let mut change: RobotChange = spec.parse()?;
    if key == "payload" {
        change.payload = sizes.payload_kg;
    }
    let z = &sizes.e8;
    let at = z.nominal_minutes;
    let revert_at = reverts.then_some(at + z.changed_minutes);
    let end = revert_at.map_or(at + z.changed_minutes, |r| r + z.after_minutes);
    let schedule = ChangeSchedule {
        change: change.clone(),
        at,
        revert_at,
    };
    let changed = checked_change(setup, &change)?;
    let mut cfg = continuation(setup.train_config(), end);
    cfg.curriculum.stages.clear();
    cfg.curriculum.brake_error = BRAKE_ERROR;
    cfg.eval_every_minutes = z.eval_every_minutes;

    // Frozen: the learner's evaluation depends only on the robot it runs on.
    let frozen_nominal = mm(&setup
        .evaluator(setup.model())?
        .evaluate(&mut learner.clone())?);
    let frozen_changed = mm(&setup.evaluator(&changed)?.evaluate(&mut learner.clone())?);
    let eq7_nominal = eq7_on(setup, setup.model().clone(), sizes.analytical_seconds)?;
    let eq7_stale = eq7_on(setup, changed.clone(), sizes.analytical_seconds)?;

    // Re-adapting, on the robot that changes (and back); before it learns, its evaluation on
    // the changed robot is the disturbance observer alone (the evaluation runs a copy).
    let mut adapting = learner.clone();
    adapting.set_adaptation(AdaptationConfig {
        enabled: true,
        ..AdaptationConfig::default()
    })?;
    adapting.reset_adaptation();
    let observer_on = adapting.observer().is_on();
    let observer_frozen = match observer_on {
        true => mm(&setup.evaluator(&changed)?.evaluate(&mut adapting)?),
        false => None,
    };
    let summary = run_changing(setup, &changed, &schedule, &mut adapting, &cfg, &mut |_| {})?;
    let peak = adapting.adaptation().peak_level;

    let curve = crate::stats::dedup_curve(&summary.learning_curve);
    let mut tl = Timeline::default();
    let with_change = |t: f64| t > at && revert_at.is_none_or(|r| t <= r);
    let mut push = |t: f64, a: Option<f64>| {
        tl.sim_minutes.push(t);
        tl.adapting_mm.push(a);
        let on_changed = with_change(t);
        tl.frozen_mm.push(if on_changed {
            frozen_changed
        } else {
            frozen_nominal
        });
        tl.eq7_stale_mm
            .push(if on_changed { eq7_stale } else { eq7_nominal });
    };
    push(0.0, frozen_nominal);
    for (t, e) in &curve {
        push(*t, mm(e));
    }
    let points: Vec<(f64, Option<f64>)> = (tl.sim_minutes.iter().copied())
        .zip(tl.adapting_mm.iter().copied())
        .collect();
    let two_x = frozen_nominal.map_or(f64::NAN, |n| 2.0 * n);
    let until = revert_at.unwrap_or(end);
    let last_changed = curve.iter().rev().find(|(t, _)| with_change(*t));
    Ok(ChangeRow {
        change: change.to_string(),
        seed: cfg.seed,
        change_at_minutes: at,
        revert_at_minutes: revert_at,
        nominal_tracking_rms_mm: frozen_nominal,
        frozen_tracking_rms_mm: frozen_changed,
        observer_frozen_tracking_rms_mm: observer_frozen,
        eq7_nominal_tracking_rms_mm: eq7_nominal,
        eq7_stale_tracking_rms_mm: eq7_stale,
        minutes_to_1mm: first(&points, at, until, &|v| v <= 1.0),
        minutes_to_2x_nominal: first(&points, at, until, &|v| v <= two_x),
        minutes_to_1mm_stable: stays(&points, at, until, &|v| v <= 1.0),
        minutes_to_2x_nominal_stable: stays(&points, at, until, &|v| v <= two_x),
        adapted_tracking_rms_mm: last_changed.and_then(|(_, e)| mm(e)),
        adapted_command_nmse: last_changed
            .filter(|(_, e)| !e.diverged)
            .and_then(|(_, e)| finite(e.command_nmse)),
        after_removal: revert_at.map(|r| AfterRemoval {
            minutes_to_1mm: first(&points, r, end, &|v| v <= 1.0),
            minutes_to_2x_nominal: first(&points, r, end, &|v| v <= two_x),
            tracking_rms_mm: curve.last().and_then(|(_, e)| mm(e)),
        }),
        aborted_episodes: summary.aborted_episodes,
        braked_episodes: summary.braked_episodes,
        rollbacks: summary.rollbacks,
        max_command_step: summary.max_command_step,
        max_torque_rate: summary.max_torque_rate,
        adaptation_peak_level: peak,
        diverged: Vec::new(),
        timeline: tl,
    }
    .note_diverged(observer_on))
}

/// E8 per robot and change.
pub type Rows = crate::results::ByRobot<std::collections::BTreeMap<String, ChangeRow>>;

/// Every E8 timeline in parallel, each from its robot's reference controller of `done` (RWR,
/// seed 0, trained on the unchanged arm: [`crate::Job::is_reference`]); a robot without one
/// (its training failed) has no E8 rows. Returns the rows and the failed timelines (name and
/// error).
pub fn run_all(
    sizes: &Sizes,
    setups: &[(&str, Setup)],
    done: &[crate::JobResult],
    observer: &dyn crate::Observer,
) -> (Rows, Vec<(String, String)>) {
    use rayon::prelude::*;
    let mut cases = Vec::new();
    for j in done.iter().filter(|j| j.job.is_reference()) {
        let Some(model) = j.outcome.as_ref().ok().and_then(|t| t.model.as_ref()) else {
            continue;
        };
        for (key, _, _) in CHANGES {
            cases.push((j, model, key));
        }
    }
    observer.note(&format!(
        "E8: {} timelines of a changing robot ({} + {} + {} min simulated)",
        cases.len(),
        sizes.e8.nominal_minutes,
        sizes.e8.changed_minutes,
        sizes.e8.after_minutes
    ));
    let out: Vec<_> = cases
        .par_iter()
        .map(|(j, model, key)| {
            let row = crate::setup_of(setups, j.job.robot)
                .and_then(|base| crate::jobs::job_setup(base, &j.job, sizes))
                .and_then(|s| run(&s, model.learner(), key, sizes));
            (j.job.robot, *key, row)
        })
        .collect();
    let mut rows = Rows::new();
    let mut failed = Vec::new();
    for (robot, key, row) in out {
        match row {
            Ok(r) => {
                rows.entry(robot.to_string())
                    .or_default()
                    .insert(key.to_string(), r);
            }
            Err(e) => failed.push((format!("E8 {robot} {key}"), e.to_string())),
        }
    }
    (rows, failed)
}

#[cfg(test)]
mod tests {
    use super::*;
    use osrl_learn::train::{BabbleConfig, TrainConfig};

    #[test]
    fn recovery_is_the_first_point_after_the_change_that_meets_the_bound() {
        let c = [
            (0.0, Some(0.1)),
            (0.5, Some(0.2)),
            (0.75, None),
            (1.0, Some(3.0)),
            (1.25, Some(0.5)),
        ];
        assert_eq!(first(&c, 0.5, 1.25, &|v| v <= 1.0), Some(0.75));
        // The point at the change itself belongs to the time before it.
        assert_eq!(first(&c, 0.0, 1.25, &|v| v <= 1.0), Some(0.5));
        assert_eq!(first(&c, 0.5, 1.0, &|v| v <= 1.0), None);
    }

    /// "For good" is the first point after the last one that misses the bound (a diverged one
    /// misses it), within the window; `None` when the window ends outside the bound.
    #[test]
    fn recovery_for_good_counts_a_relapse() {
        let c = [
            (0.0, Some(0.1)),
            (0.25, Some(0.5)),
            (0.5, None),
            (0.75, Some(0.4)),
            (1.0, Some(3.0)),
            (1.25, Some(0.5)),
            (1.5, Some(0.6)),
        ];
        let ok = |v: f64| v <= 1.0;
        assert_eq!(first(&c, 0.0, 1.5, &ok), Some(0.25));
        assert_eq!(stays(&c, 0.0, 1.5, &ok), Some(1.25));
        assert_eq!(stays(&c, 0.0, 1.0, &ok), None);
        assert_eq!(stays(&c, 1.0, 1.5, &ok), Some(0.25));
        assert_eq!(stays(&c, 0.0, 0.25, &ok), Some(0.25));
    }

    /// A tiny timeline: the three lines have one point per evaluation, the frozen and eq. 7
    /// lines switch exactly over the change, the payload is removed again and the others are
    /// not, and the same seed gives the same row.
    #[test]
    fn a_tiny_timeline_is_consistent_and_repeatable() {
        let train = TrainConfig {
            minutes: 0.2,
            babble: BabbleConfig {
                minutes: 0.1,
                ..BabbleConfig::default()
            },
            eval_every_minutes: 0.0,
            ..TrainConfig::default()
        };
        let setup = Setup::new("planar3")
            .unwrap()
            .with_train(train)
            .unwrap()
            .with_eval_periods(1)
            .unwrap();
        let (learner, _) = setup.train(setup.model(), &mut |_| {}).unwrap();
        let mut sizes = Sizes::quick();
        sizes.e8 = crate::ChangeSizes {
            nominal_minutes: 0.1,
            changed_minutes: 0.1,
            after_minutes: 0.1,
            eval_every_minutes: 0.05,
        };
        let row = run(&setup, &learner, "payload", &sizes).unwrap();
        let tl = &row.timeline;
        let n = tl.sim_minutes.len();
        assert!(n >= 6, "{n} points");
        assert_eq!(
            (
                tl.adapting_mm.len(),
                tl.frozen_mm.len(),
                tl.eq7_stale_mm.len()
            ),
            (n, n, n)
        );
        for (t, (f, e)) in tl
            .sim_minutes
            .iter()
            .zip(tl.frozen_mm.iter().zip(&tl.eq7_stale_mm))
        {
            let on = *t > 0.1 && *t <= 0.2;
            assert_eq!(
                *f,
                if on {
                    row.frozen_tracking_rms_mm
                } else {
                    row.nominal_tracking_rms_mm
                }
            );
            assert_eq!(
                *e,
                if on {
                    row.eq7_stale_tracking_rms_mm
                } else {
                    row.eq7_nominal_tracking_rms_mm
                }
            );
        }
        // Eq. 7 with the stale model misses the payload (E7: ~9 mm against ~0.01 mm).
        assert!(
            row.eq7_stale_tracking_rms_mm.unwrap()
                > 10.0 * row.eq7_nominal_tracking_rms_mm.unwrap()
        );
        assert!(row.after_removal.is_some() && row.revert_at_minutes == Some(0.2));
        assert_eq!(row, run(&setup, &learner, "payload", &sizes).unwrap());
        let mass = run(&setup, &learner, "mass_x1.3", &sizes).unwrap();
        assert!(mass.after_removal.is_none() && mass.revert_at_minutes.is_none());
        assert_eq!(mass.change, "mass=1.3");
        assert!(run(&setup, &learner, "wings", &sizes).is_err());
    }
}
