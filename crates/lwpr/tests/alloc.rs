//! Update and predict do not allocate in steady state (no RF added, no PLS direction added
//! beyond the reserved ones), checked with a counting global allocator.

mod common;

#[global_allocator]
static GLOBAL: osrl_testkit::Counting = osrl_testkit::Counting;

fn structure(m: &lwpr::Lwpr) -> Vec<Vec<usize>> {
    (0..m.n_sub())
        .map(|s| m.rfs(s).unwrap().flat_map(|v| v.n_reg()).collect())
        .collect()
}

fn check(cfg: lwpr::LwprConfig, n_in: usize, n_out: usize) {
    use rand::{RngExt, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
    let mut m = lwpr::Lwpr::new(n_in, n_out, &cfg).unwrap();
    let f = |x: &[f64], o: usize| common::cross(x[0], x[1]) + o as f64 * x[n_in - 1];
    let sample = |rng: &mut rand_chacha::ChaCha8Rng| -> Vec<f64> {
        (0..n_in).map(|_| rng.random_range(-1.0..1.0)).collect()
    };
    let mut y = vec![0.0; n_out];
    let mut t = vec![0.0; n_out];
    let mut conf = vec![0.0; n_out];
    let mut jac = vec![0.0; n_out * n_in];
    for _ in 0..3000 {
        let x = sample(&mut rng);
        (0..n_out).for_each(|o| t[o] = f(&x, o));
        m.update(&x, &t).unwrap();
    }
    m.drain_events().for_each(drop);
    let mut steady = 0;
    for _ in 0..2000 {
        let x = sample(&mut rng);
        (0..n_out).for_each(|o| t[o] = f(&x, o));
        let before = structure(&m);
        let a0 = osrl_testkit::allocations();
        let info = m.update(&x, &t).unwrap();
        let _ = m.predict(&x, &mut y);
        let _ = m.predict_conf(&x, &mut y, &mut conf);
        let _ = m.predict_jacobian(&x, &mut y, &mut jac);
        let _ = m.predict_everywhere(&x, &mut y);
        let a1 = osrl_testkit::allocations();
        m.drain_events().for_each(drop);
        if info.added == 0 && info.pruned == 0 && structure(&m) == before {
            assert_eq!(a1, a0, "allocation in a steady-state update/predict");
            steady += 1;
        }
    }
    assert!(steady > 1500, "only {steady} steady-state steps");
}

#[test]
fn hot_paths_do_not_allocate() {
    check(common::cross_config(), 2, 1);
    let shared = lwpr::LwprConfig {
        shared_rfs: true,
        kernel_dims: Some(vec![0, 1]),
        regression_dims: Some(vec![1, 2]),
        ..Default::default()
    };
    check(shared, 3, 2);
    check(lwpr::LwprConfig::default(), 3, 2);
}
