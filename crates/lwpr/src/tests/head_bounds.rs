//! The heads' lower bound of `q` (`head/bound.rs`) against the distance in double precision:
//! one head at ordinary values and where single precision overflows or underflows, heads that
//! share blocks through additions and removals, and the AVX2 bounds against the portable ones.

use super::activation::draw;
use crate::distance::quad;
use crate::head::{self, Heads};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A value of any scale the bound must survive: `draw`'s mix, beyond single precision's
/// range (both ends), and huge or tiny metrics.
fn extreme(rng: &mut ChaCha8Rng) -> f64 {
    match rng.random_range(0..14) {
        0 => 1e39 * rng.random_range(-1.0..1.0),
        1 => 1e-300 * rng.random_range(0.0..1.0),
        2 => 1e300 * rng.random_range(0.0..1.0),
        3 => 3e38,
        6 => 6e29 * rng.random_range(-1.0..1.0),
        // Subnormal in single precision.
        4 => 1e-44 * rng.random_range(0.0..1.0),
        5 => 1e-39 * rng.random_range(-1.0..1.0),
        _ => draw(rng),
    }
}

/// `q` in double precision, as the update computes it, and from the head.
fn both(c: &[f64], d: &[f64], x: &[f64]) -> (f64, f64) {
    let q = quad(false, true, c, d, x, &mut [], f64::INFINITY);
    let mut h = Heads::default();
    h.push(c, d);
    let lb = h.bound(0, &h.probe(x));
    (q, lb)
}

#[test]
fn the_head_bound_lies_below_q() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let (mut huge, mut tight) = (0, 0);
    for trial in 0..20_000 {
        let nk = [9, 16, 21, 33][trial % 4];
        let ordinary = trial % 3 == 0;
        let v = |rng: &mut ChaCha8Rng| {
            if ordinary {
                rng.random_range(-2.0..2.0)
            } else {
                extreme(rng)
            }
        };
        let c: Vec<f64> = (0..nk).map(|_| v(&mut rng)).collect();
        let mut x: Vec<f64> = (0..nk).map(|_| v(&mut rng)).collect();
        // Inputs at the centre, or one rounding away from it, in some dimensions.
        for j in 0..nk {
            match rng.random_range(0..6) {
                0 => x[j] = c[j],
                1 => x[j] = c[j] * (1.0 + f64::EPSILON),
                _ => {}
            }
        }
        // Large inputs a little off large centres: single precision cannot hold `x − c`.
        if trial % 7 == 1 {
            for j in 0..nk {
                x[j] = c[j] + 1e-9 * c[j].abs() * rng.random_range(-1.0..1.0);
            }
        }
        let d: Vec<f64> = (0..nk)
            .map(|_| {
                if ordinary {
                    rng.random_range(0.1..10.0)
                } else {
                    extreme(&mut rng).abs()
                }
            })
            .collect();
        let (q, lb) = both(&c, &d, &x);
        // Where the bound reaches a cutoff, so does `q`: never `lb > q`.
        assert!(
            lb <= q,
            "nk {nk}: bound {lb:e} above q {q:e}\nc {c:?}\nd {d:?}\nx {x:?}"
        );
        huge += usize::from(q > f64::from(f32::MAX));
        if ordinary && trial % 7 != 1 {
            // And it is tight where nothing overflows: within 1 % of the head's own terms.
            let n = nk.min(head::HEAD);
            let (q_head, _) = both(&c[..n], &d[..n], &x[..n]);
            assert!(
                lb >= 0.99 * q_head,
                "nk {nk}: bound {lb} far below {q_head}"
            );
            tight += 1;
        }
    }
    // Both kinds of case were drawn: `q` beyond single precision, and ordinary values.
    assert!(
        huge > 1000 && tight > 5000,
        "{huge} cases of huge q, {tight} ordinary ones"
    );
}

/// Centre and metric rows of `nk` dimensions: ordinary values, or of any scale.
fn rows(rng: &mut ChaCha8Rng, nk: usize, ordinary: bool) -> (Vec<f64>, Vec<f64>) {
    if ordinary {
        let c = (0..nk).map(|_| rng.random_range(-2.0..2.0)).collect();
        let d = (0..nk).map(|_| rng.random_range(0.1..10.0)).collect();
        (c, d)
    } else {
        let c = (0..nk).map(|_| extreme(rng)).collect();
        let d = (0..nk).map(|_| extreme(rng).abs()).collect();
        (c, d)
    }
}

/// An input of `nk` dimensions: ordinary values, or of any scale.
fn input(rng: &mut ChaCha8Rng, nk: usize, ordinary: bool) -> Vec<f64> {
    let v = |rng: &mut ChaCha8Rng| {
        if ordinary {
            rng.random_range(-2.0..2.0)
        } else {
            extreme(rng)
        }
    };
    (0..nk).map(|_| v(rng)).collect()
}

/// Several heads sharing blocks, with removals in between: every head's bound lies below its
/// `q`, the slack set by the heads' largest centre (rescanned when a removal takes it), and
/// the heads equal their rebuild from the rows.
#[test]
fn the_bounds_of_shared_blocks_lie_below_q_after_removals() {
    let mut rng = ChaCha8Rng::seed_from_u64(13);
    let mut positive = 0;
    for trial in 0..300 {
        let nk = [9, 16, 21, 24, 33][trial % 5];
        let ordinary = trial % 2 == 0;
        let (mut h, mut all) = (Heads::default(), Vec::new());
        for _ in 0..rng.random_range(1..40) {
            let (c, d) = rows(&mut rng, nk, ordinary);
            h.push(&c, &d);
            all.push((c, d));
            if rng.random_range(0..4) == 0 {
                let i = rng.random_range(0..all.len());
                h.swap_remove(i);
                all.swap_remove(i);
            }
        }
        let mut fresh = Heads::default();
        all.iter().for_each(|(c, d)| fresh.push(c, d));
        assert!(
            fresh == h,
            "trial {trial}: the heads differ from their rebuild"
        );
        for _ in 0..10 {
            let x = input(&mut rng, nk, ordinary);
            let pr = h.probe(&x);
            for (i, (c, d)) in all.iter().enumerate() {
                let q = quad(false, true, c, d, &x, &mut [], f64::INFINITY);
                let lb = h.bound(i, &pr);
                assert!(
                    lb <= q,
                    "trial {trial}, head {i}: bound {lb:e} above q {q:e}"
                );
                positive += usize::from(lb > 0.0);
            }
        }
    }
    assert!(positive > 10_000, "{positive} positive bounds");
}

#[cfg(target_arch = "x86_64")]
#[test]
fn the_avx2_bounds_are_the_portable_bounds() {
    if !crate::fast::has_avx2() {
        eprintln!("no AVX2 on this CPU: nothing to compare");
        return;
    }
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    let mut positive = 0;
    for trial in 0..400 {
        let nk = [9, 16, 21, 24, 33][trial % 5];
        let ordinary = trial % 2 == 0;
        let mut h = Heads::default();
        for _ in 0..rng.random_range(1..30) {
            let (c, d) = rows(&mut rng, nk, ordinary);
            h.push(&c, &d);
            if h.len() > 1 && rng.random_range(0..5) == 0 {
                h.swap_remove(rng.random_range(0..h.len()));
            }
        }
        for _ in 0..20 {
            let x = input(&mut rng, nk, ordinary);
            let pr = h.probe(&x);
            for b in 0..h.blocks() {
                let bits = |v: [f64; head::LANES]| v.map(f64::to_bits);
                let avx = h.bounds(true, b, &pr);
                assert_eq!(
                    bits(avx),
                    bits(h.bounds(false, b, &pr)),
                    "nk {nk}, block {b}"
                );
                positive += avx.iter().filter(|&&v| v > 0.0).count();
            }
        }
    }
    assert!(positive > 10_000, "{positive} positive bounds");
}
