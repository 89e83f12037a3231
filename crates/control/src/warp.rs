//! The smooth start of periodic trajectories: a time warp `s(t)` whose rate ramps from 0 to 1.

use serde::{Deserialize, Serialize};

/// Time warp `s(t)` that starts a periodic path at rest.
///
/// A path `p(φ)` run at phase `φ = ω s(t)` starts with zero velocity and zero acceleration when
/// `ṡ(0) = s̈(0) = 0`. The rate `ṡ` rises from 0 to 1 with the quintic smooth step
/// `ṡ(t) = 10τ³ − 15τ⁴ + 6τ⁵`, `τ = t / ramp`, over the first `ramp` seconds (its first and
/// second derivatives vanish at both ends), then stays at 1. Integrated:
/// `s(t) = ramp·(2.5τ⁴ − 3τ⁵ + τ⁶)` during the ramp and `s(t) = t − ramp/2` after it, so the
/// path lags the unwarped one by `ramp/2` seconds for ever after. `ramp = 0` means no warp
/// (`s = t`: the path then starts with its full velocity). Times before 0 are treated as 0.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct TimeWarp {
    /// Ramp duration (s), ≥ 0.
    pub ramp: f64,
}

impl TimeWarp {
    /// `(s, ṡ, s̈)` at time `t` (s, 1, 1/s).
    #[inline]
    pub fn eval(&self, t: f64) -> (f64, f64, f64) {
        let t = t.max(0.0);
        if t >= self.ramp {
            return (t - 0.5 * self.ramp, 1.0, 0.0);
        }
        let r = self.ramp;
        let x = t / r;
        let (x2, x3) = (x * x, x * x * x);
        let s = r * x3 * x * (2.5 - 3.0 * x + x2);
        let sd = x3 * (10.0 - 15.0 * x + 6.0 * x2);
        let sdd = 30.0 * x2 * (1.0 - 2.0 * x + x2) / r;
        (s, sd, sdd)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn warp_is_continuous_and_its_derivatives_match_finite_differences() {
        let w = TimeWarp { ramp: 1.0 };
        assert_eq!(w.eval(0.0), (0.0, 0.0, 0.0));
        let (s1, sd1, sdd1) = w.eval(1.0 - 1e-12);
        assert!((s1 - 0.5).abs() < 1e-9 && (sd1 - 1.0).abs() < 1e-9 && sdd1.abs() < 1e-9);
        let h = 1e-6;
        for &t in &[0.1, 0.37, 0.5, 0.81, 0.99, 1.5, 3.0] {
            let (s, sd, sdd) = w.eval(t);
            let (sp, sdp, _) = w.eval(t + h);
            let (sm, sdm, _) = w.eval(t - h);
            assert!(((sp - sm) / (2.0 * h) - sd).abs() < 1e-8, "ṡ at {t}");
            assert!(((sdp - sdm) / (2.0 * h) - sdd).abs() < 1e-6, "s̈ at {t}");
            assert!(s <= t);
        }
        let none = TimeWarp { ramp: 0.0 };
        assert_eq!(none.eval(0.7), (0.7, 1.0, 0.0));
    }
}
