//! The static gravity model's sample budget per posture (`docs/decisions.md`, D30).
//!
//! A still sample measures `g(q)` at one posture only: it pins the local models' value there and
//! says nothing about their slopes. On-policy the arm rests at home between every two episodes,
//! so home collects about 550 still samples a simulated minute against 20–120 at each posture of
//! the babbling; regressed on `q`, the jitter of those samples (`|q̇| < 0.01 rad/s`, `|q̈| < 0.1
//! rad/s²`: torques of `M q̈`, not of gravity) outweighs the babbling's spread, tilts the fields
//! around home and drifts `ĝ` along the path (the Panda's `u0` error doubled between minutes 16
//! and 30). A budget of samples per posture keeps the first ones of every posture and ignores
//! the repeats, so a posture that the arm returns to counts as much as one it visited once.

use serde::{Deserialize, Serialize};

/// Postures seen so far (centres `radius` apart at least, in the max-norm over joints) and how
/// many samples each has given.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub(super) struct PostureBudget {
    /// The postures' centres, `n` values each, in the order first seen.
    centres: Vec<f64>,
    /// Samples admitted at each posture.
    counts: Vec<u32>,
}

impl PostureBudget {
    /// Whether a still sample at `q` is admitted: `true` while the posture within `radius`
    /// (rad, every joint) of `q` has given fewer than `cap` samples, or when `q` is a new
    /// posture (which becomes a centre); the admitted sample is counted.
    pub fn admit(&mut self, q: &[f64], radius: f64, cap: u32) -> bool {
        let n = q.len();
        let near = self
            .centres
            .chunks_exact(n)
            .position(|c| c.iter().zip(q).all(|(a, b)| (a - b).abs() <= radius));
        match near {
            Some(k) if self.counts[k] >= cap => false,
            Some(k) => {
                self.counts[k] += 1;
                true
            }
            None => {
                self.centres.extend_from_slice(q);
                self.counts.push(1);
                true
            }
        }
    }

    /// Number of postures seen.
    pub fn len(&self) -> usize {
        self.counts.len()
    }
}

#[cfg(test)]
mod tests {
    use super::PostureBudget;

    /// A posture gives `cap` samples, then none; a posture further than `radius` on one joint is
    /// a new one with its own budget, and the first posture stays full.
    #[test]
    fn budget_keeps_the_first_samples_of_each_posture() {
        let mut b = PostureBudget::default();
        let home = [0.1, -0.2];
        let admitted = (0..10)
            .filter(|k| b.admit(&[home[0] + 1e-3 * (k % 3) as f64, home[1]], 0.02, 4))
            .count();
        assert_eq!(admitted, 4);
        assert_eq!(b.len(), 1);
        assert!(
            b.admit(&[0.1, -0.2 + 0.03], 0.02, 4),
            "0.03 rad away is a new posture"
        );
        assert_eq!(b.len(), 2);
        assert!(!b.admit(&home, 0.02, 4), "home stays full");
        assert!(b.admit(&[0.1, -0.17], 0.02, 4));
    }
}
