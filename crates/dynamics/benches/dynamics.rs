//! Time per call of the dynamics algorithms and of one simulated control period, for `sarcos7`
//! and `planar3`. Run: `cargo bench -p osrl-dynamics --bench dynamics`. Pinocchio's figures for
//! the same calls: `scripts/bench_pinocchio.py` (and `scripts/bench_pinocchio_cpp.sh` for C++).

use criterion::{criterion_group, criterion_main, Criterion};
use osrl_dynamics::{aba, compute_all, crba, jacobian, rnea, robots, Robot, SimConfig, SimRobot};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    for model in [robots::sarcos7(), robots::planar3()] {
        let n = model.nq();
        let name = model.name().to_string();
        let mut data = model.data();
        let q: Vec<f64> = (0..n).map(|i| 0.1 * i as f64 + 0.2).collect();
        let qd: Vec<f64> = (0..n).map(|i| 0.3 - 0.05 * i as f64).collect();
        let qdd: Vec<f64> = (0..n).map(|i| 0.5 + 0.1 * i as f64).collect();
        c.bench_function(&format!("{name}/fk_jacobian"), |b| {
            b.iter(|| jacobian(&model, &mut data, black_box(&q)).unwrap())
        });
        c.bench_function(&format!("{name}/rnea"), |b| {
            b.iter(|| {
                rnea(&model, &mut data, black_box(&q), &qd, &qdd)
                    .map(|t| t[0])
                    .unwrap()
            })
        });
        c.bench_function(&format!("{name}/crba"), |b| {
            b.iter(|| {
                crba(&model, &mut data, black_box(&q))
                    .map(|m| m[(0, 0)])
                    .unwrap()
            })
        });
        c.bench_function(&format!("{name}/aba"), |b| {
            b.iter(|| {
                aba(&model, &mut data, black_box(&q), &qd, &qdd)
                    .map(|a| a[0])
                    .unwrap()
            })
        });
        c.bench_function(&format!("{name}/compute_all"), |b| {
            b.iter(|| compute_all(&model, &mut data, black_box(&q), &qd).unwrap())
        });
        let mut sim = SimRobot::new(model.clone(), SimConfig::default()).unwrap();
        let u = model.spec().q_start.iter().map(|_| 0.0).collect::<Vec<_>>();
        c.bench_function(&format!("{name}/sim_control_period"), |b| {
            b.iter(|| {
                if sim.step(black_box(&u)).is_err() || sim.time() > 1.0 {
                    let q0 = model.spec().q_start.clone();
                    sim.reset(&q0, &vec![0.0; n]).unwrap();
                }
            })
        });
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().warm_up_time(std::time::Duration::from_millis(500)).measurement_time(std::time::Duration::from_secs(2));
    targets = bench
}
criterion_main!(benches);
