//! The Rust side of `examples/python/bench_lwpr_update.py`: times `Lwpr::update` on a CSV file
//! in file order (the order and config the Python side uses, so both models do the same work,
//! bit for bit) and prints one JSON line: `update_us` (wall µs per update, best of the repeats)
//! and `n_rfs`.
//!
//! `cargo run --release -p osrl-py --example lwpr_update_timing -- CONFIG.json TRAIN.csv
//! INPUTS EPOCHS REPEATS`

use lwpr::{Lwpr, LwprConfig};
use std::time::Instant;

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let [config, train, inputs, epochs, repeats] = &a[..] else {
        panic!("usage: CONFIG.json TRAIN.csv INPUTS EPOCHS REPEATS");
    };
    let cfg: LwprConfig =
        serde_json::from_str(&std::fs::read_to_string(config).expect("config")).expect("config");
    let k: usize = inputs.parse().unwrap();
    let (epochs, repeats): (usize, usize) = (epochs.parse().unwrap(), repeats.parse().unwrap());
    let text = std::fs::read_to_string(train).expect("train");
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.split(',').map(|c| c.parse().expect("a number")).collect())
        .collect();
    let n_out = rows[0].len() - k;
    let mut best = f64::INFINITY;
    let mut n_rfs = 0;
    for _ in 0..repeats {
        let mut m = Lwpr::new(k, n_out, &cfg).expect("config");
        let t = Instant::now();
        for _ in 0..epochs {
            for r in &rows {
                m.update(&r[..k], &r[k..]).expect("a valid sample");
                m.drain_events().for_each(drop);
            }
        }
        let us = t.elapsed().as_secs_f64() * 1e6 / (epochs * rows.len()) as f64;
        best = best.min(us);
        n_rfs = m.n_rfs_total();
    }
    println!("{{\"update_us\": {best}, \"n_rfs\": {n_rfs}}}");
}
