//! `osrl lwpr fit` and `osrl lwpr eval` on small CSV files: the report, saving and testing a
//! model again, and errors that name what was wrong.

mod common;

use common::{last_json, osrl};
use rand::{RngExt, SeedableRng};
use std::path::{Path, PathBuf};

/// A fresh folder for one test.
fn folder(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("lwpr-cli-{name}"));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn cross(x1: f64, x2: f64) -> f64 {
    (-10.0 * x1 * x1)
        .exp()
        .max((-50.0 * x2 * x2).exp())
        .max(1.25 * (-5.0 * (x1 * x1 + x2 * x2)).exp())
}

/// `n` rows of the cross function (with noise of standard deviation `noise`) as CSV.
fn cross_csv(path: &Path, n: usize, noise: f64, seed: u64) {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut s = String::from("x1,x2,y\n");
    for _ in 0..n {
        let (a, b): (f64, f64) = (rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0));
        let e: f64 = rng.random_range(-1.0..1.0) * noise;
        s += &format!("{a},{b},{}\n", cross(a, b) + e);
    }
    std::fs::write(path, s).unwrap();
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// `osrl lwpr fit --train TRAIN --test TEST --inputs 2 EXTRA…`: (success, stdout, stderr).
fn fit2(train: &Path, test: &Path, extra: &[&str]) -> (bool, String, String) {
    let mut args = vec![
        "lwpr",
        "fit",
        "--train",
        s(train),
        "--test",
        s(test),
        "--inputs",
        "2",
    ];
    args.extend_from_slice(extra);
    osrl(&args)
}

#[test]
fn fit_reports_and_eval_of_the_saved_model_agrees() {
    let d = folder("fit");
    let (train, test, model) = (d.join("train.csv"), d.join("test.csv"), d.join("m.bin"));
    cross_csv(&train, 400, 0.05, 1);
    cross_csv(&test, 200, 0.0, 2);
    let fit = |seed: &str| {
        let (ok, out, err) = fit2(
            &train,
            &test,
            &[
                "--epochs",
                "10",
                "--seed",
                seed,
                "--save",
                s(&model),
                "--json",
            ],
        );
        assert!(ok, "{err}");
        assert_eq!(out.lines().count(), 1, "--json prints only the JSON object");
        last_json(&out)
    };
    let j = fit("3");
    for key in [
        "nmse",
        "n_rfs",
        "update_us",
        "predict_us",
        "train_seconds",
        "unsupported",
        "metric_skipped",
        "removed_non_finite",
    ] {
        assert!(!j[key].is_null(), "{key} missing: {j}");
    }
    assert_eq!(j["removed_non_finite"], 0, "{j}");
    let nmse = j["nmse"][0].as_f64().unwrap();
    // A fitted cross, not the mean (nMSE 1) nor a failed fit.
    assert!(nmse > 0.0 && nmse < 0.5, "{j}");
    assert_eq!(j["n_rfs"].as_array().unwrap().len(), 1);
    assert_eq!(j["outputs"], serde_json::json!(["y"]));
    assert_eq!(
        (j["n_train"].as_u64(), j["n_test"].as_u64()),
        (Some(400), Some(200))
    );
    // The same seed gives the same numbers.
    assert_eq!(fit("3")["nmse"], j["nmse"]);
    // No temporary file is left next to the model.
    let mut names: Vec<_> = std::fs::read_dir(&d)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(names, ["m.bin", "test.csv", "train.csv"]);
    // The saved model predicts the test set exactly as the model that was fitted.
    let (ok, out, err) = osrl(&["lwpr", "eval", "--model", s(&model), "--test", s(&test)]);
    assert!(ok, "{err}");
    assert!(out.contains("nMSE"), "table expected without --json: {out}");
    let e = last_json(&out);
    assert_eq!(e["nmse"], j["nmse"]);
    assert_eq!(e["n_rfs"], j["n_rfs"]);
    // A truncated model file is an error naming the file.
    let bytes = std::fs::read(&model).unwrap();
    let cut = d.join("cut.bin");
    std::fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap();
    let (ok, _, err) = osrl(&["lwpr", "eval", "--model", s(&cut), "--test", s(&test)]);
    assert!(
        !ok && err.contains("cut.bin") && err.contains("cannot read LWPR model"),
        "{err}"
    );
}

#[test]
fn bad_csv_files_name_the_line_column_and_text() {
    let d = folder("csv");
    let good = d.join("good.csv");
    cross_csv(&good, 50, 0.0, 3);
    let cases: [(&str, &str, &[&str]); 7] = [
        (
            "x1;x2;y\n0.1;0.2;0.3\n",
            "semicolons",
            &[":2:", "separator must be a comma"],
        ),
        (
            "x1,x2,y\n0.1,0.2,0.3\n0.2,abc,0.4\n",
            "nonnum",
            &[":3:", "column 2 (x2)", "'abc'"],
        ),
        (
            "x1,x2,y\n0.1,NaN,0.3\n",
            "nan",
            &[":2:", "column 2 (x2)", "not finite"],
        ),
        (
            "x1,x2,y\n0.1,0.2\n",
            "ragged",
            &[":2:", "2 columns", "header has 3"],
        ),
        (
            "0.1,0.2,0.3\n0.2,0.3,0.4\n",
            "noheader",
            &[":1:", "header row"],
        ),
        (
            "x1,x1,y\n0.1,0.2,0.3\n",
            "dup",
            &["columns 1 and 2", "'x1'"],
        ),
        ("x1,x2,y\n", "nodata", &["no data rows"]),
    ];
    for (text, name, want) in cases {
        let p = d.join(format!("{name}.csv"));
        std::fs::write(&p, text).unwrap();
        let (ok, _, err) = fit2(&p, &good, &[]);
        assert!(!ok, "{name} accepted");
        assert!(err.contains(&format!("{name}.csv")), "{name}: {err}");
        for w in want {
            assert!(err.contains(w), "{name}: '{w}' not in {err}");
        }
    }
    // Line numbers count blank lines; other encodings and line ends are named.
    let cases: [(&[u8], &str, &str); 3] = [
        (
            b"x1,x2,y\n\n0.1,0.2,0.3\n\n0.2,x,0.4\n",
            "blank",
            "blank.csv:5: column 2",
        ),
        (
            b"x1,x2,y\n0.1,0.2,\xe90.3\n",
            "latin1",
            "latin1.csv:2: not UTF-8",
        ),
        (b"x1,x2,y\r0.1,0.2,0.3\r", "cr", "lone carriage return"),
    ];
    for (bytes, name, want) in cases {
        let p = d.join(format!("{name}.csv"));
        std::fs::write(&p, bytes).unwrap();
        let (ok, _, err) = fit2(&p, &good, &[]);
        assert!(!ok && err.contains(want), "{name}: {err}");
    }
    // A byte-order mark, \r\n line ends, blank lines, quoted names and spaces are fine: the
    // same numbers as the plain file.
    let plain = std::fs::read_to_string(&good).unwrap();
    let mut lines = plain.lines();
    lines.next();
    let fancy = d.join("fancy.csv");
    let body: Vec<String> = lines
        .map(|l| format!(" {} \r\n\r\n", l.replace(',', " , ")))
        .collect();
    std::fs::write(
        &fancy,
        format!("\u{feff}\"x1\",\"x2\",\"y\"\r\n{}", body.concat()),
    )
    .unwrap();
    let run = |train: &Path| {
        let (ok, out, err) = fit2(train, &good, &["--epochs", "2", "--json"]);
        assert!(ok, "{err}");
        last_json(&out)
    };
    let (a, b) = (run(&good), run(&fancy));
    assert_eq!(a["nmse"], b["nmse"]);
    assert_eq!(b["outputs"], serde_json::json!(["y"]));
    // A test file whose columns differ from the training file's.
    let other = d.join("other.csv");
    std::fs::write(&other, "y,x2,x1\n0.1,0.2,0.3\n").unwrap();
    let (ok, _, err) = fit2(&good, &other, &[]);
    assert!(
        !ok && err.contains("column 1 is 'y'") && err.contains("good.csv"),
        "{err}"
    );
}

#[test]
fn bad_configs_and_save_paths_fail_before_training() {
    let d = folder("cfg");
    let data = d.join("data.csv");
    cross_csv(&data, 50, 0.0, 4);
    let fit = |extra: &[&str]| fit2(&data, &data, extra);
    let cfg = d.join("c.toml");
    let cases = [
        (
            "init_alpha = 0\n",
            vec!["c.toml", "init_alpha = 0", "must be finite and > 0"],
        ),
        (
            "cutoff = 1\n",
            vec!["c.toml", "cutoff = 1 is outside [0, 1)"],
        ),
        (
            "meta = true\ninit_d = \"abc\"\n",
            vec![
                "c.toml:2:10",
                "`init_d = \"abc\"`",
                "expected a number r (for r·I)",
            ],
        ),
        (
            "norm_in = \"mean\"\n",
            vec!["c.toml:1:11", "`norm_in = \"mean\"`", "\"std\""],
        ),
        (
            "norm_out = 1e-300\n",
            vec!["c.toml", "norm_out = 1e-300 is outside [1e-100, 1e100]"],
        ),
        ("w_gem = 0.2\n", vec!["c.toml:1:1", "w_gem"]),
    ];
    for (text, want) in cases {
        std::fs::write(&cfg, text).unwrap();
        let (ok, _, err) = fit(&["--config", s(&cfg)]);
        assert!(!ok, "{text} accepted");
        assert_eq!(err.lines().count(), 1, "one line: {err}");
        for w in want {
            assert!(err.contains(w), "{text}: '{w}' not in {err}");
        }
    }
    // Saving into a folder that does not exist, or onto a folder, fails before training.
    let missing = d.join("no/such/folder/m.bin");
    let (ok, out, err) = fit(&["--save", s(&missing)]);
    assert!(
        !ok && out.is_empty() && err.contains("folder does not exist"),
        "{out} {err}"
    );
    let (ok, out, err) = fit(&["--save", s(&d)]);
    assert!(
        !ok && out.is_empty() && err.contains("is a directory"),
        "{out} {err}"
    );
    let slash = format!("{}/", d.join("nosuch").display());
    let (ok, out, err) = fit(&["--save", &slash]);
    assert!(
        !ok && out.is_empty() && err.contains("is a folder"),
        "{out} {err}"
    );
    // Too many epochs (or updates to count) is an error naming the range, not an abort.
    let (ok, _, err) = fit(&["--epochs", "18446744073709551615"]);
    assert!(!ok && err.contains("accepted range 1–100000"), "{err}");
    // Outputs scaled by 1e100 by their normalisation (the smallest it may be; their squares
    // and higher powers would overflow in the update, and the model diverge): an error naming
    // the file and line, the value and the divisor, before anything is learnt from that row.
    std::fs::write(&cfg, "norm_out = 1e-100\n").unwrap();
    let (ok, out, err) = fit2(&data, &data, &["--config", s(&cfg), "--json"]);
    let line = err
        .split("data.csv:")
        .nth(1)
        .and_then(|r| r.split(": y[0] = ").next()?.parse::<usize>().ok());
    assert!(
        !ok && out.is_empty()
            && line.is_some_and(|l| l >= 2)
            && err.contains("norm_out[0] = 1e-100"),
        "{out} {err}"
    );
    // norm_in = "std" on an input whose standard deviation is above the normalisation range
    // (values ±2^340, so that it is exactly 2^340 ≈ 2.2e102): an error naming the config, the
    // data, the parameter, the input and the value.
    let wide = d.join("wide.csv");
    let big = 2f64.powi(340);
    let rows: String = (0..50)
        .map(|i| {
            format!(
                "{:e},0.2,{}\n",
                big * (2 * (i % 2) - 1) as f64,
                i as f64 / 50.0
            )
        })
        .collect();
    std::fs::write(&wide, format!("x1,x2,y\n{rows}")).unwrap();
    std::fs::write(&cfg, "norm_in = \"std\"\n").unwrap();
    let (ok, out, err) = fit2(&wide, &data, &["--config", s(&cfg)]);
    assert!(!ok && out.is_empty(), "{out} {err}");
    let want = format!(
        "norm_in[0] = \"std\" = {big:e}, the standard deviation of input 0, is above 1e100"
    );
    for w in ["c.toml", "wide.csv", &want] {
        assert!(err.contains(w), "'{w}' not in {err}");
    }
    // A constant test target (0.1: its computed variance is a rounding residue, not 0): nMSE
    // undefined, said on stderr, null in the JSON.
    let flat = d.join("flat.csv");
    let rows: String = (0..100)
        .map(|i| format!("{},0.2,0.1\n", i as f64 / 100.0))
        .collect();
    std::fs::write(&flat, format!("x1,x2,y\n{rows}")).unwrap();
    let (ok, out, err) = fit2(&data, &flat, &["--json"]);
    assert!(ok, "{err}");
    assert!(err.contains("constant"), "{err}");
    assert!(last_json(&out)["nmse"][0].is_null());
}
