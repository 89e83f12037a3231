//! The full-metric step above 4 dimensions (`fast::wide::wide_step`) against the fused step
//! (`fast::fused`) (itself bit-identical to the separate derivatives and step): the same
//! maths with other roundings, so equal to a relative 1e-12; its AVX2+FMA and baseline copies
//! bit-identical; its exponential within an ulp of `f64::exp`.

use super::fused::case;
use crate::fast::fused::full_step;

/// Runs the reference and the wide step on the same case; returns both results
/// `[M, D, α, b, h]`.
fn both(nk: usize, meta: bool, seed: u64) -> ([Vec<f64>; 5], [Vec<f64>; 5]) {
    let c = case(nk, meta, seed);
    let (p, acc, dwdq, ddwdqdq) = (&c.p, c.acc, c.dwdq, c.ddwdqdq);
    let mut r = [
        c.m.clone(),
        c.d.clone(),
        c.alpha.clone(),
        c.b.clone(),
        c.hm.clone(),
    ];
    let mut w = r.clone();
    let mut ws1 = c.ws.clone();
    let [m1, d1, a1, b1, h1] = &mut r;
    full_step(nk, p, m1, d1, a1, b1, h1, acc, dwdq, ddwdqdq, &mut ws1);
    let mut ws2 = c.ws.clone();
    // The step must not depend on what its scratch held before.
    ws2.wide.fill(f64::NAN);
    let [m2, d2, a2, b2, h2] = &mut w;
    crate::fast::wide::wide_step::<0, false>(
        nk, p, m2, d2, a2, b2, h2, acc, dwdq, ddwdqdq, &mut ws2,
    );
    (r, w)
}

#[test]
fn wide_step_matches_the_fused_step() {
    for nk in [5, 6, 7, 8, 9, 13, 21, 37] {
        for meta in [false, true] {
            for seed in 0..3 {
                let before = case(nk, meta, seed);
                let (r, w) = both(nk, meta, seed);
                let names = ["M", "D", "alpha", "b", "h"];
                for (k, name) in names.iter().enumerate() {
                    let scale = r[k].iter().fold(0.0f64, |a, v| a.max(v.abs()));
                    let orig = [&before.m, &before.d, &before.alpha, &before.b, &before.hm];
                    for i in 0..nk * nk {
                        let (row, col) = (i / nk, i % nk);
                        let (x, y) = (r[k][i], w[k][i]);
                        if *name != "D" && col < row {
                            // Below the diagonal: M stays zero, the rest untouched.
                            assert_eq!(y.to_bits(), orig[k][i].to_bits(), "{name}[{row},{col}]");
                            continue;
                        }
                        // Relative to the result, or to the value before the step where the step
                        // cancels it (then the rounding of the inputs dominates).
                        let tol = 1e-12 * x.abs().max(orig[k][i].abs()).max(1e-6 * scale);
                        assert!(
                            (x - y).abs() <= tol,
                            "{name}[{row},{col}] nk {nk} meta {meta} seed {seed}: {x:e} vs {y:e}"
                        );
                    }
                }
                // D = MᵀM comes out exactly symmetric.
                for i in 0..nk {
                    for j in 0..i {
                        assert_eq!(w[1][i * nk + j], w[1][j * nk + i], "D[{i},{j}]");
                    }
                }
                // The step did something (the test is not vacuous).
                assert!(r[0] != before.m, "nk {nk}: M unchanged");
            }
        }
    }
}

#[cfg(target_arch = "x86_64")]
#[test]
fn wide_step_copies_give_the_same_bits() {
    if !crate::fast::has_avx2() {
        return;
    }
    for nk in [5, 9, 21, 37] {
        for meta in [false, true] {
            let c = case(nk, meta, 7);
            let run = |avx: bool| {
                let mut c = case(nk, meta, 7);
                let (p, acc, dwdq, ddwdqdq) = (&c.p, c.acc, c.dwdq, c.ddwdqdq);
                let (m, d, a, b, h) = (&mut c.m, &mut c.d, &mut c.alpha, &mut c.b, &mut c.hm);
                if avx {
                    // SAFETY: the CPU has AVX2 and FMA (checked above).
                    unsafe {
                        crate::fast::wide_avx2::<0>(
                            nk, p, m, d, a, b, h, acc, dwdq, ddwdqdq, &mut c.ws,
                        )
                    }
                } else {
                    crate::fast::wide_base::<0>(nk, p, m, d, a, b, h, acc, dwdq, ddwdqdq, &mut c.ws)
                }
                [c.m, c.d, c.alpha, c.b, c.hm]
            };
            let (x, y) = (run(true), run(false));
            assert!(x[0] != c.m);
            for k in 0..5 {
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&x[k]), bits(&y[k]), "array {k}, nk {nk}, meta {meta}");
            }
        }
    }
}

#[test]
fn exp4_is_accurate() {
    let mut worst: f64 = 0.0;
    let n = 100_000;
    for i in 0..=n {
        let x = -10.0 + 20.0 * i as f64 / n as f64;
        let v = crate::fast::lanes::exp4([x, -x, 0.5 * x, x + 1e-9]);
        for (l, t) in [x, -x, 0.5 * x, x + 1e-9].into_iter().enumerate() {
            worst = worst.max(((v[l] - t.exp()) / t.exp()).abs());
        }
    }
    assert_eq!(crate::fast::lanes::exp4([0.0; 4]), [1.0; 4]);
    assert!(worst < 3e-16, "relative error {worst:e}");
}

#[cfg(target_arch = "x86_64")]
#[test]
fn lane_sums_and_maxima_on_avx2_give_the_same_bits() {
    use crate::fast::lanes::{hsum, max_abs0};
    if !crate::fast::has_avx2() {
        return;
    }
    let specials = [
        0.0,
        -0.0,
        1.5,
        -2.5,
        f64::NAN,
        f64::INFINITY,
        -1e-300,
        3e300,
    ];
    let mut v = Vec::new();
    for i in 0..40 {
        // SAFETY (the calls below): the CPU has AVX2 (checked above).
        let (a, b) = (max_abs0::<true>(&v), max_abs0::<false>(&v));
        assert_eq!(a.to_bits(), b.to_bits(), "max over {i} values");
        v.push(specials[(i * 5) % specials.len()] * (1.0 + i as f64));
    }
    for i in 0..200 {
        let l = std::array::from_fn(|j| specials[(i * 3 + j * 7 + i / 8) % 6] + (i * j) as f64);
        assert_eq!(
            hsum::<true>(l).to_bits(),
            hsum::<false>(l).to_bits(),
            "{l:?}"
        );
    }
}
