//! The task-space disturbance observer (DOB) of the re-adaptation (`docs/learner.md`,
//! "Re-adaptation"; `[learner.adaptation] observer_seconds`, off by default): the difference
//! between the measured task acceleration `ẍ` and the reference `ẍ_ref` the learned command was
//! asked for, low-passed with the time constant `T`, is subtracted from the next reference:
//!
//! `d̂ ← d̂ + (Δt / T) (ẍ − ẍ_sent − d̂)`, `ẍ_sent = ẍ_ref − d̂`.
//!
//! A payload or heavier links are, along a path, an acceleration offset that changes with the
//! posture; the learning absorbs it in minutes, the observer within a few `T`. Where the learned
//! model is right, `ẍ = ẍ_sent` up to the exploration and `d̂` stays near 0. `|d̂|` is bounded
//! (`observer_max`, counted when it acts) so that a model that is badly wrong cannot wind it
//! up. Measurements only: `ẍ` is the hand's measured acceleration under the last command.

use osrl_control::{reference_acceleration, Target, TaskGains};
use osrl_dynamics::Measurement;

/// The reference every driver of the learned command sends: eq. 2's `ẍ_ref` for `target` at the
/// measured `x, ẋ` of `meas` with `gains` on the task `axes`, less the observer's estimate
/// (learned from the measured `ẍ` of `meas` when `learn`) — into `out`.
pub(crate) fn observed_reference(
    gains: &TaskGains,
    target: &Target,
    axes: &[usize],
    meas: &Measurement,
    dob: &mut Dob,
    learn: bool,
    out: &mut [f64],
) {
    let (x, xd) = (meas.x.as_slice(), meas.xd.as_slice());
    reference_acceleration(gains, target, axes, x, xd, out);
    dob.correct(meas.xdd.as_slice(), learn, out);
}

/// The observer's state: the estimate `d̂` and the reference last sent. Allocates only in
/// [`Dob::new`].
#[derive(Clone, Debug)]
pub struct Dob {
    /// `Δt / T`, 0 when off.
    alpha: f64,
    /// Bound on `|d̂|` (m/s², Euclidean).
    max: f64,
    d: Vec<f64>,
    sent: Vec<f64>,
    primed: bool,
    saturated: u64,
    /// `d̂` low-passed over [`SLOW_SECONDS`]: the persistent part of what the command misses
    /// (the exploration's effect averages out of it).
    slow: Vec<f64>,
    slow_alpha: f64,
}

/// Time constant of the observer's slow estimate `d̄` (s): the re-adaptation level's own.
pub const SLOW_SECONDS: f64 = 0.5;

impl Dob {
    /// An observer for an `m`-D task at the control period `dt` (s) with the time constant
    /// `seconds` (0: off) and the bound `max` (m/s²) on the estimate's norm.
    pub fn new(m: usize, dt: f64, seconds: f64, max: f64) -> Self {
        let alpha = if seconds > 0.0 {
            (dt / seconds).min(1.0)
        } else {
            0.0
        };
        Self {
            alpha,
            max,
            d: vec![0.0; m],
            sent: vec![0.0; m],
            primed: false,
            saturated: 0,
            slow: vec![0.0; m],
            slow_alpha: (dt / SLOW_SECONDS).min(1.0),
        }
    }

    /// Whether the observer acts.
    pub fn is_on(&self) -> bool {
        self.alpha > 0.0
    }

    /// Forgets the estimate and the last reference (a new episode, a new run).
    pub fn reset(&mut self) {
        self.d.fill(0.0);
        self.slow.fill(0.0);
        self.primed = false;
    }

    /// The norm of the slow estimate `‖d̄‖` (m/s², 0 when off): a change of the robot that
    /// the learned command misses along the path (`adaptation.offset_floor`).
    pub fn offset(&self) -> f64 {
        self.slow.iter().map(|v| v * v).sum::<f64>().sqrt()
    }

    /// The current estimate `d̂` (m/s²).
    pub fn estimate(&self) -> &[f64] {
        &self.d
    }

    /// How often the bound on `|d̂|` acted.
    pub fn saturated(&self) -> u64 {
        self.saturated
    }

    /// Updates `d̂` from the measured `xdd` (when `learn` and a reference was sent before) and
    /// subtracts it from `xdd_ref`, which is then the reference sent. Nothing happens when off.
    pub fn correct(&mut self, xdd: &[f64], learn: bool, xdd_ref: &mut [f64]) {
        if !self.is_on() {
            return;
        }
        if learn && self.primed && xdd.iter().all(|v| v.is_finite()) {
            for ((d, x), s) in self.d.iter_mut().zip(xdd).zip(&self.sent) {
                *d += self.alpha * (x - s - *d);
            }
            let norm = self.d.iter().map(|v| v * v).sum::<f64>().sqrt();
            if norm > self.max {
                let k = self.max / norm;
                self.d.iter_mut().for_each(|v| *v *= k);
                self.saturated += 1;
            }
            for (s, d) in self.slow.iter_mut().zip(&self.d) {
                *s += self.slow_alpha * (d - *s);
            }
        }
        for ((r, d), s) in xdd_ref.iter_mut().zip(&self.d).zip(self.sent.iter_mut()) {
            *r -= d;
            *s = *r;
        }
        self.primed = true;
    }
}

#[cfg(test)]
mod tests {
    use super::Dob;

    /// A constant offset of the plant's acceleration is estimated within a few time constants
    /// and then cancelled; off, nothing changes; the bound holds and is counted.
    #[test]
    fn a_constant_offset_is_estimated_and_cancelled() {
        let (dt, offset) = (0.002, [0.7, -0.3]);
        let mut dob = Dob::new(2, dt, 0.05, 5.0);
        let target = [0.2, 0.1];
        let mut xdd = [0.0; 2];
        for _ in 0..1000 {
            let mut r = target;
            dob.correct(&xdd, true, &mut r);
            // The plant: ẍ = what was asked for + the offset.
            xdd = [r[0] + offset[0], r[1] + offset[1]];
        }
        for k in 0..2 {
            assert!(
                (dob.estimate()[k] - offset[k]).abs() < 1e-6,
                "{:?}",
                dob.estimate()
            );
            assert!((xdd[k] - target[k]).abs() < 1e-6, "{xdd:?}");
        }
        let mut off = Dob::new(2, dt, 0.0, 5.0);
        let mut r = target;
        off.correct(&[9.0, 9.0], true, &mut r);
        off.correct(&[9.0, 9.0], true, &mut r);
        assert_eq!(r, target);
        let mut small = Dob::new(2, dt, 0.05, 0.1);
        let mut xdd = [0.0; 2];
        for _ in 0..500 {
            let mut r = target;
            small.correct(&xdd, true, &mut r);
            xdd = [r[0] + offset[0], r[1] + offset[1]];
        }
        let norm = small.estimate().iter().map(|v| v * v).sum::<f64>().sqrt();
        assert!(norm <= 0.1 + 1e-12 && small.saturated() > 0, "{norm}");
        // Not learning: the estimate holds.
        let held = small.estimate().to_vec();
        let mut r = target;
        small.correct(&[50.0, 50.0], false, &mut r);
        assert_eq!(small.estimate(), &held[..]);
    }

    /// The slow estimate `d̄` follows a constant offset (after a few `SLOW_SECONDS`), so its
    /// norm is the offset's; an offset that flips sign every few periods (like fast
    /// exploration) averages out of it while `d̂` follows it; a reset clears it.
    #[test]
    fn the_slow_estimate_keeps_the_persistent_part() {
        let dt = 0.002;
        let run = |flip: usize| {
            let mut dob = Dob::new(2, dt, 0.02, 5.0);
            let mut xdd = [0.0; 2];
            for k in 0..3000 {
                let sign = if flip > 0 && (k / flip) % 2 == 1 {
                    -1.0
                } else {
                    1.0
                };
                let mut r = [0.0; 2];
                dob.correct(&xdd, true, &mut r);
                xdd = [r[0] + sign * 0.6, r[1] - sign * 0.8];
            }
            dob
        };
        let steady = run(0);
        assert!((steady.offset() - 1.0).abs() < 1e-3, "{}", steady.offset());
        let flipping = run(25);
        assert!(flipping.offset() < 0.15, "{}", flipping.offset());
        let mut steady = steady;
        steady.reset();
        assert_eq!(steady.offset(), 0.0);
    }
}
