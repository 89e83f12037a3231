//! The normalisation guards: normalisations must lie in `NORM_RANGE` (given, or resolved from
//! `"std"`), samples beyond ±`MAX_NORMALISED` once normalised are refused, and a model of
//! data scaled to the range's ends is the unscaled one, exactly.

mod common;

use common::{assert_sound, train_resting};
use lwpr::{Lwpr, LwprConfig, LwprError, Norm, MAX_NORMALISED, NORM_RANGE};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

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
