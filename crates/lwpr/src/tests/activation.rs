//! The 2-D activation pass four RFs at a time (`fast::plane_quad::for_each_q`) against the
//! distance of one RF (`distance::quad`), bit for bit, for every count of RFs up to 13 (whole blocks of
//! four and every remainder), with and without AVX2; and the selection of the RFs to update
//! and of the two nearest (`update::activation::Top2`) against a direct computation.

use crate::distance::quad;
use crate::fast::plane_quad::for_each_q;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// `(i, q)` in the order `for_each_q` visits them, and the RFs it computed four at a time.
fn visits<const AVX: bool>(centers: &[f64], ms: &[f64], x: &[f64]) -> (Vec<(usize, u64)>, usize) {
    let mut out = Vec::new();
    let blocks = for_each_q::<AVX>(centers, ms, x, |i, q| out.push((i, q.to_bits())));
    (out, blocks)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn visits_avx2(centers: &[f64], ms: &[f64], x: &[f64]) -> (Vec<(usize, u64)>, usize) {
    visits::<true>(centers, ms, x)
}

/// A value drawn from a mix of scales, with zeros of both signs. (A sign of zero cannot show
/// in `q`, every sum ends squared; the test guards the lanes' order and elements, with a
/// random lower element of `M` that must be ignored, and would catch a fused multiply-add.)
pub(crate) fn draw(rng: &mut ChaCha8Rng) -> f64 {
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
                (
                    i,
                    quad(false, false, c, m, &x, &mut dx, f64::INFINITY).to_bits(),
                )
            })
            .collect();
        assert_eq!(
            visits::<false>(&centers, &ms, &x),
            (want.clone(), 0),
            "scalar, {n} RFs"
        );
        #[cfg(target_arch = "x86_64")]
        if crate::fast::has_avx2() {
            // SAFETY: the CPU supports AVX2 (checked above).
            let (got, blocks) = unsafe { visits_avx2(&centers, &ms, &x) };
            assert_eq!(got, want, "AVX2, {n} RFs");
            assert_eq!(blocks, 4 * (n / 4), "RFs four at a time of {n}");
            checked_avx = true;
        }
    }
    #[cfg(target_arch = "x86_64")]
    if crate::fast::has_avx2() {
        assert!(checked_avx);
    }
}

/// `Top2` against a direct computation: the RFs to update (activation above `W_UPDATE`, in
/// order) and the two nearest by a stable sort (the first visited wins a tie), with their
/// activations only where `q < qb`. Distances from a small set, so that ties are common, with
/// `∞` and NaN (never nearest).
#[test]
fn top2_keeps_the_two_nearest_and_the_active_rfs() {
    use crate::params::W_UPDATE;
    use crate::update::activation::Top2;
    let p = crate::config::LwprConfig::default().validate(2, 1).unwrap();
    let qb = p.q_bound(W_UPDATE);
    let pool = [
        0.0,
        0.5,
        0.5,
        1.0,
        3.0,
        qb,
        qb + 1.0,
        f64::INFINITY,
        f64::NAN,
    ];
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for trial in 0..500 {
        let n = trial % 9;
        let qs: Vec<f64> = (0..n)
            .map(|_| pool[rng.random_range(0..pool.len())])
            .collect();
        let (mut top, mut active) = (Top2::new(), Vec::new());
        for (i, &q) in qs.iter().enumerate() {
            top.visit(&p, qb, i, q, &mut active);
        }
        let want_active: Vec<_> = (qs.iter().enumerate())
            .filter(|&(_, &q)| q < qb && p.kernel(q).0 > W_UPDATE)
            .map(|(i, &q)| {
                let (w, dw, ddw) = p.kernel(q);
                (i, w, dw, ddw)
            })
            .collect();
        assert_eq!(active, want_active, "{qs:?}");
        let mut order: Vec<usize> = (0..n).filter(|&i| qs[i] < f64::INFINITY).collect();
        order.sort_by(|&a, &b| qs[a].total_cmp(&qs[b]));
        let w = |i: usize| (qs[i] < qb).then(|| p.kernel(qs[i]).0);
        let (i1, i2) = (order.first().copied(), order.get(1).copied());
        assert_eq!(top.i1, i1.unwrap_or(usize::MAX), "{qs:?}");
        assert_eq!(top.i2, i2.unwrap_or(usize::MAX), "{qs:?}");
        assert_eq!(top.w1, i1.and_then(w), "{qs:?}");
        assert_eq!(top.w2, i2.and_then(w), "{qs:?}");
        let q = |i: Option<usize>| i.map_or(f64::INFINITY, |i| qs[i]);
        assert_eq!((top.q1, top.q2), (q(i1), q(i2)), "{qs:?}");
    }
}
