//! The run-time choice of the AVX2 copies of the hot loops (`Stats::add`, the solve of eq. 23)
//! and of the AVX2 / AVX-512 kernels of `Stats::flush` (`held_x86.rs`).
//!
//! A copy is the same Rust code compiled with AVX2 enabled: four lanes instead of two, the same
//! operations in the same order per element (Rust never fuses a multiply and an add on its
//! own), so the results are the same bits on every x86-64 CPU — tested here and in `held.rs`
//! against the baseline copy. The workspace builds that copy for x86-64-v3 (AVX2 already;
//! `.cargo/config.toml`), so `.ci/run` runs these tests once more on a build for the SSE2
//! baseline (`docs/decisions.md`, D52).

/// Whether the CPU supports AVX2 (cached by the standard library after the first query).
#[cfg(target_arch = "x86_64")]
#[inline]
pub(crate) fn avx2() -> bool {
    std::arch::is_x86_feature_detected!("avx2")
}

/// Whether the CPU supports AVX-512F (eight lanes; cached like [`avx2`]).
#[cfg(target_arch = "x86_64")]
#[inline]
pub(crate) fn avx512() -> bool {
    std::arch::is_x86_feature_detected!("avx512f")
}

/// The AVX2 mask selecting the first `n` (0..=4) of four lanes.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(crate) unsafe fn mask4(n: usize) -> std::arch::x86_64::__m256i {
    const MASK: [[i64; 4]; 5] = [
        [0, 0, 0, 0],
        [-1, 0, 0, 0],
        [-1, -1, 0, 0],
        [-1, -1, -1, 0],
        [-1, -1, -1, -1],
    ];
    std::arch::x86_64::_mm256_loadu_si256(MASK[n].as_ptr().cast())
}

/// `body` for `$g` = 0, 1, …, 7: literal indices, so the accumulators stay in registers.
macro_rules! unroll {
    ($g:ident => $body:block) => {{
                unroll!(@ $g $body 0 1 2 3 4 5 6 7)
    }};
    (@ $g:ident $body:block $($i:literal)*) => {{
        $({
            let $g: usize = $i;
            $body
        })*
    }};
}

pub(crate) use unroll;

#[cfg(test)]
mod tests {
    use crate::stats::{Solver, Stats};
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The dispatched calls (AVX2 where the CPU has it) give the baseline copy's bits: the
    /// statistics after many samples and the solve, at the learner's sizes (18 and 71 features).
    #[test]
    fn the_avx2_copies_give_the_baseline_bits() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for (p, d) in [(18, 7), (71, 3), (5, 2)] {
            let (mut a, mut b) = (Stats::new(p, d), Stats::new(p, d));
            for _ in 0..300 {
                let phi: Vec<f64> = (0..p).map(|_| rng.random_range(-2.0..2.0)).collect();
                let u: Vec<f64> = (0..d).map(|_| rng.random_range(-5.0..5.0)).collect();
                let (w, r) = (rng.random_range(0.0..1.0), rng.random_range(0.0..3.0));
                a.add(w, &phi, &u, r);
                b.add_body(w, &phi, &u, r);
            }
            assert_eq!(a, b, "statistics differ at p = {p}");
            let (mut sa, mut sb) = (Solver::new(p, d), Solver::new(p, d));
            sa.solve_with_prior(&a, 1e-4, None).unwrap();
            sb.solve_body(&b, 1e-4, None).unwrap();
            let (ra, rb) = (sa.residual(&a), sb.residual_body(&b));
            assert_eq!(ra.to_bits(), rb.to_bits());
            assert_eq!(sa.theta, sb.theta, "solutions differ at p = {p}");
        }
    }
}
