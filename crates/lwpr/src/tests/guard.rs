//! The removal guard's bookkeeping: several RFs diverging in one update are all removed (and
//! only they), announced, kept out of the update's blend, and that update does not add an RF.

use crate::datasets::{cross_config, cross_train};
use crate::model::Lwpr;
use crate::rf::{Activation, RfEvent, RfId};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// A 2-D cross model and an input where at least three trustworthy RFs are active but none
/// above `w_gen` (so an update there adds an RF unless something stops it), with the ids of
/// two of them.
fn model_and_input() -> (Lwpr, Vec<f64>, Vec<RfId>) {
    let cfg = cross_config();
    let mut m = Lwpr::new(2, 1, &cfg).unwrap();
    let data = cross_train(&mut ChaCha8Rng::seed_from_u64(1), 500);
    for _ in 0..4 {
        for (x, y) in data.x.iter().zip(&data.y) {
            m.update(x, &[*y]).unwrap();
        }
    }
    m.drain_events().for_each(drop);
    let mut act: Vec<Activation> = Vec::new();
    // Just outside the data's square, where only the tails of RFs reach.
    for k in 0..=600 {
        let t = -1.5 + 0.005 * k as f64;
        let x = if k % 2 == 0 {
            vec![t, 1.12]
        } else {
            vec![1.12, t]
        };
        m.activations(0, &x, 0.002, &mut act).unwrap();
        let trusted: Vec<RfId> = act
            .iter()
            .filter(|a| m.rf(0, a.id).unwrap().trustworthy())
            .map(|a| a.id)
            .collect();
        let w_max = act.iter().map(|a| a.w).fold(0.0, f64::max);
        if trusted.len() >= 3 && w_max <= cfg.w_gen {
            return (m, x, trusted[..2].to_vec());
        }
    }
    panic!("no input with three active RFs below w_gen");
}

#[test]
fn diverged_rfs_are_removed_together_and_nothing_is_added() {
    let (mut m, x, bad) = model_and_input();
    // The reference: the same model with those RFs taken out by their owner.
    let mut r = m.clone();
    for id in &bad {
        assert!(r.remove_rf(0, *id).unwrap());
    }
    r.drain_events().for_each(drop);
    // Poison the two RFs: an infinite `SSYres` makes their regression coefficient infinite.
    for id in &bad {
        let i = m.subs[0].rfs.iter().position(|rf| rf.id == id.0).unwrap();
        m.subs[0].rfs[i].outs[0].ss_yres[0] = f64::INFINITY;
    }
    let n = m.n_rfs_total();
    let info = m.update(&x, &[0.3]).unwrap();
    assert_eq!(info.removed_non_finite, 2);
    assert_eq!(
        (info.added, info.pruned),
        (0, 0),
        "no add or prune in this update"
    );
    assert_eq!(m.n_rfs_total(), n - 2);
    let pruned: Vec<RfId> = m
        .drain_events()
        .map(|e| match e {
            RfEvent::Pruned { id, .. } => id,
            e => panic!("unexpected {e:?}"),
        })
        .collect();
    let mut want = bad.clone();
    want.sort();
    let mut got = pruned.clone();
    got.sort();
    assert_eq!(got, want, "exactly the diverged RFs are removed");
    for id in &bad {
        assert!(m.rf(0, *id).is_none());
    }
    // Every other RF is still there, unchanged where the sample did not reach it.
    for v in r.rfs(0).unwrap() {
        assert!(m.rf(0, v.id()).is_some(), "{:?} kept", v.id());
    }
    // The update's blend is that of the surviving RFs (the same RFs updated in another order).
    let info_r = r.update(&x, &[0.3]).unwrap();
    assert_eq!(
        info_r.added, 1,
        "without the diverged RFs the sample is far from all"
    );
    let (a, b) = (m.last_update_prediction()[0], r.last_update_prediction()[0]);
    assert!(
        b.is_finite() && (a - b).abs() <= 1e-12 * b.abs().max(1.0),
        "{a} {b}"
    );
    assert_eq!(m.warnings().removed_non_finite, 2);
}
