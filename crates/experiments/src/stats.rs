//! Numbers over seeds and runs as `results.json` writes them: `{mean, min, max}` summaries, the
//! status that replaces a number that was not measured, one evaluation's metrics, learning
//! curves.

use osrl_learn::eval::EvalResult;
use serde::{Deserialize, Serialize};

/// `{mean, min, max}` of some numbers.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Spread {
    pub mean: f64,
    pub min: f64,
    pub max: f64,
}

impl Spread {
    /// Of `v` (callers pass at least one number; empty gives mean 0, min ∞, max −∞).
    pub fn of(v: &[f64]) -> Self {
        Self {
            mean: v.iter().sum::<f64>() / v.len().max(1) as f64,
            min: v.iter().copied().fold(f64::INFINITY, f64::min),
            max: v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        }
    }
}

/// Why a number is missing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// Every run's evaluation diverged.
    Diverged,
    /// Every run failed (an error, not a divergence).
    Failed,
}

/// What replaces a number or an experiment that was not measured: `{status, errors}`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Missing {
    pub status: Status,
    /// The failures' messages (`seed S: …`), if any.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub errors: Vec<String>,
}

impl Missing {
    /// `{"status": "failed", "errors": errors}`.
    pub fn failed(errors: Vec<String>) -> Self {
        Self {
            status: Status::Failed,
            errors,
        }
    }
}

/// A [`Spread`], or why there is none.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Stat {
    Spread(Spread),
    Missing(Missing),
}

impl Stat {
    /// The spread, if measured.
    pub fn spread(&self) -> Option<&Spread> {
        match self {
            Stat::Spread(s) => Some(s),
            Stat::Missing(_) => None,
        }
    }
}

/// An experiment's result, or why there is none (`{"status": "failed", "errors": [...]}`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Outcome<T> {
    Failed(Missing),
    Done(T),
}

impl<T> Outcome<T> {
    /// The result, if there is one.
    pub fn done(&self) -> Option<&T> {
        match self {
            Outcome::Done(t) => Some(t),
            Outcome::Failed(_) => None,
        }
    }
}

/// Mean, min and max over seeds of one metric at each point of a learning curve.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SpreadSeries {
    pub mean: Vec<f64>,
    pub min: Vec<f64>,
    pub max: Vec<f64>,
}

/// Whether an evaluation measured anything: an evaluation that diverged during its warm-up
/// reports the metrics of the steps before the divergence (flagged `diverged`); only one that
/// failed at its very first step has zeros, which are not measurements.
pub fn measured(e: &EvalResult) -> bool {
    !(e.diverged && e.tracking_rms_mm == 0.0)
}

/// One evaluation's metrics (issue 6's keys). An evaluation that did not measure anything
/// ([`measured`]) has only `diverged`, `evaluated: false` and `max_command_step_analytical`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EvalSummary {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tracking_rms_mm: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tracking_max_mm: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub command_nmse: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub command_cost_ratio: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fallback_share: Option<f64>,
    /// Largest command step of the evaluation (N·m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_command_step_eval: Option<f64>,
    /// Largest step of the analytical `u*` at the same states (N·m).
    pub max_command_step_analytical: f64,
    pub diverged: bool,
    pub evaluated: bool,
}

impl From<&EvalResult> for EvalSummary {
    fn from(e: &EvalResult) -> Self {
        let ok = measured(e);
        let m = |v: f64| ok.then_some(v);
        Self {
            tracking_rms_mm: m(e.tracking_rms_mm),
            tracking_max_mm: m(e.tracking_max_mm),
            command_nmse: m(e.command_nmse),
            command_cost_ratio: m(e.command_cost_ratio),
            fallback_share: m(e.fallback_share),
            max_command_step_eval: m(e.max_command_step),
            max_command_step_analytical: e.max_command_step_analytical,
            diverged: !ok || e.diverged,
            evaluated: ok,
        }
    }
}

/// One point of a learning curve as `osrl train --json` lists it (the metrics left out where
/// the evaluation did not measure anything).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CurvePoint {
    pub sim_minutes: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tracking_rms_mm: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub command_nmse: Option<f64>,
    pub diverged: bool,
}

/// The learning curve without repeated evaluations at the same simulated minute (the
/// driver's final evaluation after a scheduled one at the end): the last is kept.
pub fn dedup_curve(curve: &[(f64, EvalResult)]) -> Vec<(f64, EvalResult)> {
    let mut out: Vec<(f64, EvalResult)> = Vec::with_capacity(curve.len());
    for (t, e) in curve {
        match out.last_mut() {
            Some(last) if (last.0 - t).abs() < 1e-9 => *last = (*t, e.clone()),
            _ => out.push((*t, e.clone())),
        }
    }
    out
}

/// [`dedup_curve`] as [`CurvePoint`]s.
pub fn curve_points(curve: &[(f64, EvalResult)]) -> Vec<CurvePoint> {
    dedup_curve(curve)
        .iter()
        .map(|(t, e)| {
            let ok = measured(e);
            CurvePoint {
                sim_minutes: *t,
                tracking_rms_mm: ok.then_some(e.tracking_rms_mm),
                command_nmse: ok.then_some(e.command_nmse),
                diverged: !ok || e.diverged,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn j<T: Serialize>(v: &T) -> String {
        serde_json::to_string(v).unwrap()
    }

    #[test]
    fn the_json_of_missing_numbers_and_evaluations() {
        let s = Stat::Spread(Spread::of(&[1.0, 3.0]));
        assert_eq!(j(&s), r#"{"mean":2.0,"min":1.0,"max":3.0}"#);
        let d = Stat::Missing(Missing {
            status: Status::Diverged,
            errors: vec![],
        });
        assert_eq!(j(&d), r#"{"status":"diverged"}"#);
        for v in [s, d] {
            assert_eq!(serde_json::from_str::<Stat>(&j(&v)).unwrap(), v);
        }
        let f: Outcome<Spread> = Outcome::Failed(Missing::failed(vec!["seed 0: x".into()]));
        assert_eq!(j(&f), r#"{"status":"failed","errors":["seed 0: x"]}"#);
        assert_eq!(serde_json::from_str::<Outcome<Spread>>(&j(&f)).unwrap(), f);
        let none = EvalResult {
            diverged: true,
            max_command_step_analytical: 2.0,
            ..EvalResult::default()
        };
        assert_eq!(
            j(&EvalSummary::from(&none)),
            r#"{"max_command_step_analytical":2.0,"diverged":true,"evaluated":false}"#
        );
        let curve = vec![
            (1.0, none.clone()),
            (2.0, none.clone()),
            (2.0, EvalResult::default()),
        ];
        let pts = curve_points(&curve);
        assert_eq!(pts.len(), 2);
        assert_eq!(pts[1].tracking_rms_mm, Some(0.0));
        assert_eq!(pts[0].tracking_rms_mm, None);
    }
}
