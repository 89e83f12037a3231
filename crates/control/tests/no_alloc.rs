//! A controller command does not allocate: a counting global allocator (this file is its own
//! test binary, with one test, so nothing else allocates meanwhile).

use osrl_control::{Law, MetricKind, Osc, OscConfig, TaskController, TrajectoryConfig};
use osrl_dynamics::{robots, Robot, SimConfig, SimRobot};

#[global_allocator]
static GLOBAL: osrl_testkit::Counting = osrl_testkit::Counting;

#[test]
fn commands_do_not_allocate() {
    for model in [
        robots::planar3(),
        robots::sarcos7(),
        robots::random_arm(6, 2, true),
    ] {
        let n = model.nq();
        let traj = TrajectoryConfig::default().build(&model).unwrap();
        let sim = SimRobot::new(model.clone(), SimConfig::default()).unwrap();
        let metric_matrix: Vec<Vec<f64>> = (0..n)
            .map(|i| (0..n).map(|j| if i == j { 2.0 } else { 0.1 }).collect())
            .collect();
        let cfgs = [
            OscConfig::default(),
            OscConfig {
                law: Law::Eq4,
                ..OscConfig::default()
            },
            OscConfig {
                metric: MetricKind::Mass,
                ..OscConfig::default()
            },
            OscConfig {
                metric: MetricKind::InverseMass,
                ..OscConfig::default()
            },
            OscConfig {
                metric: MetricKind::Matrix,
                metric_matrix,
                ..OscConfig::default()
            },
        ];
        for cfg in cfgs {
            let mut osc = Osc::new(model.clone(), cfg).unwrap();
            let mut u = vec![0.0; n];
            let (mut u0, xr) = (vec![0.0; n], [0.5, -0.2, 0.1]);
            let meas = sim.measurement().clone();
            let (q, qd) = (meas.q.as_slice().to_vec(), vec![0.2; n]);
            let m = model.task_dim();
            let target = traj.sample(1.3);
            osc.command(&meas, &target, &mut u).unwrap(); // warm-up
            let before = osrl_testkit::allocations();
            for _ in 0..100 {
                osc.command(&meas, &target, &mut u).unwrap();
                osc.nominal(&q, &qd, &mut u0).unwrap();
                osc.solve(&q, &qd, &xr[..m], &u0, &mut u).unwrap();
            }
            let after = osrl_testkit::allocations();
            assert_eq!(
                after - before,
                0,
                "{}: {} allocations",
                model.name(),
                after - before
            );
        }
    }
}
