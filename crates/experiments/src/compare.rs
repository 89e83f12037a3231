//! E6 (ablation: the learner's variants side by side) and E7 (analytical eq. 7 with a wrong
//! model vs the learned controller trained on the true robot).

use crate::analytical::{AnalyticalRun, ERRORS};
use crate::jobs::JobResult;
use crate::learned::{curves, select, summarize};
use crate::results::{AblationRow, Curves, ModelErrorRow};
use crate::stats::{EvalSummary, Missing, Outcome, Stat, Status};
use osrl_control::Law;
use osrl_learn::Variant;
use std::collections::BTreeMap;

/// E6 of one robot: per variant ([`Variant::key`]), its row.
pub type AblationRows = BTreeMap<String, Outcome<AblationRow>>;

/// E6 of one robot: per variant ([`Variant::key`]) the final metrics over its seeds, and each
/// finished variant's learning curves (label, curves) for the figure.
pub fn e6(jobs: &[JobResult], robot: &str) -> (AblationRows, Vec<(String, Curves)>) {
    let (mut rows, mut plotted) = (BTreeMap::new(), Vec::new());
    for v in Variant::ALL {
        let (runs, failed) = select(jobs, robot, v, false);
        let row = if runs.is_empty() {
            Outcome::Failed(Missing::failed(failed))
        } else {
            plotted.push((v.label().to_string(), curves(&runs)));
            Outcome::Done(AblationRow {
                summary: summarize(&runs),
                label: v.label().into(),
                seeds: runs.len(),
                failed_seeds: failed,
            })
        };
        rows.insert(v.key().to_string(), row);
    }
    (rows, plotted)
}

/// The analytical eq. 7 run of `robot` with the model error `key`.
fn eq7<'a>(runs: &'a [AnalyticalRun], robot: &str, key: &str) -> Option<&'a AnalyticalRun> {
    runs.iter()
        .find(|r| r.case.robot == robot && r.case.error_key == key && r.case.law == Law::Eq7)
}

/// E7 of one robot: per model error, eq. 7 with that wrong model against the learned
/// controller on the robot.
pub fn e7(
    jobs: &[JobResult],
    analytical: &[AnalyticalRun],
    robot: &str,
) -> BTreeMap<String, ModelErrorRow> {
    let (rwr, _) = select(jobs, robot, Variant::Rwr, false);
    let learned_true = if rwr.is_empty() {
        Stat::Missing(Missing {
            status: Status::Failed,
            errors: Vec::new(),
        })
    } else {
        summarize(&rwr).tracking_rms_mm
    };
    let seed0 = jobs
        .iter()
        .find(|j| j.job.robot == robot && j.job.is_reference())
        .and_then(|j| j.outcome.as_ref().ok());
    let (pay, pay_failed) = select(jobs, robot, Variant::Rwr, true);
    let mut rows = BTreeMap::new();
    for key in std::iter::once("none").chain(ERRORS.iter().map(|e| e.0)) {
        let a = eq7(analytical, robot, key);
        let mut row = ModelErrorRow {
            analytical_eq7_tracking_rms_mm: a.map(|r| r.row.tracking_rms_mm),
            analytical_eq7_tracking_max_mm: a.map(|r| r.row.tracking_max_mm),
            model_error: a.map(|r| r.row.model_error.clone()),
            learned_tracking_rms_mm: learned_true.clone(),
            learned_trained_with_payload: None,
            learned_trained_without_payload: None,
        };
        if key == "payload" {
            // The robot carries the payload: the learned controller trained on it, and the one
            // trained without it (not retrained).
            if pay.is_empty() {
                row.learned_tracking_rms_mm = Stat::Missing(Missing::failed(pay_failed.clone()));
            } else {
                let s = summarize(&pay);
                row.learned_tracking_rms_mm = s.tracking_rms_mm.clone();
                row.learned_trained_with_payload = Some(s);
            }
            row.learned_trained_without_payload = seed0
                .and_then(|t| t.on_payload.as_ref())
                .map(EvalSummary::from);
        }
        rows.insert(key.to_string(), row);
    }
    rows
}
