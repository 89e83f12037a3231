"""LWPR from Python gives the Rust crate's numbers bit for bit, on the same data in the same order.

Two references, both Rust programs of this repository run by cargo:
- `crates/lwpr/examples/trace.rs`: one seed of the crate's 2-D cross benchmark (the run of
  `osrl bench lwpr`), every update's prediction before learning and RF count, then the test
  grid's predictions and confidence bounds; replayed here through `osrl.Lwpr.update`;
- `crates/py/examples/lwpr_reference.rs`: any config and CSV data (several outputs, shared RFs,
  kernel and regression dimensions, the SARCOS data), the same numbers plus Jacobians and the
  saved model's bytes.
"""

import json

import numpy as np
import pytest

import osrl


def bits(a) -> np.ndarray:
    return np.ascontiguousarray(a, dtype=np.float64).view(np.uint64)


def from_hex(tokens) -> np.ndarray:
    return np.array([int(t, 16) for t in tokens], dtype=np.uint64)


def test_trace_of_the_cross_benchmark(cargo, tmp_path):
    out = tmp_path / "trace.txt"
    cargo("-p", "lwpr", "--example", "trace", "--", "--test", "cross2", "--seed", "3",
          "--epochs", "2", "--out", str(out))
    lines = out.read_text().splitlines()
    k = lines.index(next(l for l in lines if l.startswith("samples ")))
    n = int(lines[k].split()[1])
    samples = np.array([[float(v) for v in l.split()] for l in lines[k + 1:k + 1 + n]])
    u = lines.index(next(l for l in lines if l.startswith("updates ")))
    n_upd = int(lines[u].split()[1])
    # The crate's cross_config (crates/lwpr/src/datasets.rs).
    m = osrl.Lwpr(2, 1, init_d=25.0, init_alpha=250.0, w_gen=0.2, diag_only=False, meta=True,
                  meta_rate=250.0)
    for line in lines[u + 1:u + 1 + n_upd]:
        i, p, rfs = line.split()
        x, y = samples[int(i), :2], samples[int(i), 2:]
        pred = m.update(x, y)
        assert bits(pred)[0] == bits([float(p)])[0], line
        assert m.n_rfs == [int(rfs)], line
    t = lines.index(next(l for l in lines if l.startswith("test ")))
    grid = [(-1.0 + 0.05 * i, -1.0 + 0.05 * j) for i in range(41) for j in range(41)]
    test_lines = lines[t + 1:]
    assert len(test_lines) == len(grid) == 1681
    for (a, b), line in zip(grid, test_lines):
        y, conf = (float(v) for v in line.split())
        try:
            yp, cp = m.predict_conf(np.array([a, b]))
        except osrl.NoSupportError:
            assert y == 0.0 and np.isnan(conf)
            continue
        assert bits(yp)[0] == bits([y])[0] and bits(cp)[0] == bits([conf])[0], (a, b)


def write_csv(path, rows: np.ndarray) -> None:
    text = "\n".join(",".join(repr(float(v)) for v in r) for r in rows)
    path.write_text(",".join(f"c{i}" for i in range(rows.shape[1])) + "\n" + text + "\n")


def cross_data(rng, n, n_in=2):
    x = rng.uniform(-1, 1, (n, n_in))
    a, b = x[:, 0], x[:, 1]
    cross = np.maximum.reduce([np.exp(-10 * a**2), np.exp(-50 * b**2),
                               1.25 * np.exp(-5 * (a**2 + b**2))])
    y = np.stack([cross + rng.normal(0, 0.1, n), np.sin(3 * a) * b], axis=1)
    return x, y


def run_parity(cargo, tmp_path, config, x, y, x_test, epochs, batch):
    """Trains the crate (reference example) and osrl.Lwpr on the same rows; compares all."""
    k = x.shape[1]
    (tmp_path / "config.json").write_text(json.dumps(config))
    write_csv(tmp_path / "train.csv", np.hstack([x, y]))
    write_csv(tmp_path / "test.csv", np.hstack([x_test, np.zeros((len(x_test), y.shape[1]))]))
    cargo("-p", "osrl-py", "--example", "lwpr_reference", "--",
          *(str(tmp_path / f) for f in ("config.json", "train.csv", "test.csv")),
          str(k), str(epochs), str(tmp_path))
    m = osrl.Lwpr(k, y.shape[1], **config)
    if batch:
        preds = np.vstack([m.update_batch(x, y) for _ in range(epochs)])
    else:
        preds = np.array([m.update(xi, yi) for _ in range(epochs) for xi, yi in zip(x, y)])
    ref = (tmp_path / "updates.txt").read_text().splitlines()
    assert len(ref) == len(preds) == epochs * len(x)
    n_out = y.shape[1]
    for i, (line, p) in enumerate(zip(ref, preds)):
        tok = line.split()
        assert (bits(p) == from_hex(tok[:n_out])).all(), f"update {i}"
    assert m.n_rfs == [int(t) for t in ref[-1].split()[n_out:]]
    unsupported = 0
    for i, (line, xt) in enumerate(zip((tmp_path / "test.txt").read_text().splitlines(), x_test)):
        if line == "none":
            with pytest.raises(osrl.NoSupportError):
                m.predict(xt)
            with pytest.raises(osrl.NoSupportError):
                m.predict_conf(xt)
            unsupported += 1
            continue
        tok = line.split()
        y_plain = m.predict(xt)
        yp, conf = m.predict_conf(xt)
        jac = m.jacobian(xt)
        assert jac.shape == (n_out, k)
        got = np.concatenate([bits(y_plain), bits(yp), bits(conf), bits(jac.ravel())])
        want = from_hex(tok)
        assert (got == want).all(), f"test row {i}: {np.flatnonzero(got != want)} {got.view(np.float64)} {want.view(np.float64)}"
    assert m.to_bytes() == (tmp_path / "model.bin").read_bytes()
    return m, unsupported


def test_two_outputs_full_metric_meta(cargo, tmp_path):
    rng = np.random.default_rng(0)
    x, y = cross_data(rng, 300)
    x_test = np.vstack([rng.uniform(-1, 1, (50, 2)), [[40.0, 40.0]]])
    cfg = dict(init_d=25.0, init_alpha=250.0, w_gen=0.2, diag_only=False, meta=True)
    m, unsupported = run_parity(cargo, tmp_path, cfg, x, y, x_test, epochs=3, batch=False)
    assert unsupported >= 1 and min(m.n_rfs) > 5


def test_shared_rfs_kernel_and_regression_dims(cargo, tmp_path):
    rng = np.random.default_rng(1)
    x2, y = cross_data(rng, 400)
    x = np.hstack([x2, rng.uniform(-1, 1, (400, 2))])
    cfg = dict(shared_rfs=True, kernel="bisquare", kernel_dims=[0, 1],
               regression_dims=[0, 1, 3], init_d=[30.0, 30.0], w_prune=0.7,
               norm_out=[1.0, 2.0])
    run_parity(cargo, tmp_path, cfg, x, y, rng.uniform(-1, 1, (40, 4)), epochs=2, batch=True)


def test_sarcos_rows(cargo, tmp_path, sarcos):
    train, test = sarcos
    x, y = train[:400, :21], train[:400, 21:]
    # crates/lwpr/examples/sarcos.toml with "std" resolved here (the same lists for both).
    cfg = dict(norm_in=x.std(axis=0).tolist(), norm_out=y.std(axis=0).tolist(), init_d=0.3,
               init_alpha=250.0, w_gen=0.2, meta=True)
    run_parity(cargo, tmp_path, cfg, x, y, test[:60, :21], epochs=1, batch=True)
