//! Where the 21-D cross test's rotation acts: the same samples, config and seeds with and
//! without the random rotation (`datasets::Embedding`), and what the learned metrics and the
//! meta-learned rates look like after training.
//!
//! Per embedding and seed it prints one JSON line, then one line of medians over the seeds:
//! - `nmse`, `n_rfs`: as `osrl bench lwpr --only cross21 --cross21-embedding …`;
//! - `d_plane_lo`, `d_plane_hi`: eigenvalues of the metric restricted to the data's plane
//!   (`PᵀDP`, `P` the plane's basis: the first two columns of the embedding), medians over the
//!   RFs: how narrow the RFs are where the data is;
//! - `d_off_plane`: `tr D − tr PᵀDP`, median over the RFs: metric outside the plane, which no
//!   sample or test point can see (a fresh RF has 19 · 0.25 = 4.75);
//! - `rates_grown`: per RF, the elements of `M` whose rate `α` (`RfView::learning_rates`)
//!   meta learning raised above 2 · `init_alpha`, median over the RFs; `rate_gain_max`: per RF
//!   the largest `α / init_alpha`, median over the RFs.
//!
//! `cargo run -p lwpr --release --example rotation -- [--seeds N] [--epochs E] [--no-meta]`
//! (10 seeds, 25 epochs: the standard test; `--no-meta` switches meta learning off, the
//! rates then stay at `init_alpha` but for halvings).

use lwpr::datasets::{cross21_config, cross21_data, fit, median, test_nmse, Embedding};
use lwpr::LwprConfig;
use nalgebra::DMatrix;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let get = |k: &str, d: usize| {
        let Some(i) = args.iter().position(|a| a == k) else {
            return d;
        };
        let v = args
            .get(i + 1)
            .unwrap_or_else(|| panic!("{k} needs a value"));
        v.parse()
            .unwrap_or_else(|_| panic!("{k}: not a non-negative integer: {v}"))
    };
    let (seeds, epochs) = (get("--seeds", 10), get("--epochs", 25));
    assert!(
        seeds > 0 && epochs > 0,
        "--seeds and --epochs must be at least 1"
    );
    let cfg = LwprConfig {
        meta: !args.iter().any(|a| a == "--no-meta"),
        ..cross21_config()
    };
    for (name, e) in [
        ("rotation", Embedding::Rotation),
        ("identity", Embedding::Identity),
    ] {
        let mut rows: Vec<[f64; 7]> = vec![];
        for seed in 0..seeds as u64 {
            let (train, test, emb) = cross21_data(seed, e);
            let (mut m, _) = fit(&cfg, &train, epochs, seed).expect("the standard config fits");
            let nmse = test_nmse(&mut m, &test).expect("test inputs fit the model");
            let plane = emb.columns(0, 2).into_owned();
            let (mut lo, mut hi, mut off, mut grown, mut gain) =
                (vec![], vec![], vec![], vec![], vec![]);
            for rf in m.rfs(0).expect("one output") {
                let d: DMatrix<f64> = rf.metric();
                let dp = plane.transpose() * &d * &plane;
                let ev = dp.symmetric_eigenvalues();
                lo.push(ev.min());
                hi.push(ev.max());
                off.push(d.trace() - dp.trace());
                let rates = rf.learning_rates();
                let up = rates.iter().filter(|&&a| a > 0.0);
                let g: Vec<f64> = up.map(|a| a / cfg.init_alpha).collect();
                grown.push(g.iter().filter(|&&r| r > 2.0).count() as f64);
                gain.push(g.iter().cloned().fold(0.0, f64::max));
            }
            let row = [
                nmse,
                m.n_rfs_total() as f64,
                median(lo),
                median(hi),
                median(off),
                median(grown),
                median(gain),
            ];
            println!(
                "{{\"embedding\":\"{name}\",\"seed\":{seed},\"nmse\":{:.4},\"n_rfs\":{},\
                 \"d_plane_lo\":{:.1},\"d_plane_hi\":{:.1},\"d_off_plane\":{:.4},\
                 \"rates_grown\":{},\"rate_gain_max\":{:.2}}}",
                row[0], row[1], row[2], row[3], row[4], row[5], row[6]
            );
            rows.push(row);
        }
        let med = |k: usize| median(rows.iter().map(|r| r[k]).collect());
        println!(
            "{{\"embedding\":\"{name}\",\"seeds\":{seeds},\"epochs\":{epochs},\"median\":{{\
             \"nmse\":{:.4},\"n_rfs\":{},\"d_plane_lo\":{:.1},\"d_plane_hi\":{:.1},\
             \"d_off_plane\":{:.4},\"rates_grown\":{},\"rate_gain_max\":{:.2}}}}}",
            med(0),
            med(1),
            med(2),
            med(3),
            med(4),
            med(5),
            med(6)
        );
    }
}
