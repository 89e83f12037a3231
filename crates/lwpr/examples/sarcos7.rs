//! Robot inverse-dynamics benchmark (issue 4): inputs `[q, q̇, q̈]` (21-D), outputs the 7 joint
//! torques `τ` of the SARCOS master arm (`osrl_dynamics::robots::sarcos7`, by RNEA), sampled at
//! 100 Hz along random smooth trajectories: per joint a sum of three sinusoids (0.1–0.6 Hz, random
//! phases) staying within 80 % of the joint range. As in the SARCOS data set, a random 10 % of
//! the samples is held out for testing (never trained on). Diagonal metric, one model per
//! output (the reference library's layout), inputs and outputs normalised by the training
//! data's standard deviation.
//!
//! `cargo run -p lwpr --release --example sarcos7 -- [--traj 10] [--seconds 5] [--epochs 3]
//! [--init-d 0.05] [--alpha 250] [--meta 1] [--seed 0]`
//!
//! Prints one JSON object: RFs (total and per output), µs per update and per predict (mean over
//! all calls of the whole 7-output model), nMSE per output on the test trajectories.

use lwpr::{Lwpr, LwprConfig, MetricInit, Norm, NormKeyword};
use osrl_dynamics::{rnea, robots};
use rand::seq::SliceRandom;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;
use std::time::Instant;

/// Samples `(x, τ)` along one random trajectory of `seconds` at 100 Hz.
fn trajectory(rng: &mut ChaCha8Rng, seconds: f64, xs: &mut Vec<Vec<f64>>, ys: &mut Vec<Vec<f64>>) {
    let model = robots::sarcos7();
    let mut data = model.data();
    let n = model.nq();
    let (lo, hi): (Vec<f64>, Vec<f64>) = (model.q_min().collect(), model.q_max().collect());
    // Per joint: centre, and three (amplitude, ω, phase).
    let mut waves = Vec::new();
    for i in 0..n {
        let (a, b) = if lo[i].is_finite() && hi[i].is_finite() {
            (lo[i], hi[i])
        } else {
            (-PI, PI)
        };
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        let r: [f64; 3] = std::array::from_fn(|_| rng.random_range(0.2..1.0));
        let sum: f64 = r.iter().sum();
        let w: [(f64, f64, f64); 3] = std::array::from_fn(|k| {
            (
                0.8 * half * r[k] / sum,
                2.0 * PI * rng.random_range(0.1..0.6),
                rng.random_range(0.0..2.0 * PI),
            )
        });
        waves.push((mid, w));
    }
    let (mut q, mut qd, mut qdd) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let steps = (seconds * 100.0) as usize;
    for s in 0..steps {
        let t = s as f64 * 0.01;
        for (i, (mid, w)) in waves.iter().enumerate() {
            q[i] = *mid;
            qd[i] = 0.0;
            qdd[i] = 0.0;
            for &(amp, om, ph) in w {
                q[i] += amp * (om * t + ph).sin();
                qd[i] += amp * om * (om * t + ph).cos();
                qdd[i] -= amp * om * om * (om * t + ph).sin();
            }
        }
        let tau = rnea(&model, &mut data, &q, &qd, &qdd).expect("finite trajectory");
        xs.push([q.as_slice(), &qd, &qdd].concat());
        ys.push(tau.iter().copied().collect());
    }
}

fn std_dev(rows: &[Vec<f64>]) -> Vec<f64> {
    let (n, d) = (rows.len() as f64, rows[0].len());
    (0..d)
        .map(|j| {
            let m = rows.iter().map(|r| r[j]).sum::<f64>() / n;
            (rows.iter().map(|r| (r[j] - m).powi(2)).sum::<f64>() / n).sqrt()
        })
        .collect()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let get = |k: &str, d: f64| {
        args.iter()
            .position(|a| a == k)
            .map(|i| args[i + 1].parse().expect("a number"))
            .unwrap_or(d)
    };
    let n_traj = get("--traj", 10.0) as usize;
    let (seconds, epochs) = (get("--seconds", 5.0), get("--epochs", 3.0) as usize);
    let seed = get("--seed", 0.0) as u64;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (mut xs, mut ys) = (vec![], vec![]);
    for _ in 0..n_traj {
        trajectory(&mut rng, seconds, &mut xs, &mut ys);
    }
    let mut idx: Vec<usize> = (0..xs.len()).collect();
    idx.shuffle(&mut rng);
    let n_test = xs.len() / 10;
    let pick = |ii: &[usize], v: &[Vec<f64>]| ii.iter().map(|&i| v[i].clone()).collect::<Vec<_>>();
    let (xte, yte) = (pick(&idx[..n_test], &xs), pick(&idx[..n_test], &ys));
    let (xtr, ytr) = (pick(&idx[n_test..], &xs), pick(&idx[n_test..], &ys));
    let mut cfg = LwprConfig {
        init_d: MetricInit::Scalar(get("--init-d", 0.05)),
        init_alpha: get("--alpha", 250.0),
        w_gen: 0.2,
        meta: get("--meta", 1.0) != 0.0,
        diag_only: true,
        norm_in: Norm::Keyword(NormKeyword::Std),
        norm_out: Norm::Keyword(NormKeyword::Std),
        ..Default::default()
    };
    cfg.resolve_std(&std_dev(&xtr), &std_dev(&ytr));
    let mut m = Lwpr::new(21, 7, &cfg).expect("valid config");
    let mut order: Vec<usize> = (0..xtr.len()).collect();
    let mut upd_s = 0.0;
    for _ in 0..epochs {
        order.shuffle(&mut rng);
        let t0 = Instant::now();
        for &i in &order {
            m.update(&xtr[i], &ytr[i]).expect("finite sample");
        }
        upd_s += t0.elapsed().as_secs_f64();
    }
    let n_upd = (epochs * xtr.len()) as f64;
    let mut yp = vec![0.0; 7];
    let mut sup = vec![0.0; 7];
    let mut se = [0.0; 7];
    let t1 = Instant::now();
    for (x, y) in xte.iter().zip(&yte) {
        m.predict_with_support(x, &mut yp, &mut sup)
            .expect("finite input");
        for o in 0..7 {
            se[o] += (yp[o] - y[o]).powi(2);
        }
    }
    let pred_us = t1.elapsed().as_secs_f64() * 1e6 / xte.len() as f64;
    let sd = std_dev(&yte);
    let nmse: Vec<f64> = (0..7)
        .map(|o| (se[o] / xte.len() as f64 / (sd[o] * sd[o]) * 1e4).round() / 1e4)
        .collect();
    println!(
        "{{\"test\":\"sarcos7_invdyn\",\"train\":{},\"test_n\":{},\"epochs\":{epochs},\"n_rfs\":{},\"n_rfs_per_output\":{:?},\"update_us\":{:.2},\"predict_us\":{:.2},\"nmse_mean\":{:.4},\"nmse\":{:?}}}",
        xtr.len(),
        xte.len(),
        m.n_rfs_total(),
        m.n_rfs(),
        upd_s * 1e6 / n_upd,
        pred_us,
        nmse.iter().sum::<f64>() / 7.0,
        nmse
    );
}
