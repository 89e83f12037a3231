//! The online hot path (observe, update, mean, sample) does not allocate.
#![allow(clippy::needless_range_loop)]

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rwr::{OnlineRwr, RwrConfig};

#[global_allocator]
static GLOBAL: osrl_testkit::Counting = osrl_testkit::Counting;

#[test]
fn online_observe_update_and_sampling_do_not_allocate() {
    let cfg = RwrConfig {
        forgetting: 0.99,
        tau_max: Some(1e3),
        min_ess: 5.0,
        ..Default::default()
    };
    let mut online = OnlineRwr::new(4, 3, cfg).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(0);
    let (mut phi, mut u) = ([0.0, 0.0, 0.0, 1.0], [0.0; 3]);
    let before = osrl_testkit::allocations();
    for k in 0..500 {
        let s = k as f64 * 0.01;
        phi[0] = s.sin();
        phi[1] = s.cos();
        phi[2] = s;
        online.sample_into(&phi, &mut rng, &mut u).unwrap();
        let r = u.iter().map(|x| (x - 0.3).powi(2)).sum::<f64>();
        online.observe(&phi, &u, r, 0.7).unwrap();
        if k >= 10 {
            online.update().unwrap();
        }
        online.mean_into(&phi, &mut u).unwrap();
    }
    // More samples than the statistics hold before folding them in, then the residual.
    for _ in 0..100 {
        online.observe(&phi, &u, 0.1, 0.7).unwrap();
    }
    online.update().unwrap();
    online.mean_sq_residual();
    let _ = online.observe(&phi, &u, -1.0, 1.0); // the error path does not allocate either
    assert_eq!(osrl_testkit::allocations() - before, 0);
}
