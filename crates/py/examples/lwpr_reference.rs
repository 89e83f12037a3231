//! The Rust side of the Python package's bit-for-bit LWPR test (`python/tests/test_lwpr_parity.py`):
//! trains the `lwpr` crate on a CSV file in file order and writes every number the test
//! compares, as `f64` bit patterns (16 hex digits, so nothing is lost in printing).
//!
//! `cargo run --release -p osrl-py --example lwpr_reference -- CONFIG.json TRAIN.csv TEST.csv
//! INPUTS EPOCHS OUT_DIR`: `CONFIG.json` is an `lwpr::LwprConfig` in JSON; the CSV files have a
//! header row, `INPUTS` input columns, then the outputs. Writes `OUT_DIR/updates.txt` (per
//! update: the prediction before learning, then the RF count per sub-model), `OUT_DIR/test.txt`
//! (per test row: the prediction of `predict`, the prediction and confidence bound of
//! `predict_conf`, and the Jacobian of `predict_jacobian`, row-major; or `none` where the model
//! has no support) and `OUT_DIR/model.bin` (the saved model).

use lwpr::{Lwpr, LwprConfig, LwprError};
use std::fmt::Write;
use std::path::Path;

fn rows(path: &str) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    text.lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            l.split(',')
                .map(|c| c.trim().parse().expect("a number"))
                .collect()
        })
        .collect()
}

fn hex(out: &mut String, v: &[f64]) {
    for x in v {
        write!(out, " {:016x}", x.to_bits()).unwrap();
    }
}

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let [config, train, test, inputs, epochs, out] = &a[..] else {
        panic!("usage: CONFIG.json TRAIN.csv TEST.csv INPUTS EPOCHS OUT_DIR");
    };
    let cfg: LwprConfig =
        serde_json::from_str(&std::fs::read_to_string(config).expect("config")).expect("config");
    let (k, epochs): (usize, usize) = (inputs.parse().unwrap(), epochs.parse().unwrap());
    let (train, test) = (rows(train), rows(test));
    let n_out = train[0].len() - k;
    let mut m = Lwpr::new(k, n_out, &cfg).expect("config");
    let mut s = String::new();
    for _ in 0..epochs {
        for r in &train {
            m.update(&r[..k], &r[k..]).expect("a valid sample");
            m.drain_events().for_each(drop);
            hex(&mut s, m.last_update_prediction());
            for c in m.n_rfs() {
                write!(s, " {c}").unwrap();
            }
            s.push('\n');
        }
    }
    let out = Path::new(out);
    std::fs::write(out.join("updates.txt"), &s).unwrap();
    s.clear();
    let (mut y, mut conf, mut jac) = (vec![0.0; n_out], vec![0.0; n_out], vec![0.0; n_out * k]);
    for r in &test {
        let x = &r[..k];
        match m.predict(x, &mut y) {
            Err(LwprError::NoActiveRf { .. }) => s.push_str("none"),
            res => {
                res.expect("a valid input");
                hex(&mut s, &y);
                m.predict_conf(x, &mut y, &mut conf).unwrap();
                hex(&mut s, &y);
                hex(&mut s, &conf);
                m.predict_jacobian(x, &mut y, &mut jac).unwrap();
                hex(&mut s, &jac);
            }
        }
        s.push('\n');
    }
    std::fs::write(out.join("test.txt"), &s).unwrap();
    m.save(out.join("model.bin")).unwrap();
}
