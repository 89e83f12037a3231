//! The hot calls never allocate: a counting global allocator around them.

use osrl_dynamics::sim::SensorNoise;
use osrl_dynamics::{
    aba, compute_all, crba, forward_dynamics, gravity, jacobian, kinematics, nonlinear_effects,
    rnea, robots, Robot, SimConfig, SimRobot,
};

#[global_allocator]
static GLOBAL: osrl_testkit::Counting = osrl_testkit::Counting;

fn allocations(f: impl FnOnce()) -> usize {
    let before = osrl_testkit::allocations();
    f();
    osrl_testkit::allocations() - before
}

#[test]
fn dynamics_calls_and_simulation_steps_do_not_allocate() {
    let xarm7 = osrl_dynamics::urdf::load_urdf(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/fixtures/example-robot-data/xarm7.urdf"),
    )
    .unwrap();
    // xarm7: its stiff friction takes the implicit path of the simulator.
    for model in [
        robots::planar3(),
        robots::sarcos7(),
        robots::random_arm(9, 5, true),
        robots::random_mixed_arm(6, 2, true),
        xarm7,
    ] {
        let n = model.nq();
        let mut data = model.data();
        let (q, qd, qdd) = (vec![0.3; n], vec![0.2; n], vec![0.1; n]);
        let count = allocations(|| {
            rnea(&model, &mut data, &q, &qd, &qdd).unwrap();
            crba(&model, &mut data, &q).unwrap();
            aba(&model, &mut data, &q, &qd, &qdd).unwrap();
            forward_dynamics(&model, &mut data, &q, &qd, &qdd).unwrap();
            gravity(&model, &mut data, &q).unwrap();
            nonlinear_effects(&model, &mut data, &q, &qd).unwrap();
            jacobian(&model, &mut data, &q).unwrap();
            kinematics(&model, &mut data, &q, &qd).unwrap();
            compute_all(&model, &mut data, &q, &qd).unwrap();
        });
        assert_eq!(count, 0, "{}: dynamics calls allocated", model.name());
        let cfg = SimConfig {
            sensor_noise: SensorNoise {
                q: 1e-3,
                qd: 1e-3,
                x: 1e-3,
                xd: 1e-3,
                xdd: 1e-2,
            },
            actuator_noise: 0.1,
            ..SimConfig::default()
        };
        let mut sim = SimRobot::new(model.clone(), cfg).unwrap();
        let u = vec![0.5; n];
        let mut last = sim.measurement().clone();
        let count = allocations(|| {
            for _ in 0..100 {
                // A learner's loop: step, then keep the measurement in its own buffer.
                last.copy_from(sim.step(&u).unwrap());
            }
        });
        assert_eq!(count, 0, "{}: simulation steps allocated", model.name());
        assert_eq!(&last, sim.measurement());
    }
}
