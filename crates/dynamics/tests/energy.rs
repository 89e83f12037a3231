//! Energy conservation of the simulator: no friction, no torque, 10 s.

mod common;
use common::{models, rand_vec, rng};
use osrl_dynamics::sim::Integrator;
use osrl_dynamics::{energy, Friction, JointKind, Model, Robot, SimConfig, SimRobot};

fn frictionless(model: &Model) -> Model {
    let mut spec = model.spec().clone();
    for l in spec.links.iter_mut() {
        l.friction = Friction::default();
    }
    Model::new(spec).unwrap()
}

/// Largest energy deviation (J) over 10 s of torque-free motion and the energy scale it is
/// judged against (initial kinetic energy plus the potential swing of 10 cm).
fn drift(model: &Model, substeps: usize, seed: u64) -> (f64, f64) {
    let mut r = rng(seed);
    let n = model.nq();
    let cfg = SimConfig {
        joint_limits: false,
        integrator: Integrator::Rk4,
        substeps,
        ..SimConfig::default()
    };
    let mut sim = SimRobot::new(model.clone(), cfg).unwrap();
    sim.reset(&rand_vec(&mut r, n, 1.5), &rand_vec(&mut r, n, 1.0))
        .unwrap();
    let mut data = model.data();
    let mut e = |sim: &SimRobot| {
        let (q, qd) = sim.state();
        let (k, p) = energy(model, &mut data, q.as_slice(), qd.as_slice()).unwrap();
        (k + p, k)
    };
    let (e0, k0) = e(&sim);
    let zero = vec![0.0; n];
    let mut worst: f64 = 0.0;
    for _ in 0..5000 {
        sim.step(&zero).unwrap();
        worst = worst.max((e(&sim).0 - e0).abs());
    }
    (worst, k0 + model.total_mass() * 9.81 * 0.1 + 1e-3)
}

#[test]
fn energy_is_conserved_without_friction_and_torque() {
    for (i, model) in models().iter().enumerate() {
        let model = frictionless(model);
        // Default integration (RK4, 1 ms): small drift. Torque-free prismatic chains slide off
        // under gravity (to ~90 m/s in 10 s): they are judged at 8× finer steps.
        let prismatic = model.links().iter().any(|l| l.kind == JointKind::Prismatic);
        let (sub_coarse, sub_fine) = if prismatic { (16, 64) } else { (2, 8) };
        let (coarse, scale) = drift(&model, sub_coarse, 21 + i as u64);
        assert!(
            coarse / scale < 1e-4,
            "{}: drift {coarse:e} J over 10 s (scale {scale:.3} J)",
            model.name()
        );
        // The drift is integration error: it shrinks with the step (RK4 is 4th order; at least 8×
        // for a 4× smaller step, unless it is already at round-off).
        let (fine, _) = drift(&model, sub_fine, 21 + i as u64);
        assert!(
            fine / scale < 1e-5 && (fine * 8.0 < coarse || fine / scale < 1e-9),
            "{}: drift {coarse:e} J at {sub_coarse} substeps, {fine:e} J at {sub_fine}",
            model.name()
        );
    }
}
