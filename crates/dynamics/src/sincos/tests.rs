//! The vectorised sine and cosine against the standard library's, and its copies against each
//! other.

use super::*;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// How many doubles lie between `a` and `b` (0: the same value; `±0` count as one).
fn ulps_apart(a: f64, b: f64) -> u64 {
    let key = |x: f64| {
        let bits = x.to_bits() as i64;
        if bits < 0 {
            -(bits & i64::MAX)
        } else {
            bits
        }
    };
    key(a).abs_diff(key(b))
}

/// Angles of every kind the joints see and beyond: uniform on growing ranges, log-uniform
/// magnitudes up to the end of the reduced range, the doubles next to `k π/2`, tiny ones.
fn angles(count: usize, seed: u64) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut out = vec![
        0.0,
        -0.0,
        1e-300,
        -5e-324,
        f64::MIN_POSITIVE,
        1e-9,
        MAX_ANGLE,
        -MAX_ANGLE,
    ];
    for k in 0..count {
        let x = match k % 5 {
            0 => rng.random_range(-1.0..1.0) * std::f64::consts::FRAC_PI_4,
            1 => rng.random_range(-10.0..10.0),
            2 => rng.random_range(-1e3..1e3),
            3 => rng.random_range(-1.0..1.0) * 10f64.powf(rng.random_range(-20.0..6.0)),
            _ => {
                // A double within a few steps of k π/2 (the most cancellation in the reduction).
                let m = rng.random_range(0..600_000) as f64 * std::f64::consts::FRAC_PI_2;
                let step = rng.random_range(-4i64..=4);
                f64::from_bits((m.to_bits() as i64 + step) as u64)
            }
        };
        out.push(x.clamp(-MAX_ANGLE, MAX_ANGLE));
    }
    out
}

/// The largest distance to the standard library's `sin` and `cos` in units in the last place.
fn max_ulps(xs: &[f64]) -> (u64, u64) {
    let (mut s_max, mut c_max) = (0, 0);
    for &x in xs {
        let (s, c) = sin_cos(x);
        s_max = s_max.max(ulps_apart(s, x.sin()));
        c_max = c_max.max(ulps_apart(c, x.cos()));
    }
    (s_max, c_max)
}

#[test]
fn within_one_ulp_of_the_standard_library() {
    let (s, c) = max_ulps(&angles(200_000, 1));
    assert!(s <= 1 && c <= 1, "sin {s} ulp, cos {c} ulp");
    assert_eq!(sin_cos(0.0), (0.0, 1.0));
    assert_eq!(sin_cos(-0.0), (0.0, 1.0)); // +0 for −0 (glibc: −0)
}

/// `cargo test --release -p osrl-dynamics sincos -- --ignored --nocapture`: 10⁸ angles.
#[test]
#[ignore = "long: 10^8 angles (about 7 s); .ci/run runs it"]
fn sweep_many_angles() {
    let xs = angles(100_000_000, 2);
    let (s, c) = max_ulps(&xs);
    let exact = xs
        .iter()
        .filter(|&&x| sin_cos(x) == (x.sin(), x.cos()))
        .count();
    println!(
        "{} angles: max sin {s} ulp, cos {c} ulp; both equal to std for {exact}",
        xs.len()
    );
    assert!(s <= 1 && c <= 1);
}

#[test]
fn large_and_non_finite_angles_take_the_standard_library() {
    for x in [
        1.0e6 + 1.0,
        -3.0e7,
        1e300,
        f64::MAX,
        f64::INFINITY,
        f64::NAN,
    ] {
        let (s, c) = sin_cos(x);
        assert_eq!(
            (s.to_bits(), c.to_bits()),
            (x.sin().to_bits(), x.cos().to_bits()),
            "{x}"
        );
    }
}

/// The AVX2 lanes (where the CPU has them; the standard library's for a lane out of range)
/// give the bits of the `f64` copy of the kernel, for any number of angles.
#[test]
fn every_copy_gives_the_same_bits() {
    let mut xs = angles(40_000, 3);
    xs.extend([
        2e6,
        f64::NAN,
        0.5,
        -0.25,
        1e300,
        3.0,
        -0.0,
        7.0,
        f64::NEG_INFINITY,
    ]);
    let (mut s, mut c) = (vec![0.0; xs.len() + 4], vec![0.0; xs.len() + 4]);
    let mut start = 0;
    for len in (1..=9).cycle() {
        let q = &xs[start..(start + len).min(xs.len())];
        sin_cos_slices(q, &mut s, &mut c);
        for (i, &x) in q.iter().enumerate() {
            let (ws, wc) = sin_cos_f64(x);
            assert_eq!(
                (s[i].to_bits(), c[i].to_bits()),
                (ws.to_bits(), wc.to_bits()),
                "{x}"
            );
            assert_eq!(sin_cos(x).0.to_bits(), ws.to_bits());
        }
        start += len;
        if start >= xs.len() {
            break;
        }
    }
}
