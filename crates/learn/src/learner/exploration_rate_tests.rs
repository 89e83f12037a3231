//! `exploration.max_rate`: the exploration torque's rate of change is bounded by construction,
//! whatever the noise process draws and however the blended `σ` jumps (`docs/decisions.md`,
//! D24).

use super::fixture::one_trained_field;
use rand::SeedableRng;

/// The largest change between consecutive commands at a fixed state (where only the noise
/// moves the command) over 4000 exploring commands of white noise, with the noise's gain (its
/// `σ`) switched between 1 and 0 every 500 commands; and the RMS of the commands about their
/// mean.
fn steps_at_a_fixed_state(max_rate: Option<f64>) -> (f64, f64) {
    let mut cfg = super::fixture::config();
    cfg.guards.torque_rate_limit = Some(f64::MAX);
    cfg.exploration.correlation_time = 0.0; // white noise: the largest steps
    cfg.exploration.max_rate = max_rate;
    let (mut learner, c) = one_trained_field(cfg);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
    let (q, vd) = (c[..3].to_vec(), c[3..].to_vec());
    let (mut prev, mut u) = (None::<[f64; 3]>, [0.0; 3]);
    let (mut largest, mut sent) = (0.0f64, Vec::new());
    learner.start_episode(None).unwrap();
    for k in 0..4000 {
        learner.set_exploration_gain(if (k / 500) % 2 == 0 { 1.0 } else { 0.0 });
        learner
            .command(&q, &vd, &[0.1, 0.0], Some(&mut rng), &mut u)
            .unwrap();
        if let Some(p) = prev {
            let d = p.iter().zip(&u).map(|(a, b)| (a - b).abs());
            largest = largest.max(d.fold(0.0, f64::max));
        }
        prev = Some(u);
        sent.push(u[0]);
    }
    let mean = sent.iter().sum::<f64>() / sent.len() as f64;
    let var = sent.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / sent.len() as f64;
    (largest, var.sqrt())
}

/// With `max_rate` the command at a fixed state changes by at most `max_rate · dt` per command
/// (white noise and `σ` switched on and off included), while it still explores; without it the
/// same noise steps many times further.
#[test]
fn the_exploration_rate_is_bounded_by_max_rate() {
    let rate = 5.0;
    let bound = rate * 0.002;
    let (bounded, spread) = steps_at_a_fixed_state(Some(rate));
    let (free, _) = steps_at_a_fixed_state(None);
    assert!(bounded <= bound * (1.0 + 1e-9), "{bounded} > {bound}");
    assert!(bounded > 0.9 * bound, "the bound never acted: {bounded}");
    assert!(spread > 2.0 * bound, "no exploration left: RMS {spread}");
    assert!(free > 10.0 * bound, "white noise steps only {free}");
}
