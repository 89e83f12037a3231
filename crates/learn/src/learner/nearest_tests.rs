//! The nearest trained controllers where the blend's support is thin (`nearest.rs`): the
//! command there is `u0` plus the nearest field's controller evaluated at the edge of its
//! support, faded by `λ`; `u0` alone beyond `neighbour_cutoff`.

use super::fixture::{self, one_trained_field};
use super::CommandSource;
use crate::local::smoothstep;

/// The command at `(q, q̇)` without exploration, and its source.
fn command(learner: &mut crate::Learner, q: &[f64], qd: &[f64]) -> ([f64; 3], CommandSource) {
    let mut u = [0.0; 3];
    learner.start_episode(None).unwrap(); // no rate limit against the previous query
    let src = learner
        .command::<rand_chacha::ChaCha8Rng>(q, qd, &[0.3, -0.2], None, &mut u)
        .unwrap();
    (u, src)
}

/// Between the blend's cutoff and `neighbour_cutoff` the command is `u0(x)` plus `λ` times the
/// field's controller at the state pulled radially to where its activation is the cutoff — in
/// a closed form computed here from the field's centre, `β` and activation; beyond, `u0`.
#[test]
fn below_the_cutoff_the_nearest_field_commands_from_its_edge() {
    let mut cfg = fixture::config();
    cfg.controllers.command_projection = 0.0;
    let (cut, far) = (
        cfg.partition.activation_cutoff,
        cfg.controllers.neighbour_cutoff,
    );
    let (mut learner, c) = one_trained_field(cfg);
    let vd = c[3..].to_vec();
    let models = fixture::models(&mut learner);
    let (id, local) = models.locals.map.iter().find(|(_, l)| l.ess > 1e8).unwrap();
    let (id, beta) = (*id, local.rwr.theta().clone());
    let (mut checked, mut beyond) = (0, 0);
    for s in [0.2, 0.3, 0.4, 0.6, 1.5] {
        let q: Vec<f64> = c[..3].iter().map(|v| v + s).collect();
        let mut acts = Vec::new();
        let fwd = &mut fixture::models(&mut learner).forward;
        fwd.activations(&q, &vd, 1e-300, &mut acts).unwrap();
        let w = acts.iter().find(|a| a.id == id).map_or(0.0, |a| a.w);
        let (u, src) = command(&mut learner, &q, &vd);
        let mut u0 = [0.0; 3];
        learner.nominal(&q, &vd, &mut u0).unwrap();
        if w <= far {
            assert_eq!(src, CommandSource::Fallback, "s {s}, w {w}");
            assert_eq!(u, u0);
            beyond += 1;
            continue;
        }
        assert!(w < cut, "s {s}: w {w} is not below the cutoff");
        assert_eq!(src, CommandSource::Extrapolated);
        // The state pulled to the edge: only q differs from the centre (q̇ is the centre's).
        let k = (cut.ln() / w.ln()).sqrt();
        let qp: Vec<f64> = (0..3).map(|i| c[i] + k * (q[i] - c[i])).collect();
        let mut phi = vec![0.0; beta.nrows()];
        learner
            .features
            .controller_common(&mut phi, &[0.3, -0.2], &vd);
        learner.features.controller_local(&mut phi, &qp, &c);
        let lambda = smoothstep((w / far).ln() / (cut / far).ln());
        assert!(lambda > 0.0 && lambda <= 1.0);
        let mut largest = 0.0f64;
        for j in 0..3 {
            let mean: f64 = (0..phi.len()).map(|r| phi[r] * beta[(r, j)]).sum();
            let want = u0[j] + lambda * mean;
            assert!(
                (u[j] - want).abs() < 1e-9 * (1.0 + want.abs()),
                "s {s}: {u:?} against {want} (joint {j})"
            );
            largest = largest.max((lambda * mean).abs());
        }
        assert!(largest > 1e-3, "s {s}: the field's part is not exercised");
        checked += 1;
    }
    assert!(
        checked >= 2 && beyond >= 1,
        "{checked} inside, {beyond} beyond"
    );
}

/// With the option off the learned part fades into `u0` alone (the behaviour before).
#[test]
fn neighbour_cutoff_zero_is_u0_below_the_cutoff() {
    let mut cfg = fixture::config();
    cfg.controllers.neighbour_cutoff = 0.0;
    let (mut off, c) = one_trained_field(cfg);
    let (mut on, _) = one_trained_field(fixture::config());
    let q: Vec<f64> = c[..3].iter().map(|v| v + 0.3).collect();
    let vd = c[3..].to_vec();
    let (u_off, src) = command(&mut off, &q, &vd);
    assert_eq!(src, CommandSource::Fallback);
    let mut u0 = [0.0; 3];
    off.nominal(&q, &vd, &mut u0).unwrap();
    assert_eq!(u_off, u0);
    let (u_on, _) = command(&mut on, &q, &vd);
    assert!(u_on.iter().zip(&u0).any(|(a, b)| (a - b).abs() > 1e-6));
}

/// A config with `neighbour_cutoff` at or above the blend's cutoff, or negative, is refused.
#[test]
fn a_neighbour_cutoff_above_the_blends_is_refused() {
    for bad in [-1e-8, 0.05, 0.5, f64::NAN] {
        let mut cfg = fixture::config();
        cfg.controllers.neighbour_cutoff = bad;
        let err = crate::Learner::new(3, 2, 0.002, cfg)
            .unwrap_err()
            .to_string();
        assert!(err.contains("neighbour_cutoff"), "{bad}: {err}");
    }
}
