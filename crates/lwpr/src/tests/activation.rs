//! The 2-D activation pass four RFs at a time (`activation::for_each_q`) against the distance of
//! one RF (`scratch::quad`), bit for bit, for every count of RFs up to 13 (whole blocks of
//! four and every remainder), with and without AVX2.

use crate::activation::for_each_q;
use crate::scratch::quad;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// `(i, q)` in the order `for_each_q` visits them.
fn visits<const AVX: bool>(centers: &[f64], ms: &[f64], x: &[f64]) -> Vec<(usize, u64)> {
    let mut out = Vec::new();
    for_each_q::<AVX>(centers, ms, x, |i, q| out.push((i, q.to_bits())));
    out
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn visits_avx2(centers: &[f64], ms: &[f64], x: &[f64]) -> Vec<(usize, u64)> {
    visits::<true>(centers, ms, x)
}

/// A value drawn from a mix of scales and signed zeros (the cases where an operation order
/// or a dropped `0.0 +` would show in the bits).
fn draw(rng: &mut ChaCha8Rng) -> f64 {
    match rng.random_range(0..6) {
        0 => 0.0,
        1 => -0.0,
        2 => rng.random_range(-1e-3..1e-3),
        3 => rng.random_range(-1e3..1e3),
        _ => rng.random_range(-2.0..2.0),
    }
}

#[test]
fn four_at_a_time_gives_the_bits_of_one_at_a_time() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut checked_avx = false;
    for trial in 0..200 {
        let n = trial % 14;
        let centers: Vec<f64> = (0..2 * n).map(|_| draw(&mut rng)).collect();
        // Row-major upper-triangular `M`: the lower element is 0 in a model, but any value
        // there must be ignored.
        let ms: Vec<f64> = (0..4 * n).map(|_| draw(&mut rng)).collect();
        let x = [draw(&mut rng), draw(&mut rng)];
        let mut dx = [0.0; 2];
        let want: Vec<(usize, u64)> = (0..n)
            .map(|i| {
                let (c, m) = (&centers[2 * i..2 * i + 2], &ms[4 * i..4 * i + 4]);
                (i, quad(false, c, m, &x, &mut dx, f64::INFINITY).to_bits())
            })
            .collect();
        assert_eq!(visits::<false>(&centers, &ms, &x), want, "scalar, {n} RFs");
        #[cfg(target_arch = "x86_64")]
        if crate::simd::has_avx2() {
            // SAFETY: the CPU supports AVX2 (checked above).
            let got = unsafe { visits_avx2(&centers, &ms, &x) };
            assert_eq!(got, want, "AVX2, {n} RFs");
            checked_avx = true;
        }
    }
    #[cfg(target_arch = "x86_64")]
    if crate::simd::has_avx2() {
        assert!(checked_avx);
    }
}
