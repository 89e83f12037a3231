//! The data sets of `osrl bench references`, as [`Samples`] in update order: the cross tests
//! of `osrl bench lwpr` (`lwpr::datasets`: the same points, configs and per-epoch shuffles as
//! `datasets::fit`) and the real SARCOS split of `../shared/data/sarcos` with the settings of
//! `crates/lwpr/examples/sarcos.toml`.

use super::samples::Samples;
use crate::util;
use anyhow::{ensure, Context, Result};
use lwpr::datasets::{cross21_config, cross_config, cross_grid, cross_nd_data, cross_train};
use lwpr::datasets::{Data, Embedding};
use lwpr::{LwprConfig, MetricInit, Norm};
use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::path::Path;

/// A data set of the comparison.
#[derive(clap::ValueEnum, Clone, Copy, PartialEq, Debug)]
pub enum Set {
    /// The 2-D cross (500 noisy points, 41×41 test grid).
    Cross2,
    /// The same points rotated into 21 dimensions.
    Cross21,
    /// The real SARCOS inverse-dynamics split (3,449 train, 1,000 test rows, 7 outputs).
    Sarcos7,
}

impl Set {
    /// The JSON key.
    pub fn key(self) -> &'static str {
        match self {
            Set::Cross2 => "cross2",
            Set::Cross21 => "cross21",
            Set::Sarcos7 => "sarcos7",
        }
    }
}

/// `rows` visited `epochs` times, each epoch in a fresh order from a generator seeded with
/// `seed ^ 0x5eed` (as `lwpr::datasets::fit` orders its updates).
fn ordered(rows: &[Vec<f64>], epochs: usize, seed: u64) -> Vec<Vec<f64>> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5eed);
    let mut order: Vec<usize> = (0..rows.len()).collect();
    let mut out = Vec::with_capacity(rows.len() * epochs);
    for _ in 0..epochs {
        order.shuffle(&mut rng);
        out.extend(order.iter().map(|&i| rows[i].clone()));
    }
    out
}

/// Rows `x ‖ y` of a one-output data set.
fn joined(d: &Data) -> Vec<Vec<f64>> {
    d.x.iter()
        .zip(&d.y)
        .map(|(x, &y)| [x.as_slice(), &[y]].concat())
        .collect()
}

/// A cross test's samples for `seed`.
fn cross(
    cfg: LwprConfig,
    train: &Data,
    test: &Data,
    epochs: usize,
    seed: u64,
) -> Result<(Samples, LwprConfig)> {
    let mut s = Samples::new(train.x[0].len(), 1, &cfg)?;
    s.train = ordered(&joined(train), epochs, seed);
    s.test = joined(test);
    Ok((s, cfg))
}

/// A CSV table with a header line, every row `width` numbers.
fn csv(path: &Path, width: usize) -> Result<Vec<Vec<f64>>> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
    let mut rows = Vec::new();
    for (i, line) in text
        .lines()
        .enumerate()
        .skip(1)
        .filter(|(_, l)| !l.trim().is_empty())
    {
        let row: Vec<f64> = line
            .split(',')
            .map(|v| v.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .with_context(|| format!("{} line {}: not a list of numbers", path.display(), i + 1))?;
        ensure!(
            row.len() == width && row.iter().all(|v| v.is_finite()),
            "{} line {}: {} values, expected {width} finite numbers",
            path.display(),
            i + 1,
            row.len()
        );
        rows.push(row);
    }
    ensure!(!rows.is_empty(), "{}: no data rows", path.display());
    Ok(rows)
}

/// Standard deviation of each of the columns `cols`, 1 where it is below 1e-12.
fn stds(rows: &[Vec<f64>], cols: std::ops::Range<usize>) -> Vec<f64> {
    cols.map(|c| util::std_dev(rows, c))
        .map(|s| if s > 1e-12 { s } else { 1.0 })
        .collect()
}

/// The SARCOS split in `dir` with the settings of `crates/lwpr/examples/sarcos.toml`.
fn sarcos(dir: &Path, epochs: usize, seed: u64) -> Result<(Samples, LwprConfig)> {
    let train = csv(&dir.join("parity_train.csv"), 28)?;
    let test = csv(&dir.join("parity_test.csv"), 28)?;
    let cfg = LwprConfig {
        init_d: MetricInit::Scalar(0.3),
        init_alpha: 250.0,
        w_gen: 0.2,
        meta: true,
        norm_in: Norm::List(stds(&train, 0..21)),
        norm_out: Norm::List(stds(&train, 21..28)),
        ..Default::default()
    };
    let mut s = Samples::new(21, 7, &cfg)?;
    s.train = ordered(&train, epochs, seed);
    s.test = test;
    Ok((s, cfg))
}

/// The samples and config of `set` for `seed` with `epochs` epochs (`sarcos_dir`: the SARCOS
/// split's folder).
pub fn samples(
    set: Set,
    seed: u64,
    epochs: usize,
    sarcos_dir: &Path,
) -> Result<(Samples, LwprConfig)> {
    match set {
        Set::Cross2 => {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            cross(
                cross_config(),
                &cross_train(&mut rng, 500),
                &cross_grid(),
                epochs,
                seed,
            )
        }
        Set::Cross21 => {
            let (train, test, _) = cross_nd_data(seed, 21, Embedding::Rotation);
            cross(cross21_config(), &train, &test, epochs, seed)
        }
        Set::Sarcos7 => sarcos(sarcos_dir, epochs, seed),
    }
}
