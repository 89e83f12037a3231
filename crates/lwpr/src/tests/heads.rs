//! The heads of diagonal-metric RFs (`head/`) in the model: the activation pass over the heads
//! against the pass over the rows, bit for bit, along a training run whose RFs the heads mostly
//! exclude; the activation query against a direct computation; and the heads rebuilt on
//! loading. Their bound itself: `head_bounds.rs`.

use crate::config::{LwprConfig, MetricInit};
use crate::distance::quad;
use crate::model::Lwpr;
use crate::params::Params;
use crate::rf::SubModel;
use crate::scratch::Scratch;
use crate::update::activation::{pass_heads, pass_rows, Top2};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A smooth path through 21 dimensions (as a robot's joint states), two outputs.
fn sample(t: f64, phase: &[f64]) -> (Vec<f64>, [f64; 2]) {
    let x: Vec<f64> = (0..21)
        .map(|j| (t * (0.3 + 0.05 * j as f64) + phase[j]).sin() * (1.0 + 0.1 * j as f64))
        .collect();
    let y = [x[0] * x[1] + x[20].sin(), (x[3] - x[7]).cos()];
    (x, y)
}

fn model() -> Lwpr {
    let cfg = LwprConfig {
        init_d: MetricInit::Scalar(2.0),
        init_alpha: 250.0,
        meta_rate: 250.0,
        // Fast forgetting: the metric steps start after a few dozen samples per RF.
        init_lambda: 0.98,
        final_lambda: 0.98,
        w_gen: 0.2,
        w_prune: 0.6,
        update_d: true,
        diag_only: true,
        meta: true,
        ..Default::default()
    };
    Lwpr::new(21, 2, &cfg).unwrap()
}

/// [`model`] trained on `n` samples of the path of `phase`, `dt` apart.
fn trained(phase: &[f64], n: usize, dt: f64) -> Lwpr {
    let mut m = model();
    for k in 0..n {
        let (x, y) = sample(dt * k as f64, phase);
        m.update(&x, &y).unwrap();
    }
    m
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn pass_heads_avx2(p: &Params, sub: &SubModel, ws: &mut Scratch) -> Top2 {
    pass_heads::<true>(p, sub, ws)
}

fn top_bits(t: &Top2) -> [u64; 6] {
    let w = |w: Option<f64>| w.map_or(u64::MAX, f64::to_bits);
    [
        t.q1.to_bits(),
        t.i1 as u64,
        w(t.w1),
        t.q2.to_bits(),
        t.i2 as u64,
        w(t.w2),
    ]
}

#[test]
fn the_pass_over_heads_gives_the_pass_over_rows() {
    let mut m = model();
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let phase: Vec<f64> = (0..21).map(|_| rng.random_range(0.0..6.0)).collect();
    let (mut excluded, mut measured, mut pruned) = (0usize, 0usize, 0usize);
    for k in 0..3000 {
        let (x, y) = sample(0.05 * k as f64 + 0.01 * rng.random_range(0.0..1.0), &phase);
        let Lwpr { p, subs, ws, .. } = &mut m;
        ws.load_x(p, &x);
        for sub in subs.iter() {
            let top_r = pass_rows::<0, false>(p, sub, ws);
            let act_r = ws.active.clone();
            #[cfg(target_arch = "x86_64")]
            if crate::fast::has_avx2() {
                // SAFETY: the CPU has AVX2.
                let top_a = unsafe { pass_heads_avx2(p, sub, ws) };
                assert_eq!(top_bits(&top_a), top_bits(&top_r), "sample {k}: AVX2");
                assert_eq!(ws.active, act_r, "sample {k}: AVX2's RFs to update");
            }
            let top_h = pass_heads::<false>(p, sub, ws);
            assert_eq!(
                top_bits(&top_h),
                top_bits(&top_r),
                "sample {k}: the two nearest"
            );
            let bits = |a: &[(usize, f64, f64, f64)]| {
                a.iter()
                    .map(|&(i, w, dw, ddw)| (i, w.to_bits(), dw.to_bits(), ddw.to_bits()))
                    .collect::<Vec<_>>()
            };
            assert_eq!(
                bits(&ws.active),
                bits(&act_r),
                "sample {k}: the RFs to update"
            );
            let (pr, qb) = (sub.heads.probe(&ws.xk[..21]), ws.qb_update);
            for i in 0..sub.heads.len() {
                if sub.heads.bound(i, &pr) >= qb {
                    excluded += 1;
                } else {
                    measured += 1;
                }
            }
        }
        let info = m.update(&x, &y).unwrap();
        pruned += info.pruned;
        // The heads follow every change of the rows: additions, removals, metric steps.
        for sub in &m.subs {
            let mut fresh = sub.clone();
            fresh.rebuild_heads(&m.p);
            assert!(fresh.heads == sub.heads, "sample {k}: the heads are stale");
        }
    }
    // The metric steps ran: most metric entries moved from their initial value.
    let moved = m
        .subs
        .iter()
        .flat_map(|s| &s.ds)
        .filter(|&&d| d != 2.0)
        .count();
    let all = m.subs.iter().map(|s| s.ds.len()).sum::<usize>();
    assert!(2 * moved > all, "{moved} of {all} metric entries moved");
    assert!(pruned >= 5, "{pruned} RFs pruned: the test misses removals");
    // Both branches ran often: most RFs excluded by their heads, many measured.
    assert!(
        excluded > 4 * measured && measured > 10_000,
        "{excluded} RFs excluded by the heads, {measured} measured"
    );
}

#[test]
fn loading_rebuilds_the_heads() {
    let m = trained(&[0.5; 21], 400, 0.07);
    assert!(m
        .subs
        .iter()
        .all(|s| s.heads.len() == s.rfs.len() && s.rfs.len() > 5));
    let loaded = Lwpr::from_bytes(&m.to_bytes()).unwrap();
    for (a, b) in loaded.subs.iter().zip(&m.subs) {
        assert!(a.heads == b.heads, "the loaded heads differ");
    }
}

#[test]
fn the_activation_query_skips_only_what_the_rows_put_beyond_the_cutoff() {
    let phase = [1.5; 21];
    let mut m = trained(&phase, 600, 0.05);
    let mut out = Vec::new();
    let (mut listed, mut excluded) = (0, 0);
    for k in 0..200 {
        let (x, _) = sample(0.15 * k as f64 + 0.02, &phase);
        for (s, cutoff) in [(0, 1e-3), (1, 0.05), (0, 0.0)] {
            m.activations(s, &x, cutoff, &mut out).unwrap();
            // Directly from the rows: every RF's `q` in double precision.
            let Lwpr { p, subs, ws, .. } = &mut m;
            ws.load_x(p, &x);
            let sub = &subs[s];
            let pr = sub.heads.probe(&ws.xk[..21]);
            let rows = sub.centers.chunks_exact(21).zip(sub.ds.chunks_exact(21));
            let want: Vec<(u64, u64)> = rows
                .zip(&sub.rfs)
                .filter_map(|((c, d), rf)| {
                    let w = p
                        .kernel(quad(
                            false,
                            true,
                            c,
                            d,
                            &ws.xk[..21],
                            &mut [],
                            f64::INFINITY,
                        ))
                        .0;
                    (w > cutoff).then_some((rf.id, w.to_bits()))
                })
                .collect();
            let got: Vec<(u64, u64)> = out.iter().map(|a| (a.id.0, a.w.to_bits())).collect();
            assert_eq!(got, want, "query {k}, sub-model {s}, cutoff {cutoff}");
            listed += got.len();
            let qb = p.q_bound(cutoff);
            excluded += (0..sub.heads.len())
                .filter(|&i| sub.heads.bound(i, &pr) >= qb)
                .count();
        }
    }
    assert!(
        listed > 1000 && excluded > 10_000,
        "{listed} listed, {excluded} excluded by the heads"
    );
}
