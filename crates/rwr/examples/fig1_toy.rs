//! Fig. 1 of the paper (experiment E1): iterations until `‖θ − θ*‖ < ε` for adaptive versus
//! fixed reward transformation, over seeds and initial `τ`, with and without the σ update.
//! Prints the table and the claim check; the plots are made by `osrl toy`.
//!
//! `cargo run -p rwr --example fig1_toy --release [-- SEEDS]`

use rwr::toy::{check_claims, run, summarize, Report, ToyConfig};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut cfg = ToyConfig::default();
    if let Some(s) = std::env::args().nth(1) {
        cfg.seeds = s.parse()?;
    }
    cfg.validate()?;
    let mut results = Vec::new();
    println!(
        "{:>6} {:>9} {:>6} {:>8} {:>6} {:>6} {:>6}",
        "tau0", "variant", "sigma", "median", "q25", "q75", "never"
    );
    for case in cfg.cases() {
        let runs = (0..cfg.seeds)
            .map(|seed| run(&cfg, case, seed))
            .collect::<Result<Vec<_>, _>>()?;
        let s = summarize(case, &runs, cfg.max_iters);
        println!(
            "{:>6} {:>9} {:>6} {:>8.1} {:>6.1} {:>6.1} {:>6.2}",
            s.tau0,
            format!("{:?}", s.variant).to_lowercase(),
            if s.sigma_update { "update" } else { "fixed" },
            s.median_iters,
            s.q25_iters,
            s.q75_iters,
            s.never_converged
        );
        results.push(s);
    }
    let report = Report {
        results,
        max_iters: cfg.max_iters,
        seeds: cfg.seeds,
    };
    let claims = check_claims(&report);
    for s in &claims.speedups {
        println!(
            "tau0 {:>5} sigma update {:>5}: fixed/adaptive = {:.2}",
            s.tau0, s.sigma_update, s.ratio
        );
    }
    println!(
        "adaptive >= 4x faster for tau0 <= 0.1: {}",
        claims.misscaled_4x_faster
    );
    println!("adaptive never > 20% slower: {}", claims.never_20pct_slower);
    Ok(())
}
