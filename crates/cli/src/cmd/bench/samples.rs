//! The exact samples of one run, shared by the crate and the reference C library: settings,
//! the training rows in update order (all epochs) and the test rows; the text file that
//! `scripts/lwpr_c_harness.c` reads, and the crate's run on the same samples.

use anyhow::{bail, ensure, Result};
use lwpr::{Kernel, Lwpr, LwprConfig, MetricInit, Norm, PruneRule};
use serde::Deserialize;
use std::fmt::Write as _;
use std::time::Instant;

/// The settings the harness passes on to the C library (its fields, in the file's order).
pub const SETTINGS: [&str; 15] = [
    "init_d",
    "init_alpha",
    "w_gen",
    "w_prune",
    "diag_only",
    "meta",
    "meta_rate",
    "penalty",
    "update_d",
    "init_lambda",
    "final_lambda",
    "tau_lambda",
    "init_s2",
    "add_threshold",
    "cutoff",
];

/// One run's samples: rows of `x` followed by `y`.
#[derive(Debug, Clone, PartialEq)]
pub struct Samples {
    pub n_in: usize,
    pub n_out: usize,
    /// Values of [`SETTINGS`], in order.
    pub settings: Vec<f64>,
    pub norm_in: Vec<f64>,
    pub norm_out: Vec<f64>,
    /// Training rows in update order.
    pub train: Vec<Vec<f64>>,
    pub test: Vec<Vec<f64>>,
}

/// What one implementation measured on [`Samples`].
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct Measured {
    /// Test nMSE per output.
    pub nmse: Vec<f64>,
    pub n_rfs: usize,
    /// µs per update, every call timed on its own (the clock's cost included).
    pub update_us: f64,
    /// µs per prediction, every call timed on its own.
    pub predict_us: f64,
    /// µs per update, the whole training loop timed once (a second run on a fresh model).
    pub update_us_batch: f64,
    /// µs per prediction, the whole test loop timed once (a second pass).
    pub predict_us_batch: f64,
}

impl Measured {
    /// Mean nMSE over the outputs.
    pub fn nmse_mean(&self) -> f64 {
        self.nmse.iter().sum::<f64>() / self.nmse.len().max(1) as f64
    }
}

/// `v` as a list of `n` divisors (a scalar repeated); fails for an unresolved `"std"`.
fn divisors(name: &str, v: &Norm, n: usize) -> Result<Vec<f64>> {
    match v {
        Norm::Scalar(s) => Ok(vec![*s; n]),
        Norm::List(l) if l.len() == n => Ok(l.clone()),
        _ => bail!("{name} must be a number or {n} numbers for the reference harness (got {v:?})"),
    }
}

impl Samples {
    /// Samples with `cfg`'s settings. Fails for a setting the C library's public fields cannot
    /// express (a non-scalar `init_d`, the narrower prune rule, shared RFs, sub-spaces).
    pub fn new(n_in: usize, n_out: usize, cfg: &LwprConfig) -> Result<Samples> {
        let MetricInit::Scalar(d) = cfg.init_d else {
            bail!(
                "the reference harness takes a scalar init_d (r·I), got {:?}",
                cfg.init_d
            );
        };
        ensure!(
            cfg.kernel == Kernel::Gaussian
                && cfg.prune_rule == PruneRule::Wider
                && !cfg.shared_rfs
                && cfg.kernel_dims.is_none()
                && cfg.regression_dims.is_none(),
            "the reference harness needs the Gaussian kernel, the wider prune rule, \
             one model per output and all dimensions"
        );
        let b = |v: bool| if v { 1.0 } else { 0.0 };
        let c = cfg;
        let s = Samples {
            n_in,
            n_out,
            settings: vec![
                d,
                c.init_alpha,
                c.w_gen,
                c.w_prune,
                b(c.diag_only),
                b(c.meta),
                c.meta_rate,
                c.penalty,
                b(c.update_d),
                c.init_lambda,
                c.final_lambda,
                c.tau_lambda,
                c.init_s2,
                c.add_threshold,
                c.cutoff,
            ],
            norm_in: divisors("norm_in", &c.norm_in, n_in)?,
            norm_out: divisors("norm_out", &c.norm_out, n_out)?,
            train: vec![],
            test: vec![],
        };
        debug_assert_eq!(s.settings.len(), SETTINGS.len());
        Ok(s)
    }

    /// The file the harness reads (Rust's shortest round-trip decimals: `strtod` reads back
    /// the same bits).
    pub fn to_text(&self) -> String {
        let mut s = format!("lwpr-samples 1\n{} {}\n", self.n_in, self.n_out);
        let mut line = |v: &[f64]| {
            let parts: Vec<String> = v.iter().map(|x| format!("{x:e}")).collect();
            let _ = writeln!(s, "{}", parts.join(" "));
        };
        line(&self.settings);
        line(&self.norm_in);
        line(&self.norm_out);
        for rows in [&self.train, &self.test] {
            line(&[rows.len() as f64]);
            rows.iter().for_each(|r| line(r));
        }
        s
    }

    /// Reads [`Samples::to_text`] back (the harness's reader, for tests).
    #[cfg(test)]
    pub fn from_text(text: &str) -> Result<Samples> {
        use anyhow::Context;
        let mut t = text.split_whitespace();
        ensure!(
            t.next() == Some("lwpr-samples") && t.next() == Some("1"),
            "not an lwpr-samples 1 file"
        );
        let mut num = |what: &str| -> Result<f64> {
            let w = t
                .next()
                .with_context(|| format!("the file ends before {what}"))?;
            w.parse()
                .with_context(|| format!("{what}: {w:?} is not a number"))
        };
        let (n_in, n_out) = (num("n_in")? as usize, num("n_out")? as usize);
        let mut list =
            |n: usize, what: &str| (0..n).map(|_| num(what)).collect::<Result<Vec<f64>>>();
        let settings = list(SETTINGS.len(), "the settings")?;
        let (norm_in, norm_out) = (list(n_in, "norm_in")?, list(n_out, "norm_out")?);
        let mut rows = |what: &str| -> Result<Vec<Vec<f64>>> {
            let n = list(1, what)?[0] as usize;
            (0..n).map(|_| list(n_in + n_out, what)).collect()
        };
        let (train, test) = (rows("training rows")?, rows("test rows")?);
        Ok(Samples {
            n_in,
            n_out,
            settings,
            norm_in,
            norm_out,
            train,
            test,
        })
    }

    /// The crate on these samples with `cfg`, timed as the harness times the C library (the
    /// same clock, `Instant` being `clock_gettime(CLOCK_MONOTONIC)`): every update and
    /// prediction on its own, then the training again on a fresh model and the test set again,
    /// each loop timed once (the predictions stored, checked against the first pass after the
    /// clock stops). A test output without support predicts 0, as in the C library.
    pub fn run_rust(&self, cfg: &LwprConfig) -> Result<Measured> {
        let mut m = Lwpr::new(self.n_in, self.n_out, cfg)?;
        let (ni, no) = (self.n_in, self.n_out);
        let mut up = 0.0;
        for r in &self.train {
            let t0 = Instant::now();
            m.update(&r[..ni], &r[ni..])?;
            up += t0.elapsed().as_secs_f64();
        }
        let (mut yp, mut sup, mut pr) = (vec![0.0; no], vec![0.0; no], 0.0);
        let mut se = vec![0.0; no];
        for r in &self.test {
            let t0 = Instant::now();
            m.predict_with_support(&r[..ni], &mut yp, &mut sup)?;
            pr += t0.elapsed().as_secs_f64();
            for o in 0..no {
                se[o] += (yp[o] - r[ni + o]).powi(2);
            }
        }
        let mut mb = Lwpr::new(self.n_in, self.n_out, cfg)?;
        let t0 = Instant::now();
        for r in &self.train {
            mb.update(&r[..ni], &r[ni..])?;
        }
        let up_batch = t0.elapsed().as_secs_f64();
        drop(mb);
        let mut ys = vec![0.0; self.test.len() * no];
        let t0 = Instant::now();
        for (r, y) in self.test.iter().zip(ys.chunks_exact_mut(no)) {
            m.predict_with_support(&r[..ni], y, &mut sup)?;
        }
        let pr_batch = t0.elapsed().as_secs_f64();
        let mut se_b = vec![0.0; no];
        for (r, y) in self.test.iter().zip(ys.chunks_exact(no)) {
            for o in 0..no {
                se_b[o] += (y[o] - r[ni + o]).powi(2);
            }
        }
        ensure!(
            se_b == se,
            "the predictions timed as one loop differ from the first pass"
        );
        let n = self.test.len() as f64;
        let nmse = (0..no)
            .map(|o| {
                let mean = self.test.iter().map(|r| r[ni + o]).sum::<f64>() / n;
                let var = self
                    .test
                    .iter()
                    .map(|r| (r[ni + o] - mean).powi(2))
                    .sum::<f64>()
                    / n;
                se[o] / n / var
            })
            .collect();
        Ok(Measured {
            nmse,
            n_rfs: m.n_rfs_total(),
            update_us: up * 1e6 / self.train.len() as f64,
            predict_us: pr * 1e6 / n,
            update_us_batch: up_batch * 1e6 / self.train.len() as f64,
            predict_us_batch: pr_batch * 1e6 / n,
        })
    }
}
