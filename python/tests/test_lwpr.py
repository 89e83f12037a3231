"""osrl.Lwpr's Python interface: config keywords, shapes and dtypes, errors that change nothing,
batches against single calls, the Jacobian against finite differences, files and pickling."""

import os
import pickle
import threading
import time

import numpy as np
import pytest

import osrl


def trained(n=400, seed=0, **cfg) -> osrl.Lwpr:
    rng = np.random.default_rng(seed)
    x = rng.uniform(-1, 1, (n, 2))
    y = np.stack([np.sin(3 * x[:, 0]) * x[:, 1], x[:, 0] ** 2], axis=1)
    m = osrl.Lwpr(2, 2, init_d=20.0, **cfg)
    m.update_batch(x, y)
    return m


def test_config_keywords():
    m = osrl.Lwpr(3, 1, init_d=np.array([1.0, 3.0]), kernel="bisquare", meta=True,
                  kernel_dims=np.array([0, 2]), w_gen=np.float64(0.3), init_alpha=np.int64(9))
    cfg = m.config
    assert cfg["init_d"] == [1.0, 3.0] and cfg["kernel"] == "bisquare"
    assert cfg["kernel_dims"] == [0, 2] and cfg["w_gen"] == 0.3 and cfg["init_alpha"] == 9.0
    assert osrl.Lwpr(3, 1, **cfg).config == cfg
    assert set(cfg) == set(osrl.Lwpr(1, 1).config)


@pytest.mark.parametrize("kwargs, exc, text", [
    (dict(init_dd=1.0), TypeError, "unexpected keyword argument 'init_dd'"),
    (dict(w_gen=-1.0), ValueError, "w_gen"),
    (dict(w_gen=float("nan")), ValueError, "finite"),
    (dict(kernel="box"), ValueError, "box"),
    (dict(init_d=[1.0]), ValueError, "init_d"),
    (dict(kernel_dims=[5]), ValueError, "kernel_dims"),
    (dict(norm_in="std"), ValueError, "X.std(axis=0)"),
    (dict(meta="yes"), ValueError, "invalid LWPR config"),
    (dict(init_d=object()), TypeError, "init_d"),
])
def test_bad_config_raises(kwargs, exc, text):
    with pytest.raises(exc, match=None) as e:
        osrl.Lwpr(2, 1, **kwargs)
    assert text in str(e.value)


def test_update_and_predict_shapes():
    m = osrl.Lwpr(2, 2, init_d=20.0)
    p = m.update(np.array([0.1, 0.2]), np.array([1.0, 2.0]))
    assert p.shape == (2,) and p.dtype == np.float64 and np.isnan(p).all()  # no RF yet
    m.update([0.1, 0.2], (1.0, 2.0))  # lists and tuples of numbers are accepted
    assert m.predict(np.array([0.1, 0.2]), strict=False).shape == (2,)
    assert m.n_rfs == [1, 1] and m.n_updates == 2 and (m.n_in, m.n_out) == (2, 2)
    strided = np.array([0.1, 99.0, 0.2])[::2]  # not contiguous
    assert (m.predict(strided, strict=False) == m.predict(np.array([0.1, 0.2]), strict=False)).all()


@pytest.mark.parametrize("x, text", [
    (np.array([1, 2]), "int64"),
    (np.array([0.1, 0.2], dtype=np.float32), "float32"),
    (np.array([[0.1, 0.2]]), "shape (1, 2)"),
    (np.array([0.1, 0.2, 0.3]), "length 3, expected 2"),
    (np.array([0.1, np.nan]), "x[1] is not finite"),
    (np.array([np.inf, 0.1]), "x[0] is not finite"),
    (np.array([1e45, 0.1]), "norm_in"),
    ("0.1 0.2", "str"),
    ([0.1, "a"], "list of numbers"),
])
def test_bad_inputs_raise_and_change_nothing(x, text):
    m = trained()
    before = m.to_bytes()
    for call in (lambda: m.update(x, np.array([1.0, 2.0])), lambda: m.predict(x),
                 lambda: m.predict_conf(x), lambda: m.jacobian(x)):
        if text == "norm_in" and call is not None and call.__code__.co_names[-1] != "update":
            continue  # the magnitude bound is the update's
        with pytest.raises(ValueError) as e:
            call()
        assert text in str(e.value)
    with pytest.raises(ValueError):
        m.update(np.array([0.1, 0.2]), np.array([1.0, np.nan]))
    assert m.to_bytes() == before


def test_batch_errors_change_nothing():
    m = trained()
    before = m.to_bytes()
    rng = np.random.default_rng(5)
    x, y = rng.uniform(-1, 1, (20, 2)), rng.uniform(-1, 1, (20, 2))
    for bad_x, bad_y, text in [
        (np.where(np.arange(40).reshape(20, 2) == 15, np.nan, x), y, "X[7, 1] is not finite"),
        (x, np.where(np.arange(40).reshape(20, 2) == 38, np.inf, y), "Y[19, 0] is not finite"),
        (np.where(np.arange(40).reshape(20, 2) == 30, 1e45, x), y, "row 15"),
        (x[:19], y, "19 rows"),
        (x[:, :1], y, "shape (N, 2)"),
        (x.astype(np.float32), y, "float32"),
    ]:
        with pytest.raises(ValueError) as e:
            m.update_batch(bad_x, bad_y)
        assert text in str(e.value)
    assert m.to_bytes() == before


def test_batches_equal_single_calls():
    rng = np.random.default_rng(2)
    x = rng.uniform(-1, 1, (300, 2))
    y = np.sin(3 * x[:, :1])
    a, b = osrl.Lwpr(2, 1, init_d=20.0), osrl.Lwpr(2, 1, init_d=20.0)
    pa = a.update_batch(x, y[:, 0])  # one output: a 1-D Y is a column
    pb = np.array([b.update(xi, yi) for xi, yi in zip(x, y)])
    assert pa.shape == (300, 1) and np.array_equal(pa, pb, equal_nan=True)
    assert a.to_bytes() == b.to_bytes()
    xt = np.asfortranarray(rng.uniform(-1, 1, (50, 2)))  # column-major input
    assert np.array_equal(a.predict_batch(xt), np.array([a.predict(r) for r in xt]))


def test_no_support():
    m = trained()
    far = np.array([40.0, 40.0])
    with pytest.raises(osrl.NoSupportError) as e:
        m.predict(far)
    assert isinstance(e.value, ValueError)
    assert (m.predict(far, strict=False) == 0.0).all()
    with pytest.raises(osrl.NoSupportError, match="X row 1"):
        m.predict_batch(np.array([[0.0, 0.0], far]))
    out = m.predict_batch(np.array([[0.0, 0.0], far]), strict=False)
    assert (out[1] == 0.0).all() and (out[0] == m.predict(np.zeros(2))).all()


def test_jacobian_matches_finite_differences():
    m = trained(n=2000)
    for x in np.random.default_rng(3).uniform(-0.8, 0.8, (10, 2)):
        jac = m.jacobian(x)
        h = 1e-6
        fd = np.stack([(m.predict(x + h * e) - m.predict(x - h * e)) / (2 * h)
                       for e in np.eye(2)], axis=1)
        assert np.allclose(jac, fd, rtol=1e-5, atol=1e-6)
    y, conf = m.predict_conf(np.zeros(2))
    # The crate's plain and confidence predictions are separate code paths: they agree to
    # about 1e-13 (relative), not bit for bit (each is bit-exact against Rust: test_lwpr_parity).
    assert np.allclose(y, m.predict(np.zeros(2)), rtol=1e-12, atol=0) and (conf > 0).all()


def test_save_load_round_trip(tmp_path):
    m = trained()
    path = tmp_path / "m.lwpr"
    m.save(path)
    m.save(str(path))  # replacing a regular file is fine
    n = osrl.Lwpr.load(path)
    assert n.to_bytes() == m.to_bytes() == path.read_bytes()
    xs = np.random.default_rng(4).uniform(-1, 1, (100, 2))
    assert np.array_equal(n.predict_batch(xs, strict=False), m.predict_batch(xs, strict=False))
    # Both go on learning identically.
    for model in (m, n):
        model.update(np.array([0.3, 0.3]), np.array([1.0, 1.0]))
    assert n.to_bytes() == m.to_bytes()
    p = pickle.loads(pickle.dumps(m))
    assert p.to_bytes() == m.to_bytes()


def test_file_errors(tmp_path):
    m = trained()
    with pytest.raises(FileNotFoundError, match="missing.lwpr"):
        osrl.Lwpr.load(tmp_path / "missing.lwpr")
    good = tmp_path / "good.lwpr"
    m.save(good)
    data = good.read_bytes()
    for name, bad in [("trunc", data[:-3]), ("flip", data[:40] + bytes([data[40] ^ 1]) + data[41:]),
                      ("magic", b"NOTLWPR!" + data[8:])]:
        f = tmp_path / name
        f.write_bytes(bad)
        with pytest.raises(ValueError, match=name):
            osrl.Lwpr.load(f)
    with pytest.raises(IsADirectoryError):
        m.save(tmp_path)
    with pytest.raises(FileNotFoundError):
        m.save(tmp_path / "no" / "such" / "dir.lwpr")
    link = tmp_path / "link.lwpr"
    os.symlink(good, link)
    with pytest.raises(OSError, match="not a regular file"):
        m.save(link)
    assert link.is_symlink() and good.read_bytes() == data
    assert sorted(p.name for p in tmp_path.iterdir()) == ["flip", "good.lwpr", "link.lwpr",
                                                          "magic", "trunc"]
    with pytest.raises(ValueError):
        osrl.Lwpr.from_bytes(b"garbage")


def test_batches_release_the_gil():
    """Another Python thread runs while update_batch works (it could not if the GIL were held)."""
    rng = np.random.default_rng(6)
    x = rng.uniform(-1, 1, (20000, 2))
    y = np.sin(3 * x[:, :1])
    m = osrl.Lwpr(2, 1, init_d=20.0)
    ticks, stop = [], threading.Event()

    def spin():
        while not stop.is_set():
            ticks.append(time.perf_counter())

    t = threading.Thread(target=spin)
    t.start()
    time.sleep(0.01)
    t0 = time.perf_counter()
    m.update_batch(x, y)
    t1 = time.perf_counter()
    stop.set()
    t.join()
    during = sum(t0 < s < t1 for s in ticks)
    assert during > 100, f"{during} ticks of the other thread during {t1 - t0:.3f} s"


def test_concurrent_call_during_a_batch_raises():
    """The model is borrowed while a batch runs without the GIL: another thread's call on the
    same model raises RuntimeError instead of racing."""
    rng = np.random.default_rng(7)
    x = rng.uniform(-1, 1, (100000, 2))
    y = np.sin(3 * x[:, :1])
    m = osrl.Lwpr(2, 1, init_d=20.0)
    errors = []
    t = threading.Thread(target=lambda: m.update_batch(x, y))
    t.start()
    while t.is_alive():
        try:
            m.update(np.zeros(2), np.zeros(1))
        except RuntimeError as e:
            errors.append(e)
            break
    t.join()
    assert errors, "no call overlapped the batch"


def _self_list():
    lst = []
    lst.append(lst)
    return lst


def _deep_list(depth):
    v = [1.0]
    for _ in range(depth):
        v = [v]
    return v


class _ToListSelf:
    """An array-like whose tolist() returns itself."""

    def tolist(self):
        return self


@pytest.mark.parametrize("value, path", [
    (_self_list(), "init_d[0][0]"),
    (_deep_list(6000), "init_d[0][0]"),
    (_ToListSelf(), "init_d:"),
])
def test_recursive_config_values_raise(value, path):
    # These overflowed the stack (a segfault) before the conversion had a depth limit.
    with pytest.raises(ValueError, match="nested more than 64") as e:
        osrl.Lwpr(2, 1, init_d=value)
    assert str(e.value).startswith(path)
    # 64 levels are fine as far as nesting goes (the crate then refuses the value itself).
    with pytest.raises(ValueError) as e:
        osrl.Lwpr(2, 1, init_d=_deep_list(62))
    assert "nested" not in str(e.value)


@pytest.mark.parametrize("call", ["predict_batch", "update_batch"])
def test_absurd_batch_sizes_raise_before_allocating(call):
    m = trained()
    before = m.to_bytes()
    # A broadcast view costs nothing until copied; its copy (16 TB) aborted the process.
    x = np.broadcast_to(np.zeros(2), (10**12, 2))
    y = np.broadcast_to(np.zeros(2), (10**12, 2))
    args = (x,) if call == "predict_batch" else (x, y)
    with pytest.raises(ValueError, match=r"X: 1000000000000 rows × 2 columns .* smaller batches"):
        getattr(m, call)(*args)
    assert m.to_bytes() == before
    assert osrl.MAX_BATCH_VALUES == 2**31
    # Within the limit, broadcast views work as before.
    small = np.broadcast_to(np.array([0.1, 0.2]), (5, 2))
    assert getattr(m, call)(*((small,) if call == "predict_batch"
                              else (small, np.zeros((5, 2))))).shape == (5, 2)


def test_size_arguments_are_named():
    with pytest.raises(ValueError, match=r"n_in = -1: expected an integer ≥ 0"):
        osrl.Lwpr(-1, 1)
    with pytest.raises(ValueError, match=r"n_out = -3"):
        osrl.Lwpr(2, -3)
    with pytest.raises(ValueError, match=r"n_out = 1000000000000000000000000"):
        osrl.Lwpr(2, 10**24)
    with pytest.raises(TypeError, match=r"n_in: expected an integer, got float 2.0"):
        osrl.Lwpr(2.0, 1)
    with pytest.raises(TypeError, match=r"n_out: expected an integer, got bool"):
        osrl.Lwpr(2, True)
    assert osrl.Lwpr(np.int64(2), np.uint8(1)).n_in == 2


def test_update_returns_the_prediction_of_the_updated_fields():
    m = trained(n=2000)
    x = np.array([0.3, -0.2])
    y = m.predict(x) + np.array([0.5, -0.5])  # a sample off the current prediction
    before = m.predict(x)
    returned = m.update(x, y)
    after = m.predict(x)
    # Not the prediction before learning: the updated fields have moved towards y already.
    assert np.all(np.abs(returned - y) < np.abs(before - y))
    assert not np.allclose(returned, before)
    assert np.all(np.abs(returned - after) < np.abs(before - after))
    doc = " ".join(osrl.Lwpr.update.__doc__.split())
    assert "made before learning" not in doc and "after their update" in doc
