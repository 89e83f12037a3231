//! The built-in robots against the published checks of `docs/robots.md`.

use osrl_dynamics::{crba, forward_kinematics, gravity, robots};

#[test]
fn sarcos7_matches_published_values() {
    let model = robots::sarcos7();
    let mut data = model.data();
    forward_kinematics(&model, &mut data, &[0.0; 7]).unwrap();
    let ee = [0.318443, -0.008100, -0.367257];
    for (k, &want) in ee.iter().enumerate() {
        assert!((data.ee_pos[k] - want).abs() < 1e-6, "ee {:?}", data.ee_pos);
    }
    let q = model.spec().q_start.clone();
    let g = gravity(&model, &mut data, &q).unwrap().clone();
    let g_ref = [
        6.335692, -9.479287, 2.647867, 8.559779, -2.522645, 0.301918, 0.663739,
    ];
    for i in 0..7 {
        assert!((g[i] - g_ref[i]).abs() < 1e-5, "g = {g}");
    }
    let m = crba(&model, &mut data, &q).unwrap();
    let diag = [
        0.826943, 0.579589, 0.308105, 0.288738, 0.020066, 0.022573, 0.014124,
    ];
    for i in 0..7 {
        assert!(
            (m[(i, i)] - diag[i]).abs() < 1e-5,
            "M diag {}",
            m.diagonal()
        );
    }
}

#[test]
fn planar3_moves_in_the_xz_plane() {
    let model = robots::planar3();
    let mut data = model.data();
    forward_kinematics(&model, &mut data, &[0.0; 3]).unwrap();
    assert!(
        (data.ee_pos.x - 1.05).abs() < 1e-12
            && data.ee_pos.y.abs() < 1e-12
            && data.ee_pos.z.abs() < 1e-12
    );
    // A positive shoulder angle lifts the arm.
    forward_kinematics(&model, &mut data, &[0.3, 0.0, 0.0]).unwrap();
    assert!(data.ee_pos.z > 0.3 && data.ee_pos.y.abs() < 1e-12);
    assert_eq!(model.task_axes(), &[0, 2]);
}
