//! Time per command of the learned controller (eq. 34 blend, with and without the exploration
//! noise), after a short training on each robot. Run: `cargo bench -p osrl-learn --bench command`.

use criterion::{criterion_group, criterion_main, Criterion};
use osrl_control::{check_reachable, IkOptions, TrajectoryConfig};
use osrl_dynamics::{robots, Robot, SimConfig, SimRobot};
use osrl_learn::train::{train, BabbleConfig, TrainConfig};
use osrl_learn::{Learner, LearnerConfig};
use rand::SeedableRng;
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    for name in ["sarcos7", "planar3"] {
        let model = robots::by_name(name).unwrap();
        let (n, m) = (model.nq(), model.task_dim());
        let traj = TrajectoryConfig::default().build(&model).unwrap();
        let home = check_reachable(&model, &traj, &IkOptions::default())
            .unwrap()
            .q_start;
        let mut sim = SimRobot::new(model.clone(), SimConfig::default()).unwrap();
        sim.reset(&home, &vec![0.0; n]).unwrap();
        let spec = model.spec();
        let mut learner = Learner::new(
            n,
            m,
            0.002,
            LearnerConfig::for_robot(
                &spec.kp,
                &spec.kd,
                &spec.q_rest,
                &model.tau_max().collect::<Vec<_>>(),
            ),
        )
        .unwrap();
        let cfg = TrainConfig {
            minutes: 1.5,
            babble: BabbleConfig {
                minutes: 1.0,
                ..BabbleConfig::default()
            },
            eval_every_minutes: 0.0,
            ..TrainConfig::default()
        };
        let axes = model.task_axes().to_vec();
        let _ = train(
            &mut sim,
            &mut learner,
            &traj,
            &axes,
            &cfg,
            &mut |_| Ok(Default::default()),
            &mut |_| {},
        );
        let meas = sim.measurement().clone();
        let (q, qd) = (meas.q.as_slice().to_vec(), meas.qd.as_slice().to_vec());
        let xdd_ref = vec![0.1; m];
        let mut u = vec![0.0; n];
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0);
        eprintln!(
            "{name}: {} local models after 1.5 simulated minutes",
            learner.n_local_models()
        );
        c.bench_function(&format!("{name}/learned_command"), |b| {
            b.iter(|| {
                learner
                    .command::<rand_chacha::ChaCha8Rng>(black_box(&q), &qd, &xdd_ref, None, &mut u)
                    .unwrap()
            })
        });
        c.bench_function(&format!("{name}/learned_command_exploring"), |b| {
            b.iter(|| {
                learner
                    .command(black_box(&q), &qd, &xdd_ref, Some(&mut rng), &mut u)
                    .unwrap()
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
