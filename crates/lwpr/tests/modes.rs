//! Shared receptive fields, localised kernels (paper eq. 32–33), partition access, events,
//! Jacobian and confidence (the learning rates are in `rates.rs`).
#![allow(clippy::needless_range_loop)]

mod common;

use lwpr::{Activation, Lwpr, LwprConfig, MetricInit, RfEvent};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Region centres along the kernel input `z`; inside region k the outputs are linear in `v`.
const REGIONS: [f64; 3] = [-4.0, 0.0, 4.0];
const A: [[[f64; 2]; 2]; 3] = [
    [[1.0, -2.0], [0.5, 0.0]],
    [[-1.5, 0.3], [2.0, 1.0]],
    [[0.2, 0.8], [-0.7, 3.0]],
];
const B: [[f64; 2]; 3] = [[0.5, -1.0], [2.0, 0.0], [-0.3, 1.2]];

fn target(k: usize, v: &[f64]) -> [f64; 2] {
    [0, 1].map(|o| B[k][o] + A[k][o][0] * v[0] + A[k][o][1] * v[1])
}

/// Inputs `(z, v₁, v₂)`, kernel on `z`, regression on `v`. `z` sits exactly on a region
/// centre, so each region is covered by exactly one RF (no metric learning, narrow enough
/// kernels that neighbouring regions do not see each other).
fn fit(shared: bool) -> Lwpr {
    let cfg = LwprConfig {
        shared_rfs: shared,
        kernel_dims: Some(vec![0]),
        regression_dims: Some(vec![1, 2]),
        init_d: MetricInit::Scalar(4.0),
        update_d: false,
        init_lambda: 0.99,
        final_lambda: 0.99,
        ..Default::default()
    };
    let mut m = Lwpr::new(3, 2, &cfg).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(2);
    for _ in 0..15000 {
        let k = rng.random_range(0..3);
        let v = [rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)];
        m.update(&[REGIONS[k], v[0], v[1]], &target(k, &v)).unwrap();
    }
    m
}

fn check_fit(mut m: Lwpr, shared: bool) {
    let n_sub = if shared { 1 } else { 2 };
    assert_eq!(
        m.n_rfs(),
        vec![3; n_sub],
        "one RF per kernel region and sub-model"
    );
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let (mut y, mut jac) = ([0.0; 2], [0.0; 6]);
    for _ in 0..100 {
        let k = rng.random_range(0..3);
        let v = [rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)];
        m.predict_jacobian(&[REGIONS[k], v[0], v[1]], &mut y, &mut jac)
            .unwrap();
        let t = target(k, &v);
        for o in 0..2 {
            let scale = 1.0 + A[k][o][0].abs() + A[k][o][1].abs();
            assert!(
                (y[o] - t[o]).abs() < 0.02 * scale,
                "out {o}: {} vs {}",
                y[o],
                t[o]
            );
            assert!((jac[o * 3 + 1] - A[k][o][0]).abs() < 0.02 * scale);
            assert!((jac[o * 3 + 2] - A[k][o][1]).abs() < 0.02 * scale);
        }
    }
    // Partition access: the RF at each region centre, its local model is the region's.
    let mut acts: Vec<Activation> = Vec::with_capacity(8);
    for (k, &z) in REGIONS.iter().enumerate() {
        for s in 0..n_sub {
            m.activations(s, &[z, 0.3, -0.1], 1e-3, &mut acts).unwrap();
            assert_eq!(acts.len(), 1);
            assert!((acts[0].w - 1.0).abs() < 1e-12);
            let rf = m.rf(s, acts[0].id).unwrap();
            assert_eq!(rf.center(), vec![z]);
            assert!((rf.metric()[(0, 0)] - 4.0).abs() < 1e-12);
            for lo in 0..(if shared { 2 } else { 1 }) {
                let o = if shared { lo } else { s };
                let lm = rf.local_model(lo).unwrap();
                assert_eq!(lm.slope.len(), 2);
                for j in 0..2 {
                    assert!((lm.slope[j] - A[k][o][j]).abs() < 0.02 * (1.0 + A[k][o][j].abs()));
                }
            }
        }
    }
}

#[test]
fn shared_rfs_with_localised_kernel_learn_linear_regions() {
    let mut m = fit(true);
    let ev: Vec<RfEvent> = m.drain_events().collect();
    assert_eq!(ev.len(), 3);
    assert!(ev
        .iter()
        .all(|e| matches!(e, RfEvent::Added { sub: 0, .. })));
    check_fit(m, true);
}

#[test]
fn per_output_mode_with_localised_kernel_learns_linear_regions() {
    check_fit(fit(false), false);
}

#[test]
fn events_track_additions_and_prunings() {
    let cfg = LwprConfig {
        w_prune: 0.5,
        init_d: MetricInit::Scalar(5.0),
        ..Default::default()
    };
    let mut m = Lwpr::new(2, 1, &cfg).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let mut live = std::collections::BTreeSet::new();
    let mut pruned = 0;
    for _ in 0..5000 {
        let x = [rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)];
        m.update(&x, &[common::cross(x[0], x[1])]).unwrap();
        for e in m.drain_events() {
            match e {
                RfEvent::Added {
                    id, copied_from, ..
                } => {
                    assert!(live.insert(id));
                    if let Some(c) = copied_from {
                        assert!(live.contains(&c));
                    }
                }
                RfEvent::Pruned { id, .. } => {
                    assert!(live.remove(&id));
                    pruned += 1;
                }
            }
        }
    }
    assert!(pruned > 0, "this setting prunes");
    let ids: std::collections::BTreeSet<_> = m.rfs(0).unwrap().map(|v| v.id()).collect();
    assert_eq!(ids, live);
}

#[test]
fn removing_an_rf_drops_only_it_and_learning_goes_on() {
    let cfg = LwprConfig {
        init_d: MetricInit::Scalar(25.0),
        ..Default::default()
    };
    let mut m = Lwpr::new(2, 1, &cfg).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let mut sample = |m: &mut Lwpr| {
        let x = [rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)];
        m.update(&x, &[common::cross(x[0], x[1])]).unwrap();
    };
    for _ in 0..3000 {
        sample(&mut m);
    }
    m.drain_events().for_each(drop);
    let x = [0.1, -0.2];
    let mut before: Vec<Activation> = Vec::new();
    m.activations(0, &x, 1e-3, &mut before).unwrap();
    assert!(before.len() >= 2, "several RFs active at x");
    let gone = before[0].id;
    let n = m.n_rfs_total();
    assert!(m.remove_rf(0, gone).unwrap());
    assert_eq!(m.n_rfs_total(), n - 1);
    assert_eq!(
        m.drain_events().collect::<Vec<_>>(),
        vec![RfEvent::Pruned { sub: 0, id: gone }]
    );
    // The cached query of `x` is gone with the RF: the others keep their activations.
    let mut after = Vec::new();
    m.activations(0, &x, 1e-3, &mut after).unwrap();
    let mut expect: Vec<_> = before.iter().filter(|a| a.id != gone).copied().collect();
    expect.sort_by_key(|a| a.id);
    after.sort_by_key(|a| a.id);
    assert_eq!(after, expect);
    assert!(!m.remove_rf(0, gone).unwrap(), "already removed");
    assert!(m.remove_rf(1, gone).is_err(), "no sub-model 1");
    // Learning goes on; ids are never reused; save/load keeps the smaller partition.
    for _ in 0..3000 {
        sample(&mut m);
    }
    assert!(m.rfs(0).unwrap().all(|v| v.id() != gone));
    let back = Lwpr::from_bytes(&m.to_bytes()).unwrap();
    assert_eq!(back.n_rfs_total(), m.n_rfs_total());
}

#[test]
fn jacobian_matches_finite_differences_and_conf_is_positive() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let d = common::cross_train(&mut rng, 500);
    for diag in [true, false] {
        let cfg = LwprConfig {
            diag_only: diag,
            norm_in: lwpr::Norm::List(vec![0.5, 2.0]),
            norm_out: lwpr::Norm::Scalar(3.0),
            ..common::cross_config()
        };
        let mut m = Lwpr::new(2, 1, &cfg).unwrap();
        for _ in 0..10 {
            for (x, &y) in d.x.iter().zip(&d.y) {
                m.update(x, &[y]).unwrap();
            }
        }
        let (mut y, mut jac, mut conf) = ([0.0], [0.0; 2], [0.0]);
        for x in [[0.1, 0.2], [-0.5, 0.7], [0.33, -0.05]] {
            m.predict_jacobian(&x, &mut y, &mut jac).unwrap();
            m.predict_conf(&x, &mut y, &mut conf).unwrap();
            assert!(conf[0] > 0.0 && conf[0].is_finite());
            for i in 0..2 {
                let h = 1e-6;
                let (mut xp, mut xm) = (x, x);
                xp[i] += h;
                xm[i] -= h;
                let (mut yp, mut ym) = ([0.0], [0.0]);
                m.predict(&xp, &mut yp).unwrap();
                m.predict(&xm, &mut ym).unwrap();
                let fd = (yp[0] - ym[0]) / (2.0 * h);
                assert!(
                    (jac[i] - fd).abs() < 1e-5 * (1.0 + fd.abs()),
                    "{} vs {fd}",
                    jac[i]
                );
            }
        }
    }
}
