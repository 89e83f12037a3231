//! The numerical guards of the update: inputs too large once normalised are refused, the
//! leverage guard of the metric step, and the removal of receptive fields whose state diverged.

use lwpr::{Lwpr, LwprConfig, LwprError, MetricInit, Norm, RfEvent, MAX_NORMALISED, NORM_RANGE};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A robot that rests at one point and moves rarely: `x` (in `[-1, 1]^n`) is `0.5` in every
/// dimension 99 % of the time; `y = Σ sin(x_i)` plus uniform noise of ±0.1.
fn resting_sample(rng: &mut ChaCha8Rng, n: usize) -> (Vec<f64>, f64) {
    let moving = rng.random_bool(0.01);
    let x: Vec<f64> = (0..n)
        .map(|_| {
            if moving {
                rng.random_range(-1.0..1.0)
            } else {
                0.5
            }
        })
        .collect();
    let y = x.iter().map(|v| v.sin()).sum::<f64>() + 0.1 * rng.random_range(-1.0..1.0);
    (x, y)
}

/// Trains `cfg` on `steps` resting samples in `n` inputs; checks after every update that the
/// reported counts match the queued events, and returns the model.
fn train_resting(cfg: &LwprConfig, n: usize, steps: usize, seed: u64) -> Lwpr {
    let mut m = Lwpr::new(n, 1, cfg).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    for _ in 0..steps {
        let (x, y) = resting_sample(&mut rng, n);
        let info = m.update(&x, &[y]).unwrap();
        let pruned = m
            .drain_events()
            .filter(|e| matches!(e, RfEvent::Pruned { .. }))
            .count();
        assert_eq!(pruned, info.pruned + info.removed_non_finite);
    }
    m
}

/// Every RF's metric and local model are finite, the model saves and loads, and it predicts
/// finite values (or reports no support) along a line through its data.
fn assert_sound(m: &mut Lwpr) {
    let n = m.n_in();
    for v in m.rfs(0).unwrap() {
        assert!(
            v.metric().iter().all(|a| a.is_finite()),
            "metric of {:?}",
            v.id()
        );
        if let Some(lm) = v.local_model(0) {
            assert!(lm.offset.is_finite() && lm.slope.iter().all(|a| a.is_finite()));
        }
    }
    Lwpr::from_bytes(&m.to_bytes()).expect("the model loads again");
    let mut y = [0.0];
    for k in 0..=20 {
        let x = vec![-1.0 + 0.1 * k as f64; n];
        match m.predict_jacobian(&x, &mut y, &mut vec![0.0; n]) {
            Ok(_) => assert!(y[0].is_finite(), "prediction at {x:?}"),
            Err(e) => assert!(matches!(e, LwprError::NoActiveRf { .. })),
        }
    }
}

/// A value beyond ±`MAX_NORMALISED` once divided by its normalisation is refused with an error
/// that names it and its divisor, and the model is unchanged; the same value with a larger
/// divisor is learnt.
#[test]
fn values_too_large_once_normalised_are_refused() {
    let mut m = train_resting(&LwprConfig::default(), 2, 500, 0);
    let before = m.to_bytes();
    let big = 2.0 * MAX_NORMALISED;
    let e = m.update(&[0.1, -big], &[0.0]).unwrap_err();
    assert!(
        matches!(
            e,
            LwprError::Scale {
                what: "x",
                index: 1,
                ..
            }
        ),
        "{e:?}"
    );
    let msg = e.to_string();
    assert!(msg.contains("x[1]") && msg.contains("norm_in[1]"), "{msg}");
    let e = m.update(&[0.1, 0.2], &[big]).unwrap_err();
    assert!(
        matches!(
            e,
            LwprError::Scale {
                what: "y",
                index: 0,
                ..
            }
        ),
        "{e:?}"
    );
    assert!(e.to_string().contains("norm_out[0]"), "{e}");
    assert_eq!(before, m.to_bytes(), "a refused sample changes nothing");
    // At the limit itself the sample is accepted.
    m.update(&[0.1, MAX_NORMALISED], &[-MAX_NORMALISED])
        .unwrap();

    // An input the model does not use is not checked.
    let cfg = LwprConfig {
        kernel_dims: Some(vec![0]),
        regression_dims: Some(vec![0]),
        ..Default::default()
    };
    let mut m = Lwpr::new(2, 1, &cfg).unwrap();
    m.update(&[0.1, 1e300], &[0.0]).unwrap();
    assert!(matches!(
        m.update(&[-1e300, 0.0], &[0.0]),
        Err(LwprError::Scale { index: 0, .. })
    ));

    // Normalised by 1e10, the same output is 2e30: learnt, and the model stays sound.
    let cfg = LwprConfig {
        norm_out: Norm::Scalar(1e10),
        ..Default::default()
    };
    let mut m = Lwpr::new(1, 1, &cfg).unwrap();
    for k in 0..200 {
        let x = (k % 20) as f64 / 10.0 - 1.0;
        m.update(&[x], &[big * x]).unwrap();
    }
    assert_sound(&mut m);
}

/// Fast forgetting with a robot that rests at one point: the input's variance decays to
/// nothing, so a rare excursion has a leverage `h ≥ 1` in the RFs that see it. The reference
/// step divides by `1 − h` there and the RF's state turns NaN (without the guard, these runs
/// lose 2–10 RFs each to the removal guard); the leverage guard skips those terms instead.
#[test]
fn leverage_guard_keeps_fast_forgetting_finite() {
    let mut skipped = 0;
    for (seed, meta) in [(0, false), (1, false), (2, true)] {
        let cfg = LwprConfig {
            init_d: MetricInit::Scalar(10.0),
            meta,
            init_lambda: 0.95,
            final_lambda: 0.6,
            tau_lambda: 0.5,
            w_gen: 0.2,
            ..Default::default()
        };
        let mut m = train_resting(&cfg, 1, 3000, seed);
        assert_eq!(m.warnings().removed_non_finite, 0, "seed {seed}");
        skipped += m.warnings().metric_skipped;
        assert_sound(&mut m);
    }
    assert!(skipped > 0, "the guard was needed");
}

/// Meta learning under forgetting at 0.99 with a resting robot: a few RFs still diverge (their
/// rates climb to the cap and a memory trace overflows). Each is removed, announced as
/// `Pruned`, counted, and never seen again; the models stay sound.
#[test]
fn diverged_rfs_are_removed_and_announced() {
    let mut removed = 0;
    for (seed, alpha, final_lambda) in [(2, 20.0, 0.99), (2, 100.0, 0.995), (0, 20.0, 0.99)] {
        let cfg = LwprConfig {
            init_d: MetricInit::Scalar(12.0),
            init_alpha: alpha,
            diag_only: false,
            meta: true,
            init_lambda: 0.92,
            final_lambda,
            tau_lambda: 0.64,
            w_gen: 0.24,
            w_prune: 0.8,
            init_s2: 3.6e-13,
            ..Default::default()
        };
        let mut m = Lwpr::new(1, 1, &cfg).unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut gone = Vec::new();
        for _ in 0..5000 {
            let (x, y) = resting_sample(&mut rng, 1);
            let info = m.update(&x, &[y]).unwrap();
            let pruned: Vec<_> = m
                .drain_events()
                .filter_map(|e| match e {
                    RfEvent::Pruned { id, .. } => Some(id),
                    _ => None,
                })
                .collect();
            assert_eq!(pruned.len(), info.pruned + info.removed_non_finite);
            if info.removed_non_finite > 0 {
                assert_eq!(
                    info.added + info.pruned,
                    0,
                    "no add or prune in that update"
                );
                let s = m.last_update_prediction()[0];
                assert!(s.is_finite() || s.is_nan(), "no infinite blend");
                gone.extend(pruned);
            }
        }
        for id in &gone {
            assert!(m.rf(0, *id).is_none(), "{id:?} removed");
        }
        assert_eq!(gone.len() as u64, m.warnings().removed_non_finite);
        removed += gone.len();
        assert_sound(&mut m);
    }
    assert!(removed > 0, "these runs diverge somewhere");
}

fn log_uniform(rng: &mut ChaCha8Rng, lo: f64, hi: f64) -> f64 {
    rng.random_range(lo.ln()..hi.ln()).exp()
}

/// Random configurations over (nearly) the whole valid range of every parameter, 1–4 inputs,
/// 1–2 outputs, shared RFs or not, data at scales from 1e-20 to 1e20 (normalised or not) and
/// four input distributions (uniform, seven collinear values, resting at one point, a tiny
/// cube): after 3,000 updates every model is finite, predicts finite values and loads again.
/// Without the guards 108 of these 300 runs fail; without the PLS step's guard alone, 4 (a
/// direction that does not predict yet overflows, and the saved model cannot be loaded).
#[test]
fn random_configs_stay_finite_and_loadable() {
    let (mut skipped, mut removed) = (0, 0);
    for case in 0..300u64 {
        let r = &mut ChaCha8Rng::seed_from_u64(case);
        let n_in = r.random_range(1..5usize);
        let n_out = r.random_range(1..3usize);
        let xs = log_uniform(r, 1e-20, 1e20);
        let ys = log_uniform(r, 1e-20, 1e20);
        let normalise = r.random_bool(0.5);
        let cfg = LwprConfig {
            init_d: MetricInit::Scalar(log_uniform(r, 1e-3, 1e4)),
            init_alpha: log_uniform(r, 1e-3, 1e8),
            diag_only: r.random_bool(0.5),
            meta: r.random_bool(0.5),
            meta_rate: log_uniform(r, 1e-3, 1e8),
            penalty: if r.random_bool(0.2) {
                0.0
            } else {
                log_uniform(r, 1e-12, 1e3)
            },
            w_gen: r.random_range(0.01..0.9),
            w_prune: r.random_range(0.3..1.0),
            init_lambda: r.random_range(0.5..1.0),
            final_lambda: r.random_range(0.5..1.0),
            tau_lambda: r.random_range(0.0..1.0),
            init_s2: log_uniform(r, 1e-300, 1e10),
            add_threshold: log_uniform(r, 1e-3, 1e3),
            kernel: if r.random_bool(0.5) {
                lwpr::Kernel::Gaussian
            } else {
                lwpr::Kernel::Bisquare
            },
            shared_rfs: r.random_bool(0.3),
            norm_in: Norm::Scalar(if normalise { xs } else { 1.0 }),
            norm_out: Norm::Scalar(if normalise { ys } else { 1.0 }),
            ..Default::default()
        };
        let mut m = Lwpr::new(n_in, n_out, &cfg).unwrap();
        let kind = r.random_range(0..4);
        let (mut x, mut y) = (vec![0.0; n_in], vec![0.0; n_out]);
        for k in 0..3000 {
            for v in x.iter_mut() {
                *v = xs
                    * match kind {
                        0 => r.random_range(-1.0..1.0),
                        1 => (k % 7) as f64 * 0.1,
                        2 if r.random_bool(0.99) => 0.5,
                        2 => r.random_range(-1.0..1.0),
                        _ => r.random_range(-1.0..1.0) * 1e-6,
                    };
            }
            for (o, v) in y.iter_mut().enumerate() {
                let s: f64 = x.iter().map(|a| (a / xs * (o + 1) as f64).sin()).sum();
                *v = (s + 0.1 * r.random_range(-1.0..1.0)) * ys;
            }
            m.update(&x, &y).unwrap();
        }
        let back = Lwpr::from_bytes(&m.to_bytes());
        assert!(back.is_ok(), "case {case}: {:?}\n{cfg:?}", back.err());
        for s in 0..m.n_sub() {
            for v in m.rfs(s).unwrap() {
                let ok = v
                    .center()
                    .iter()
                    .chain(v.metric().iter())
                    .all(|a| a.is_finite());
                assert!(ok, "case {case}: RF {:?}", v.id());
            }
        }
        let mut yp = vec![0.0; n_out];
        if m.predict(&x, &mut yp).is_ok() {
            assert!(yp.iter().all(|a| a.is_finite()), "case {case}: {yp:?}");
        }
        skipped += m.warnings().metric_skipped;
        removed += m.warnings().removed_non_finite;
    }
    // Both guards were exercised.
    assert!(skipped > 0 && removed > 0, "{skipped} {removed}");
}

/// `"std"` resolved to the data's standard deviations: tiny ones (constant columns) and NaN
/// become 1; one above the range, or infinite, is refused, naming the parameter, the
/// dimension and the value, and the config is left as it was.
#[test]
fn std_normalisation_is_resolved_within_the_range() {
    use lwpr::NormKeyword::Std;
    let std = || Norm::Keyword(Std);
    let mut cfg = LwprConfig {
        norm_in: std(),
        norm_out: std(),
        ..lwpr::datasets::cross_config()
    };
    cfg.resolve_std(&[1e-13, 1e100], &[f64::NAN]).unwrap();
    assert_eq!(cfg.norm_in, Norm::List(vec![1.0, 1e100]));
    assert_eq!(cfg.norm_out, Norm::List(vec![1.0]));
    Lwpr::new(2, 1, &cfg).unwrap();
    for (s_in, s_out, want) in [
        (
            [1.0, 1e101],
            1.0,
            "norm_in[1] = \"std\" = 1e101, the standard deviation of input 1, is above 1e100",
        ),
        (
            [1.0, 1.0],
            f64::INFINITY,
            "norm_out[0] = \"std\": the standard deviation of output 0 is too large to compute",
        ),
    ] {
        let mut cfg = LwprConfig {
            norm_in: std(),
            norm_out: std(),
            ..lwpr::datasets::cross_config()
        };
        let e = cfg.resolve_std(&s_in, &[s_out]).unwrap_err();
        assert!(matches!(e, LwprError::Config(_)));
        assert!(e.to_string().contains(want), "{e}");
        // Neither normalisation resolved.
        assert_eq!((cfg.norm_in, cfg.norm_out), (std(), std()));
    }
    // Only "std" is resolved: a given normalisation is kept, even with a huge deviation.
    let mut cfg = LwprConfig {
        norm_in: Norm::Scalar(2.0),
        ..lwpr::datasets::cross_config()
    };
    cfg.resolve_std(&[1e300, 1e300], &[1e300]).unwrap();
    assert_eq!(
        (cfg.norm_in, cfg.norm_out),
        (Norm::Scalar(2.0), Norm::Scalar(1.0))
    );
}

/// A normalisation outside [`NORM_RANGE`] is refused with an error naming the entry; at the
/// range's ends, with powers of two (so that scaling is exact), a model of scaled data is the
/// unscaled one to the bit, and its metrics, centres, local models, predictions and Jacobians
/// in user units are finite: the unscaled ones times the scales, exactly. (The input and
/// output scales are independent, so that one used for the other would show.)
#[test]
fn normalisations_at_the_ends_of_their_range() {
    let (lo, hi) = NORM_RANGE;
    for (norm_in, norm_out, want) in [
        (
            Norm::Scalar(lo / 10.0),
            Norm::Scalar(1.0),
            "norm_in = 1e-101 is outside",
        ),
        (
            Norm::List(vec![1.0, hi * 10.0]),
            Norm::Scalar(1.0),
            "norm_in[1] = 1e101",
        ),
        (
            Norm::Scalar(1.0),
            Norm::List(vec![f64::NAN]),
            "norm_out[0] = NaN",
        ),
        (
            Norm::Scalar(1.0),
            Norm::Scalar(0.0),
            "norm_out = 0 is outside [1e-100, 1e100]",
        ),
    ] {
        let cfg = LwprConfig {
            norm_in,
            norm_out,
            ..lwpr::datasets::cross_config()
        };
        let e = Lwpr::new(2, 1, &cfg).unwrap_err().to_string();
        assert!(e.contains(want), "{e}");
    }
    let data = lwpr::datasets::cross_train(&mut ChaCha8Rng::seed_from_u64(5), 300);
    // 2^±332 lie within the range (1.1e-100 and 8.7e99), as do 2^200 and 2^-300.
    let (tiny, huge) = (2f64.powi(-332), 2f64.powi(332));
    let (big, small) = (2f64.powi(200), 2f64.powi(-300));
    assert!(lo <= tiny && huge <= hi && lo <= small && big <= hi);
    let train = |sx: f64, sy: f64| {
        let cfg = LwprConfig {
            norm_in: Norm::Scalar(sx),
            norm_out: Norm::Scalar(sy),
            ..lwpr::datasets::cross_config()
        };
        let mut m = Lwpr::new(2, 1, &cfg).unwrap();
        for _ in 0..3 {
            for (x, y) in data.x.iter().zip(&data.y) {
                m.update(&[x[0] * sx, x[1] * sx], &[y * sy]).unwrap();
            }
        }
        m
    };
    let mut base = train(1.0, 1.0);
    for (sx, sy) in [(tiny, big), (huge, small), (tiny, tiny), (huge, huge)] {
        let mut m = train(sx, sy);
        assert!(m.n_rfs_total() > 5);
        assert_eq!(m.n_rfs(), base.n_rfs());
        for (a, b) in m.rfs(0).unwrap().zip(base.rfs(0).unwrap()) {
            assert_eq!(a.id(), b.id());
            let d = a.metric();
            assert_eq!(d, b.metric() / (sx * sx), "metric");
            // Finite, and not flushed to 0 on the diagonal.
            assert!(d.iter().all(|v| v.is_finite()) && d.diagonal().iter().all(|v| *v > 0.0));
            assert_eq!(
                a.center(),
                b.center().iter().map(|c| c * sx).collect::<Vec<_>>()
            );
            let (la, lb) = (a.local_model(0).unwrap(), b.local_model(0).unwrap());
            assert_eq!(la.offset, lb.offset * sy);
            assert_eq!(la.mean, lb.mean.iter().map(|c| c * sx).collect::<Vec<_>>());
            let slope: Vec<f64> = lb.slope.iter().map(|s| s * sy / sx).collect();
            assert_eq!(la.slope, slope);
            assert!(la.slope.iter().all(|v| v.is_finite()));
        }
        let (mut ya, mut yb, mut ja, mut jb) = ([0.0], [0.0], [0.0; 2], [0.0; 2]);
        for k in 0..=10 {
            let x = [-0.5 + 0.1 * k as f64, 0.3];
            base.predict_jacobian(&x, &mut yb, &mut jb).unwrap();
            m.predict_jacobian(&[x[0] * sx, x[1] * sx], &mut ya, &mut ja)
                .unwrap();
            assert_eq!(ya[0], yb[0] * sy);
            assert_eq!(ja, [jb[0] * sy / sx, jb[1] * sy / sx]);
            assert!(ja.iter().all(|v| v.is_finite()));
        }
    }
}
