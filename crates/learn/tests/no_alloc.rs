//! A command of the learned controller does not allocate.

mod common;

#[global_allocator]
static GLOBAL: osrl_testkit::Counting = osrl_testkit::Counting;

#[test]
fn learned_commands_do_not_allocate() {
    let s = common::planar3();
    let mut learner = common::learner(&s);
    common::run(&s, &mut learner, 0.5, 0.5, 0.0, 3);
    assert!(learner.n_trained() > 0);
    let mut rng = <rand_chacha::ChaCha8Rng as rand::SeedableRng>::seed_from_u64(0);
    let (mut u, q, qd) = (vec![0.0; 3], s.q_start.clone(), vec![0.1, -0.1, 0.05]);
    // Warm the buffers once, then count.
    learner
        .command(&q, &qd, &[0.1, 0.2], Some(&mut rng), &mut u)
        .unwrap();
    let before = osrl_testkit::allocations();
    for k in 0..100 {
        let x = 0.01 * k as f64;
        learner
            .command(&q, &qd, &[x, -x], Some(&mut rng), &mut u)
            .unwrap();
        learner
            .command::<rand_chacha::ChaCha8Rng>(&q, &qd, &[x, x], None, &mut u)
            .unwrap();
    }
    assert_eq!(osrl_testkit::allocations() - before, 0);
    // Out of the trained fields: thin support (the nearest controllers, `nearest.rs`), then `u0`.
    let (mut sources, mut q) = (Vec::with_capacity(400), s.q_start.clone());
    let before = osrl_testkit::allocations();
    for k in 0..400 {
        for (v, v0) in q.iter_mut().zip(&s.q_start) {
            *v = v0 + 0.005 * k as f64;
        }
        let src = learner
            .command::<rand_chacha::ChaCha8Rng>(&q, &qd, &[0.1, 0.2], None, &mut u)
            .unwrap();
        if sources.last() != Some(&src) {
            sources.push(src);
        }
    }
    let after = osrl_testkit::allocations();
    assert!(
        sources.contains(&osrl_learn::CommandSource::Extrapolated)
            && sources.last() == Some(&osrl_learn::CommandSource::Fallback),
        "{sources:?}"
    );
    assert!(sources.len() <= 8, "{sources:?}");
    assert_eq!(after - before, 0);
}
