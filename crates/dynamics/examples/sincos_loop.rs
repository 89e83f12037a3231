//! The 7 joint sines and cosines of a `sarcos7` call, alone (issue 31):
//! `sincos::sin_cos_slices` against 7 calls of the standard library's `sin_cos`, best ns per
//! call of 300 × 2,000.
//! `cargo run --release -p osrl-dynamics --example sincos_loop`

use osrl_dynamics::sincos::sin_cos_slices;
use std::hint::black_box;

fn best(mut f: impl FnMut()) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..300 {
        let t0 = std::time::Instant::now();
        for _ in 0..2000 {
            f();
        }
        best = best.min(t0.elapsed().as_nanos() as f64 / 2000.0);
    }
    best
}

fn main() {
    let q: Vec<f64> = (0..7).map(|i| 0.1 * i as f64 + 0.2).collect();
    let (mut s, mut c) = ([0.0; 8], [0.0; 8]);
    let libm = best(|| {
        for &x in black_box(&q) {
            black_box(x.sin_cos());
        }
    });
    let lanes = best(|| {
        sin_cos_slices(black_box(&q), &mut s, &mut c);
        black_box((&s, &c));
    });
    println!("7 angles: std sin_cos {libm:.1} ns, sincos::sin_cos_slices {lanes:.1} ns");
}
