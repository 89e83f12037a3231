//! Eq. 7 and eq. 4: the constraint, optimality, the literal formula, eq. 4 as a special case,
//! the null-space term, bad metrics and singular configurations.

mod common;

use approx::assert_relative_eq;
use common::*;
use nalgebra::{DMatrix, DVector};
use osrl_control::{ControlError, Law, MetricKind, Osc, OscConfig};
use osrl_dynamics::{robots, Robot, SimConfig, SimRobot};

fn osc(
    model: &osrl_dynamics::Model,
    law: Law,
    metric: MetricKind,
    n: Option<&DMatrix<f64>>,
) -> Osc {
    let cfg = OscConfig {
        law,
        metric,
        metric_matrix: n.map(rows).unwrap_or_default(),
        ..OscConfig::default()
    };
    Osc::new(model.clone(), cfg).unwrap()
}

/// Random states, random SPD metrics, random u0 and ẍ_ref on every model.
fn cases(
    mut f: impl FnMut(
        &osrl_dynamics::Model,
        &[f64],
        &[f64],
        &DMatrix<f64>,
        &DVector<f64>,
        &DVector<f64>,
    ),
) {
    let mut r = rng(42);
    for model in models() {
        for _ in 0..20 {
            let (q, qd) = random_state(&model, &mut r);
            let n = random_spd(model.nq(), &mut r);
            let u0 = DVector::from_vec(uniform(&mut r, model.nq(), -5.0, 5.0));
            let xr = DVector::from_vec(uniform(&mut r, model.task_dim(), -3.0, 3.0));
            f(&model, &q, &qd, &n, &u0, &xr);
        }
    }
}

#[test]
fn eq7_command_produces_the_reference_acceleration() {
    cases(|model, q, qd, n, u0, xr| {
        for (metric, nm) in [
            (MetricKind::Identity, None),
            (MetricKind::Mass, None),
            (MetricKind::InverseMass, None),
            (MetricKind::Matrix, Some(n)),
        ] {
            let mut c = osc(model, Law::Eq7, metric, nm);
            let mut u = vec![0.0; model.nq()];
            let info = c
                .solve(q, qd, xr.as_slice(), u0.as_slice(), &mut u)
                .unwrap();
            if info.lambda2 > 0.0 {
                continue; // damped near a singularity: the constraint holds only approximately
            }
            let xdd = task_accel(model, q, qd, &u);
            assert_relative_eq!(xdd, xr.clone(), epsilon = 1e-7 * (1.0 + xr.amax()));
        }
    });
}

#[test]
fn one_simulated_step_with_u_star_gives_the_reference_acceleration() {
    // The command is held over the step, so `Δẋ/Δt` is the mean of `ẍ` over the step: it equals
    // ẍ_ref up to O(Δt) (the jerk under a held torque). Check that at a 2 ms and a 0.1 ms period
    // and that the error shrinks in proportion to the period.
    let mut r = rng(7);
    for model in [robots::planar3(), robots::sarcos7()] {
        let mut c = osc(&model, Law::Eq7, MetricKind::Identity, None);
        let mut checked = 0;
        for _ in 0..10 {
            let (q, _) = random_state(&model, &mut r);
            let qd = uniform(&mut r, model.nq(), -0.2, 0.2);
            let xr = uniform(&mut r, model.task_dim(), -2.0, 2.0);
            let mut u0 = vec![0.0; model.nq()];
            c.nominal(&q, &qd, &mut u0).unwrap();
            let mut u = vec![0.0; model.nq()];
            let info = c.solve(&q, &qd, &xr, &u0, &mut u).unwrap();
            if info.lambda2 > 0.0 || u.iter().any(|v| v.abs() > 100.0) {
                continue;
            }
            let mut errs = vec![];
            for dt in [2e-3, 1e-4] {
                let cfg = SimConfig {
                    control_period: dt,
                    joint_limits: false,
                    ..SimConfig::default()
                };
                let mut sim = SimRobot::new(model.clone(), cfg).unwrap();
                let xd0 = sim.reset(&q, &qd).unwrap().xd.clone();
                let m = sim.step(&u).unwrap();
                let mean = (&m.xd - xd0) / dt;
                errs.push((mean - DVector::from_vec(xr.clone())).amax());
            }
            assert!(errs[1] < 0.02, "{errs:?}"); // 1 % of the ẍ_ref scale at 0.1 ms
            assert!(
                errs[1] < errs[0] / 10.0 + 1e-9,
                "error does not shrink with the period: {errs:?}"
            );
            checked += 1;
        }
        assert!(checked >= 5, "too few states checked: {checked}");
    }
}

#[test]
fn eq7_matches_the_literal_formula_of_design_md() {
    cases(|model, q, qd, n, u0, xr| {
        let d = dynamics(model, q, qd);
        let mut c = osc(model, Law::Eq7, MetricKind::Matrix, Some(n));
        let mut u = vec![0.0; model.nq()];
        if c.solve(q, qd, xr.as_slice(), u0.as_slice(), &mut u)
            .unwrap()
            .lambda2
            > 0.0
        {
            return;
        }
        let lit = eq7_literal(&d, n, xr, u0);
        assert_relative_eq!(
            DVector::from_vec(u.clone()),
            lit.clone(),
            epsilon = 1e-6 * (1.0 + lit.amax())
        );
        // N = I and N = M through their own code paths.
        let eye = DMatrix::identity(model.nq(), model.nq());
        for (metric, nm) in [(MetricKind::Identity, eye), (MetricKind::Mass, d.m.clone())] {
            let mut c = osc(model, Law::Eq7, metric, None);
            c.solve(q, qd, xr.as_slice(), u0.as_slice(), &mut u)
                .unwrap();
            let lit = eq7_literal(&d, &nm, xr, u0);
            assert_relative_eq!(
                DVector::from_vec(u.clone()),
                lit.clone(),
                epsilon = 1e-6 * (1.0 + lit.amax())
            );
        }
    });
}

#[test]
fn no_null_space_step_lowers_the_cost() {
    cases(|model, q, qd, n, u0, xr| {
        let d = dynamics(model, q, qd);
        let mut c = osc(model, Law::Eq7, MetricKind::Matrix, Some(n));
        let mut u = vec![0.0; model.nq()];
        if c.solve(q, qd, xr.as_slice(), u0.as_slice(), &mut u)
            .unwrap()
            .lambda2
            > 0.0
        {
            return;
        }
        let u = DVector::from_vec(u);
        let cost = |v: &DVector<f64>| ((v - u0).transpose() * n * (v - u0))[0];
        // Basis of the null space of B = J M⁻¹ from its SVD.
        let b = &d.j * d.m.clone().try_inverse().unwrap();
        // Eigenvectors of BᵀB with (numerically) zero eigenvalue span the null space.
        let eig = (b.transpose() * &b).symmetric_eigen();
        let mut order: Vec<usize> = (0..model.nq()).collect();
        order.sort_by(|&i, &j| eig.eigenvalues[i].partial_cmp(&eig.eigenvalues[j]).unwrap());
        let m = model.task_dim();
        let c0 = cost(&u);
        for &k in &order[..model.nq() - m] {
            let z = eig.eigenvectors.column(k).into_owned();
            assert!((&b * &z).amax() < 1e-9 * b.amax());
            for eps in [-1.0, -1e-2, 1e-3, 0.5] {
                let c1 = cost(&(&u + &z * eps));
                assert!(c1 >= c0 - 1e-9 * (1.0 + c0), "{c1} < {c0}");
                // The cost is exactly quadratic around the optimum: no linear term.
                let expect = eps * eps * (z.transpose() * n * &z)[0];
                assert!(
                    (c1 - c0 - expect).abs() < 1e-7 * (1.0 + c0),
                    "{} vs {expect}",
                    c1 - c0
                );
            }
        }
    });
}

#[test]
fn eq4_equals_eq7_with_inverse_mass_metric_and_zero_u0() {
    cases(|model, q, qd, _n, _u0, xr| {
        let d = dynamics(model, q, qd);
        let zero = vec![0.0; model.nq()];
        let mut u4 = vec![0.0; model.nq()];
        let mut c4 = osc(model, Law::Eq4, MetricKind::Identity, None);
        if c4
            .solve(q, qd, xr.as_slice(), &zero, &mut u4)
            .unwrap()
            .lambda2
            > 0.0
        {
            return;
        }
        let lit = eq4_literal(&d, xr);
        let tol = 1e-6 * (1.0 + lit.amax());
        assert_relative_eq!(DVector::from_vec(u4.clone()), lit.clone(), epsilon = tol);
        // The general path with a numerically inverted M as a constant metric.
        let minv = d.m.clone().try_inverse().unwrap();
        let minv = (&minv + minv.transpose()) * 0.5;
        let mut c7 = osc(model, Law::Eq7, MetricKind::Matrix, Some(&minv));
        let mut u7 = vec![0.0; model.nq()];
        c7.solve(q, qd, xr.as_slice(), &zero, &mut u7).unwrap();
        assert_relative_eq!(DVector::from_vec(u7), lit, epsilon = tol);
    });
}

#[test]
fn the_null_space_term_leaves_the_task_acceleration_unchanged() {
    cases(|model, q, qd, n, u0, xr| {
        let mut c = osc(model, Law::Eq7, MetricKind::Matrix, Some(n));
        let (mut with, mut without) = (vec![0.0; model.nq()], vec![0.0; model.nq()]);
        let zero = vec![0.0; model.nq()];
        if c.solve(q, qd, xr.as_slice(), u0.as_slice(), &mut with)
            .unwrap()
            .lambda2
            > 0.0
        {
            return;
        }
        c.solve(q, qd, xr.as_slice(), &zero, &mut without).unwrap();
        let diff = DVector::from_vec(with.clone()) - DVector::from_vec(without.clone());
        assert!(diff.amax() > 1e-6, "u0 should change the command");
        let (a, b) = (
            task_accel(model, q, qd, &with),
            task_accel(model, q, qd, &without),
        );
        assert_relative_eq!(a, b, epsilon = 1e-7 * (1.0 + xr.amax()));
    });
}

#[test]
fn bad_metrics_are_rejected_with_a_clear_error() {
    let model = robots::planar3();
    let bad = |m: Vec<Vec<f64>>| {
        let cfg = OscConfig {
            metric: MetricKind::Matrix,
            metric_matrix: m,
            ..OscConfig::default()
        };
        Osc::new(model.clone(), cfg).unwrap_err()
    };
    let indefinite = vec![
        vec![1.0, 0.0, 0.0],
        vec![0.0, -1.0, 0.0],
        vec![0.0, 0.0, 1.0],
    ];
    let e = bad(indefinite);
    assert!(
        matches!(e, ControlError::MetricNotPositiveDefinite(_)),
        "{e}"
    );
    assert!(e.to_string().contains("Cholesky"), "{e}");
    let asym = vec![
        vec![2.0, 1.0, 0.0],
        vec![0.0, 2.0, 0.0],
        vec![0.0, 0.0, 1.0],
    ];
    assert!(bad(asym).to_string().contains("symmetric"));
    assert!(bad(vec![vec![1.0]]).to_string().contains("3×3"));
    let nan = vec![
        vec![f64::NAN, 0.0, 0.0],
        vec![0.0, 1.0, 0.0],
        vec![0.0, 0.0, 1.0],
    ];
    assert!(bad(nan).to_string().contains("finite"));
    // A matrix without metric = "matrix" (and vice versa) is a config error.
    let cfg = OscConfig {
        metric_matrix: vec![vec![1.0]],
        ..OscConfig::default()
    };
    assert!(Osc::new(model.clone(), cfg).is_err());
    let cfg = OscConfig {
        metric: MetricKind::Matrix,
        ..OscConfig::default()
    };
    assert!(Osc::new(model, cfg).is_err());
}

#[test]
fn singular_configuration_is_damped_or_a_clear_error_never_nan() {
    // planar3 stretched out along x: the Jacobian loses its x row.
    let model = robots::planar3();
    let (q, qd) = ([0.0, 0.0, 0.0], [0.0; 3]);
    let xr = [1.0, -0.5];
    let zero = [0.0; 3];
    for law in [Law::Eq7, Law::Eq4] {
        let mut c = osc(&model, law, MetricKind::Identity, None);
        let mut u = [0.0; 3];
        let info = c.solve(&q, &qd, &xr, &zero, &mut u).unwrap();
        assert!(info.lambda2 > 0.0 && info.sigma_ratio < 1e-6, "{info:?}");
        assert!(u.iter().all(|v| v.is_finite() && v.abs() < 1e3), "{u:?}");
        // Damping switched off: a clear error, u untouched.
        let cfg = OscConfig {
            law,
            damping_threshold: 0.0,
            ..OscConfig::default()
        };
        let mut c = Osc::new(model.clone(), cfg).unwrap();
        let mut u = [7.0; 3];
        let e = c.solve(&q, &qd, &xr, &zero, &mut u).unwrap_err();
        assert!(matches!(e, ControlError::Singular(_)), "{e}");
        assert_eq!(u, [7.0; 3]);
    }
    // Near (not at) the singularity the damped command stays bounded and continuous.
    let mut c = osc(&model, Law::Eq7, MetricKind::Identity, None);
    let mut prev: Option<Vec<f64>> = None;
    for k in 0..=20 {
        let e = 1e-3 * (10 - k) as f64; // elbow angle through zero
        let mut u = vec![0.0; 3];
        c.solve(&[0.0, e, 0.0], &qd, &xr, &zero, &mut u).unwrap();
        assert!(u.iter().all(|v| v.is_finite() && v.abs() < 1e3));
        if let Some(p) = prev {
            let jump = p
                .iter()
                .zip(&u)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(jump < 50.0, "jump {jump} at elbow {e}");
        }
        prev = Some(u);
    }
}

#[test]
fn bad_inputs_give_errors_and_leave_the_command_unchanged() {
    let model = robots::sarcos7();
    let mut c = osc(&model, Law::Eq7, MetricKind::Identity, None);
    let q = model.spec().q_start.clone();
    let qd = vec![0.0; 7];
    let mut u = vec![3.0; 7];
    let zero = vec![0.0; 7];
    let mut bad_q = q.clone();
    bad_q[2] = f64::NAN;
    assert!(c.solve(&bad_q, &qd, &[0.0; 3], &zero, &mut u).is_err());
    assert!(c
        .solve(&q, &qd, &[0.0, f64::INFINITY, 0.0], &zero, &mut u)
        .is_err());
    assert!(c.solve(&q, &qd, &[0.0; 2], &zero, &mut u).is_err());
    assert!(c.solve(&q, &qd, &[0.0; 3], &zero[..6], &mut u).is_err());
    assert!(c.solve(&q, &qd, &[0.0; 3], &zero, &mut u[..6]).is_err());
    assert_eq!(u, vec![3.0; 7]);
    assert!(Osc::new(
        model.clone(),
        OscConfig {
            damping_threshold: 1.5,
            ..OscConfig::default()
        }
    )
    .is_err());
    assert!(Osc::new(
        model,
        OscConfig {
            nominal_scale: f64::NAN,
            ..OscConfig::default()
        }
    )
    .is_err());
}
