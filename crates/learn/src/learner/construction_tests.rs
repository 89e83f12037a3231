//! A learner is refused when it is made (`Learner::new`) for a control period a saved model
//! would refuse or an LWPR section (`Models::check_config`) that would fail only when the
//! warm-up ends; a transition is refused unless it spans one control period.

use super::fixture;
use crate::{LearnError, Learner};
use osrl_dynamics::Robot;

/// A control period a saved model would refuse, and an LWPR section that would only fail
/// when the warm-up ends, are refused when the learner is made, the section named.
#[test]
fn a_learner_is_refused_at_once_for_a_bad_period_or_lwpr_section() {
    for dt in [5e-324, 1e-300, 0.5, 1e300, f64::NAN] {
        let e = Learner::new(3, 2, dt, fixture::config()).unwrap_err();
        assert!(matches!(e, LearnError::InvalidConfig(_)), "{e}");
        assert!(e.to_string().contains("control period"), "{e}");
    }
    Learner::new(3, 2, 1e-4, fixture::config()).unwrap();
    let mut cfg = fixture::config();
    cfg.partition.lwpr.init_d = lwpr::MetricInit::Scalar(-1.0);
    let e = Learner::new(3, 2, 0.002, cfg).unwrap_err().to_string();
    assert!(
        e.contains("partition.lwpr: invalid LWPR config: init_d"),
        "{e}"
    );
    let mut cfg = fixture::config();
    cfg.gravity.lwpr.w_gen = 0.0;
    let e = Learner::new(3, 2, 0.002, cfg).unwrap_err().to_string();
    assert!(
        e.contains("gravity.lwpr: invalid LWPR config: w_gen"),
        "{e}"
    );
}

/// The same measurement twice, time going backwards or a missed step is refused and counted,
/// and nothing is learned; a transition within half a period of the control period learns.
#[test]
fn a_transition_must_span_one_control_period() {
    let mut learner = Learner::new(3, 2, 0.002, fixture::config()).unwrap();
    let mut sim = fixture::robot();
    let prev = sim.measurement().clone();
    let cur = sim.step(&[0.0; 3]).unwrap().clone();
    let mut late = cur.clone();
    late.t = prev.t + 0.004;
    for (a, b) in [(&prev, &prev), (&cur, &prev), (&prev, &late)] {
        let before = learner.stats();
        let e = learner.learn(a, b).unwrap_err().to_string();
        assert!(e.contains("is not one control period"), "{e}");
        assert_eq!(learner.stats().rejected, before.rejected + 1);
        assert_eq!(learner.stats().samples, before.samples);
    }
    let mut jittered = cur.clone();
    jittered.t = prev.t + 0.0029;
    learner.learn(&prev, &jittered).unwrap();
}
