//! The grouped RF updates of the 2-D shape (`rf_update_group`) against the same RFs updated one
//! at a time by the 2-D code, bit for bit: saved models, every update's own prediction and
//! guard count, and predictions after training, for every configuration of the 2-D path's
//! tests (`rf_2d::cases`), a model whose RFs diverge, and a model where some RFs have one
//! direction (they are updated alone, the others still in groups). Both group sizes must have
//! run where the shape groups.

use super::rf_2d::{cases, train, train_on, Path, Run};
use crate::config::LwprConfig;
use crate::datasets::cross_config;
use crate::fast::groups_apply;
use crate::model::Lwpr;
use crate::pls::Pls;
use crate::rf::Rf;

/// `train` with grouping on or off; the updates whose active RFs form groups of two and of
/// three (where every RF has two directions).
fn run(off: bool, m: &mut Lwpr, seed: u64, n: usize) -> (Run, [u64; 2]) {
    let path = if off { Path::NoGroups } else { Path::Fast };
    let r = train_on(path, m, seed, n);
    let sizes = r.5;
    (r, sizes)
}

/// Asserts that grouped and one-at-a-time training agree, that the dispatch groups the shape
/// exactly when `grouped`, and that updates with groups of both sizes were common.
fn compare(name: &str, grouped: bool, mk: impl Fn() -> Lwpr, seed: u64, n: usize) {
    let m = mk();
    let p = m.params();
    assert_eq!(
        groups_apply(p.nk(), p.nr(), p),
        grouped,
        "{name}: the dispatch's choice"
    );
    let (g, counts) = run(false, &mut mk(), seed, n);
    let (s, _) = run(true, &mut mk(), seed, n);
    assert!(
        counts[0] > 100 && counts[1] > 100,
        "{name}: updates with groups of two and of three {counts:?}: the test misses its case"
    );
    assert!(g.1.len() > 150, "{name}: too few predictions");
    assert!(g.0 == s.0, "{name}: the saved models differ");
    assert_eq!(g.1, s.1, "{name}: the predictions differ");
    assert_eq!(g.4, s.4, "{name}: pruned RFs differ");
    assert_eq!(
        (g.2, g.3),
        (s.2, s.3),
        "{name}: 2-D steps or halvings differ"
    );
}

/// Every configuration of the 2-D path's tests (`rf_2d::cases`); all group but shared RFs
/// with two outputs (one partition regressing both: two outputs per RF).
#[test]
fn grouped_updates_match_one_at_a_time() {
    for (name, n_in, n_out, cfg) in cases() {
        let grouped = !(cfg.shared_rfs && n_out > 1);
        compare(
            name,
            grouped,
            || Lwpr::new(n_in, n_out, &cfg).unwrap(),
            11,
            3000,
        );
    }
}

/// RFs with one direction (as a loaded model may have) cannot join a group: every other RF
/// of a trained model is given a fresh one-direction PLS model, then both paths train on.
#[test]
fn rfs_with_one_direction_are_updated_alone() {
    let cfg = cross_config();
    let mut m = Lwpr::new(2, 1, &cfg).unwrap();
    train(false, &mut m, 5, 1500);
    let p = m.params().clone();
    for (k, rf) in m.subs[0].rfs.iter_mut().enumerate() {
        if k % 2 == 1 {
            rf.outs[0] = Pls::new(&p, 1, rf.outs[0].beta0);
        }
    }
    let bytes = m.to_bytes();
    compare(
        "one direction",
        true,
        || Lwpr::from_bytes(&bytes).unwrap(),
        6,
        1500,
    );
}

/// Trains a cross model (`cfg`), applies `poison` to every third RF, trains on with and
/// without grouping and compares; most poisoned RFs must have been removed.
fn poison_and_compare(name: &str, cfg: &LwprConfig, poison: impl Fn(&mut Rf)) {
    let mut m = Lwpr::new(2, 1, cfg).unwrap();
    train(false, &mut m, 5, 1500);
    let mut poisoned = Vec::new();
    for (k, rf) in m.subs[0].rfs.iter_mut().enumerate() {
        if k % 3 == 0 {
            poison(rf);
            poisoned.push(rf.id);
        }
    }
    let (g, _) = run(false, &mut m.clone(), 6, 300);
    let mut single = m.clone();
    let (s, _) = run(true, &mut single, 6, 300);
    let left = poisoned
        .iter()
        .filter(|id| single.subs[0].rfs.iter().any(|rf| rf.id == **id))
        .count();
    assert!(
        left + 5 < poisoned.len(),
        "{name}: {left} of {} poisoned RFs left: the test misses its case",
        poisoned.len()
    );
    assert!(g.0 == s.0, "{name}: the saved models differ");
    assert_eq!(g.1, s.1, "{name}: the predictions differ");
}

/// RFs whose state diverges inside a group are removed as when updated alone, for each part
/// of the guard: the prediction (an infinite `SSYres` of the first direction), the metric
/// alone with finite predictions (infinite learning rates, meta learning off), and a
/// direction that does not predict yet (the second, with `n_data₁ = 2`).
#[test]
fn diverging_rfs_in_groups_are_removed_alike() {
    let b = cross_config();
    poison_and_compare("prediction", &b, |rf| rf.outs[0].ss_yres[0] = f64::INFINITY);
    let no_meta = LwprConfig {
        meta: false,
        ..b.clone()
    };
    poison_and_compare("metric", &no_meta, |rf| rf.alpha.fill(f64::INFINITY));
    poison_and_compare("second direction", &b, |rf| {
        rf.outs[0].ss_yres[1] = f64::INFINITY;
        rf.outs[0].n_data[1] = 2.0;
    });
}
