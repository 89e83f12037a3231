//! The metric's learning rates `α`: their layout (full or diagonal metric, localised kernel)
//! and how meta learning moves them.
#![allow(clippy::needless_range_loop)]

use lwpr::{Lwpr, LwprConfig};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

#[test]
fn learning_rates_follow_the_layout_and_meta_learning() {
    use lwpr::datasets::{cross_config, cross_train};
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let data = cross_train(&mut rng, 400);
    // (meta, diag_only): the rates after training and their initial value.
    for (meta, diag) in [(true, false), (false, false), (true, true)] {
        let cfg = LwprConfig {
            meta,
            diag_only: diag,
            ..cross_config()
        };
        let a0 = cfg.init_alpha;
        let mut m = Lwpr::new(2, 1, &cfg).unwrap();
        m.update(&data.x[0], &[data.y[0]]).unwrap();
        let fresh = m.rfs(0).unwrap().next().unwrap().learning_rates();
        let upper = |r: usize, c: usize| if diag { r == c } else { c >= r };
        for r in 0..2 {
            for c in 0..2 {
                let want = if upper(r, c) { a0 } else { 0.0 };
                assert_eq!(
                    fresh[(r, c)],
                    want,
                    "fresh RF, ({r}, {c}), meta {meta} diag {diag}"
                );
            }
        }
        for _ in 0..3 {
            for (x, &y) in data.x.iter().zip(&data.y) {
                m.update(x, &[y]).unwrap();
            }
        }
        // Elements whose rate differs from `init_alpha` in some RF.
        let mut changed = [[false; 2]; 2];
        for rf in m.rfs(0).unwrap() {
            let a = rf.learning_rates();
            for r in 0..2 {
                for c in 0..2 {
                    let v = a[(r, c)];
                    if !upper(r, c) {
                        assert_eq!(v, 0.0);
                        continue;
                    }
                    assert!(v > 0.0 && v.is_finite(), "({r}, {c}): {v}");
                    changed[r][c] |= v != a0;
                    if !meta {
                        // Without meta learning a rate only halves: a0 / 2^k.
                        let k = (a0 / v).log2();
                        assert!(k >= 0.0 && (k - k.round()).abs() < 1e-12, "({r}, {c}): {v}");
                    }
                }
            }
        }
        // A new RF far from the data (no template): its own rates, all `init_alpha`.
        m.update(&[5.0, 5.0], &[0.0]).unwrap();
        let far = m
            .rfs(0)
            .unwrap()
            .find(|rf| rf.center() == [5.0, 5.0])
            .unwrap();
        let a = far.learning_rates();
        for r in 0..2 {
            for c in 0..2 {
                assert_eq!(a[(r, c)], if upper(r, c) { a0 } else { 0.0 }, "new RF");
            }
        }
        for r in 0..2 {
            for c in 0..2 {
                // Meta learning adapts every free element somewhere.
                let want = meta && upper(r, c);
                assert!(
                    !want || changed[r][c],
                    "({r}, {c}) never adapted, diag {diag}"
                );
            }
        }
    }
}

/// With a third input that is always 0, nothing moves the rates of the elements of `M`
/// between it and the others (their gradients are exactly 0): they stay at `init_alpha` (up
/// to `e^{ln α}` rounding), while those of the data's two inputs adapt.
#[test]
fn learning_rates_adapt_only_where_the_data_varies() {
    use lwpr::datasets::{cross_config, cross_train};
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let data = cross_train(&mut rng, 400);
    let cfg = cross_config();
    let a0 = cfg.init_alpha;
    let mut m = Lwpr::new(3, 1, &cfg).unwrap();
    for _ in 0..3 {
        for (x, &y) in data.x.iter().zip(&data.y) {
            m.update(&[x[0], x[1], 0.0], &[y]).unwrap();
        }
    }
    let mut adapted = [[false; 3]; 3];
    for rf in m.rfs(0).unwrap() {
        let a = rf.learning_rates();
        for (r, c) in [(0, 2), (1, 2)] {
            assert!(
                (a[(r, c)] / a0 - 1.0).abs() < 1e-9,
                "({r}, {c}): {}",
                a[(r, c)]
            );
        }
        for r in 0..3 {
            for c in 0..r {
                assert_eq!(a[(r, c)], 0.0, "lower element ({r}, {c})");
            }
            for c in r..3 {
                adapted[r][c] |= (a[(r, c)] / a0 - 1.0).abs() > 1e-3;
            }
        }
    }
    for (r, c) in [(0, 0), (0, 1), (1, 1)] {
        assert!(adapted[r][c], "({r}, {c}) never adapted");
    }
}
