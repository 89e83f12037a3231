//! Validated, resolved parameters: what the algorithm reads on every update (made by
//! [`crate::LwprConfig::validate`], in `validate.rs`).

use crate::config::{Kernel, LwprConfig};
use serde::{Deserialize, Serialize};

pub use crate::norm::NORM_RANGE;

/// Threshold on `w` for updating a receptive field (reference constant).
pub(crate) const W_UPDATE: f64 = 0.001;

/// A config after [`LwprConfig::validate`]: dimensions fixed, `init_D` factored.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Params {
    /// Number of inputs.
    pub n_in: usize,
    /// Number of outputs.
    pub n_out: usize,
    /// Kernel dimensions (indices into the input).
    pub kdims: Vec<usize>,
    /// Regression dimensions (indices into the input).
    pub rdims: Vec<usize>,
    /// Input divisors.
    pub norm_in: Vec<f64>,
    /// Output divisors.
    pub norm_out: Vec<f64>,
    /// `M` of a new RF: `nk` entries (diagonal) or `nk²` row-major upper-triangular.
    pub init_m: Vec<f64>,
    /// `D` of a new RF, same layout as `init_m` (`nk²` symmetric when full).
    pub init_d: Vec<f64>,
    /// The config as given (after `"std"` resolution).
    pub cfg: LwprConfig,
    /// `γ / nk`.
    pub penalty_n: f64,
}

impl Params {
    /// Number of kernel dimensions.
    pub fn nk(&self) -> usize {
        self.kdims.len()
    }

    /// Number of regression dimensions.
    pub fn nr(&self) -> usize {
        self.rdims.len()
    }

    /// Number of sub-models: 1 with shared RFs, else one per output.
    pub fn n_sub(&self) -> usize {
        if self.cfg.shared_rfs {
            1
        } else {
            self.n_out
        }
    }

    /// Outputs regressed by each RF of a sub-model.
    pub fn n_local_out(&self) -> usize {
        if self.cfg.shared_rfs {
            self.n_out
        } else {
            1
        }
    }

    /// Length of the metric storage per RF (`nk` diagonal, `nk²` full).
    pub fn mlen(&self) -> usize {
        if self.cfg.diag_only {
            self.nk()
        } else {
            self.nk() * self.nk()
        }
    }

    /// Kernel value and its first two derivatives with respect to `q`.
    #[inline]
    pub fn kernel(&self, q: f64) -> (f64, f64, f64) {
        match self.cfg.kernel {
            Kernel::Gaussian => {
                let w = (-0.5 * q).exp();
                (w, -0.5 * w, 0.25 * w)
            }
            Kernel::Bisquare => {
                let a = 1.0 - 0.25 * q;
                if a < 0.0 {
                    (0.0, 0.0, 0.0)
                } else {
                    (a * a, -0.5 * a, 0.125)
                }
            }
        }
    }

    /// A `q` above which the activation is certainly ≤ `w` (used to skip far RFs cheaply;
    /// the exact test on `w` is still made below it).
    pub fn q_bound(&self, w: f64) -> f64 {
        let q = match self.cfg.kernel {
            Kernel::Gaussian if w > 0.0 => -2.0 * w.ln(),
            Kernel::Bisquare => 4.0 * (1.0 - w.sqrt()),
            _ => f64::INFINITY,
        };
        q * (1.0 + 1e-9) + 1e-12
    }
}
