//! Time of one M-step (`OnlineRwr::update`: the Cholesky solve of eq. 23) at the sarcos7
//! learner's sizes: the local dynamics (71 features, 3 outputs) and the controller (18
//! features, 7 outputs). `cargo run --release -p rwr --example solve_bench`. Only ratios
//! against another build run alternately on the same machine mean anything.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rwr::{OnlineRwr, RwrConfig};
use std::time::Instant;

fn main() {
    for (p, d) in [(71usize, 3usize), (18, 7)] {
        let mut rwr = OnlineRwr::new(p, d, RwrConfig::default()).unwrap();
        let mut phi = vec![0.0; p];
        let mut u = vec![0.0; d];
        // Seeded, well-spread samples.
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        for _ in 0..4 * p {
            phi.iter_mut()
                .for_each(|f| *f = rng.random_range(-0.5..0.5));
            u.iter_mut().for_each(|a| *a = rng.random_range(-0.5..0.5));
            rwr.observe(&phi, &u, 0.0, 1.0).unwrap();
        }
        let n = 20_000;
        let mut best = f64::INFINITY;
        for _ in 0..5 {
            let t = Instant::now();
            for _ in 0..n {
                rwr.update().unwrap();
            }
            best = best.min(t.elapsed().as_secs_f64() * 1e9 / n as f64);
        }
        println!("features {p}, outputs {d}: {best:.0} ns/M-step (best of 5)");
    }
}
