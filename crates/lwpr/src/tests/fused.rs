//! The fused full-metric step (`fast::fused::full_step`) against the reference's separate
//! derivatives and step (`update::metric_derivatives`, `update::metric_step`): bit-identical
//! results.

use crate::config::{LwprConfig, MetricInit};
use crate::fast::fused::full_step;
use crate::params::Params;
use crate::update::metric::{MetricAcc, MetricScratch};
use crate::update::metric_derivatives::derivatives;
use crate::update::metric_step::{mtm, step};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A random full-metric RF state (`M` upper-triangular with `D = MᵀM`, `α`, `b = ln α`, IDBD
/// memory), sample offset `x − c` in the scratch, output sums and kernel derivatives.
pub(super) struct Case {
    pub p: Params,
    pub m: Vec<f64>,
    pub d: Vec<f64>,
    pub alpha: Vec<f64>,
    pub b: Vec<f64>,
    pub hm: Vec<f64>,
    pub ws: MetricScratch,
    pub acc: MetricAcc,
    pub dwdq: f64,
    pub ddwdqdq: f64,
}

pub(super) fn case(nk: usize, meta: bool, seed: u64) -> Case {
    let cfg = LwprConfig {
        diag_only: false,
        meta,
        penalty: 0.3, // large, so the penalty terms matter
        init_d: MetricInit::Scalar(1.0),
        ..Default::default()
    };
    let p = cfg.validate(nk, 1).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut m = vec![0.0; nk * nk];
    for n in 0..nk {
        for k in n..nk {
            m[n * nk + k] = if k == n {
                rng.random_range(0.5..1.5)
            } else {
                rng.random_range(-0.4..0.4)
            };
        }
    }
    let mut d = vec![0.0; nk * nk];
    let mut ws = MetricScratch::new(nk, nk * nk, crate::fast::wide::scratch_len(nk, nk * nk));
    mtm(nk, &m, &mut d);
    let alpha: Vec<f64> = (0..nk * nk).map(|_| rng.random_range(1.0..300.0)).collect();
    let b: Vec<f64> = alpha.iter().map(|a: &f64| a.ln()).collect();
    let hm: Vec<f64> = (0..nk * nk)
        .map(|_| rng.random_range(-1e-3..1e-3))
        .collect();
    for k in 0..nk {
        ws.dx[k] = rng.random_range(-0.6..0.6);
    }
    let acc = MetricAcc {
        a: 0.3,
        b: rng.random_range(-2.0..2.0),
        c: rng.random_range(-2.0..2.0),
        n: 1,
    };
    Case {
        p,
        m,
        d,
        alpha,
        b,
        hm,
        ws,
        acc,
        dwdq: -0.31,
        ddwdqdq: 0.155,
    }
}

fn check(nk: usize, meta: bool, seed: u64) {
    let Case {
        p,
        m,
        d,
        alpha,
        b,
        hm,
        mut ws,
        acc,
        dwdq,
        ddwdqdq,
    } = case(nk, meta, seed);
    let (mut m1, mut d1, mut a1, mut b1, mut h1) =
        (m.clone(), d.clone(), alpha.clone(), b.clone(), hm.clone());
    let mut ws1 = ws.clone();
    derivatives(
        nk,
        false,
        meta,
        &m1,
        &d1,
        dwdq,
        ddwdqdq,
        p.penalty_n,
        &mut ws1,
    );
    step(
        nk, &p, &mut m1, &mut d1, &mut a1, &mut b1, &mut h1, acc, &mut ws1,
    );
    let (mut m2, mut d2, mut a2, mut b2, mut h2) = (m, d, alpha, b, hm);
    full_step(
        nk, &p, &mut m2, &mut d2, &mut a2, &mut b2, &mut h2, acc, dwdq, ddwdqdq, &mut ws,
    );
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    for (name, x, y) in [
        ("M", &m1, &m2),
        ("D", &d1, &d2),
        ("alpha", &a1, &a2),
        ("b", &b1, &b2),
        ("h", &h1, &h2),
    ] {
        assert_eq!(bits(x), bits(y), "{name}, nk = {nk}, meta = {meta}");
    }
}

#[test]
fn fused_full_step_is_bit_identical_to_derivatives_then_step() {
    for nk in [1, 2, 3, 4, 5, 7, 8, 9, 21] {
        for meta in [false, true] {
            for seed in 0..3 {
                check(nk, meta, seed);
            }
        }
    }
}
