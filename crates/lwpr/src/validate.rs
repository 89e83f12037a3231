//! Validation of an [`LwprConfig`] for a model's dimensions, once, into [`Params`]: every value
//! in its range, the dimension lists, the normalisations, and `init_D` factored as `MᵀM`.

use crate::config::{LwprConfig, MetricInit};
use crate::error::num;
use crate::norm::{Norm, NORM_RANGE};
use crate::params::Params;
use crate::LwprError;

impl LwprConfig {
    /// Checks every value against the model's dimensions and resolves the config.
    /// Fails with [`crate::LwprError::Config`] naming the first bad parameter.
    pub fn validate(&self, n_in: usize, n_out: usize) -> Result<Params, LwprError> {
        Params::from_config(self, n_in, n_out)
    }
}

fn bad(msg: impl Into<String>) -> LwprError {
    LwprError::Config(msg.into())
}

fn dims(name: &str, d: &Option<Vec<usize>>, n_in: usize) -> Result<Vec<usize>, LwprError> {
    let v: Vec<usize> = d.clone().unwrap_or_else(|| (0..n_in).collect());
    if v.is_empty() {
        return Err(bad(format!("{name} is empty")));
    }
    for (i, &a) in v.iter().enumerate() {
        if a >= n_in {
            return Err(bad(format!(
                "{name} has index {a} but there are {n_in} inputs"
            )));
        }
        if v[..i].contains(&a) {
            return Err(bad(format!("{name} repeats index {a}")));
        }
    }
    Ok(v)
}

impl Norm {
    /// Checks every divisor given (a number or a list) against [`NORM_RANGE`], whatever the
    /// number of dimensions; `"std"` passes (it is resolved from the data later).
    ///
    /// # Errors
    /// [`LwprError::Config`] naming `name` (and the list index) and the value.
    pub fn check_values(&self, name: &str) -> Result<(), LwprError> {
        let (lo, hi) = NORM_RANGE;
        match self {
            Norm::Scalar(s) => range(name, *s, lo, hi, false, false),
            Norm::List(l) => l
                .iter()
                .enumerate()
                .try_for_each(|(i, &a)| range(&format!("{name}[{i}]"), a, lo, hi, false, false)),
            Norm::Keyword(_) => Ok(()),
        }
    }
}

fn norm(name: &str, n: &Norm, len: usize) -> Result<Vec<f64>, LwprError> {
    match n {
        Norm::Scalar(s) => {
            n.check_values(name)?;
            Ok(vec![*s; len])
        }
        Norm::List(l) if l.len() == len => {
            n.check_values(name)?;
            Ok(l.clone())
        }
        Norm::List(l) => Err(bad(format!("{name} has {} entries, need {len}", l.len()))),
        Norm::Keyword(_) => Err(bad(format!("{name} = \"std\" was not resolved"))),
    }
}

/// Checks `lo < v` (`lo_open`) or `lo ≤ v`, and `v ≤ hi` or `v < hi` (`hi_open`); `hi = ∞`
/// means only finite.
fn range(
    name: &str,
    v: f64,
    lo: f64,
    hi: f64,
    lo_open: bool,
    hi_open: bool,
) -> Result<(), LwprError> {
    let above = if lo_open { v > lo } else { v >= lo };
    let below = if hi_open { v < hi } else { v <= hi };
    if v.is_finite() && above && below {
        return Ok(());
    }
    let (l, r) = (
        if lo_open { "(" } else { "[" },
        if hi_open { ")" } else { "]" },
    );
    let (v, lo) = (num(v), num(lo));
    Err(bad(if hi == f64::INFINITY {
        let op = if lo_open { ">" } else { "≥" };
        format!("{name} = {v}: must be finite and {op} {lo}")
    } else {
        format!("{name} = {v} is outside {l}{lo}, {}{r}", num(hi))
    }))
}

/// Full symmetric `D` (row-major `nk²`) from the init spec.
fn init_d_full(init: &MetricInit, nk: usize) -> Result<Vec<f64>, LwprError> {
    let mut d = vec![0.0; nk * nk];
    match init {
        MetricInit::Scalar(r) => (0..nk).for_each(|i| d[i * nk + i] = *r),
        MetricInit::Diagonal(v) if v.len() == nk => (0..nk).for_each(|i| d[i * nk + i] = v[i]),
        MetricInit::Diagonal(v) => {
            return Err(bad(format!("init_d has {} entries, need {nk}", v.len())))
        }
        MetricInit::Full(rows) => {
            if rows.len() != nk || rows.iter().any(|r| r.len() != nk) {
                return Err(bad(format!("init_d must be {nk}×{nk}")));
            }
            for i in 0..nk {
                for j in 0..nk {
                    d[i * nk + j] = rows[i][j];
                }
            }
        }
    }
    if d.iter().any(|a| !a.is_finite()) {
        return Err(bad("init_d has non-finite entries"));
    }
    for i in 0..nk {
        for j in 0..i {
            if (d[i * nk + j] - d[j * nk + i]).abs() > 1e-12 * (1.0 + d[i * nk + j].abs()) {
                return Err(bad("init_d is not symmetric"));
            }
        }
    }
    Ok(d)
}

impl Params {
    /// Validates `cfg` for a model with `n_in` inputs and `n_out` outputs.
    pub fn from_config(cfg: &LwprConfig, n_in: usize, n_out: usize) -> Result<Params, LwprError> {
        if n_in == 0 || n_out == 0 {
            return Err(bad("a model needs at least one input and one output"));
        }
        if n_in > crate::MAX_DIMS || n_out > crate::MAX_DIMS {
            // Each receptive field holds n_in × n_in matrices: beyond this, memory runs out.
            return Err(bad(format!(
                "{n_in} inputs and {n_out} outputs: accepted 1–{} of each",
                crate::MAX_DIMS
            )));
        }
        let kdims = dims("kernel_dims", &cfg.kernel_dims, n_in)?;
        let rdims = dims("regression_dims", &cfg.regression_dims, n_in)?;
        let nk = kdims.len();
        range("init_alpha", cfg.init_alpha, 0.0, f64::INFINITY, true, true)?;
        range("meta_rate", cfg.meta_rate, 0.0, f64::INFINITY, true, true)?;
        range("penalty", cfg.penalty, 0.0, f64::INFINITY, false, true)?;
        range("w_gen", cfg.w_gen, 0.0, 1.0, true, false)?;
        range("w_prune", cfg.w_prune, 0.0, 1.0, true, false)?;
        range("init_lambda", cfg.init_lambda, 0.0, 1.0, true, false)?;
        range("final_lambda", cfg.final_lambda, 0.0, 1.0, true, false)?;
        range("tau_lambda", cfg.tau_lambda, 0.0, 1.0, false, false)?;
        range("init_s2", cfg.init_s2, 0.0, f64::INFINITY, true, true)?;
        range(
            "add_threshold",
            cfg.add_threshold,
            0.0,
            f64::INFINITY,
            true,
            true,
        )?;
        range("cutoff", cfg.cutoff, 0.0, 1.0, false, true)?;
        let norm_in = norm("norm_in", &cfg.norm_in, n_in)?;
        let norm_out = norm("norm_out", &cfg.norm_out, n_out)?;
        let d = init_d_full(&cfg.init_d, nk)?;
        let chol = nalgebra::DMatrix::from_row_slice(nk, nk, &d)
            .cholesky()
            .ok_or_else(|| bad("init_d is not positive definite"))?;
        // D = L Lᵀ = MᵀM with M = Lᵀ upper-triangular.
        let l = chol.l();
        let (init_m, init_d) = if cfg.diag_only {
            if (0..nk).any(|i| (0..nk).any(|j| i != j && d[i * nk + j] != 0.0)) {
                return Err(bad("init_d has off-diagonal entries but diag_only = true"));
            }
            let dd: Vec<f64> = (0..nk).map(|i| d[i * nk + i]).collect();
            (dd.iter().map(|a| a.sqrt()).collect(), dd)
        } else {
            let mut m = vec![0.0; nk * nk];
            for r in 0..nk {
                for c in r..nk {
                    m[r * nk + c] = l[(c, r)];
                }
            }
            (m, d)
        };
        Ok(Params {
            n_in,
            n_out,
            kdims,
            rdims,
            norm_in,
            norm_out,
            init_m,
            init_d,
            cfg: cfg.clone(),
            penalty_n: cfg.penalty / nk as f64,
        })
    }
}
