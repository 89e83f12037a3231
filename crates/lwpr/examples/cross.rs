//! The standard LWPR benchmarks: the 2-D cross (20 epochs) and the 21-D rotated cross
//! (25 epochs), over several seeds; prints one JSON object per test.
//!
//! `cargo run -p lwpr --release --example cross -- [--seeds N] [--only 2|21] [--repeat R]`
//! (`--repeat R`: each seed's run is repeated R times, 1 by default, and the fastest repetition's
//! times are kept; the repetitions compute the same numbers, so on a shared machine this
//! measures the speed without the other jobs' interruptions)
//! (`LWPR_PRUNE=narrower` in the environment selects `shared/LWPR.md`'s prune rule for the 21-D
//! test; the default is the reference C library's, see `lwpr::PruneRule`).

#[path = "../tests/common/mod.rs"]
mod common;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let get = |k: &str| {
        args.iter()
            .position(|a| a == k)
            .map(|i| args[i + 1].clone())
    };
    let seeds: u64 = get("--seeds").map(|s| s.parse().unwrap()).unwrap_or(10);
    let only = get("--only");
    let repeat: usize = get("--repeat").map_or(1, |s| s.parse().unwrap());
    for (name, dim, epochs) in [("cross_2d", "2", 20), ("cross_21d", "21", 25)] {
        if only.as_deref().is_some_and(|o| o != dim) {
            continue;
        }
        let runs: Vec<common::RunResult> = (0..seeds)
            .map(|s| {
                let run = || {
                    if dim == "2" {
                        common::cross_run(s, epochs)
                    } else {
                        common::cross21_run(s, epochs)
                    }
                };
                let mut best = run();
                for _ in 1..repeat {
                    let r = run();
                    best.update_us = best.update_us.min(r.update_us);
                    best.predict_us = best.predict_us.min(r.predict_us);
                }
                best
            })
            .collect();
        let col = |f: fn(&common::RunResult) -> f64| median(runs.iter().map(f).collect());
        println!(
            "{{\"test\":\"{name}\",\"seeds\":{seeds},\"nmse\":{:.5},\"n_rfs\":{},\"update_us\":{:.3},\"predict_us\":{:.3},\"nmse_all\":{:?},\"n_rfs_all\":{:?}}}",
            col(|r| r.nmse),
            col(|r| r.n_rfs as f64),
            col(|r| r.update_us),
            col(|r| r.predict_us),
            runs.iter().map(|r| (r.nmse * 1e5).round() / 1e5).collect::<Vec<_>>(),
            runs.iter().map(|r| r.n_rfs).collect::<Vec<_>>(),
        );
    }
}
