//! The global part of the null-space correction (`gravity.null_scale`; `docs/learner.md`,
//! "Null-space correction"): `r(q) ≈ k ĝ(q)`, one scale `k` fitted by ridge least squares to the
//! holds' gravity errors `u − ĝ(q)` (`null_gravity.rs`). Heavier links, or a tool that makes
//! every link heavier, change the gravity torques in proportion to the learned ones at every
//! posture, where the correction's LWPR fields know only the postures that were held; those
//! fields then learn what the scale leaves, `u − ĝ − k ĝ`.
//!
//! The joints enter in units of their torque scales `s_j`, and each hold counts once, whatever
//! its number of still samples: its means `Σ_j ⟨ĝ_j²⟩ / s_j²` and `Σ_j ⟨ĝ_j e_j⟩ / s_j²` (`e` the
//! gravity error) enter sums `A` and `B` that forget by `1 − 1 / memory` per hold, and
//! `k = B / (A + ρ n W)`, `W` the forgetting sums' weight, `ρ` the ridge, so holds that
//! barely load the arm leave `k` near 0. One scale for all joints, not one per joint: per joint,
//! the scales of joints that the holds load little came out far from the change (up to 1.5 and
//! −1.2 for links 30 % heavier, `docs/decisions.md` D45).

use serde::{Deserialize, Serialize};

/// The scale and its sufficient statistics.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub(crate) struct NullScale {
    /// `A = Σ γ^i Σ_j ⟨ĝ_j²⟩ / s_j²` and `B = Σ γ^i Σ_j ⟨ĝ_j e_j⟩ / s_j²` over the holds.
    a: f64,
    b: f64,
    /// The forgetting sums' weight `W = Σ γ^i`.
    weight: f64,
    /// `C = Σ γ^i Σ_j ⟨e_j²⟩ / s_j²`, for the share of the errors the scale explains.
    c: f64,
    /// Holds learned.
    holds: u64,
    /// `k` (dimensionless).
    k: f64,
}

impl NullScale {
    /// Whether no hold has been learned (then the scale adds nothing).
    pub fn is_empty(&self) -> bool {
        self.holds == 0
    }

    /// The scale `k` (0 before the first hold).
    pub fn scale(&self) -> f64 {
        self.k
    }

    /// Learns one hold: `g` and `e` hold its rows' `ĝ(q)` and gravity errors (`n` values per
    /// row, the same number of rows, at least one). `memory` (holds, ≥ 1) and `ridge` (≥ 0)
    /// from the config; `torque_scale` has `n` entries, all > 0.
    pub fn learn_hold(
        &mut self,
        g: &[f64],
        e: &[f64],
        torque_scale: &[f64],
        memory: f64,
        ridge: f64,
    ) {
        let n = torque_scale.len();
        let rows = g.len() / n;
        debug_assert!(rows > 0 && g.len() == e.len() && g.len().is_multiple_of(n));
        let (mut a, mut b, mut c) = (0.0, 0.0, 0.0);
        for (gr, er) in g.chunks_exact(n).zip(e.chunks_exact(n)) {
            for ((gj, ej), s) in gr.iter().zip(er).zip(torque_scale) {
                let inv = 1.0 / (s * s);
                a += gj * gj * inv;
                b += gj * ej * inv;
                c += ej * ej * inv;
            }
        }
        let keep = 1.0 - 1.0 / memory;
        let per_row = 1.0 / rows as f64;
        self.a = keep * self.a + a * per_row;
        self.b = keep * self.b + b * per_row;
        self.c = keep * self.c + c * per_row;
        self.weight = keep * self.weight + 1.0;
        self.holds += 1;
        let den = self.a + ridge * n as f64 * self.weight;
        // Holds that load nothing with no ridge: no information, no scale.
        self.k = if den > 0.0 && den.is_finite() {
            self.b / den
        } else {
            0.0
        };
    }

    /// Checks a loaded scale: finite sums, `A`, `C`, `W` ≥ 0, `|B| ≤ √(A C)` (Cauchy–Schwarz,
    /// so `R²` ≤ 1 and `k` is bounded), `k` finite.
    ///
    /// # Errors
    /// The first inconsistent value, named.
    pub fn check(&self) -> Result<(), String> {
        let values = [
            ("A", self.a),
            ("B", self.b),
            ("C", self.c),
            ("W", self.weight),
        ];
        if let Some((name, v)) = values.iter().find(|(_, v)| !v.is_finite()) {
            return Err(format!("null scale: {name} = {v} is not finite"));
        }
        if self.a < 0.0 || self.c < 0.0 || self.weight < 0.0 || !self.k.is_finite() {
            return Err(format!(
                "null scale: A = {}, C = {}, W = {} must be ≥ 0 and k = {} finite",
                self.a, self.c, self.weight, self.k
            ));
        }
        if self.b * self.b > self.a * self.c * (1.0 + 1e-9) + f64::MIN_POSITIVE {
            return Err(format!(
                "null scale: B² = {} exceeds A C = {}",
                self.b * self.b,
                self.a * self.c
            ));
        }
        Ok(())
    }

    /// The share of the holds' gravity errors that `k ĝ` explains, `R² = k B / C` in [0, 1]
    /// (0 before the first hold or without errors).
    pub fn explained(&self) -> f64 {
        if self.c > 0.0 {
            (self.k * self.b / self.c).clamp(0.0, 1.0)
        } else {
            0.0
        }
    }

    /// The share `a` of the global part in the correction: 0 below `R² = lo`, 1 above `hi`,
    /// linear between; 0 before the first hold. `lo < hi` in [0, 1].
    pub fn share(&self, [lo, hi]: [f64; 2]) -> f64 {
        if self.is_empty() {
            return 0.0;
        }
        ((self.explained() - lo) / (hi - lo)).clamp(0.0, 1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::NullScale;

    /// Rows of `ĝ` for two joints.
    fn gravity() -> Vec<f64> {
        (0..40)
            .map(|i| (f64::from(i) * 0.37).sin() * 20.0)
            .collect()
    }

    #[test]
    fn recovers_a_proportional_gravity_error_and_forgets_it() {
        let scale = [10.0, 5.0];
        let g = gravity();
        let e: Vec<f64> = g.iter().map(|v| 0.3 * v).collect();
        let mut s = NullScale::default();
        assert!(s.is_empty());
        assert_eq!(s.share([0.8, 0.95]), 0.0);
        s.learn_hold(&g, &e, &scale, 10.0, 0.0);
        assert!((s.scale() - 0.3).abs() < 1e-12, "{}", s.scale());
        assert!((s.explained() - 1.0).abs() < 1e-12);
        assert_eq!(s.share([0.8, 0.95]), 1.0);
        // A ridge shrinks towards 0: holds that do not load the arm teach k = 0.
        let mut r = NullScale::default();
        r.learn_hold(&vec![0.0; 40], &e, &scale, 10.0, 1e-3);
        assert_eq!(r.scale(), 0.0);
        // Without a ridge, holds that load nothing leave the scale at 0, not NaN.
        let mut z = NullScale::default();
        z.learn_hold(&vec![0.0; 40], &e, &scale, 10.0, 0.0);
        assert_eq!(z.scale(), 0.0);
        assert!(z.check().is_ok() && s.check().is_ok());
        let mut bad = s.clone();
        bad.b = 1e300;
        assert!(bad.check().unwrap_err().contains("exceeds"));
        bad.b = f64::NAN;
        assert!(bad.check().unwrap_err().contains("B = NaN"));
        // The change undone: the old holds fade by 0.9 per hold, so k falls to about 0.3 · 0.9⁵⁰ / 10.
        let none = vec![0.0; 40];
        for _ in 0..50 {
            s.learn_hold(&g, &none, &scale, 10.0, 0.0);
        }
        assert!(
            s.scale().abs() < 0.3 * 0.11 * 0.9f64.powi(50),
            "{}",
            s.scale()
        );
    }

    #[test]
    fn a_mixed_error_gives_the_weighted_least_squares_scale() {
        // Joint 0 gains 20 %, joint 1 40 %, with equal loads in units of their scales: k = 0.3.
        let scale = [1.0, 1.0];
        let g = [2.0, 2.0, -1.0, -1.0];
        let e = [0.4, 0.8, -0.2, -0.4];
        let mut s = NullScale::default();
        s.learn_hold(&g, &e, &scale, 1.0, 0.0);
        assert!((s.scale() - 0.3).abs() < 1e-12, "{}", s.scale());
        // Residuals of 0.3 ĝ: ∓0.2, ±0.1, so R² = 1 − 0.1 / 1.0 = 0.9.
        assert!((s.explained() - 0.9).abs() < 1e-12, "{}", s.explained());
        assert!((s.share([0.8, 0.95]) - 2.0 / 3.0).abs() < 1e-9);
        assert!((s.share([0.5, 1.0]) - 0.8).abs() < 1e-9);
    }
}
