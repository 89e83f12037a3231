//! The loaders' fuzz run (issue 30): every loader and parser of the tool (`targets.rs`) on
//! seeded mutations (`mutate.rs`) of a committed corpus (`fuzz/corpus/<loader>/`). A case
//! fails on a panic, on a hang (the watchdog ends the run when one case takes longer than
//! [`CASE_SECONDS`]) or on an allocation beyond [`CASE_BYTES`] (`guard.rs`). Stable Rust, a
//! test of the `osrl` binary:
//!
//! ```text
//! cargo test --release -p osrl-cli --bin osrl fuzz_loaders -- --ignored --nocapture
//! FUZZ_CASES=100000 …  (more cases)   FUZZ_CASE=1234 …  (one case; its input is written)
//! FUZZ_VERBOSE=1 …  (every distinct error message)
//! ```
//!
//! It prints the number of cases, the time, and per loader the cases, the `Ok` outcomes and the
//! distinct error messages (numbers masked): a proxy of the branches it reached.

mod guard;
mod mutate;
mod targets;

pub use guard::Bounded;

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::{BTreeMap, BTreeSet};
use std::path::PathBuf;
use std::time::{Duration, Instant};
use targets::TARGETS;

/// Cases of the CI run (`FUZZ_CASES` overrides).
pub const CASES: usize = 60_000;
/// The run's seed: case `k` uses `SEED + k`.
pub const SEED: u64 = 30;
/// Most bytes one case may hold at once.
pub const CASE_BYTES: usize = 256 << 20;
/// A case running longer than this is a hang.
pub const CASE_SECONDS: u64 = 20;

fn corpus(name: &str) -> Vec<Vec<u8>> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("fuzz/corpus")
        .join(name);
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    let inputs: Vec<Vec<u8>> = files.iter().map(|p| std::fs::read(p).unwrap()).collect();
    assert!(!inputs.is_empty(), "{}: no corpus", dir.display());
    inputs
}

/// What the run saw of one loader.
#[derive(Default)]
struct Seen {
    cases: usize,
    ok: BTreeMap<&'static str, usize>,
    errors: BTreeSet<String>,
}

/// An error message with its numbers and quoted text masked and its length bounded.
fn shape(msg: &str) -> String {
    let mut out = String::new();
    let (mut last_digit, mut quote) = (false, None);
    for c in msg.chars().take(160) {
        if let Some(q) = quote {
            if c == q {
                quote = None;
                out.push(c);
            }
            continue;
        }
        if matches!(c, '\'' | '`' | '"') {
            quote = Some(c);
            out.push(c);
            last_digit = false;
        } else if c.is_ascii_digit() {
            if !last_digit {
                out.push('#');
            }
            last_digit = true;
        } else {
            out.push(c);
            last_digit = false;
        }
    }
    out
}

/// The input of case `k` and its loader's index.
fn input(k: usize, corpora: &[Vec<Vec<u8>>]) -> (usize, Vec<u8>) {
    let t = k % TARGETS.len();
    let c = &corpora[t];
    let round = k / TARGETS.len();
    // The corpus as it is first, then mutations.
    if round < c.len() {
        return (t, c[round].clone());
    }
    let mut rng = ChaCha8Rng::seed_from_u64(SEED + k as u64);
    let (a, b) = (rng.random_range(0..c.len()), rng.random_range(0..c.len()));
    if let Some(part) = TARGETS[t].part.filter(|_| rng.random_bool(0.5)) {
        let r = part(&c[a]);
        let inner = mutate::mutate(&mut rng, &c[a][r.clone()], &c[b][part(&c[b])]);
        let mut v = c[a].clone();
        v.splice(r, inner);
        TARGETS[t].fix.inspect(|fix| fix(&mut v));
        return (t, v);
    }
    let mut v = mutate::mutate(&mut rng, &c[a], &c[b]);
    if let Some(fix) = TARGETS[t].fix.filter(|_| rng.random_bool(0.7)) {
        fix(&mut v);
    }
    (t, v)
}

/// Runs `cases` cases; returns the findings (panics, allocations beyond the bound).
fn run(cases: std::ops::Range<usize>) -> Vec<String> {
    guard::watchdog(Duration::from_secs(CASE_SECONDS));
    let corpora: Vec<Vec<Vec<u8>>> = TARGETS.iter().map(|t| corpus(t.name)).collect();
    let mut seen: Vec<Seen> = TARGETS.iter().map(|_| Seen::default()).collect();
    let mut findings = Vec::new();
    let t0 = Instant::now();
    let n = cases.len();
    for k in cases {
        let (t, bytes) = input(k, &corpora);
        if std::env::var_os("FUZZ_CASE").is_some() {
            let p = std::env::temp_dir().join(format!("osrl-fuzz-case-{k}"));
            std::fs::write(&p, &bytes).unwrap();
            eprintln!("case {k}: {} input in {}", TARGETS[t].name, p.display());
        }
        guard::begin(k);
        let out = std::panic::catch_unwind(|| (TARGETS[t].run)(&bytes));
        let peak = guard::end();
        let s = &mut seen[t];
        s.cases += 1;
        match out {
            Ok(Ok(label)) => *s.ok.entry(label).or_default() += 1,
            Ok(Err(e)) => {
                s.errors.insert(shape(&e));
            }
            Err(p) => {
                let msg = p
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_default();
                findings.push(format!("case {k} ({}): panic: {msg}", TARGETS[t].name));
            }
        }
        if peak > CASE_BYTES {
            findings.push(format!(
                "case {k} ({}): {peak} bytes allocated at once (bound {CASE_BYTES})",
                TARGETS[t].name
            ));
        }
        if k % 2000 == 0 {
            eprintln!("fuzz: case {k} ({:.0} s)", t0.elapsed().as_secs_f64());
        }
    }
    println!(
        "fuzz: {n} cases in {:.1} s, seed {SEED}, {} findings",
        t0.elapsed().as_secs_f64(),
        findings.len()
    );
    println!(
        "{:<14} {:>6} {:>6} {:>15}  ok outcomes",
        "loader", "cases", "ok", "distinct errors"
    );
    for (t, s) in TARGETS.iter().zip(&seen) {
        let ok: usize = s.ok.values().sum();
        println!(
            "{:<14} {:>6} {:>6} {:>15}  {:?}",
            t.name,
            s.cases,
            ok,
            s.errors.len(),
            s.ok
        );
        if std::env::var_os("FUZZ_VERBOSE").is_some() {
            s.errors.iter().for_each(|e| println!("    {e}"));
        }
    }
    findings
}

fn assert_none(findings: Vec<String>) {
    assert!(
        findings.is_empty(),
        "fuzz findings:\n{}",
        findings.join("\n")
    );
}

/// The CI run (`.ci/run`): [`CASES`] cases, or `FUZZ_CASES`; `FUZZ_CASE=k` runs case k alone.
#[test]
#[ignore = "the bounded fuzz run of .ci/run (about 20 s)"]
fn fuzz_loaders() {
    let var = |k: &str| std::env::var(k).ok().and_then(|v| v.parse::<usize>().ok());
    let cases = match (var("FUZZ_CASE"), var("FUZZ_CASES")) {
        (Some(k), _) => k..k + 1,
        (None, n) => 0..n.unwrap_or(CASES),
    };
    assert_none(run(cases));
}

/// Every corpus input and the first mutations of each loader (part of the ordinary tests).
#[test]
fn fuzz_smoke() {
    assert_none(run(0..300));
}

/// The guard measures what a case holds at once (an allocation the bound would refuse).
#[test]
fn the_guard_measures_a_case() {
    guard::begin(usize::MAX - 1);
    let v = vec![0u8; 300 << 20];
    let held = v.len();
    drop(v);
    let small = vec![0u8; 1 << 10];
    drop(small);
    assert!(guard::end() >= held && held > CASE_BYTES);
}
