//! The plumbing of `osrl bench references`, without the reference library: the sample file's
//! round trip, the harness's JSON, the accuracy check, the skip path, the Markdown.

use super::datasets::{samples, Set};
use super::samples::{Measured, Samples};
use super::{c_ref, markdown, references};
use lwpr::datasets::{cross_config, cross_run};
use lwpr::{LwprConfig, MetricInit, PruneRule};
use serde_json::json;
use std::path::Path;

#[test]
fn sample_file_round_trips_bit_for_bit() {
    let (mut s, _) = samples(Set::Cross21, 3, 2, Path::new("-")).unwrap();
    s.train.truncate(50);
    s.train[0][0] = 0.1 + 0.2; // not a short decimal
    s.test[1][2] = -1e-300;
    let back = Samples::from_text(&s.to_text()).unwrap();
    assert_eq!(back, s);
    assert_eq!((back.n_in, back.n_out, back.train[0].len()), (21, 1, 22));
}

#[test]
fn a_truncated_or_foreign_file_is_refused_with_the_reason() {
    let (s, _) = samples(Set::Cross2, 0, 1, Path::new("-")).unwrap();
    let text = s.to_text();
    let err = Samples::from_text(&text[..text.len() / 2]).unwrap_err();
    assert!(format!("{err:#}").contains("ends before"), "{err:#}");
    let err = Samples::from_text("lwpr-samples 2\n").unwrap_err();
    assert!(err.to_string().contains("not an lwpr-samples 1 file"));
}

#[test]
fn settings_the_c_library_cannot_take_are_refused() {
    let diag = LwprConfig {
        init_d: MetricInit::Diagonal(vec![1.0, 2.0]),
        ..cross_config()
    };
    assert!(Samples::new(2, 1, &diag)
        .unwrap_err()
        .to_string()
        .contains("scalar init_d"));
    let narrower = LwprConfig {
        prune_rule: PruneRule::Narrower,
        ..cross_config()
    };
    assert!(Samples::new(2, 1, &narrower).is_err());
}

#[test]
fn the_crate_on_the_written_samples_is_the_bench_lwpr_run() {
    // Same points, same per-epoch orders, same settings as `lwpr::datasets::cross_run`.
    let (s, cfg) = samples(Set::Cross2, 4, 2, Path::new("-")).unwrap();
    assert_eq!(s.train.len(), 1000);
    let ours = s.run_rust(&cfg).unwrap();
    let theirs = cross_run(&cross_config(), 4, 2).unwrap();
    assert_eq!(ours.n_rfs, theirs.n_rfs);
    assert!(
        (ours.nmse[0] - theirs.nmse).abs() <= 1e-12 * theirs.nmse,
        "{ours:?} {theirs:?}"
    );
}

#[test]
fn harness_json_is_parsed_and_bad_output_named() {
    let m = c_ref::parse(
        "{\"nmse\": [0.03, 0.05], \"n_rfs\": 40, \"update_us\": 3.5, \"predict_us\": 0.7, \"update_us_batch\": 3.4, \"predict_us_batch\": 0.65, \"updates\": 10, \"tests\": 4}\n",
    )
    .unwrap();
    assert_eq!(
        m,
        Measured {
            nmse: vec![0.03, 0.05],
            n_rfs: 40,
            update_us: 3.5,
            predict_us: 0.7,
            update_us_batch: 3.4,
            predict_us_batch: 0.65,
        }
    );
    assert!((m.nmse_mean() - 0.04).abs() < 1e-15);
    let err = c_ref::parse("Segmentation fault").unwrap_err();
    assert!(err.to_string().contains("Segmentation fault"), "{err}");
    assert!(
        c_ref::parse("{\"nmse\": [], \"n_rfs\": 1, \"update_us\": 1, \"predict_us\": 1, \"update_us_batch\": 1, \"predict_us_batch\": 1}").is_err()
    );
    // Without the timings of whole loops (a harness from before they were added).
    assert!(
        c_ref::parse("{\"nmse\": [0.1], \"n_rfs\": 1, \"update_us\": 1, \"predict_us\": 1}")
            .is_err()
    );
}

#[test]
fn a_missing_reference_is_a_reason_to_skip() {
    let why = c_ref::missing(Path::new("/nonexistent/lwpr-c")).unwrap();
    assert!(why.contains("/nonexistent/lwpr-c"), "{why}");
}

fn set(rust: f64, lo: f64, hi: f64) -> serde_json::Value {
    json!({"rust": {"nmse": {"median": rust}}, "c_o2": {"nmse": {"min": lo, "max": hi}}})
}

#[test]
fn the_check_takes_the_range_with_its_margin_and_passes_skipped_sets() {
    let lwpr = json!({"cross2": set(0.035, 0.03, 0.04), "sarcos7": {"skipped": "no data"}});
    references::check(&lwpr, 0.1).unwrap();
    references::check(&json!({"a": set(0.043, 0.03, 0.04)}), 0.1).unwrap();
    let err = references::check(&json!({"a": set(0.045, 0.03, 0.04)}), 0.1).unwrap_err();
    assert!(
        err.to_string()
            .contains("outside the reference's range on a"),
        "{err}"
    );
    assert!(references::check(&json!({"b": set(0.02, 0.03, 0.04)}), 0.1).is_err());
    assert!(
        references::check(&json!({"c": {"rust": {}}}), 0.1).is_err(),
        "missing numbers fail"
    );
}

#[test]
fn markdown_shows_skipped_parts_as_skipped_not_zero() {
    let out = json!({
        "machine": {"date": "2026-12-02 12:00 UTC", "cpu": "Some CPU", "cores": 2, "loadavg": "3.1 2.0 1.5"},
        "lwpr": {"sarcos7": {"skipped": "no SARCOS split at x"}},
        "dynamics": {"skipped": "the pin wheel is not importable"},
    });
    let md = markdown::render(&out);
    assert!(
        md.contains("Some CPU") && md.contains("load average 3.1 2.0 1.5"),
        "{md}"
    );
    assert!(
        md.contains("| sarcos7 | skipped: no SARCOS split at x |"),
        "{md}"
    );
    assert!(
        md.contains("Pinocchio's C++ library: skipped (the pin wheel"),
        "{md}"
    );
    assert!(!md.contains("| 0"), "{md}");
}
