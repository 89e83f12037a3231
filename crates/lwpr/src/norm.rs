//! Input and output normalisation: [`Norm`] (a divisor, one per dimension, or `"std"`), the
//! range every divisor must lie in, and the resolution of `"std"` from the training data's
//! standard deviations (for [`crate::LwprConfig::resolve_std`]).

use crate::error::num;
use crate::LwprError;
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
    /// [`crate::LwprConfig::resolve_std`] before building a model.
    Keyword(NormKeyword),
}

impl Default for Norm {
    fn default() -> Self {
        Norm::Scalar(1.0)
    }
}

/// The range of a `norm_in` or `norm_out` entry, both ends included. Beyond it a model's
/// quantities in user units — its metrics `D / (norm_in_i·norm_in_j)`, its Jacobians
/// `slope·norm_out/norm_in`, its centres and predictions — could overflow, or lose their
/// precision to subnormals.
pub const NORM_RANGE: (f64, f64) = (1e-100, 1e100);

/// `norm` (the config's `name`, normalising `what`) with `"std"` replaced by the standard
/// deviations `s` (values ≤ 1e-12, and NaN, become 1); `None` when `norm` is not `"std"`.
/// Fails, naming the parameter, the dimension and the value, on a deviation above
/// [`NORM_RANGE`] or infinite.
pub(crate) fn resolve(
    name: &str,
    what: &str,
    norm: &Norm,
    s: &[f64],
) -> Result<Option<Norm>, LwprError> {
    if *norm != Norm::Keyword(NormKeyword::Std) {
        return Ok(None);
    }
    let hi = num(NORM_RANGE.1);
    let fix = format!("give {name} explicitly or rescale the data");
    let mut l = Vec::with_capacity(s.len());
    for (k, &v) in s.iter().enumerate() {
        if v == f64::INFINITY {
            return Err(LwprError::Config(format!(
                "{name}[{k}] = \"std\": the standard deviation of {what} {k} is too \
                 large to compute (inf); {fix}"
            )));
        }
        if v > NORM_RANGE.1 {
            return Err(LwprError::Config(format!(
                "{name}[{k}] = \"std\" = {}, the standard deviation of {what} {k}, is \
                 above {hi}; {fix}",
                num(v)
            )));
        }
        l.push(if v > 1e-12 { v } else { 1.0 });
    }
    Ok(Some(Norm::List(l)))
}
