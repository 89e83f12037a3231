//! The SARCOS parity split as `osrl lwpr fit --config examples/sarcos.toml` trains it (the
//! same settings, the training data's standard deviations as normalisation, ChaCha8-shuffled
//! epochs), for speed work on the 21-D, 7-output update: prints the best and median µs per
//! update over the epochs' updates (each timed), the RFs, the mean RF updates per sample and a
//! hash of the saved model (the same bits or not).
//!
//! `cargo run -p lwpr --release --example sarcos_fit -- [DATA_DIR] [EPOCHS] [SEED]`
//! (DATA_DIR: `../shared/data/sarcos`, EPOCHS: 1, SEED: 0)

use lwpr::{Lwpr, LwprConfig, MetricInit, Norm};
use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::time::Instant;

fn std_dev(rows: &[Vec<f64>], col: usize) -> f64 {
    let n = rows.len() as f64;
    let mean = rows.iter().map(|r| r[col]).sum::<f64>() / n;
    (rows.iter().map(|r| (r[col] - mean).powi(2)).sum::<f64>() / n).sqrt()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let dir = args.get(1).map_or("../shared/data/sarcos", |s| s.as_str());
    let epochs: usize = args.get(2).map_or(1, |s| s.parse().expect("EPOCHS"));
    let seed: u64 = args.get(3).map_or(0, |s| s.parse().expect("SEED"));
    let text = std::fs::read_to_string(format!("{dir}/parity_train.csv")).expect("train CSV");
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.trim().parse().unwrap()).collect())
        .collect();
    let (k, cols) = (21, rows[0].len());
    let cfg = LwprConfig {
        init_d: MetricInit::Scalar(0.3),
        init_alpha: 250.0,
        w_gen: 0.2,
        meta: true,
        norm_in: Norm::List((0..k).map(|c| std_dev(&rows, c)).collect()),
        norm_out: Norm::List((k..cols).map(|c| std_dev(&rows, c)).collect()),
        ..LwprConfig::default()
    };
    let mut model = Lwpr::new(k, cols - k, &cfg).expect("config");
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut order: Vec<usize> = (0..rows.len()).collect();
    let (mut us, mut updated) = (Vec::new(), 0usize);
    for _ in 0..epochs {
        order.shuffle(&mut rng);
        for &i in &order {
            let (x, y) = rows[i].split_at(k);
            let t = Instant::now();
            let info = model.update(x, y).expect("update");
            us.push(t.elapsed().as_nanos() as f64 / 1e3);
            updated += info.updated;
        }
    }
    let n = us.len();
    let total: f64 = us.iter().sum();
    us.sort_by(f64::total_cmp);
    let hash = model
        .to_bytes()
        .iter()
        .fold(0xcbf2_9ce4_8422_2325u64, |h, &b| {
            (h ^ b as u64).wrapping_mul(0x100_0000_01b3)
        });
    println!(
        "{{\"updates\": {n}, \"mean_us\": {:.1}, \"median_us\": {:.1}, \"rfs\": {}, \"rf_updates_per_sample\": {:.1}, \"hash\": \"{hash:016x}\"}}",
        total / n as f64,
        us[n / 2],
        model.n_rfs_total(),
        updated as f64 / n as f64
    );
}
