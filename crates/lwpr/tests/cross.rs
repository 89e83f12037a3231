//! The standard cross test (`shared/LWPR.md`), small version: seeds 0–3 of the full 500-point,
//! 20-epoch protocol. This is a regression guard (every seed below 0.06, at most 45 RFs); the
//! target itself (median over 10 seeds ≤ 0.04) is measured by `osrl bench lwpr`.

mod common;

#[test]
fn cross_2d_learns() {
    for seed in 0..4 {
        let r = common::cross_run(&common::cross_config(), seed, 20).unwrap();
        assert!(r.nmse < 0.06, "seed {seed}: nMSE {}", r.nmse);
        assert!(r.n_rfs <= 45, "seed {seed}: {} RFs", r.n_rfs);
    }
}
