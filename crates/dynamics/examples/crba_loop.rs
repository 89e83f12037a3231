//! CRBA alone on `sarcos7`, for profiling (issue 31): best time per call over `REPS` (default
//! 300) repetitions of 2,000 calls, as `bench_min`, on standard error.
//! `cargo run --release -p osrl-dynamics --example crba_loop -- 10` under
//! `valgrind --tool=callgrind` gives the instructions per call.

use osrl_dynamics::{crba, robots};
use std::hint::black_box;
fn main() {
    let model = robots::sarcos7();
    let n = model.nq();
    let mut data = model.data();
    let q: Vec<f64> = (0..n).map(|i| 0.1 * i as f64 + 0.2).collect();
    let reps: usize = std::env::args()
        .nth(1)
        .map(|s| s.parse().unwrap())
        .unwrap_or(300);
    let mut best = f64::INFINITY;
    for _ in 0..reps {
        let t0 = std::time::Instant::now();
        for _ in 0..2000 {
            black_box(crba(&model, &mut data, black_box(&q)).unwrap()[(0, 0)]);
        }
        best = best.min(t0.elapsed().as_nanos() as f64 / 2000.0);
    }
    eprintln!("{best:.1} ns/call (best of {reps} x 2000)");
}
