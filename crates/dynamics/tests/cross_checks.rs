//! Algorithms against each other: CRBA vs RNEA, ABA vs M⁻¹(u − h), RNEA(ABA(u)) = u, Jacobian and
//! J̇q̇ vs finite differences, on the built-in robots and random arms at random states.

mod common;
use common::{max_diff, models, rand_vec, rng};
use osrl_dynamics::{
    aba, compute_all, crba, forward_dynamics, forward_kinematics, gravity, jacobian, kinematics,
    nonlinear_effects, rnea,
};

#[test]
fn crba_columns_equal_rnea_differences() {
    let mut r = rng(11);
    for model in models() {
        let n = model.nq();
        let mut data = model.data();
        for _ in 0..20 {
            let q = rand_vec(&mut r, n, 2.0);
            let qd = rand_vec(&mut r, n, 2.0);
            let m = crba(&model, &mut data, &q).unwrap().clone();
            assert!((&m - m.transpose()).amax() < 1e-12);
            let bias = rnea(&model, &mut data, &q, &qd, &vec![0.0; n])
                .unwrap()
                .clone();
            for j in 0..n {
                let mut e = vec![0.0; n];
                e[j] = 1.0;
                let col = rnea(&model, &mut data, &q, &qd, &e).unwrap() - &bias;
                let err = (col - m.column(j)).amax();
                assert!(
                    err < 1e-10 * (1.0 + m.amax()),
                    "{} column {j}: {err}",
                    model.name()
                );
            }
        }
    }
}

#[test]
fn aba_equals_inverse_mass_times_torque_and_rnea_inverts_it() {
    let mut r = rng(12);
    for model in models() {
        let n = model.nq();
        let mut data = model.data();
        for _ in 0..20 {
            let q = rand_vec(&mut r, n, 2.0);
            let qd = rand_vec(&mut r, n, 2.0);
            let u = rand_vec(&mut r, n, 5.0);
            // With friction: q̈ = M⁻¹ (u − h).
            let qdd = forward_dynamics(&model, &mut data, &q, &qd, &u)
                .unwrap()
                .clone();
            let h = nonlinear_effects(&model, &mut data, &q, &qd)
                .unwrap()
                .clone();
            let m = crba(&model, &mut data, &q).unwrap().clone();
            let rhs = nalgebra::DVector::from_column_slice(&u) - h;
            let direct = m
                .clone()
                .cholesky()
                .expect("M positive definite")
                .solve(&rhs);
            let scale = 1.0 + direct.amax();
            assert!(
                (&qdd - &direct).amax() < 1e-9 * scale,
                "{}: ABA vs M⁻¹(u−h)",
                model.name()
            );
            // Rigid body: RNEA(q, q̇, ABA(q, q̇, τ)) = τ.
            let qdd = aba(&model, &mut data, &q, &qd, &u).unwrap().clone();
            let tau = rnea(&model, &mut data, &q, &qd, qdd.as_slice()).unwrap();
            assert!(
                max_diff(tau.as_slice(), &u) < 1e-9 * 5.0,
                "{}: RNEA(ABA(u)) ≠ u",
                model.name()
            );
        }
    }
}

#[test]
fn gravity_and_h_are_rnea_special_cases() {
    let mut r = rng(13);
    for model in models() {
        let n = model.nq();
        let mut data = model.data();
        let q = rand_vec(&mut r, n, 2.0);
        let qd = rand_vec(&mut r, n, 2.0);
        compute_all(&model, &mut data, &q, &qd).unwrap();
        let (g, h, mass) = (data.g.clone(), data.h.clone(), data.mass.clone());
        let mut other = model.data();
        assert_eq!(&g, gravity(&model, &mut other, &q).unwrap());
        assert_eq!(&h, nonlinear_effects(&model, &mut other, &q, &qd).unwrap());
        assert_eq!(&mass, crba(&model, &mut other, &q).unwrap());
    }
}

#[test]
fn jacobian_and_jdot_qd_match_finite_differences() {
    let mut r = rng(14);
    let eps = 1e-6;
    for model in models() {
        let n = model.nq();
        let mut data = model.data();
        for _ in 0..10 {
            let q = rand_vec(&mut r, n, 2.0);
            let qd = rand_vec(&mut r, n, 2.0);
            jacobian(&model, &mut data, &q).unwrap();
            let jac = data.jac.clone();
            for j in 0..n {
                let (mut qp, mut qm) = (q.clone(), q.clone());
                qp[j] += eps;
                qm[j] -= eps;
                forward_kinematics(&model, &mut data, &qp).unwrap();
                let xp = data.ee_pos;
                forward_kinematics(&model, &mut data, &qm).unwrap();
                let fd = (xp - data.ee_pos) / (2.0 * eps);
                assert!(
                    (fd - jac.column(j)).amax() < 1e-8,
                    "{} J column {j}",
                    model.name()
                );
            }
            // ẋ = J q̇, and J̇ q̇ = d/dt (J q̇) along q(t) = q + t q̇.
            kinematics(&model, &mut data, &q, &qd).unwrap();
            let (vel, jdqd) = (data.ee_vel, data.jdot_qd);
            assert!((vel - &jac * nalgebra::DVector::from_column_slice(&qd)).amax() < 1e-12);
            let step = |t: f64, data: &mut osrl_dynamics::Data| {
                let qt: Vec<f64> = q.iter().zip(&qd).map(|(a, b)| a + t * b).collect();
                jacobian(&model, data, &qt).unwrap();
                &data.jac * nalgebra::DVector::from_column_slice(&qd)
            };
            let fd = (step(eps, &mut data) - step(-eps, &mut data)) / (2.0 * eps);
            assert!(
                (fd - jdqd).amax() < 1e-6 * (1.0 + jdqd.amax()),
                "{} J̇q̇",
                model.name()
            );
        }
    }
}

#[test]
fn coordinate_axis_rotations_equal_the_general_formula() {
    use osrl_dynamics::sincos::sin_cos;
    use osrl_dynamics::spatial::rotate_about as fast;
    use osrl_dynamics::spatial::{axis_angle, axis_rotation};
    let mut r = rng(15);
    for k in 0..60_000 {
        let a = k % 6;
        let mut axis = nalgebra::Vector3::zeros();
        axis[a % 3] = if a < 3 { 1.0 } else { -1.0 };
        let o = axis_angle(
            &nalgebra::Vector3::from_column_slice(&rand_vec(&mut r, 3, 1.0)).normalize(),
            rand_vec(&mut r, 1, 3.0)[0],
        );
        let q = rand_vec(&mut r, 1, 10.0)[0];
        assert_eq!(
            fast(&o, &axis, q),
            o * axis_rotation(&axis, sin_cos(q)),
            "axis {axis:?} q {q}"
        );
    }
}
