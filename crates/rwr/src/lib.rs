//! Reward-weighted regression (RWR) with the adaptive reward transformation, after Peters &
//! Schaal, "Reinforcement Learning for Operational Space Control" (ICRA 2007), section III.
//!
//! Immediate-reward reinforcement learning for Gaussian policies linear in features,
//! `π(u | s) = N(u | θᵀφ(s), σ² I)` (eq. 21) with `d`-dimensional actions, reduced to a weighted
//! regression: samples `(φ_i, u_i, r_i)` with costs `r_i ≥ 0` are weighted by the transformed
//! reward `U_τ(r) = τ exp(−τ r)` (eq. 22), and an EM iteration (Algorithm 2) is
//!
//! * `θ = (ΦᵀWΦ + λI)⁻¹ ΦᵀWY` (eq. 23, with a small ridge `λ`),
//! * `σ² = Σ w_i ‖u_i − θᵀφ_i‖² / (d Σ w_i)` (eq. 24, with the maximum-likelihood `1/d`),
//! * `τ = Σ w_i / Σ w_i r_i` (eq. 28, the adaptive reward transformation).
//!
//! Two forms: [`BatchRwr`] (one EM step per batch) and [`OnlineRwr`] (weighted sufficient
//! statistics with a forgetting factor and external per-sample weights, allocation-free, as a
//! local controller uses it). Both compute weights in log space, have a ridge, a floor on `σ`,
//! an optional fixed `τ`, an optional cap on `τ` and floor on the effective sample size
//! ([`RwrConfig`]). [`toy`] is the paper's Fig. 1 experiment (no plotting).
//!
//! There is no robotics in this crate.
//!
//! # Example
//! Learn `a = 0.5 s` (the minimiser of `r = (a − 0.5 s)²`) by batch EM:
//! ```
//! use nalgebra::DMatrix;
//! use rand::{RngExt, SeedableRng};
//! use rand_chacha::ChaCha8Rng;
//! use rwr::{BatchRwr, RwrConfig};
//!
//! let mut rng = ChaCha8Rng::seed_from_u64(1);
//! let mut rwr = BatchRwr::new(2, 1, RwrConfig::default())?;
//! let n = 200;
//! for _ in 0..30 {
//!     let (mut phi, mut u) = (DMatrix::zeros(n, 2), DMatrix::zeros(n, 1));
//!     let mut costs = vec![0.0; n];
//!     for i in 0..n {
//!         let s: f64 = rng.random_range(-1.0..1.0);
//!         let f = [s, 1.0];
//!         let mut a = [0.0];
//!         rwr.policy().sample_into(&f, &mut rng, &mut a)?;
//!         phi[(i, 0)] = s;
//!         phi[(i, 1)] = 1.0;
//!         u[(i, 0)] = a[0];
//!         costs[i] = (a[0] - 0.5 * s).powi(2);
//!     }
//!     rwr.em_step(&phi, &u, &costs, None)?;
//! }
//! assert!((rwr.theta()[(0, 0)] - 0.5).abs() < 0.05);
//! assert!(rwr.theta()[(1, 0)].abs() < 0.05);
//! # Ok::<(), rwr::RwrError>(())
//! ```

// Index loops over small dense matrices read like the maths.
#![allow(clippy::needless_range_loop)]

mod batch;
mod cholesky;
#[cfg(target_arch = "x86_64")]
mod cholesky_x86;
mod config;
mod error;
mod external;
mod held;
#[cfg(target_arch = "x86_64")]
mod held_x86;
mod online;
mod policy;
mod simd;
mod stats;
pub mod toy;
mod trust;
pub mod weights;

pub use batch::{BatchRwr, StepInfo};
pub use config::RwrConfig;
pub use error::{Result, RwrError};
pub use online::OnlineRwr;
pub use policy::LinearGaussianPolicy;
