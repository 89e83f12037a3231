//! The safety numbers that scale with the robot (`docs/decisions.md`, D19): where the user did
//! not set them, the torque-rate limit and the braking step of each joint are computed from the
//! joint's torque limit — a data-sheet value (the profile's `torque_limits`: the URDF's `effort`
//! or the user's), never the simulator's dynamics. A joint without a torque limit, and every
//! joint whose limit is at most [`REFERENCE_TORQUE`], gets the fixed values the learner was tuned
//! with on the built-in arms (1000 N·m/s and 1 N·m), so those arms keep them.

/// The torque limit (N·m) up to which the fixed values hold: the built-in arms' largest
/// (sarcos7's 100 N·m per joint; planar3's are 60, 40 and 20).
pub const REFERENCE_TORQUE: f64 = 100.0;

/// The torque-rate limit of a joint up to [`REFERENCE_TORQUE`] (N·m/s): the rate at which a
/// Franka arm's controller stops the robot.
pub const REFERENCE_TORQUE_RATE: f64 = 1000.0;

/// The braking step of a joint up to [`REFERENCE_TORQUE`] (N·m): well above the exploration's
/// steps on the built-in arms (below 0.5 N·m), half the torque-rate limit's step at 2 ms.
pub const REFERENCE_BRAKE_STEP: f64 = 1.0;

/// Scale of a joint with torque limit `tau_max` (N·m): `max(1, tau_max / REFERENCE_TORQUE)`;
/// 1 for a joint without a finite limit (a huge value or `f64::MAX` stands for none).
pub fn torque_scale(tau_max: f64) -> f64 {
    if tau_max.is_finite() && tau_max < 1e12 {
        (tau_max / REFERENCE_TORQUE).max(1.0)
    } else {
        1.0
    }
}

/// Per-joint torque-rate limits (N·m/s) for `n` joints: `given` for every joint if set, else
/// `REFERENCE_TORQUE_RATE · torque_scale(τ_max,j)` (a 330 N·m joint: 3300 N·m/s, the full
/// torque in 0.1 s as for the reference joint). `torque_limits` empty: no limit known.
pub fn torque_rate_limits(given: Option<f64>, torque_limits: &[f64], n: usize) -> Vec<f64> {
    per_joint(given, torque_limits, n, REFERENCE_TORQUE_RATE)
}

/// Per-joint braking steps (N·m), the same rule from [`REFERENCE_BRAKE_STEP`]: a command that
/// would move joint `j` by more than this from the last one sent brakes the episode.
pub fn brake_steps(given: Option<f64>, torque_limits: &[f64], n: usize) -> Vec<f64> {
    per_joint(given, torque_limits, n, REFERENCE_BRAKE_STEP)
}

fn per_joint(given: Option<f64>, torque_limits: &[f64], n: usize, reference: f64) -> Vec<f64> {
    (0..n)
        .map(|j| {
            given.unwrap_or_else(|| {
                reference * torque_limits.get(j).copied().map_or(1.0, torque_scale)
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A heavier arm gets proportionally larger limits; the built-in arms (torque limits up to
    /// 100 N·m) keep the fixed 1000 N·m/s and 1 N·m; a set value wins; no limit: the reference.
    #[test]
    fn limits_scale_with_the_torque_limits_above_the_built_in_arms() {
        let planar3 = [60.0, 40.0, 20.0];
        let sarcos7 = [100.0; 7];
        for tl in [&planar3[..], &sarcos7[..]] {
            assert!(torque_rate_limits(None, tl, tl.len())
                .iter()
                .all(|r| *r == 1000.0));
            assert!(brake_steps(None, tl, tl.len()).iter().all(|s| *s == 1.0));
        }
        let ur10 = [330.0, 330.0, 150.0, 56.0, 56.0, 56.0];
        let rates = torque_rate_limits(None, &ur10, 6);
        assert_eq!(rates, vec![3300.0, 3300.0, 1500.0, 1000.0, 1000.0, 1000.0]);
        let heavy: Vec<f64> = ur10.iter().map(|t| 2.0 * t).collect();
        let (b1, b2) = (brake_steps(None, &ur10, 6), brake_steps(None, &heavy, 6));
        assert!((b2[0] / b1[0] - 2.0).abs() < 1e-12 && (b2[2] / b1[2] - 2.0).abs() < 1e-12);
        assert_eq!(torque_rate_limits(Some(50.0), &ur10, 6), vec![50.0; 6]);
        assert_eq!(brake_steps(None, &[], 2), vec![1.0; 2]);
        assert_eq!(brake_steps(None, &[f64::MAX], 1), vec![1.0]);
    }
}
