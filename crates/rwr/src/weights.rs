//! Transformed-reward weights in log space (eq. 22, 25, 29).

use crate::error::{Result, RwrError};

/// Log of the unnormalised weight of one sample: `ln a − τ r`, where `a ≥ 0` is an external
/// weight (e.g. a receptive field's activation; 1 when there is none) and `exp(−τ r)` is the
/// transformed reward `U_τ(r) = τ exp(−τ r)` of eq. 22 without its factor `τ`, which cancels in
/// the normalisation of eq. 25. `a = 0` gives `−∞` (no weight).
#[inline]
pub fn log_weight(tau: f64, cost: f64, ext: f64) -> f64 {
    ext.ln() - tau * cost
}

/// Checks one cost: finite and `≥ 0`.
#[inline]
pub fn check_cost(r: f64) -> Result<()> {
    if r.is_finite() && r >= 0.0 {
        Ok(())
    } else {
        Err(RwrError::BadCost(r))
    }
}

/// Checks one external weight: finite and `≥ 0`.
#[inline]
pub fn check_ext(a: f64) -> Result<()> {
    if a.is_finite() && a >= 0.0 {
        Ok(())
    } else {
        Err(RwrError::BadWeight(a))
    }
}

/// Effective sample size `(Σw)² / Σw²` from the sums `Σw` and `Σw²` (0 with no weight).
pub fn ess_of(sum: f64, sum2: f64) -> f64 {
    if sum2 > 0.0 {
        sum * sum / sum2
    } else {
        0.0
    }
}

/// Effective sample size `(Σa)²/Σa²` of the external weights of `n` samples (`n` without
/// them; 0 when they are all zero): the reference of [`crate::RwrConfig::min_ess_share`].
pub fn external_ess(ext: Option<&[f64]>, n: usize) -> f64 {
    match ext {
        None => n as f64,
        Some(e) => {
            let (s, s2) = e.iter().fold((0.0, 0.0), |(s, s2), a| (s + a, s2 + a * a));
            ess_of(s, s2)
        }
    }
}

/// Normalised weights `q_i` of eq. 25/29, computed in log space so that they neither underflow
/// nor overflow however large `τ r` gets: `q_i = exp(l_i − max l) / Σ_j exp(l_j − max l)` with
/// `l_i = ln a_i − τ r_i`. `ext = None` means all `a_i = 1`. Writes `out` (length n) and returns
/// the effective sample size `1 / Σ q_i²`.
///
/// Fails (writing nothing) on a negative or non-finite cost or external weight, on length
/// mismatches, or when every external weight is zero.
pub fn normalized_weights(
    tau: f64,
    costs: &[f64],
    ext: Option<&[f64]>,
    out: &mut [f64],
) -> Result<f64> {
    let n = costs.len();
    for (what, len) in [
        ("weights out", out.len()),
        ("external weights", ext.map_or(n, <[f64]>::len)),
    ] {
        if len != n {
            return Err(RwrError::Dimension {
                what,
                expected: n,
                got: len,
            });
        }
    }
    costs.iter().try_for_each(|&r| check_cost(r))?;
    let a = |i: usize| ext.map_or(1.0, |e| e[i]);
    (0..n).try_for_each(|i| check_ext(a(i)))?;
    let max = (0..n)
        .map(|i| log_weight(tau, costs[i], a(i)))
        .fold(f64::NEG_INFINITY, f64::max);
    if max == f64::NEG_INFINITY {
        return Err(RwrError::NoWeight);
    }
    let mut sum = 0.0;
    for (i, o) in out.iter_mut().enumerate() {
        *o = (log_weight(tau, costs[i], a(i)) - max).exp();
        sum += *o;
    }
    let mut sum_sq = 0.0;
    for o in out.iter_mut() {
        *o /= sum;
        sum_sq += *o * *o;
    }
    Ok(1.0 / sum_sq)
}
