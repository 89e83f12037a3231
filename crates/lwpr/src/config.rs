//! The user-facing configuration: every parameter of the reference library with its default.
//!
//! Field names are the snake-case parameter names of the reference library (`docs/lwpr.md`,
//! "Parameters"), so a TOML or JSON file maps onto [`LwprConfig`] directly; unknown keys are
//! rejected. [`LwprConfig::validate`] runs once, in [`crate::Lwpr::new`], and resolves the config
//! into [`crate::Params`].

use crate::norm::{Norm, NormKeyword};
use crate::LwprError;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// Serde for enums that are untagged in human-readable formats (TOML, JSON) and externally
/// tagged in binary ones (postcard cannot decode untagged enums).
/// `$expecting` is the error message of a human-readable value that fits no variant.
macro_rules! dual_serde {
    ($ty:ident, $h:ident, $b:ident, $expecting:literal, { $($var:ident($t:ty)),* }) => {
        #[derive(Serialize, Deserialize)]
        #[serde(untagged, expecting = $expecting)]
        enum $h { $($var($t)),* }
        #[derive(Serialize, Deserialize)]
        enum $b { $($var($t)),* }
        impl Serialize for $ty {
            fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                if s.is_human_readable() {
                    match self.clone() { $($ty::$var(v) => $h::$var(v)),* }.serialize(s)
                } else {
                    match self.clone() { $($ty::$var(v) => $b::$var(v)),* }.serialize(s)
                }
            }
        }
        impl<'de> Deserialize<'de> for $ty {
            fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                if d.is_human_readable() {
                    Ok(match $h::deserialize(d)? { $($h::$var(v) => $ty::$var(v)),* })
                } else {
                    Ok(match $b::deserialize(d)? { $($b::$var(v) => $ty::$var(v)),* })
                }
            }
        }
    };
}

dual_serde!(MetricInit, MetricInitH, MetricInitB,
    "expected a number r (for r·I), a list of numbers (a diagonal) or a list of rows (a full matrix)",
    { Scalar(f64), Diagonal(Vec<f64>), Full(Vec<Vec<f64>>) });
dual_serde!(Norm, NormH, NormB,
    "expected a number, a list of numbers (one per column) or \"std\" (the training data's standard deviation)",
    { Scalar(f64), List(Vec<f64>), Keyword(NormKeyword) });

/// The kernel turning the distance `q = (x − c)ᵀ D (x − c)` into an activation `w`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Kernel {
    /// `w = exp(−q/2)`.
    #[default]
    Gaussian,
    /// `w = (1 − q/4)²` for `q < 4`, else 0.
    Bisquare,
}

/// Which of two overlapping receptive fields is pruned.
///
/// The default is [`PruneRule::Wider`], what the reference C library v1.2 does, although
/// the written description of LWPR (`docs/lwpr.md`, the library's own documentation and its
/// Matlab code) says "the narrower".
/// Evidence (21-D rotated cross of issue 4, 10 seeds): with `Wider` the median is 40 RFs
/// (reference library: 39) and nMSE 0.054; with `Narrower` the partition collapses on some
/// seeds (seed 1: 27 RFs at epoch 20, 2 at epoch 24), median 28.5 RFs and nMSE 0.120. With a
/// wide `init_D` every new RF overlaps its neighbours above `w_prune`, and removing the narrower
/// of a pair removes exactly the RFs whose metric learning has already shrunk them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum PruneRule {
    /// The narrower one (larger trace of `D`), as the written description of LWPR, the
    /// reference library's documentation and its Matlab code specify.
    Narrower,
    /// The wider one (smaller trace of `D`), as the reference C library v1.2 actually does
    /// (its source marks the comparison "original logic was reversed -- check"). Default.
    #[default]
    Wider,
}

/// The initial distance metric `D` of a new receptive field, in normalised input units.
/// In TOML/JSON a number, a list, or a list of rows.
#[derive(Clone, Debug, PartialEq)]
pub enum MetricInit {
    /// `r·I`.
    Scalar(f64),
    /// A diagonal matrix with these entries (one per kernel dimension).
    Diagonal(Vec<f64>),
    /// A full symmetric positive definite matrix, row by row (needs `diag_only = false`).
    Full(Vec<Vec<f64>>),
}

/// All LWPR parameters. Defaults are the reference library's (`LwprConfig::default()`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LwprConfig {
    /// Distance metric `D = MᵀM` of a new receptive field (normalised input units⁻²).
    /// Default `25·I` (so `M = 5·I`).
    pub init_d: MetricInit,
    /// Learning rate of every element of `M`. Default 50.
    pub init_alpha: f64,
    /// Keep `D`, `M`, `alpha` diagonal. Default true.
    pub diag_only: bool,
    /// Learn the distance metric at all. Default true.
    pub update_d: bool,
    /// Second-order (IDBD) adaptation of the learning rates. Default false.
    pub meta: bool,
    /// Meta learning rate. Default 250.
    pub meta_rate: f64,
    /// Smoothness penalty `γ`, used as `γ / n` with `n` the number of kernel dimensions.
    /// Default 1e-6.
    pub penalty: f64,
    /// Create a receptive field when the largest activation is ≤ `w_gen`. Default 0.1.
    pub w_gen: f64,
    /// Prune when the second-largest activation is > `w_prune`. Default 1.0 (never).
    pub w_prune: f64,
    /// Initial forgetting factor of a PLS direction. Default 0.999.
    pub init_lambda: f64,
    /// Final forgetting factor. Default 0.99999.
    pub final_lambda: f64,
    /// Annealing rate: `λ ← τλ·λ + final·(1 − τλ)` per update. Default 0.9999.
    pub tau_lambda: f64,
    /// Initial `SSs2` of a PLS direction. Default 1e-10.
    pub init_s2: f64,
    /// PLS growth when `mse_R < add_threshold · mse_{R−1}`. Default 0.5.
    pub add_threshold: f64,
    /// Kernel. Default Gaussian.
    pub kernel: Kernel,
    /// Inputs are divided by these (input units), each within [`crate::NORM_RANGE`]
    /// (1e-100 to 1e100). Default 1.
    pub norm_in: Norm,
    /// Outputs are divided by these (output units), each within
    /// [`crate::NORM_RANGE`] (1e-100 to 1e100). Default 1.
    pub norm_out: Norm,
    /// Which RF of an overlapping pair is pruned. Default `"wider"` (the reference C library;
    /// its documentation says narrower, see [`PruneRule`]).
    pub prune_rule: PruneRule,
    /// Receptive fields with activation `w ≤ cutoff` are skipped when predicting. Default 0.001.
    pub cutoff: f64,
    /// One set of receptive fields shared by all outputs (each RF regresses every output);
    /// false gives the reference library's independent model per output. Default false.
    pub shared_rfs: bool,
    /// Input dimensions (0-based) the kernel and its metric live on; `None` = all inputs.
    /// Paper eq. 33: e.g. `(q, q̇)`. Default `None`.
    pub kernel_dims: Option<Vec<usize>>,
    /// Input dimensions (0-based) of the local linear regression; `None` = all inputs.
    /// Paper eq. 32: e.g. `(q̇, u)`. Default `None`.
    pub regression_dims: Option<Vec<usize>>,
}

impl Default for LwprConfig {
    fn default() -> Self {
        LwprConfig {
            init_d: MetricInit::Scalar(25.0),
            init_alpha: 50.0,
            diag_only: true,
            update_d: true,
            meta: false,
            meta_rate: 250.0,
            penalty: 1e-6,
            w_gen: 0.1,
            w_prune: 1.0,
            init_lambda: 0.999,
            final_lambda: 0.99999,
            tau_lambda: 0.9999,
            init_s2: 1e-10,
            add_threshold: 0.5,
            kernel: Kernel::Gaussian,
            norm_in: Norm::default(),
            norm_out: Norm::default(),
            prune_rule: PruneRule::Wider,
            cutoff: 0.001,
            shared_rfs: false,
            kernel_dims: None,
            regression_dims: None,
        }
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
        // Both first, so that an error leaves the config as it was.
        let norm_in = crate::norm::resolve("norm_in", "input", &self.norm_in, std_in)?;
        let norm_out = crate::norm::resolve("norm_out", "output", &self.norm_out, std_out)?;
        if let Some(n) = norm_in {
            self.norm_in = n;
        }
        if let Some(n) = norm_out {
            self.norm_out = n;
        }
        Ok(())
    }
}
