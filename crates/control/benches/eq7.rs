//! Time per eq. 7 command for sarcos7 (target < 5 µs): the whole command (dynamics of the
//! controller's model, eq. 2, u0, eq. 7) and, for reference, the dynamics call alone.

use criterion::{criterion_group, criterion_main, Criterion};
use osrl_control::{Law, MetricKind, Osc, OscConfig, TaskController, TrajectoryConfig};
use osrl_dynamics::{compute_all, robots, Robot, SimConfig, SimRobot};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let model = robots::sarcos7();
    let traj = TrajectoryConfig::default().build(&model).unwrap();
    let mut sim = SimRobot::new(model.clone(), SimConfig::default()).unwrap();
    let q: Vec<f64> = model.spec().q_start.clone();
    let qd = vec![0.3, -0.2, 0.1, 0.4, -0.5, 0.2, 0.1];
    sim.reset(&q, &qd).unwrap();
    let meas = sim.measurement().clone();
    let target = traj.sample(1.7);
    let mut u = vec![0.0; 7];
    for (name, law, metric) in [
        (
            "eq7_identity_command_sarcos7",
            Law::Eq7,
            MetricKind::Identity,
        ),
        ("eq7_mass_command_sarcos7", Law::Eq7, MetricKind::Mass),
        ("eq4_command_sarcos7", Law::Eq4, MetricKind::Identity),
    ] {
        let cfg = OscConfig {
            law,
            metric,
            ..OscConfig::default()
        };
        let mut osc = Osc::new(model.clone(), cfg).unwrap();
        c.bench_function(name, |b| {
            b.iter(|| {
                osc.command(black_box(&meas), black_box(&target), &mut u)
                    .unwrap();
                black_box(&u);
            })
        });
    }
    let mut data = model.data();
    c.bench_function("compute_all_sarcos7", |b| {
        b.iter(|| compute_all(&model, &mut data, black_box(&q), black_box(&qd)).unwrap())
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
