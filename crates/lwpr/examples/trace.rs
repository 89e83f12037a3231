//! Writes one seed of a cross test as run by `lwpr::datasets` (the same samples, order and
//! config as `osrl bench lwpr`) in the fixture format of `tests/reference.rs`: the 2-D samples,
//! the rotation, every update's sample index, prediction before learning and RF count, and the
//! final predictions and confidence bounds on the test grid. `scripts/lwpr_reference.py replay
//! FILE` then trains the independent implementation on the same samples and compares.
//!
//! `cargo run -p lwpr --release --example trace -- --test cross2|cross21|cross21diag [--seed S]
//! [--epochs E] --out FILE` (E: 20 for cross2, 25 for the others)

use lwpr::datasets::{
    cross21_config, cross21_data, cross21_run, cross_config, cross_grid, cross_run, cross_train,
    embed, predict_conf_or_nan, rotation, test_nmse, Data, Embedding,
};
use lwpr::{Lwpr, LwprConfig};
use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::fmt::Write;

/// `v` as the fixtures write it: the shortest exact decimal, or `nan`.
fn num(v: f64) -> String {
    if v.is_nan() {
        "nan".into()
    } else {
        format!("{v:?}")
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let get = |k: &str| {
        let i = args.iter().position(|a| a == k)?;
        args.get(i + 1).cloned()
    };
    let case = get("--test").unwrap_or_else(|| "cross2".into());
    let seed: u64 = get("--seed").map_or(0, |s| s.parse().expect("--seed: an integer"));
    let out = get("--out").expect("--out FILE");
    // The data of `datasets::cross_run` / `cross21_data`: points first, then the rotation.
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let flat = cross_train(&mut rng, 500);
    let (cfg, rot, epochs) = match case.as_str() {
        "cross2" => (cross_config(), None, 20),
        "cross21" => (cross21_config(), Some(rotation(&mut rng, 21)), 25),
        "cross21diag" => {
            let cfg = LwprConfig {
                diag_only: true,
                ..cross21_config()
            };
            (cfg, Some(rotation(&mut rng, 21)), 25)
        }
        c => panic!("--test {c}: cross2, cross21 or cross21diag"),
    };
    let epochs = get("--epochs").map_or(epochs, |e| e.parse().expect("--epochs: an integer"));
    let (train, test) = match &rot {
        Some(r) => {
            // The same data as `cross21_data` (which does not return the 2-D points).
            let (train, test, rot) = cross21_data(seed, Embedding::Rotation);
            assert!(
                &rot == r && embed(&flat, r).x == train.x,
                "not cross21_data's samples"
            );
            (train, test)
        }
        None => {
            let (x, y) = (flat.x.clone(), flat.y.clone());
            (Data { x, y }, cross_grid())
        }
    };
    let mut s = String::new();
    writeln!(
        s,
        "# LWPR trace of lwpr::datasets, written by examples/trace.rs"
    )
    .unwrap();
    writeln!(s, "# seed {seed}, epochs {epochs}").unwrap();
    writeln!(s, "case {case}\nguard 1\nsamples {}", flat.y.len()).unwrap();
    for (x, y) in flat.x.iter().zip(&flat.y) {
        writeln!(s, "{:?} {:?} {y:?}", x[0], x[1]).unwrap();
    }
    let d = rot.as_ref().map_or(0, |r| r.nrows());
    writeln!(s, "rotation {d}").unwrap();
    if let Some(r) = &rot {
        for row in r.row_iter() {
            let v: Vec<String> = row.iter().map(|v| format!("{v:?}")).collect();
            writeln!(s, "{}", v.join(" ")).unwrap();
        }
    }
    // The training of `datasets::fit`: a fresh order per epoch from `seed ^ 0x5eed`.
    let mut order_rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5eed);
    let mut m = Lwpr::new(train.x[0].len(), 1, &cfg).unwrap();
    let mut order: Vec<usize> = (0..train.x.len()).collect();
    writeln!(s, "updates {}", epochs * order.len()).unwrap();
    for _ in 0..epochs {
        order.shuffle(&mut order_rng);
        for &i in &order {
            m.update(&train.x[i], &[train.y[i]]).unwrap();
            let p = num(m.last_update_prediction()[0]);
            writeln!(s, "{i} {p} {}", m.n_rfs_total()).unwrap();
        }
    }
    writeln!(s, "test {}", test.y.len()).unwrap();
    for x in &test.x {
        let (y, conf) = predict_conf_or_nan(&mut m, x).unwrap();
        writeln!(s, "{y:?} {}", num(conf)).unwrap();
    }
    std::fs::write(&out, s).unwrap_or_else(|e| panic!("{out}: {e}"));
    let nmse = test_nmse(&mut m, &test).unwrap();
    // The run of `osrl bench lwpr` for this seed ends with the same model.
    let bench = match rot {
        None => cross_run(&cfg, seed, epochs),
        Some(_) => cross21_run(&cfg, seed, epochs),
    }
    .unwrap();
    assert!(
        bench.nmse == nmse && bench.n_rfs == m.n_rfs_total(),
        "the trace is not the benchmark's run: nMSE {nmse} against {}",
        bench.nmse
    );
    println!(
        "{out}: {case} seed {seed} epochs {epochs}: {} RFs, nMSE {nmse:.6}",
        m.n_rfs_total()
    );
}
