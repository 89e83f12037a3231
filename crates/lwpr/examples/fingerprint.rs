//! A fixed workload for speed work: trains one seed of a test, then hashes the saved model and
//! every prediction, confidence bound, Jacobian and activation on the test inputs (bit
//! patterns), so a change that alters any floating-point result shows up as a different hash.
//! Prints one JSON line with the hash, nMSE, RFs and wall µs per update (mean over the epochs;
//! the first epochs, with few RFs, are the fastest) and per prediction (min over passes).
//!
//! `cargo run -p lwpr --release --example fingerprint -- [--test 2|21|21diag|shared]
//! [--epochs E] [--seed S] [--passes P] [--per-epoch]` (P timed prediction passes over the test
//! set, 5; `--per-epoch` prints each epoch's µs per update on stderr)

#[path = "../tests/common/mod.rs"]
mod common;

use lwpr::{Lwpr, LwprConfig};
use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::time::Instant;

/// FNV-1a over 64-bit words.
fn mix(h: &mut u64, v: u64) {
    for b in v.to_le_bytes() {
        *h = (*h ^ b as u64).wrapping_mul(0x100_0000_01b3);
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let get = |k: &str| {
        let i = args.iter().position(|a| a == k)?;
        args.get(i + 1).cloned()
    };
    let test = get("--test").unwrap_or_else(|| "2".into());
    let seed: u64 = get("--seed").map_or(0, |s| s.parse().unwrap());
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let train = common::cross_train(&mut rng, 500);
    let grid = common::cross_grid();
    let (cfg, train, test_d, n_out, def_ep): (LwprConfig, _, _, usize, usize) = match &*test {
        "2" => (common::cross_config(), train, grid, 1, 20),
        "shared" => {
            let cfg = LwprConfig {
                shared_rfs: true,
                kernel: lwpr::Kernel::Bisquare,
                ..common::cross_config()
            };
            (cfg, train, grid, 2, 20)
        }
        t => {
            let rot = common::rotation(&mut rng, 21);
            let cfg = LwprConfig {
                diag_only: t == "21diag",
                ..common::cross21_config()
            };
            (
                cfg,
                common::embed(&train, &rot),
                common::embed(&grid, &rot),
                1,
                5,
            )
        }
    };
    let epochs: usize = get("--epochs").map_or(def_ep, |s| s.parse().unwrap());
    let passes: usize = get("--passes").map_or(5, |s| s.parse().unwrap());
    let n_in = train.x[0].len();
    let mut m = Lwpr::new(n_in, n_out, &cfg).unwrap();
    let mut order: Vec<usize> = (0..train.x.len()).collect();
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5eed);
    let mut t = vec![0.0; n_out];
    let mut upd_us = 0.0;
    let per_epoch = args.iter().any(|a| a == "--per-epoch");
    for _ in 0..epochs {
        order.shuffle(&mut rng);
        let t0 = Instant::now();
        let mut n_upd = 0;
        for &i in &order {
            // Output o: the target scaled by (1 + o) (shared mode regresses both).
            (0..n_out).for_each(|o| t[o] = train.y[i] * (1 + o) as f64);
            n_upd += m.update(&train.x[i], &t).unwrap().updated;
        }
        let us = t0.elapsed().as_secs_f64() * 1e6 / order.len() as f64;
        if per_epoch {
            let per = n_upd as f64 / order.len() as f64;
            eprintln!(
                "epoch µs/update {us:.3} rfs {} RF-updates/update {per:.2}",
                m.n_rfs_total()
            );
        }
        upd_us += us / epochs as f64;
    }
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for b in m.to_bytes() {
        mix(&mut h, b as u64);
    }
    let (mut y, mut conf, mut jac) = (vec![0.0; n_out], vec![0.0; n_out], vec![0.0; n_out * n_in]);
    let mut se = 0.0;
    for (x, &ty) in test_d.x.iter().zip(&test_d.y) {
        let ok = m.predict_conf(x, &mut y, &mut conf).is_ok();
        mix(&mut h, ok as u64);
        y.iter().chain(&conf).for_each(|v| mix(&mut h, v.to_bits()));
        se += if ok { (y[0] - ty).powi(2) } else { ty * ty };
        if m.predict_jacobian(x, &mut y, &mut jac).is_ok() {
            jac.iter().for_each(|v| mix(&mut h, v.to_bits()));
        }
    }
    // The partition's activations (every sub-model).
    let mut acts = Vec::new();
    for x in &test_d.x {
        for s in 0..m.n_sub() {
            m.activations(s, x, 0.001, &mut acts).unwrap();
            acts.iter()
                .for_each(|a| mix(&mut h, a.id.0 ^ a.w.to_bits()));
        }
    }
    // Plain predictions, timed (consecutive inputs differ: the repeated-query cache never answers).
    let mut pred_us = f64::INFINITY;
    for _ in 0..passes {
        let t0 = Instant::now();
        for x in &test_d.x {
            let r = m.predict(x, &mut y);
            mix(&mut h, r.is_ok() as u64);
            mix(&mut h, y[0].to_bits());
        }
        pred_us = pred_us.min(t0.elapsed().as_secs_f64() * 1e6 / test_d.x.len() as f64);
    }
    let n = test_d.y.len() as f64;
    let mean = test_d.y.iter().sum::<f64>() / n;
    let var = test_d.y.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n;
    println!(
        "{{\"test\":\"{test}\",\"seed\":{seed},\"epochs\":{epochs},\"hash\":\"{h:016x}\",\"nmse\":{:.6},\"n_rfs\":{},\"update_us\":{upd_us:.3},\"predict_us\":{pred_us:.3}}}",
        se / n / var,
        m.n_rfs_total()
    );
}
