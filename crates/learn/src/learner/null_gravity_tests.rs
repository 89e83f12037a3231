//! The null-space correction (`null_gravity.rs`): it moves the command only in the null space
//! of `Â`, learns a hold only at its end and only a long enough one, and is saved.

use crate::learner::fixture;
use crate::Learner;
use rand_chacha::ChaCha8Rng;

/// The command (no exploration) at `q` with `q̇ = 0`, and the `Â` of its blend.
fn command_and_gain(learner: &mut Learner, q: &[f64]) -> ([f64; 3], [f64; 6]) {
    let (mut u, mut a, qd) = ([0.0; 3], [0.0; 6], [0.0; 3]);
    learner.start_episode(None).unwrap();
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
    let (null_delta, _) = null_and_task(&a, &delta);
    let (null_du, task) = null_and_task(&a, &du);
    assert!(task <= 1e-9, "task part {task} of {du:?}");
    let fade = null_du / null_delta;
    assert!(fade > 0.5 && fade <= 1.0, "{null_du} vs {null_delta}");
    let mut loaded = Learner::from_bytes(&learner.to_bytes().unwrap()).unwrap();
    let (reloaded, _) = command_and_gain(&mut loaded, &q);
    assert_eq!(reloaded.map(f64::to_bits), after.map(f64::to_bits));
    loaded.cfg.gravity.null_correction = false;
    let (off, _) = command_and_gain(&mut loaded, &q);
    assert_eq!(off.map(f64::to_bits), before.map(f64::to_bits));
}

/// Null-space part of `v` under the 2×3 `Â` `a` (along the cross product of its rows, which
/// spans the null space), and the largest task-space part `|Â v|` relative to `|v|`.
fn null_and_task(a: &[f64; 6], v: &[f64]) -> (f64, f64) {
    let (r0, r1) = (&a[..3], &a[3..]);
    let nv = [
        r0[1] * r1[2] - r0[2] * r1[1],
        r0[2] * r1[0] - r0[0] * r1[2],
        r0[0] * r1[1] - r0[1] * r1[0],
    ];
    let nn = nv.iter().map(|x| x * x).sum::<f64>().sqrt();
    let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let task = [r0, r1]
        .iter()
        .map(|row| (0..3).map(|j| row[j] * v[j]).sum::<f64>().abs())
        .fold(0.0, f64::max);
    (
        (0..3).map(|j| v[j] * nv[j] / nn).sum(),
        task / norm.max(1e-300),
    )
}

/// One hold of 300 still samples at `q` with the torque `u(ĝ)`, learned at its end.
fn hold_with(
    learner: &mut Learner,
    last: &osrl_dynamics::Measurement,
    u: impl Fn(f64, usize) -> f64,
) {
    let q = last.q.as_slice().to_vec();
    let mut g = [0.0; 3];
    learner.gravity(&q, &mut g).unwrap();
    let mut prev = last.clone();
    prev.qd.fill(0.0);
    for (i, gi) in g.iter().enumerate() {
        prev.u[i] = u(*gi, i);
    }
    for _ in 0..300 {
        let mut cur = prev.clone();
        cur.t += 0.002;
        learner.learn_static_gravity(&prev, &cur).unwrap();
        prev = cur;
    }
    learner.end_hold().unwrap();
}

/// The global scale (`gravity.null_scale`, `null_scale.rs`): holds at one posture whose torque is
/// `1.3 ĝ` teach `k ≈ 0.3`, and at a posture the hold never visited the command then moves in
/// the null space only, by the null part of `0.3 ĝ` there, where the holds' model alone carries
/// the held posture's error; a saved and reloaded learner commands the same bits. Errors that
/// are not proportional to `ĝ` (a constant offset) leave the scale's share at 0 and the command
/// that of the learner without the scale, bit for bit.
#[test]
fn the_global_scale_carries_a_proportional_error_to_other_postures() {
    let mut cfg = fixture::config();
    cfg.gravity.null_correction = true;
    let (learner, mut sim, last) = fixture::ready(cfg, 200, 2000);
    // A posture of the sweep 0.8 s on, visited by the partition before (its period is 4.8 s).
    let other = fixture::sweep(&mut learner.clone(), &mut sim, 400);
    let qb = other.q.as_slice().to_vec();
    let qa = last.q.as_slice();
    let moved = qa
        .iter()
        .zip(&qb)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(
        moved > 0.1,
        "postures {qa:?} and {qb:?} are {moved} rad apart"
    );
    let mut scaled = learner.clone();
    scaled.cfg.gravity.null_scale = true;
    let mut plain = learner.clone();
    let (before, a) = command_and_gain(&mut plain.clone(), &qb);
    let mut gb = [0.0; 3];
    plain.gravity(&qb, &mut gb).unwrap();
    for l in [&mut scaled, &mut plain] {
        hold_with(l, &last, |g, _| 1.3 * g);
    }
    let k = fixture::models(&mut scaled).null_scale.scale();
    assert!((k - 0.3).abs() < 0.01, "k = {k}");
    let want = null_and_task(&a, &gb.map(|g| 0.3 * g)).0;
    for (name, l, tol) in [
        ("scaled", &mut scaled, 0.05),
        ("plain", &mut plain, f64::INFINITY),
    ] {
        let (after, a_after) = command_and_gain(l, &qb);
        assert_eq!(a_after, a);
        let du: Vec<f64> = (0..3).map(|j| after[j] - before[j]).collect();
        let (null, task) = null_and_task(&a, &du);
        assert!(task < 1e-9, "{name}: task part {task} of {du:?}");
        let rel = (null - want).abs() / want.abs();
        assert!(rel < tol, "{name}: null part {null} against 0.3 ĝ's {want}");
        if name == "plain" {
            // The holds' model alone is further off at the posture it never held.
            assert!(rel > 0.1, "the holds' model alone: {null} against {want}");
        }
    }
    let mut loaded = Learner::from_bytes(&scaled.to_bytes().unwrap()).unwrap();
    assert_eq!(
        command_and_gain(&mut loaded, &qb).0.map(f64::to_bits),
        command_and_gain(&mut scaled, &qb).0.map(f64::to_bits)
    );

    // A constant offset is not proportional to ĝ: no share, the same bits as without the scale.
    let mut scaled = learner.clone();
    scaled.cfg.gravity.null_scale = true;
    let mut plain = learner.clone();
    let delta = [1.0, -0.5, 0.8];
    for l in [&mut scaled, &mut plain] {
        hold_with(l, &last, |g, i| g + delta[i]);
    }
    let gate = scaled.cfg.gravity.null_scale_explained;
    let s = &fixture::models(&mut scaled).null_scale;
    let share = s.share(gate);
    assert!(share == 0.0 && s.explained() < 0.8, "R² {}", s.explained());
    assert_eq!(
        command_and_gain(&mut scaled, &qb).0.map(f64::to_bits),
        command_and_gain(&mut plain, &qb).0.map(f64::to_bits)
    );
}

/// The load correction `c` under the global scale: with the share at 1 (holds whose torque is
/// `1.3 ĝ`), `c`'s null-space part leaves the command and its task part stays, so the command
/// differs from that of the same learner without `c` by `c − (I − Â⁺Â) c`; with the share at
/// 0 (a constant offset), the command with `c` is that of the learner without the scale, bit
/// for bit.
#[test]
fn the_scale_replaces_the_load_corrections_null_space_part_by_its_share() {
    let mut cfg = fixture::config();
    cfg.gravity.null_correction = true;
    let (learner, _, last) = fixture::ready(cfg, 200, 2000);
    let q = last.q.as_slice().to_vec();
    let c = [0.7, -0.4, 0.5];
    let with_c = |mut l: Learner| {
        let cut = l.cfg.partition.activation_cutoff;
        let mut acts = Vec::new();
        let models = fixture::models(&mut l);
        models
            .forward
            .activations(&q, &[0.0; 3], cut, &mut acts)
            .unwrap();
        l.load.learn(&acts, &c, &c, 1.0);
        assert!(!l.load.is_empty());
        l
    };
    let mut scaled = learner.clone();
    scaled.cfg.gravity.null_scale = true;
    let delta = [1.0, -0.5, 0.8];
    // Share 1: the difference `c` makes is its task part alone.
    let (mut loaded, mut bare) = (with_c(scaled.clone()), scaled.clone());
    for l in [&mut loaded, &mut bare] {
        hold_with(l, &last, |g, _| 1.3 * g);
    }
    let gate = scaled.cfg.gravity.null_scale_explained;
    assert_eq!(fixture::models(&mut loaded).null_scale.share(gate), 1.0);
    let (u_c, a) = command_and_gain(&mut loaded, &q);
    let (u_0, a0) = command_and_gain(&mut bare, &q);
    assert_eq!(a, a0);
    let du: Vec<f64> = (0..3).map(|j| u_c[j] - u_0[j]).collect();
    let (null, _) = null_and_task(&a, &du);
    let (c_null, _) = null_and_task(&a, &c);
    assert!(
        null.abs() < 1e-9 && c_null.abs() > 0.1,
        "{null} of c's {c_null}"
    );
    for row in [&a[..3], &a[3..]] {
        let (t_du, t_c): (f64, f64) = (0..3).fold((0.0, 0.0), |(x, y), j| {
            (x + row[j] * du[j], y + row[j] * c[j])
        });
        assert!(
            (t_du - t_c).abs() < 1e-9 * t_c.abs().max(1.0),
            "{t_du} vs {t_c}"
        );
    }
    // Share 0: the learner with `c` commands as without the scale.
    let (mut loaded, mut plain) = (with_c(scaled), with_c(learner));
    for l in [&mut loaded, &mut plain] {
        hold_with(l, &last, |g, i| g + delta[i]);
    }
    assert_eq!(fixture::models(&mut loaded).null_scale.share(gate), 0.0);
    assert_eq!(
        command_and_gain(&mut loaded, &q).0.map(f64::to_bits),
        command_and_gain(&mut plain, &q).0.map(f64::to_bits)
    );
}
