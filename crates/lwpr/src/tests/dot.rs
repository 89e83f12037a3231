//! The AVX2 row sums of the full-metric distance (`fast::dot::dot_avx2`) against
//! `numeric::dot`, and `distance::quad` with and without them, bit for bit.

use crate::distance::quad;
use crate::numeric::dot;
use crate::tests::activation::draw;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

#[cfg(target_arch = "x86_64")]
#[test]
fn dot_avx2_gives_the_bits_of_dot() {
    if !crate::fast::has_avx2() {
        return;
    }
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for trial in 0..2000 {
        // Every length up to 40 (whole groups of four and each remainder), unequal lengths too.
        let (na, nb) = (trial % 41, trial % 41 + trial % 3);
        let a: Vec<f64> = (0..na).map(|_| draw(&mut rng)).collect();
        let b: Vec<f64> = (0..nb).map(|_| draw(&mut rng)).collect();
        // SAFETY: the CPU has AVX2 (checked above).
        let got = unsafe { crate::fast::dot::dot_avx2(&a, &b) };
        assert_eq!(got.to_bits(), dot(&a, &b).to_bits(), "lengths {na}, {nb}");
    }
    // A sum of exact zeros keeps the sign that `dot` gives it (0 + (−0) = +0).
    let (a, b) = ([-0.0; 5], [1.0; 5]);
    // SAFETY: as above.
    let got = unsafe { crate::fast::dot::dot_avx2(&a, &b) };
    assert_eq!(got.to_bits(), dot(&a, &b).to_bits());
}

#[cfg(target_arch = "x86_64")]
#[test]
fn quad_on_avx2_gives_the_same_bits() {
    if !crate::fast::has_avx2() {
        return;
    }
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    for nk in [5, 6, 7, 8, 9, 14, 21, 22, 37] {
        for _ in 0..50 {
            let c: Vec<f64> = (0..nk).map(|_| draw(&mut rng)).collect();
            let x: Vec<f64> = (0..nk).map(|_| draw(&mut rng)).collect();
            // Upper-triangular rows; the lower elements are never read.
            let m: Vec<f64> = (0..nk * nk).map(|_| draw(&mut rng)).collect();
            let exact = quad(false, false, &c, &m, &x, &mut vec![0.0; nk], f64::INFINITY);
            // Bounds that stop the sum at various rows, and none.
            for bound in [f64::INFINITY, exact, 0.5 * exact, 1e-3 * exact] {
                let mut dx = vec![0.0; nk];
                let want = quad(false, false, &c, &m, &x, &mut dx, bound);
                let got = quad(true, false, &c, &m, &x, &mut dx, bound);
                assert_eq!(got.to_bits(), want.to_bits(), "nk {nk}, bound {bound}");
            }
        }
    }
}
