"""osrl.Robot equals `osrl dynamics --json` bit for bit, its URDF equals `osrl robot --urdf`,
its algorithms agree with each other, and bad inputs raise."""

import json

import numpy as np
import pytest

import osrl


def cli_dynamics(cargo, robot, q, qd, qdd, u):
    fmt = lambda v: ",".join(repr(float(a)) for a in v)
    out = cargo("-p", "osrl-cli", "--", "dynamics", "--robot", robot, "--q", fmt(q), "--qd",
                fmt(qd), "--qdd", fmt(qdd), "--u", fmt(u), "--json")
    return json.loads(out.splitlines()[-1])


def same(a, b) -> bool:
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    return a.shape == b.shape and (a.view(np.uint64) == b.view(np.uint64)).all()


def check_against_cli(cargo, r: osrl.Robot, name: str, seed: int):
    rng = np.random.default_rng(seed)
    n = r.dof
    q = rng.uniform(np.maximum(r.q_min, -3), np.minimum(r.q_max, 3))
    qd, qdd, u = rng.normal(size=n), rng.normal(size=n), rng.normal(size=n) * 5
    ref = cli_dynamics(cargo, name, q, qd, qdd, u)
    x, xd, jdot_qd = r.kinematics(q, qd)
    assert same(r.fk(q), ref["x"]) and same(x, ref["x"])
    assert same(xd, ref["xd"]) and same(jdot_qd, ref["Jdot_qd"])
    assert same(r.jacobian(q), ref["J"])
    assert same(r.mass_matrix(q), ref["M"])
    assert same(r.gravity(q), ref["g"])
    assert same(r.nonlinear_effects(q, qd), ref["h"])
    assert same(r.friction(qd), ref["friction"])
    assert same(r.rnea(q, qd, qdd), ref["tau"])
    assert same(r.forward_dynamics(q, qd, u), ref["qdd_forward"])
    assert r.task_axes == ref["task_axes"] and r.name == ref["robot"]


@pytest.mark.parametrize("name", osrl.Robot.builtins())
def test_builtin_equals_cli(cargo, name):
    r = osrl.Robot.builtin(name)
    for seed in range(3):
        check_against_cli(cargo, r, name, seed)


@pytest.mark.parametrize("name", osrl.Robot.builtins())
def test_urdf_equals_cli(cargo, name, tmp_path):
    r = osrl.Robot.builtin(name)
    text = cargo("-p", "osrl-cli", "--", "robot", "--robot", name, "--urdf")
    # The CLI also embeds the resolved robot profile (one <osrl_profile/> line); the rest is the
    # model's URDF, which to_urdf() gives.
    lines = text.splitlines(True)
    assert sum("<osrl_profile" in line for line in lines) == 1
    assert r.to_urdf() == "".join(line for line in lines if "<osrl_profile" not in line)
    path = tmp_path / f"{name}.urdf"
    path.write_text(text)
    u = osrl.Robot.from_urdf(path)
    assert u.dof == r.dof and u.task_dim == r.task_dim
    check_against_cli(cargo, u, str(path), 7)
    summary = json.loads(cargo("-p", "osrl-cli", "--", "robot", "--robot", name, "--json")
                         .splitlines()[-1])
    assert r.dof == summary["dof"] and r.joint_names == summary["joints"]
    assert same(r.q_min, summary["q_min"]) and same(r.q_max, summary["q_max"])
    assert same(r.tau_max, summary["tau_max"]) and same(r.q_start, summary["q_start"])
    assert r.total_mass == summary["total_mass"]


@pytest.mark.parametrize("name", osrl.Robot.builtins())
def test_algorithms_agree(name):
    """ABA inverts RNEA; RNEA at unit accelerations minus bias gives the CRBA columns;
    the Jacobian is the derivative of the forward kinematics; h = RNEA(q, q̇, 0) + friction."""
    r = osrl.Robot.builtin(name)
    rng = np.random.default_rng(11)
    for _ in range(5):
        q, qd, qdd = (rng.normal(size=r.dof) for _ in range(3))
        tau = r.rnea(q, qd, qdd)
        assert np.allclose(r.aba(q, qd, tau), qdd, rtol=1e-9, atol=1e-9)
        bias = r.rnea(q, qd, np.zeros(r.dof))
        cols = np.stack([r.rnea(q, qd, e) - bias for e in np.eye(r.dof)], axis=1)
        assert np.allclose(cols, r.mass_matrix(q), rtol=1e-10, atol=1e-12)
        assert np.allclose(r.nonlinear_effects(q, qd), bias + r.friction(qd), rtol=1e-12, atol=1e-12)
        assert np.allclose(r.gravity(q), r.rnea(q, np.zeros(r.dof), np.zeros(r.dof)), atol=1e-12)
        h = 1e-6
        fd = np.stack([(r.fk(q + h * e) - r.fk(q - h * e)) / (2 * h) for e in np.eye(r.dof)], axis=1)
        assert np.allclose(r.jacobian(q), fd, atol=1e-8)


def test_bad_inputs():
    r = osrl.Robot.builtin("sarcos7")
    q = r.q_start
    for bad, text in [(q[:6], "expected 7 values, got 6"), (np.where(np.arange(7) == 2, np.nan, q), "q[2] is not finite"),
                      (q.astype(np.float32), "float32"), (q.reshape(1, 7), "shape (1, 7)"),
                      (np.arange(7), "int64")]:
        for call in (r.fk, r.jacobian, r.mass_matrix, r.gravity):
            with pytest.raises(ValueError) as e:
                call(bad)
            assert text in str(e.value)
    with pytest.raises(ValueError, match="qdd"):
        r.rnea(q, np.zeros(7), np.zeros(3))
    with pytest.raises(ValueError, match="tau"):
        r.aba(q, np.zeros(7), [0.0, np.inf, 0, 0, 0, 0, 0])
    assert same(r.fk(list(q)), r.fk(q))  # a list of numbers is accepted


def test_construction_errors(tmp_path):
    with pytest.raises(ValueError, match="unknown robot 'ur5'"):
        osrl.Robot.builtin("ur5")
    with pytest.raises(FileNotFoundError):
        osrl.Robot.from_urdf(tmp_path / "none.urdf")
    bad = tmp_path / "bad.urdf"
    bad.write_text("<robot name='x'><link name='a'/>")
    with pytest.raises(ValueError, match="bad.urdf"):
        osrl.Robot.from_urdf(bad)
    text = osrl.Robot.builtin("planar3").to_urdf()
    with pytest.raises(ValueError, match="'no_such_link'"):
        osrl.Robot.from_urdf_string(text, tip="no_such_link")
    assert osrl.Robot.from_urdf_string(text, tip=None).dof == 3


def test_urdf_tip_chooses_the_end_effector(tmp_path):
    planar3 = osrl.Robot.builtin("planar3")
    text = planar3.to_urdf()
    path = tmp_path / "planar3.urdf"
    path.write_text(text)
    q = np.array([0.3, -0.5, 0.7])
    # The export's ee_link is what the naming rule picks anyway.
    for r in (osrl.Robot.from_urdf(path, tip="ee_link"),
              osrl.Robot.from_urdf_string(text, tip="ee_link")):
        assert r.dof == 3 and same(r.fk(q), planar3.fk(q))
    # A link further up: the joints beyond it are locked, its origin is the end effector.
    short = osrl.Robot.from_urdf(path, tip="elbow_link")
    assert short.dof == 2 and short.joint_names == planar3.joint_names[:2]
    assert not np.allclose(short.fk(q[:2]), planar3.fk(q))
    with pytest.raises(ValueError, match=r"planar3.urdf: .*'nope'"):
        osrl.Robot.from_urdf(path, tip="nope")


@pytest.mark.parametrize("call, args, culprit", [
    ("rnea", ("z", "big_qd", "z"), "qd"),
    ("rnea", ("z", "z", "huge"), "qdd"),
    ("aba", ("z", "z", "huge"), "tau"),
    ("forward_dynamics", ("z", "big_qd", "z"), "qd"),
    ("forward_dynamics", ("z", "z", "huge"), "u"),
    ("nonlinear_effects", ("z", "big_qd"), "qd"),
    ("kinematics", ("z", "big_qd"), "qd"),
])
def test_results_that_overflow_raise(call, args, culprit):
    r = osrl.Robot.builtin("planar3")
    values = {"z": np.zeros(3), "big_qd": np.full(3, 1e200), "huge": np.full(3, 1e308)}
    # These returned NaN silently.
    with pytest.raises(ValueError, match=rf"^{call}: the result is not finite .* most likely "
                                         rf"through {culprit};"):
        getattr(r, call)(*(values[a] for a in args))
    # Large but representable inputs still give finite results.
    ok = {"z": np.zeros(3), "big_qd": np.full(3, 1e100), "huge": np.full(3, 1e200)}
    out = getattr(r, call)(*(ok[a] for a in args))
    assert all(np.isfinite(o).all() for o in (out if isinstance(out, tuple) else (out,)))
