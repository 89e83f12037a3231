//! Time per call with the method of `scripts/bench_pinocchio.cpp` (best of 300 repetitions of
//! 2,000 calls, about a millisecond each, shorter than a scheduler's time slice so that on a
//! loaded machine the best is a run without preemption; same states), so the two can be compared as ratios on a loaded machine:
//! `cargo run --release -p osrl-dynamics --example bench_min` prints one JSON object (ns per call).

use osrl_dynamics::{aba, crba, jacobian, rnea, robots};
use std::hint::black_box;
use std::time::Instant;

fn ns_per_call(mut f: impl FnMut()) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..300 {
        let n = 2_000;
        let t0 = Instant::now();
        for _ in 0..n {
            f();
        }
        best = best.min(t0.elapsed().as_nanos() as f64 / n as f64);
    }
    best
}

fn main() {
    let mut out = Vec::new();
    for model in [robots::sarcos7(), robots::planar3()] {
        let n = model.nq();
        let name = model.name().to_string();
        let mut data = model.data();
        let q: Vec<f64> = (0..n).map(|i| 0.1 * i as f64 + 0.2).collect();
        let qd: Vec<f64> = (0..n).map(|i| 0.3 - 0.05 * i as f64).collect();
        let qdd: Vec<f64> = (0..n).map(|i| 0.5 + 0.1 * i as f64).collect();
        let fkj = ns_per_call(|| {
            jacobian(&model, &mut data, black_box(&q)).unwrap();
            black_box(data.jac[(0, 0)]);
        });
        let t = ns_per_call(|| {
            black_box(rnea(&model, &mut data, black_box(&q), &qd, &qdd).unwrap()[0]);
        });
        let m = ns_per_call(|| {
            black_box(crba(&model, &mut data, black_box(&q)).unwrap()[(0, 0)]);
        });
        let a = ns_per_call(|| {
            black_box(aba(&model, &mut data, black_box(&q), &qd, &qdd).unwrap()[0]);
        });
        out.push(format!(
            "\"{name}/fk_jacobian_ns\": {fkj:.1}, \"{name}/rnea_ns\": {t:.1}, \"{name}/crba_ns\": {m:.1}, \"{name}/aba_ns\": {a:.1}"
        ));
    }
    println!("{{{}}}", out.join(", "));
}
