//! The grouped RF updates of the 2-D shape (`rf_update_group`) against the same RFs updated one
//! at a time by the 2-D code, bit for bit: saved models and predictions after training, for the
//! configurations that group (meta learning on and off, metric learning off, fast forgetting,
//! pruning, a kernel and a regression on different input pairs, shared RFs with one output), a
//! model whose RFs diverge, and a model where some RFs have one direction (they are updated
//! alone, the others still in groups). Both group sizes must have run.

use super::rf_2d::{train, Run};
use crate::config::LwprConfig;
use crate::datasets::cross_config;
use crate::model::Lwpr;
use crate::rf::Pls;
use std::cell::Cell;

thread_local! {
    /// Set: no grouping (see `rf_update_group::switched_off`).
    pub(crate) static OFF: Cell<bool> = const { Cell::new(false) };
    /// Groups of two and of three that ran.
    static GROUPS: Cell<[u64; 2]> = const { Cell::new([0; 2]) };
}

/// Counts a group of `g` RFs (called by `rf_update_group`).
pub(crate) fn count(g: usize) {
    GROUPS.with(|c| {
        let mut v = c.get();
        v[g - 2] += 1;
        c.set(v);
    });
}

/// `train` with grouping on or off; the groups of two and three that ran.
fn run(off: bool, m: &mut Lwpr, seed: u64, n: usize) -> (Run, [u64; 2]) {
    OFF.with(|f| f.set(off));
    GROUPS.with(|c| c.set([0; 2]));
    let r = train(false, m, seed, n);
    OFF.with(|f| f.set(false));
    (r, GROUPS.with(|c| c.get()))
}

/// Asserts that grouped and one-at-a-time training agree and that both group sizes ran.
fn compare(name: &str, mk: impl Fn() -> Lwpr, seed: u64, n: usize) {
    let (g, counts) = run(false, &mut mk(), seed, n);
    let (s, none) = run(true, &mut mk(), seed, n);
    assert_eq!(none, [0, 0], "{name}: grouped with the switch off");
    assert!(
        counts[0] > 100 && counts[1] > 100,
        "{name}: groups of two and three ran {counts:?} times: the test misses its case"
    );
    assert!(g.1.len() > 150, "{name}: too few predictions");
    assert!(g.0 == s.0, "{name}: the saved models differ");
    assert_eq!(g.1, s.1, "{name}: the predictions differ");
    assert_eq!(g.4, s.4, "{name}: pruned RFs differ");
}

#[test]
fn grouped_updates_match_one_at_a_time() {
    let b = cross_config();
    let cases: Vec<(&str, usize, LwprConfig)> = vec![
        ("cross, meta", 2, b.clone()),
        (
            "no meta",
            2,
            LwprConfig {
                meta: false,
                ..b.clone()
            },
        ),
        (
            "no metric learning",
            2,
            LwprConfig {
                update_d: false,
                ..b.clone()
            },
        ),
        (
            "very fast forgetting",
            2,
            LwprConfig {
                init_lambda: 0.9,
                final_lambda: 0.95,
                tau_lambda: 0.99,
                ..b.clone()
            },
        ),
        (
            "pruning",
            2,
            LwprConfig {
                w_prune: 0.5,
                ..b.clone()
            },
        ),
        (
            "kernel on (0, 1), regression on (1, 2)",
            3,
            LwprConfig {
                kernel_dims: Some(vec![0, 1]),
                regression_dims: Some(vec![1, 2]),
                ..b.clone()
            },
        ),
        (
            "shared RFs",
            2,
            LwprConfig {
                shared_rfs: true,
                ..b.clone()
            },
        ),
    ];
    for (name, n_in, cfg) in cases {
        compare(name, || Lwpr::new(n_in, 1, &cfg).unwrap(), 11, 3000);
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
        || Lwpr::from_bytes(&bytes).unwrap(),
        6,
        1500,
    );
}

/// RFs whose state diverges inside a group are removed as when updated alone: a model with
/// an infinite `SSYres` in every third RF.
#[test]
fn diverging_rfs_in_groups_are_removed_alike() {
    let cfg = cross_config();
    let mut m = Lwpr::new(2, 1, &cfg).unwrap();
    train(false, &mut m, 5, 1500);
    let mut poisoned = Vec::new();
    for (k, rf) in m.subs[0].rfs.iter_mut().enumerate() {
        if k % 3 == 0 {
            rf.outs[0].ss_yres[0] = f64::INFINITY;
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
        "{left} of {} poisoned RFs left: the test misses its case",
        poisoned.len()
    );
    assert!(g.0 == s.0, "the saved models differ");
    assert_eq!(g.1, s.1, "the predictions differ");
}
