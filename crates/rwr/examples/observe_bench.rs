//! Time of `OnlineRwr::observe` at the sarcos7 learner's size (71 features, 3 outputs) with the
//! samples spread round-robin over 1 to 60 controllers (their statistics in L1, L2 or beyond):
//! `cargo run --release -p rwr --example observe_bench`. Only ratios against another build run
//! alternately on the same machine mean anything.

use rwr::{OnlineRwr, RwrConfig};
use std::time::Instant;

fn main() {
    let (p, n_samples) = (71, 200_000);
    let phis: Vec<Vec<f64>> = (0..64)
        .map(|s| {
            (0..p)
                .map(|i| ((s * 31 + i * 7) % 13) as f64 * 0.1 - 0.5)
                .collect()
        })
        .collect();
    let u = [0.1, 0.2, 0.3];
    let cfg = RwrConfig {
        forgetting: 1.0,
        ..Default::default()
    };
    for k in [1usize, 4, 26, 60] {
        let mut fields: Vec<OnlineRwr> = (0..k)
            .map(|_| OnlineRwr::new(p, 3, cfg.clone()).unwrap())
            .collect();
        let t = Instant::now();
        for s in 0..n_samples {
            fields[s % k].observe(&phis[s % 64], &u, 0.0, 0.5).unwrap();
        }
        let ns = t.elapsed().as_secs_f64() * 1e9 / n_samples as f64;
        println!("controllers {k}: {ns:.1} ns/observe");
    }
}
