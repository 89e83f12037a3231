//! The gravity cache (`gravity_cache.rs`) never returns a stale `ĝ`: after each change of what
//! `ĝ(q)` depends on, `u0` equals that of a copy whose cache was emptied.

use super::fixture;
use crate::Learner;

/// `u0` at `(q, q̇)` from `learner` and from a copy with an empty cache.
fn both(learner: &mut Learner, q: &[f64], qd: &[f64]) -> ([f64; 3], [f64; 3]) {
    let mut fresh = learner.clone();
    fixture::models(&mut fresh).restore_buffers();
    let (mut a, mut b) = ([0.0; 3], [0.0; 3]);
    learner.nominal(q, qd, &mut a).unwrap();
    fresh.nominal(q, qd, &mut b).unwrap();
    (a, b)
}

#[test]
fn the_cache_never_returns_a_stale_gravity() {
    // Still samples teach the static model (not the null-space correction).
    let mut cfg = fixture::config();
    cfg.gravity.null_correction = false;
    let (mut learner, _, last) = fixture::ready(cfg, 200, 50);
    let (q, qd) = (last.q.as_slice().to_vec(), last.qd.as_slice().to_vec());
    let mut still = last.clone();
    still.qd.fill(0.0);
    let mut next = still.clone();
    next.t += 0.002;
    let teach = |learner: &mut Learner, k: usize| {
        for _ in 0..k {
            learner.learn_static_gravity(&still, &next).unwrap();
        }
    };
    teach(&mut learner, 30);
    let (a0, b0) = both(&mut learner, &q, &qd);
    assert_eq!(a0, b0);
    // Frozen: the static model takes part; a hit gives the same bits.
    learner.freeze_gravity(true);
    let (a1, b1) = both(&mut learner, &q, &qd);
    assert_eq!(a1, b1);
    assert_ne!(a0, a1, "freezing changes ĝ here");
    assert_eq!(both(&mut learner, &q, &qd), (a1, b1));
    // More still samples at `q` update the static model: the cached ĝ is not returned.
    teach(&mut learner, 30);
    let (a2, b2) = both(&mut learner, &q, &qd);
    assert_eq!(a2, b2);
    assert_ne!(a1, a2, "the updates move ĝ at q");
}
