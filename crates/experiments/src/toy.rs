//! E1 (paper Fig. 1): adaptive versus fixed reward transformation of RWR on the 1-D
//! linear-policy problem of [`rwr::toy`], over seeds and a sweep of the initial `τ`, and the EM
//! iterations that Fig. 1 draws.

use crate::error::Result;
use rayon::prelude::*;
use rwr::toy::{run, summarize, trace, Case, Report, ToyConfig, TraceStep, Variant};
use serde::{Deserialize, Serialize};

/// Initial `τ` of the drawn iterations (mis-scaled: the adaptive transformation's case).
pub const FIG1_TAU0: f64 = 0.1;
/// The EM iterations Fig. 1 draws.
pub const FIG1_STEPS: [usize; 6] = [0, 1, 2, 3, 5, 10];

/// What Fig. 1 draws: the problem and the policy over EM iterations, fixed and adaptive `τ`
/// (initial `τ` [`FIG1_TAU0`], `σ` updated, seed 0), iterations 0 to the last of
/// [`FIG1_STEPS`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Fig1 {
    pub config: ToyConfig,
    pub fixed: Vec<TraceStep>,
    pub adaptive: Vec<TraceStep>,
}

/// The sweep of `cfg` (cases × seeds, in parallel) summarised per case.
///
/// # Errors
/// An invalid config, or the first failing run.
pub fn sweep(cfg: &ToyConfig) -> Result<Report> {
    cfg.validate()?;
    let cases = cfg.cases();
    let jobs: Vec<(usize, u64)> = (0..cases.len())
        .flat_map(|c| (0..cfg.seeds).map(move |s| (c, s)))
        .collect();
    let outcomes = jobs
        .par_iter()
        .map(|&(c, s)| run(cfg, cases[c], s))
        .collect::<std::result::Result<Vec<_>, _>>()?;
    let n = cfg.seeds as usize;
    let results = cases
        .iter()
        .enumerate()
        .map(|(c, &case)| summarize(case, &outcomes[c * n..(c + 1) * n], cfg.max_iters))
        .collect();
    Ok(Report {
        results,
        max_iters: cfg.max_iters,
        seeds: cfg.seeds,
    })
}

/// The iterations of Fig. 1 for `cfg`.
///
/// # Errors
/// An invalid config.
pub fn fig1(cfg: &ToyConfig) -> Result<Fig1> {
    let last = FIG1_STEPS[FIG1_STEPS.len() - 1];
    let run = |variant| {
        let case = Case {
            tau0: FIG1_TAU0,
            variant,
            sigma_update: true,
        };
        trace(cfg, case, 0, last)
    };
    Ok(Fig1 {
        config: cfg.clone(),
        fixed: run(Variant::Fixed)?,
        adaptive: run(Variant::Adaptive)?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sweep_has_every_case_and_fig1_every_step() {
        let cfg = ToyConfig {
            seeds: 2,
            tau0s: vec![0.1, 10.0],
            ..ToyConfig::default()
        };
        let r = sweep(&cfg).unwrap();
        assert_eq!(r.results.len(), cfg.cases().len());
        assert_eq!(r.seeds, 2);
        let f = fig1(&cfg).unwrap();
        assert_eq!(f.fixed.len(), 11);
        assert_eq!(f.adaptive.len(), 11);
        assert_eq!(f.fixed[0], f.adaptive[0], "the same initial policy");
        assert!(sweep(&ToyConfig { seeds: 0, ..cfg }).is_err());
    }
}
