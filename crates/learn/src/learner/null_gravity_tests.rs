//! The null-space correction (`null_gravity.rs`): it moves the command only in the null space
//! of `Â`, learns a hold only at its end and only a long enough one, and is saved.

use crate::learner::fixture;
use crate::Learner;
use rand_chacha::ChaCha8Rng;

/// The command (no exploration) at `q` with `q̇ = 0`, and the `Â` of its blend.
fn command_and_gain(learner: &mut Learner, q: &[f64]) -> ([f64; 3], [f64; 6]) {
    let (mut u, mut a, qd) = ([0.0; 3], [0.0; 6], [0.0; 3]);
    learner.start_episode(None);
    learner
        .command::<ChaCha8Rng>(q, &qd, &[0.3, -0.2], None, &mut u)
        .unwrap();
    let cut = learner.cfg.partition.activation_cutoff;
    let weights = (cut, learner.cfg.controllers.trained_ess);
    let features = learner.features;
    let models = fixture::models(learner);
    let mut acts = Vec::new();
    models.forward.activations(q, &qd, cut, &mut acts).unwrap();
    assert!(models.command_gain(&features, &acts, q, weights, &mut a));
    (u, a)
}

/// Still samples whose torque exceeds `ĝ` by `δ` teach the correction at the end of a hold
/// long enough (a short one teaches nothing); the command then
/// moves only in the null space of its `Â` (the same task acceleration), by the faded null
/// part of `δ`; a saved and reloaded learner commands the same bits, and with the option
/// switched off the command it gave before the samples.
#[test]
fn the_correction_moves_the_command_in_the_null_space_only() {
    let mut cfg = fixture::config();
    cfg.gravity.null_correction = true;
    let (mut learner, _, last) = fixture::ready(cfg, 200, 2000);
    let q = last.q.as_slice().to_vec();
    let (before, a) = command_and_gain(&mut learner, &q);
    let mut g = [0.0; 3];
    learner.gravity(&q, &mut g).unwrap();
    let delta = [1.0, -0.5, 0.8];
    let mut prev = last.clone();
    prev.qd.fill(0.0);
    for i in 0..3 {
        prev.u[i] = g[i] + delta[i];
    }
    let mut hold = |learner: &mut Learner, k: usize| {
        for _ in 0..k {
            let mut cur = prev.clone();
            cur.t += 0.002;
            learner.learn_static_gravity(&prev, &cur).unwrap();
            prev = cur;
        }
    };
    // A hold with fewer still samples than `null_min_samples` teaches nothing.
    let short_hold = learner.cfg.gravity.null_min_samples - 1;
    hold(&mut learner, short_hold);
    learner.end_hold().unwrap();
    let (short, _) = command_and_gain(&mut learner, &q);
    assert_eq!(short.map(f64::to_bits), before.map(f64::to_bits));
    hold(&mut learner, 300);
    // Nothing is learned before the hold ends.
    let (during, _) = command_and_gain(&mut learner, &q);
    assert_eq!(during.map(f64::to_bits), before.map(f64::to_bits));
    learner.end_hold().unwrap();
    let (after, _) = command_and_gain(&mut learner, &q);
    let du: Vec<f64> = (0..3).map(|j| after[j] - before[j]).collect();
    // The null space of a 2×3 `Â` is spanned by the cross product of its rows.
    let (r0, r1) = (&a[..3], &a[3..]);
    let nv = [
        r0[1] * r1[2] - r0[2] * r1[1],
        r0[2] * r1[0] - r0[0] * r1[2],
        r0[0] * r1[1] - r0[1] * r1[0],
    ];
    let nn = nv.iter().map(|v| v * v).sum::<f64>().sqrt();
    let null_delta = (0..3).map(|j| delta[j] * nv[j] / nn).sum::<f64>();
    let null_du = (0..3).map(|j| du[j] * nv[j] / nn).sum::<f64>();
    let norm = du.iter().map(|v| v * v).sum::<f64>().sqrt();
    for row in [r0, r1] {
        let task = (0..3).map(|j| row[j] * du[j]).sum::<f64>();
        assert!(task.abs() <= 1e-9 * norm, "task part {task} of {du:?}");
    }
    let fade = null_du / null_delta;
    assert!(fade > 0.5 && fade <= 1.0, "{null_du} vs {null_delta}");
    let mut loaded = Learner::from_bytes(&learner.to_bytes().unwrap()).unwrap();
    let (reloaded, _) = command_and_gain(&mut loaded, &q);
    assert_eq!(reloaded.map(f64::to_bits), after.map(f64::to_bits));
    loaded.cfg.gravity.null_correction = false;
    let (off, _) = command_and_gain(&mut loaded, &q);
    assert_eq!(off.map(f64::to_bits), before.map(f64::to_bits));
}
