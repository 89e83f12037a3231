//! The static gravity model's sample budget per posture (`docs/decisions.md`, D30).
//!
//! A still sample measures `g(q)` at one posture only: it pins the local models' value there and
//! says nothing about their slopes. On-policy the arm rests at home between every two episodes,
//! so home would collect far more still samples than all the babbled postures together; regressed
//! on `q`, the jitter of those samples (torques of `M q̈` within the gate, not of gravity) would
//! outweigh the babbling's spread, tilt the fields around home and drift `ĝ` along the path. The
//! budget keeps the first samples of every posture and ignores the rest, so no posture counts for
//! more than `max_samples_per_posture`, about twice the most a babbled posture gives.

use serde::{Deserialize, Serialize};

/// Postures seen so far (centres more than `radius` apart in the max-norm over joints, in the
/// order first seen) and how many samples each has given. A sample near several centres belongs
/// to the first of them, and is refused when that one is full.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub(super) struct PostureBudget {
    /// The postures' centres, `n` values each.
    centres: Vec<f64>,
    /// Samples learned at each posture.
    counts: Vec<u32>,
}

/// Where an admitted sample is to be counted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Slot {
    /// The posture with this index.
    Posture(usize),
    /// A new posture, centred at the sample.
    New,
}

impl PostureBudget {
    /// Where a still sample at `q` may go: the first posture within `radius` (rad, every joint)
    /// while it has given fewer than `cap` samples, or a new posture if none is that near;
    /// `None` when that posture is full, or `q` is not finite. Nothing is counted until
    /// [`count`](Self::count).
    pub fn slot(&self, q: &[f64], radius: f64, cap: u32) -> Option<Slot> {
        if !q.iter().all(|v| v.is_finite()) {
            return None;
        }
        let near = self
            .centres
            .chunks_exact(q.len())
            .position(|c| c.iter().zip(q).all(|(a, b)| (a - b).abs() <= radius));
        match near {
            Some(k) if self.counts[k] >= cap => None,
            Some(k) => Some(Slot::Posture(k)),
            None => Some(Slot::New),
        }
    }

    /// Counts a sample learned at `slot` (from [`slot`](Self::slot) with the same `q`).
    pub fn count(&mut self, slot: Slot, q: &[f64]) {
        match slot {
            Slot::Posture(k) => self.counts[k] += 1,
            Slot::New => {
                self.centres.extend_from_slice(q);
                self.counts.push(1);
            }
        }
    }

    /// Number of postures seen.
    pub fn len(&self) -> usize {
        self.counts.len()
    }

    /// Whether the saved budget fits `n` joints: `n` finite values per posture.
    pub fn check(&self, n: usize) -> Result<(), String> {
        if self.centres.len() != n * self.counts.len() {
            return Err(format!(
                "{} values for {} postures of {n} joints",
                self.centres.len(),
                self.counts.len()
            ));
        }
        if !self.centres.iter().all(|v| v.is_finite()) {
            return Err("a centre is not finite".into());
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::{PostureBudget, Slot};

    fn admit(b: &mut PostureBudget, q: &[f64], cap: u32) -> bool {
        let slot = b.slot(q, 0.02, cap);
        if let Some(s) = slot {
            b.count(s, q);
        }
        slot.is_some()
    }

    /// A posture gives `cap` samples, then none; a posture further than `radius` on one joint is
    /// a new one with its own budget, and the first posture stays full.
    #[test]
    fn budget_keeps_the_first_samples_of_each_posture() {
        let mut b = PostureBudget::default();
        let home = [0.1, -0.2];
        let admitted = (0..10)
            .filter(|k| admit(&mut b, &[home[0] + 1e-3 * (k % 3) as f64, home[1]], 4))
            .count();
        assert_eq!(admitted, 4);
        assert_eq!(b.len(), 1);
        assert!(
            admit(&mut b, &[0.1, -0.2 + 0.03], 4),
            "0.03 rad away is new"
        );
        assert_eq!(b.len(), 2);
        assert!(!admit(&mut b, &home, 4), "home stays full");
        assert!(admit(&mut b, &[0.1, -0.17], 4));
    }

    /// A slot that is not counted leaves the budget as it was; a non-finite posture gets none.
    #[test]
    fn only_counted_samples_change_the_budget() {
        let mut b = PostureBudget::default();
        assert_eq!(b.slot(&[0.0, 0.0], 0.02, 2), Some(Slot::New));
        assert_eq!(b.slot(&[0.0, 0.0], 0.02, 2), Some(Slot::New));
        assert_eq!(b.len(), 0);
        assert_eq!(b.slot(&[f64::NAN, 0.0], 0.02, 2), None);
        b.count(Slot::New, &[0.0, 0.0]);
        assert_eq!(b.slot(&[0.01, 0.0], 0.02, 2), Some(Slot::Posture(0)));
        assert!(b.check(2).is_ok());
        assert!(b.check(3).is_err());
    }
}
