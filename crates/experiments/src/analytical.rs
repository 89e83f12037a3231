//! The analytical runs: eq. 4 and eq. 7 with the true model (E2) and eq. 7 with each wrong
//! model (E7), on both robots.

use crate::error::Result;
use crate::results::AnalyticalRow;
use crate::setup::Setup;
use osrl_control::{Law, ModelError, OscConfig, Run};
use rayon::prelude::*;

/// The robots of the experiments.
pub const ROBOTS: [&str; 2] = ["planar3", "sarcos7"];

/// The model errors of E7: key (in `results.json`) and `--model-error` spec.
pub const ERRORS: [(&str, &str); 5] = [
    ("mass_x0.7", "mass=0.7"),
    ("mass_x1.3", "mass=1.3"),
    ("com_2cm", "com=0.02"),
    ("no_friction", "friction=off"),
    ("payload", "payload=0.5"),
];

/// One analytical run.
#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    pub robot: &'static str,
    pub law: Law,
    /// Key of the model error (`none` for the true model).
    pub error_key: &'static str,
    pub error: ModelError,
    /// Simulated seconds (whole periods, the first a warm-up).
    pub seconds: f64,
}

impl Case {
    /// `eq4` or `eq7`.
    pub fn law_name(&self) -> &'static str {
        match self.law {
            Law::Eq4 => "eq4",
            Law::Eq7 => "eq7",
        }
    }

    /// Its folder in the report: `E2/<robot>_<law>` (true model) or `E7/<robot>_<error>`.
    pub fn dir(&self) -> String {
        if self.error_key == "none" {
            format!("E2/{}_{}", self.robot, self.law_name())
        } else {
            format!("E7/{}_{}", self.robot, self.error_key)
        }
    }

    /// The analytical controller's config: the law, everything else default.
    pub fn osc(&self) -> OscConfig {
        OscConfig {
            law: self.law,
            ..OscConfig::default()
        }
    }
}

/// E2 (eq. 7 and eq. 4, true model) and E7 (eq. 7, each wrong model) for both robots, each
/// `seconds` long; `payload_kg` replaces the payload spec's mass.
///
/// # Errors
/// A payload mass out of range.
pub fn cases(payload_kg: f64, seconds: f64) -> Result<Vec<Case>> {
    let mut v = Vec::new();
    for robot in ROBOTS {
        for law in [Law::Eq7, Law::Eq4] {
            v.push(Case {
                robot,
                law,
                error_key: "none",
                error: ModelError::default(),
                seconds,
            });
        }
        for (key, spec) in ERRORS {
            let mut error: ModelError = spec.parse()?;
            if key == "payload" {
                error.payload = payload_kg;
            }
            error.validate()?;
            v.push(Case {
                robot,
                law: Law::Eq7,
                error_key: key,
                error,
                seconds,
            });
        }
    }
    Ok(v)
}

/// A finished analytical run: its case, its metrics as `results.json` lists them, its series.
#[derive(Clone, Debug)]
pub struct AnalyticalRun {
    pub case: Case,
    pub row: AnalyticalRow,
    pub run: Run,
}

/// Runs `case` in `setup` (the case's robot's).
///
/// # Errors
/// As [`Setup::analytical`], the message naming the case.
pub fn run_case(setup: &Setup, case: &Case) -> Result<AnalyticalRun> {
    let run = setup
        .analytical(&case.osc(), &case.error, case.seconds)
        .map_err(|e| {
            crate::ExperimentError::Invalid(format!(
                "{} {:?} with {}: {e}",
                case.robot, case.law, case.error
            ))
        })?;
    let row = AnalyticalRow::new(
        &run.metrics,
        case.robot,
        case.law_name(),
        case.error.to_string(),
    );
    Ok(AnalyticalRun {
        case: case.clone(),
        row,
        run,
    })
}

/// Runs every case in parallel (the robots' set-ups from `setups`), calling `done` after each.
///
/// # Errors
/// The first failing case.
pub fn run_all(
    cases: &[Case],
    setups: &[(&str, Setup)],
    done: &(dyn Fn(&Case) + Sync),
) -> Result<Vec<AnalyticalRun>> {
    cases
        .par_iter()
        .map(|c| {
            let setup = crate::setup_of(setups, c.robot)?;
            let r = run_case(setup, c);
            done(c);
            r
        })
        .collect()
}
