//! Statistics over seeds and the check of the Fig. 1 claims.

use super::{Case, RunOutcome, Variant};
use serde::{Deserialize, Serialize};

/// One row of the result table: iterations to converge over the seeds of one case. A run that
/// never converged counts as `max_iters`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CaseSummary {
    /// Initial `τ`.
    pub tau0: f64,
    /// `adaptive` or `fixed`.
    pub variant: Variant,
    /// Whether `σ` was updated.
    pub sigma_update: bool,
    /// Median iterations.
    pub median_iters: f64,
    /// 25% quantile of iterations.
    pub q25_iters: f64,
    /// 75% quantile of iterations.
    pub q75_iters: f64,
    /// Share of runs (0..1) that did not converge within `max_iters`.
    pub never_converged: f64,
}

/// All cases, as printed on the last line of `osrl toy --json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Report {
    /// One row per case.
    pub results: Vec<CaseSummary>,
    /// Iteration budget per run.
    pub max_iters: usize,
    /// Seeds per case.
    pub seeds: u64,
}

/// Linear-interpolation quantile (`p` in [0, 1]) of sorted data (type 7).
fn quantile(sorted: &[f64], p: f64) -> f64 {
    let h = (sorted.len() - 1) as f64 * p;
    let (lo, hi) = (h.floor() as usize, h.ceil() as usize);
    sorted[lo] + (h - lo as f64) * (sorted[hi] - sorted[lo])
}

/// Summarises the runs of one case (`runs` non-empty), counting non-converged runs as
/// `max_iters`.
pub fn summarize(case: Case, runs: &[RunOutcome], max_iters: usize) -> CaseSummary {
    assert!(!runs.is_empty(), "summarize needs at least one run");
    let mut iters: Vec<f64> = runs
        .iter()
        .map(|r| r.iters.unwrap_or(max_iters) as f64)
        .collect();
    iters.sort_by(f64::total_cmp);
    let never = runs.iter().filter(|r| r.iters.is_none()).count();
    CaseSummary {
        tau0: case.tau0,
        variant: case.variant,
        sigma_update: case.sigma_update,
        median_iters: quantile(&iters, 0.5),
        q25_iters: quantile(&iters, 0.25),
        q75_iters: quantile(&iters, 0.75),
        never_converged: never as f64 / runs.len() as f64,
    }
}

/// Adaptive versus fixed for one `(τ0, σ update)` pair.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Speedup {
    /// Initial `τ`.
    pub tau0: f64,
    /// Whether `σ` was updated.
    pub sigma_update: bool,
    /// Median iterations with fixed `τ`.
    pub fixed_median: f64,
    /// Median iterations with adaptive `τ`.
    pub adaptive_median: f64,
    /// `fixed_median / adaptive_median` (a lower bound when fixed runs hit `max_iters`).
    pub ratio: f64,
}

/// The two claims of Fig. 1 as the issue states them, checked on a report.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Claims {
    /// One entry per `(τ0, σ update)` present with both variants.
    pub speedups: Vec<Speedup>,
    /// For every `τ0 ≤ 0.1`: adaptive at least 4× faster (median) than fixed.
    pub misscaled_4x_faster: bool,
    /// For every `τ0`: adaptive median at most 1.2 × the fixed median.
    pub never_20pct_slower: bool,
}

/// Pairs adaptive and fixed rows and checks the claims.
pub fn check_claims(report: &Report) -> Claims {
    let find = |t: f64, s: bool, v: Variant| {
        report
            .results
            .iter()
            .find(|r| r.tau0 == t && r.sigma_update == s && r.variant == v)
    };
    let mut speedups = Vec::new();
    for r in report
        .results
        .iter()
        .filter(|r| r.variant == Variant::Adaptive)
    {
        if let Some(f) = find(r.tau0, r.sigma_update, Variant::Fixed) {
            speedups.push(Speedup {
                tau0: r.tau0,
                sigma_update: r.sigma_update,
                fixed_median: f.median_iters,
                adaptive_median: r.median_iters,
                ratio: f.median_iters / r.median_iters.max(1e-12),
            });
        }
    }
    let misscaled = speedups.iter().filter(|s| s.tau0 <= 0.1);
    let misscaled_4x_faster =
        misscaled.clone().count() > 0 && misscaled.clone().all(|s| s.ratio >= 4.0);
    let never_20pct_slower = speedups
        .iter()
        .all(|s| s.adaptive_median <= 1.2 * s.fixed_median);
    Claims {
        speedups,
        misscaled_4x_faster,
        never_20pct_slower,
    }
}
