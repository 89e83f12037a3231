//! Exploration noise of the on-policy commands: temporally correlated noise of the blended `σ`
//! (eq. 24), capped per joint, plus the same kind of noise projected onto the null space of `Â`
//! (the redundancy RWR must resolve, without disturbing the task to first order). Two processes
//! (`docs/learner.md`, "Exploration"): Ornstein–Uhlenbeck (the default: correlated, but with
//! the fine-grained variation that identifies `Â` fast) and smooth knots joined by half-cosines
//! (a torque rate bounded by construction, as in state-dependent exploration resampled every few
//! hundred milliseconds).

use super::metric::project_null_in;
use super::stats::Scratch;
use super::{Features, Models};
use crate::config::{LearnerConfig, NoiseProcess};
use rand::{Rng, RngExt};
use rand_distr::{Distribution, StandardNormal};

/// Largest magnitude of a knot (standard deviations): draws are clipped here, so the noise never
/// exceeds `KNOT_CLIP · σ` and its rate never exceeds `KNOT_CLIP · π · σ / T`.
pub const KNOT_CLIP: f64 = 3.0;

/// One unit-scale process per joint. Ornstein–Uhlenbeck: `z ← a z + sqrt(1 − a²) e` with
/// `a = exp(−dt/T)` (unit variance). Smooth: knots `k0 → k1` (standard normal draws clipped at
/// [`KNOT_CLIP`]) `T` seconds apart, joined by `z = k0 + (k1 − k0)(1 − cos πs)/2` with the phase
/// `s ∈ [0, 1)` advancing by `dt/T` per period. `T = 0`: white noise (a new draw each period).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Knots {
    k0: Vec<f64>,
    k1: Vec<f64>,
    /// The current value of each process.
    pub z: Vec<f64>,
    s: f64,
    /// Phase advance per period, `dt/T` (infinite for white noise).
    ds: f64,
    /// `Some(a)`: an Ornstein–Uhlenbeck process with this per-period correlation.
    ou: Option<f64>,
    /// Uniform innovations on `[−√3, √3]` instead of standard normal ones.
    bounded: bool,
}

impl Knots {
    fn new(n: usize, ds: f64) -> Self {
        Self {
            k0: vec![0.0; n],
            k1: vec![0.0; n],
            z: vec![0.0; n],
            s: 1.0,
            ds,
            ou: None,
            bounded: false,
        }
    }

    /// Back to 0; the next knot is drawn at the next advance (so an episode starts at 0).
    fn reset(&mut self) {
        self.k0.fill(0.0);
        self.k1.fill(0.0);
        self.z.fill(0.0);
        self.s = 1.0;
    }

    /// One period on: new knots as the phase passes 1, then the value at the new phase.
    fn advance<R: Rng + ?Sized>(&mut self, rng: &mut R) {
        let draw = |rng: &mut R| {
            let e: f64 = StandardNormal.sample(rng);
            e.clamp(-KNOT_CLIP, KNOT_CLIP)
        };
        if let Some(a) = self.ou {
            let b = (1.0 - a * a).sqrt();
            let r3 = 3f64.sqrt();
            for z in self.z.iter_mut() {
                let e: f64 = if self.bounded {
                    rng.random_range(-r3..=r3)
                } else {
                    StandardNormal.sample(rng)
                };
                *z = a * *z + b * e;
            }
            return;
        }
        if !self.ds.is_finite() {
            for z in self.z.iter_mut() {
                *z = draw(rng);
            }
            return;
        }
        if self.s >= 1.0 {
            // A new segment from the value reached (0 after a reset) to a fresh knot.
            self.s -= self.s.floor();
            for ((k0, k1), z) in self.k0.iter_mut().zip(&mut self.k1).zip(&self.z) {
                *k0 = *z;
                *k1 = draw(rng);
            }
        }
        self.s += self.ds;
        let c = 0.5 * (1.0 - (std::f64::consts::PI * self.s.min(1.0)).cos());
        for ((z, k0), k1) in self.z.iter_mut().zip(&self.k0).zip(&self.k1) {
            *z = k0 + (k1 - k0) * c;
        }
    }
}

/// The state of the noise processes: the isotropic and the null-space parts.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Noise {
    iso: Knots,
    null: Knots,
    /// Factor on the noise's standard deviation set by the driver (`Learner::set_exploration_gain`),
    /// in [0, 1]; 1 unless set.
    pub gain: f64,
    /// The largest change of a joint's noise torque per command (N·m; `exploration.max_rate ·
    /// dt`), `None` if unbounded; the noise torque last added and the one being made.
    max_step: Option<f64>,
    last: Vec<f64>,
    next: Vec<f64>,
}

impl Noise {
    /// Processes of `kind` for `n` joints with correlation time `tau` (s; 0: white noise) at
    /// control period `dt` (s), starting at 0, unbounded in rate.
    #[cfg(test)]
    pub fn new(n: usize, kind: NoiseProcess, tau: f64, dt: f64) -> Self {
        Self::with_rate(n, kind, tau, dt, None)
    }

    /// As [`Noise::new`], with the noise torque's rate of change bounded by `max_rate` (N·m/s).
    pub fn with_rate(
        n: usize,
        kind: NoiseProcess,
        tau: f64,
        dt: f64,
        max_rate: Option<f64>,
    ) -> Self {
        let ds = if tau > 0.0 { dt / tau } else { f64::INFINITY };
        let mut iso = Knots::new(n, ds);
        if matches!(
            kind,
            NoiseProcess::OrnsteinUhlenbeck | NoiseProcess::OrnsteinUhlenbeckBounded
        ) {
            iso.ou = Some(if tau > 0.0 { (-dt / tau).exp() } else { 0.0 });
            iso.bounded = kind == NoiseProcess::OrnsteinUhlenbeckBounded;
        }
        Self {
            null: iso.clone(),
            iso,
            gain: 1.0,
            max_step: max_rate.map(|r| r * dt),
            last: vec![0.0; n],
            next: vec![0.0; n],
        }
    }

    /// Back to 0 (at the start of an episode).
    pub fn reset(&mut self) {
        self.iso.reset();
        self.null.reset();
        self.last.fill(0.0);
    }
}

/// Adds the exploration noise of standard deviation `sigma` (N·m) at `q` to `u`: first the
/// null-space part (if configured and `Â` is known), then the capped isotropic part. Each
/// process advances one period (`n` draws each, null-space first). With `exploration.max_rate`
/// the sum of both parts changes by at most `max_rate · dt` per joint from the last command's.
#[allow(clippy::too_many_arguments)]
pub(crate) fn explore<R: Rng + ?Sized>(
    cfg: &LearnerConfig,
    features: &Features,
    models: &Models,
    ws: &mut Scratch,
    noise: &mut Noise,
    q: &[f64],
    sigma: f64,
    rng: &mut R,
    u: &mut [f64],
) {
    let Some(max_step) = noise.max_step else {
        add_noise(cfg, features, models, ws, noise, q, sigma, rng, u);
        return;
    };
    // Bounded rate: the noise made in `next`, then moved from the last by at most `max_step`.
    let mut next = std::mem::take(&mut noise.next);
    next.fill(0.0);
    add_noise(cfg, features, models, ws, noise, q, sigma, rng, &mut next);
    for ((v, z), l) in u.iter_mut().zip(&next).zip(noise.last.iter_mut()) {
        *l = z.clamp(*l - max_step, *l + max_step);
        *v += *l;
    }
    noise.next = next;
}

/// The unbounded noise of [`explore`] added to `u`.
#[allow(clippy::too_many_arguments)]
fn add_noise<R: Rng + ?Sized>(
    cfg: &LearnerConfig,
    features: &Features,
    models: &Models,
    ws: &mut Scratch,
    noise: &mut Noise,
    q: &[f64],
    sigma: f64,
    rng: &mut R,
    u: &mut [f64],
) {
    let m = ws.y.len();
    if cfg.experimental.null_space_exploration {
        noise.null.advance(rng);
        // Formed with the command's `Â` when the command needed that (`command_gains`).
        let known = match ws.gains {
            Some((_, plain)) => plain,
            None => models.blended_gain(features, &ws.acts, q, &mut ws.a_hat_plain),
        };
        let ns_cap = cfg.experimental.null_space_cap.unwrap_or(f64::INFINITY);
        for ((z, scale), e) in ws
            .du
            .iter_mut()
            .zip(&models.torque_scale)
            .zip(&noise.null.z)
        {
            *z = sigma.min(ns_cap * scale) * e;
        }
        // z − Âᵀ (Â Âᵀ)⁻¹ Â z: no first-order effect on the task.
        let metric = models.metric.as_ref();
        if known
            && project_null_in(
                metric,
                &ws.a_hat_plain,
                &mut ws.du,
                m,
                &mut ws.y,
                &mut ws.s,
                &mut ws.a_n,
            )
        {
            for (v, z) in u.iter_mut().zip(&ws.du) {
                *v += z;
            }
        }
    }
    noise.iso.advance(rng);
    let cap = cfg.exploration.cap;
    for ((v, s), e) in u.iter_mut().zip(&models.torque_scale).zip(&noise.iso.z) {
        *v += sigma.min(cap * s) * e;
    }
}

#[cfg(test)]
mod tests {
    use super::{Knots, KNOT_CLIP};
    use rand::SeedableRng;

    /// The smooth noise: its per-period change never exceeds the bound `KNOT_CLIP·π·dt/T` (by
    /// construction, whatever the draws), it is much smaller than white noise's in RMS, it
    /// starts at 0 after a reset, and its variance is about 3/4 of the knots' (the half-cosine
    /// average).
    #[test]
    fn smooth_noise_steps_are_bounded_and_small() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
        let (dt, t) = (0.002, 0.5);
        let mut n = Knots::new(2, dt / t);
        let (mut s2, mut d2, mut dmax, mut prev) = (0.0, 0.0, 0.0f64, 0.0);
        let k = 400_000;
        n.advance(&mut rng);
        assert!(
            n.z[0].abs() < KNOT_CLIP * (std::f64::consts::PI * dt / t),
            "{:?}",
            n.z
        );
        for _ in 0..k {
            n.advance(&mut rng);
            let z = n.z[0];
            assert!(z.abs() <= KNOT_CLIP);
            s2 += z * z;
            d2 += (z - prev) * (z - prev);
            dmax = dmax.max((z - prev).abs());
            prev = z;
        }
        let bound = KNOT_CLIP * std::f64::consts::PI * dt / t;
        assert!(dmax <= bound, "{dmax} > {bound}");
        let var = s2 / k as f64;
        assert!((var - 0.75).abs() < 0.05, "variance {var}");
        let rms_step = (d2 / k as f64).sqrt();
        // White noise steps by sqrt(2) in RMS; this by about π/2·sqrt(2·E[sin²])·dt/T ≈ 0.009.
        assert!(rms_step < 0.012, "{rms_step}");
        n.reset();
        assert_eq!(n.z, vec![0.0, 0.0]);
    }

    /// The Ornstein–Uhlenbeck process has unit variance and its per-period change is
    /// `sqrt(2(1 − a))` in RMS.
    #[test]
    fn ornstein_uhlenbeck_noise_has_unit_variance_and_its_rate() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
        let (dt, tau) = (0.002, 0.1);
        let mut n = super::Noise::new(1, crate::config::NoiseProcess::OrnsteinUhlenbeck, tau, dt);
        let (mut s2, mut d2, mut prev) = (0.0, 0.0, 0.0);
        let k = 200_000;
        for _ in 0..k {
            n.iso.advance(&mut rng);
            let z = n.iso.z[0];
            s2 += z * z;
            d2 += (z - prev) * (z - prev);
            prev = z;
        }
        assert!(
            (s2 / k as f64 - 1.0).abs() < 0.05,
            "variance {}",
            s2 / k as f64
        );
        let rms_step = (d2 / k as f64).sqrt();
        let want = (2.0 * (1.0 - (-dt / tau).exp())).sqrt();
        assert!(
            (rms_step - want).abs() < 0.02 * want,
            "{rms_step} vs {want}"
        );
    }

    /// The bounded variant has the Ornstein–Uhlenbeck process's variance and RMS change, and
    /// its largest per-period change stays below the bound `2√3 sqrt(1 − a²)` — about a third of
    /// the Gaussian process's largest change over the same number of periods.
    #[test]
    fn bounded_ornstein_uhlenbeck_noise_has_the_same_moments_and_bounded_steps() {
        let (dt, tau): (f64, f64) = (0.002, 0.1);
        let a = (-dt / tau).exp();
        let bound = 2.0 * 3f64.sqrt() * (1.0 - a * a).sqrt();
        let mut largest = [0.0f64; 2];
        for (i, kind) in [
            crate::config::NoiseProcess::OrnsteinUhlenbeckBounded,
            crate::config::NoiseProcess::OrnsteinUhlenbeck,
        ]
        .into_iter()
        .enumerate()
        {
            let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(4);
            let mut n = super::Noise::new(1, kind, tau, dt);
            let (mut s2, mut d2, mut prev) = (0.0, 0.0, 0.0);
            let k = 200_000;
            for _ in 0..k {
                n.iso.advance(&mut rng);
                let z = n.iso.z[0];
                s2 += z * z;
                d2 += (z - prev) * (z - prev);
                largest[i] = largest[i].max((z - prev).abs());
                prev = z;
            }
            let var = s2 / k as f64;
            assert!((var - 1.0).abs() < 0.05, "{kind:?}: variance {var}");
            let (rms, want) = ((d2 / k as f64).sqrt(), (2.0 * (1.0 - a)).sqrt());
            assert!(
                (rms - want).abs() < 0.02 * want,
                "{kind:?}: {rms} vs {want}"
            );
        }
        assert!(largest[0] <= bound, "{} > {bound}", largest[0]);
        assert!(largest[0] < 0.45 * largest[1], "{largest:?}");
    }

    /// `T = 0` is white noise: independent clipped draws every period.
    #[test]
    fn zero_knot_time_is_white_noise() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(2);
        let mut n = Knots::new(1, f64::INFINITY);
        let (mut s2, mut prod, mut prev) = (0.0, 0.0, 0.0);
        let k = 100_000;
        for _ in 0..k {
            n.advance(&mut rng);
            s2 += n.z[0] * n.z[0];
            prod += n.z[0] * prev;
            prev = n.z[0];
        }
        assert!((s2 / k as f64 - 1.0).abs() < 0.03);
        assert!((prod / k as f64).abs() < 0.02);
    }
}
