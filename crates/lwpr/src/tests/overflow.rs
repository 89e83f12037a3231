//! A model whose coefficients are finite but overflow the blend (a hand-edited file loads: every
//! stored value is finite) predicts an error, not `±∞` or NaN, and leaves `y` untouched.

use crate::datasets::{cross_config, cross_train};
use crate::model::Lwpr;
use crate::LwprError;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

#[test]
fn a_prediction_that_overflows_is_an_error() {
    let mut m = Lwpr::new(2, 1, &cross_config()).unwrap();
    let data = cross_train(&mut ChaCha8Rng::seed_from_u64(2), 500);
    for (x, y) in data.x.iter().zip(&data.y) {
        m.update(x, &[*y]).unwrap();
    }
    let x = [0.1, -0.2];
    let mut y = [0.0];
    m.predict(&x, &mut y).unwrap();
    assert!(y[0].is_finite());
    // Every RF's local model at the largest double, and `x` one unit from its mean along each
    // input: `β₀ + slope · (x − x̄)` overflows.
    for rf in m.subs[0].rfs.iter_mut() {
        rf.mean_x = vec![x[0] - 1.0, x[1] - 1.0];
        let out = &mut rf.outs[0];
        out.refresh_slope(2);
        out.beta0 = f64::MAX;
        out.slope.fill(f64::MAX);
    }
    let mut m = Lwpr::from_bytes(&m.to_bytes()).expect("a file of finite values loads");
    let mut y = [12.5];
    match m.predict(&x, &mut y) {
        Err(LwprError::PredictionOverflow { output: 0, value }) => assert!(!value.is_finite()),
        other => panic!("expected an overflow error, got {other:?}"),
    }
    assert_eq!(y, [12.5], "y untouched");
    let e = m.predict_everywhere(&x, &mut y).unwrap_err();
    assert!(
        matches!(e, LwprError::PredictionOverflow { output: 0, .. }),
        "{e}"
    );
    assert_eq!(y, [12.5], "y untouched");
    assert!(e.to_string().contains("overflow"), "{e}");
}
