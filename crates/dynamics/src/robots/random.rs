//! A seeded generator of random serial arms, for cross-checks beyond the built-in robots.

use crate::inertia::Inertia;
use crate::model::{Friction, JointKind, JointLimits, Link, Model, ModelSpec, GRAVITY};
use crate::spatial::{axis_angle, Pose};
use nalgebra::{Matrix3, Vector3};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A random unit vector (uniform direction, by rejection from the unit ball), for random arms
/// and random model errors.
pub fn random_unit_vector(rng: &mut ChaCha8Rng) -> Vector3<f64> {
    loop {
        let v = Vector3::new(
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        );
        let n = v.norm();
        if n > 0.1 && n <= 1.0 {
            return v / n;
        }
    }
}

fn rotation(rng: &mut ChaCha8Rng) -> Matrix3<f64> {
    axis_angle(
        &random_unit_vector(rng),
        rng.random_range(-std::f64::consts::PI..std::f64::consts::PI),
    )
}

/// A random `n`-joint arm: random joint frames (links 0.1–0.5 m, random orientation), random
/// general axes, masses 0.3–3 kg with random centres of mass and physically consistent inertias
/// (principal moments obeying the triangle inequality, random orientation), and random viscous and
/// Coulomb friction when `friction` is true. Task space: the 3-D end-effector position. The same
/// `seed` gives the same arm.
pub fn random_arm(n: usize, seed: u64, friction: bool) -> Model {
    assert!(n > 0, "random_arm needs at least one joint");
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let links = (0..n)
        .map(|i| {
            let len = if i == 0 {
                0.0
            } else {
                rng.random_range(0.1..0.5)
            };
            let origin = Pose::new(rotation(&mut rng), random_unit_vector(&mut rng) * len);
            let mass = rng.random_range(0.3..3.0);
            let com = random_unit_vector(&mut rng) * rng.random_range(0.0..0.2);
            // Principal moments a ≤ b + c etc. from a random mass distribution's second moments.
            let s = [
                rng.random_range(0.001..0.02),
                rng.random_range(0.001..0.02),
                rng.random_range(0.001..0.02),
            ];
            let principal = Vector3::new(s[1] + s[2], s[0] + s[2], s[0] + s[1]) * mass;
            let r = rotation(&mut rng);
            let inertia_com = r * Matrix3::from_diagonal(&principal) * r.transpose();
            let friction = if friction {
                Friction {
                    viscous: rng.random_range(0.0..0.5),
                    coulomb: rng.random_range(0.0..0.5),
                    ..Friction::default()
                }
            } else {
                Friction::default()
            };
            Link {
                name: format!("link{i}"),
                joint_name: format!("joint{i}"),
                origin,
                axis: random_unit_vector(&mut rng),
                kind: JointKind::Revolute,
                inertia: Inertia::from_com(
                    mass,
                    com,
                    (inertia_com + inertia_com.transpose()) * 0.5,
                ),
                friction,
                limits: JointLimits::default(),
            }
        })
        .collect();
    Model::new(ModelSpec {
        name: format!("random{n}_{seed}"),
        links,
        ee_offset: random_unit_vector(&mut rng) * 0.1,
        gravity: GRAVITY,
        task_axes: vec![0, 1, 2],
        q_start: vec![0.0; n],
        q_rest: vec![0.0; n],
        kp: vec![10.0; n],
        kd: vec![1.0; n],
        urdf: None,
    })
    .expect("random arm parameters are valid")
}

/// [`random_arm`] with every third joint (indices 1, 4, 7, …) prismatic, limited to ±0.3 m, and
/// the revolute joints limited to ±π: a chain mixing both joint kinds, for the cross-checks.
pub fn random_mixed_arm(n: usize, seed: u64, friction: bool) -> Model {
    let mut spec = random_arm(n, seed, friction).spec().clone();
    spec.name = format!("mixed{n}_{seed}");
    for (i, l) in spec.links.iter_mut().enumerate() {
        let (kind, range) = if i % 3 == 1 {
            (JointKind::Prismatic, 0.3)
        } else {
            (JointKind::Revolute, std::f64::consts::PI)
        };
        l.kind = kind;
        l.limits.q_min = -range;
        l.limits.q_max = range;
    }
    Model::new(spec).expect("random arm parameters are valid")
}
