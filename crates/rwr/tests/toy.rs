//! The Fig. 1 experiment's pieces: problem, runs, statistics, claim check (fast cases only;
//! the full sweep is `osrl toy`).
#![allow(clippy::needless_range_loop)]

use rwr::toy::{check_claims, run, summarize, trace, Case, Report, RunOutcome, ToyConfig, Variant};

#[test]
fn theta_star_minimises_the_cost_for_every_state() {
    let cfg = ToyConfig::default();
    let [t1, t2] = cfg.theta_star();
    for s in [-1.0, -0.3, 0.0, 0.7, 1.0] {
        let a = t1 * s + t2;
        for da in [-1e-3, 1e-3, 0.1] {
            assert!(cfg.cost(s, a) <= cfg.cost(s, a + da));
        }
        assert!(cfg.cost(s, a) >= 0.0);
    }
}

#[test]
fn bad_configs_are_rejected() {
    let bad = [
        ToyConfig {
            q: [1.0, -3.0, 0.5],
            ..Default::default()
        }, // 4 q1 q3 < q2²: r can be < 0
        ToyConfig {
            q: [0.0, 0.0, 1.0],
            ..Default::default()
        },
        ToyConfig {
            epsilon: 0.0,
            ..Default::default()
        },
        ToyConfig {
            tau0s: vec![],
            ..Default::default()
        },
        ToyConfig {
            tau0s: vec![1.0, -0.1],
            ..Default::default()
        },
        ToyConfig {
            samples_per_iter: 2,
            ..Default::default()
        },
    ];
    for cfg in bad {
        assert!(cfg.validate().is_err(), "{cfg:?}");
        let case = Case {
            tau0: 1.0,
            variant: Variant::Adaptive,
            sigma_update: false,
        };
        assert!(run(&cfg, case, 0).is_err());
    }
}

#[test]
fn runs_are_seeded_and_converge_on_a_well_scaled_case() {
    let cfg = ToyConfig::default();
    let case = Case {
        tau0: 1.0,
        variant: Variant::Adaptive,
        sigma_update: true,
    };
    let a = run(&cfg, case, 3).unwrap();
    assert_eq!(a, run(&cfg, case, 3).unwrap());
    let it = a.iters.expect("converges");
    assert!(
        (1..=20).contains(&it) && a.final_dist < cfg.epsilon,
        "{a:?}"
    );
    // The trace repeats the run and shows τ adapting (eq. 28) and σ shrinking (eq. 24).
    let t = trace(&cfg, case, 3, it).unwrap();
    assert_eq!(t.len(), it + 1);
    assert_eq!(t[it].dist, a.final_dist);
    assert!(t[1].tau != 1.0 && t[it].sigma < t[0].sigma);
}

#[test]
fn fixed_tau_keeps_tau_and_small_fixed_tau_is_slow() {
    let cfg = ToyConfig {
        max_iters: 20,
        ..Default::default()
    };
    let case = Case {
        tau0: 0.01,
        variant: Variant::Fixed,
        sigma_update: false,
    };
    let t = trace(&cfg, case, 0, 5).unwrap();
    assert!(t.iter().all(|s| s.tau == 0.01 && s.sigma == 1.0));
    // Contraction 1/(1 + 2τσ²) ≈ 0.98 per iteration: nowhere near ε after 20 iterations.
    assert_eq!(run(&cfg, case, 0).unwrap().iters, None);
}

#[test]
fn summary_quantiles_count_failures_as_max_iters_and_claims_pair_rows() {
    let case = Case {
        tau0: 0.1,
        variant: Variant::Fixed,
        sigma_update: false,
    };
    let runs: Vec<RunOutcome> = [Some(2), Some(4), None, Some(6), Some(8)]
        .iter()
        .map(|&iters| RunOutcome {
            iters,
            final_dist: 0.0,
        })
        .collect();
    let s = summarize(case, &runs, 100);
    assert_eq!((s.q25_iters, s.median_iters, s.q75_iters), (4.0, 6.0, 8.0));
    assert_eq!(s.never_converged, 0.2);
    let fast = rwr::toy::CaseSummary {
        variant: Variant::Adaptive,
        median_iters: 1.5,
        ..s
    };
    let report = Report {
        results: vec![s, fast],
        max_iters: 100,
        seeds: 5,
    };
    let c = check_claims(&report);
    assert_eq!(c.speedups.len(), 1);
    assert_eq!(c.speedups[0].ratio, 4.0);
    assert!(c.misscaled_4x_faster && c.never_20pct_slower);
    let slow = rwr::toy::CaseSummary {
        median_iters: 7.3,
        ..fast
    };
    let c = check_claims(&Report {
        results: vec![s, slow],
        max_iters: 100,
        seeds: 5,
    });
    assert!(!c.misscaled_4x_faster && !c.never_20pct_slower);
    let json = serde_json::to_string(&report).unwrap();
    assert!(json.starts_with(
        r#"{"results":[{"tau0":0.1,"variant":"fixed","sigma_update":false,"median_iters":6.0,"#
    ));
}
