//! Input and output normalisation: [`Norm`] (a divisor, one per dimension, or `"std"`) and the
//! resolution of `"std"` from the training data ([`LwprConfig::resolve_std`]).

use crate::{LwprConfig, LwprError};
use serde::{Deserialize, Serialize};

/// Marker for `"std"` in [`Norm`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum NormKeyword {
    /// The standard deviation of the training data, per dimension.
    Std,
}

/// Normalisation divisors for inputs or outputs (no centring).
/// In TOML/JSON a number, a list, or `"std"`.
#[derive(Clone, Debug, PartialEq)]
pub enum Norm {
    /// The same divisor for every dimension.
    Scalar(f64),
    /// One divisor per dimension.
    List(Vec<f64>),
    /// `"std"`: the data's standard deviation; must be resolved with
    /// [`LwprConfig::resolve_std`] before building a model.
    Keyword(NormKeyword),
}

impl Default for Norm {
    fn default() -> Self {
        Norm::Scalar(1.0)
    }
}

impl LwprConfig {
    /// Replaces `"std"` normalisations by the given per-dimension standard deviations
    /// (values ≤ 1e-12, and NaN, become 1, so constant columns are left unscaled).
    ///
    /// Fails with [`crate::LwprError::Config`], leaving `self` unchanged, when a standard
    /// deviation it would use is above [`crate::NORM_RANGE`] or infinite; the message names
    /// the parameter, the dimension and the value.
    ///
    /// ```
    /// use lwpr::{LwprConfig, Norm, NormKeyword};
    /// let mut cfg = LwprConfig {
    ///     norm_in: Norm::Keyword(NormKeyword::Std),
    ///     ..Default::default()
    /// };
    /// cfg.resolve_std(&[2.0, 0.0], &[5.0]).unwrap();
    /// assert_eq!(cfg.norm_in, Norm::List(vec![2.0, 1.0]));
    /// assert_eq!(cfg.norm_out, Norm::Scalar(1.0)); // not "std": left as it was
    /// let err = LwprConfig { norm_out: Norm::Keyword(NormKeyword::Std), ..Default::default() }
    ///     .resolve_std(&[1.0], &[1e101])
    ///     .unwrap_err();
    /// assert!(err.to_string().contains("norm_out[0] = \"std\" = 1e101"));
    /// ```
    pub fn resolve_std(&mut self, std_in: &[f64], std_out: &[f64]) -> Result<(), LwprError> {
        let resolve = |name: &str, what: &str, n: &Norm, s: &[f64]| {
            if *n != Norm::Keyword(NormKeyword::Std) {
                return Ok(None);
            }
            let hi = crate::error::num(crate::NORM_RANGE.1);
            let fix = format!("give {name} explicitly or rescale the data");
            let mut l = Vec::with_capacity(s.len());
            for (k, &v) in s.iter().enumerate() {
                if v == f64::INFINITY {
                    return Err(LwprError::Config(format!(
                        "{name}[{k}] = \"std\": the standard deviation of {what} {k} is too \
                         large to compute (inf); {fix}"
                    )));
                }
                if v > crate::NORM_RANGE.1 {
                    return Err(LwprError::Config(format!(
                        "{name}[{k}] = \"std\" = {}, the standard deviation of {what} {k}, is \
                         above {hi}; {fix}",
                        crate::error::num(v)
                    )));
                }
                l.push(if v > 1e-12 { v } else { 1.0 });
            }
            Ok::<_, LwprError>(Some(Norm::List(l)))
        };
        // Both first, so that an error leaves the config as it was.
        let norm_in = resolve("norm_in", "input", &self.norm_in, std_in)?;
        let norm_out = resolve("norm_out", "output", &self.norm_out, std_out)?;
        if let Some(n) = norm_in {
            self.norm_in = n;
        }
        if let Some(n) = norm_out {
            self.norm_out = n;
        }
        Ok(())
    }
}
