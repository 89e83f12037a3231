"""The learned controller from Python: `osrl.LearnedController` gives the Rust controller's
commands bit for bit on a closed loop (crates/py/examples/learned_reference.rs runs a model
trained by `osrl train`), bad inputs raise and change nothing, save/load round-trips;
`osrl.Learner` learns from transitions; `osrl.train` trains on a MuJoCo robot."""

import struct

import numpy as np
import pytest

import osrl
from osrl import Measurement


@pytest.fixture(scope="session")
def model_file(cargo, tmp_path_factory):
    """A planar3 controller trained by the Rust CLI for 0.2 simulated minutes."""
    out = tmp_path_factory.mktemp("learned") / "planar3.model"
    cargo("--", "train", "--robot", "planar3", "--trajectory", "figure8", "--minutes", "0.2",
          "--out", str(out))
    return out


@pytest.fixture(scope="session")
def adapted_file(cargo, model_file, tmp_path_factory):
    """That controller after 0.1 simulated minutes of `osrl adapt` with a 0.5 kg payload: its
    re-adaptation, and with it the task-space disturbance observer, is on."""
    out = tmp_path_factory.mktemp("adapted") / "planar3.model"
    cargo("--", "adapt", "--model", str(model_file), "--change", "payload=0.5", "--minutes",
          "0.1", "--seed", "0", "--out", str(out))
    return out


def _floats(words):
    return np.array([struct.unpack("<d", bytes.fromhex(w)[::-1])[0] for w in words])


def _meas(q, qd, x, xd, n, m, xdd=None):
    return Measurement(0.0, q, qd, x, xd, np.zeros(m) if xdd is None else xdd, np.zeros(n))


@pytest.mark.parametrize("which", ["trained", "adapted"])
def test_commands_equal_the_rust_controller_bit_for_bit(cargo, model_file, adapted_file, which):
    path = model_file if which == "trained" else adapted_file
    steps = 400
    text = cargo("-p", "osrl-py", "--example", "learned_reference", "--", str(path), str(steps))
    c = osrl.LearnedController.load(path)
    # The adapted controller's disturbance observer reads the measured task acceleration.
    assert c.observer == (which == "adapted")
    n, m = c.dof, c.task_dim
    lines = text.split("\n")[:steps]
    assert len(lines) == steps
    for k, line in enumerate(lines):
        v = _floats(line.split())
        q, qd, x, xd = v[:n], v[n:2 * n], v[2 * n:2 * n + m], v[2 * n + m:2 * n + 2 * m]
        xdd = v[2 * n + 2 * m:2 * n + 3 * m]
        t = v[2 * n + 3 * m:2 * n + 6 * m]
        u_rust = v[2 * n + 6 * m:]
        u = c.command(_meas(q, qd, x, xd, n, m, xdd), t[:m], t[m:2 * m], t[2 * m:])
        assert u.tobytes() == u_rust.tobytes(), f"step {k}: {u} != {u_rust}"
    assert sum(c.counts) == steps


def test_properties_and_save_load(model_file, tmp_path):
    c = osrl.LearnedController.load(model_file)
    assert (c.dof, c.task_dim, c.robot, c.control_period) == (3, 2, "planar3", 0.002)
    assert c.home.shape == (3,) and c.n_local_models > 0 and c.task_axes == [0, 2]
    assert c.training is None and c.sim_training_minutes == pytest.approx(0.2)
    c.save(tmp_path / "copy.model")
    d = osrl.LearnedController.load(tmp_path / "copy.model")
    assert d.n_local_models == c.n_local_models
    meas = _meas(c.home, np.zeros(3), np.array([0.65, 0.25]), np.zeros(2), 3, 2)
    goal = (np.array([0.65, 0.25]), np.zeros(2), np.zeros(2))
    assert c.command(meas, *goal).tobytes() == d.command(meas, *goal).tobytes()


def test_bad_inputs_raise_and_change_nothing(model_file, tmp_path):
    c = osrl.LearnedController.load(model_file)
    ok = _meas(c.home, np.zeros(3), np.array([0.65, 0.25]), np.zeros(2), 3, 2)
    goal = [np.array([0.65, 0.25]), np.zeros(2), np.zeros(2)]
    bad_q = _meas(np.array([0.0, np.nan, 0.0]), np.zeros(3), np.zeros(2), np.zeros(2), 3, 2)
    with pytest.raises(ValueError, match=r"measurement.q\[1\] = NaN is not finite"):
        c.command(bad_q, *goal)
    with pytest.raises(ValueError, match="x_d: expected 2 values, got 3"):
        c.command(ok, np.zeros(3), *goal[1:])
    with pytest.raises(ValueError, match="int64"):
        c.command(ok, goal[0], goal[1], np.zeros(2, dtype=np.int64))
    with pytest.raises(ValueError, match="has no `q`"):
        c.command(object(), *goal)
    assert c.counts == (0, 0, 0)
    with pytest.raises(OSError):
        osrl.LearnedController.load(tmp_path / "missing.model")
    (tmp_path / "junk.model").write_bytes(b"junk")
    with pytest.raises(ValueError, match="junk.model"):
        osrl.LearnedController.load(tmp_path / "junk.model")


def test_learner_steps_and_learns():
    rng = np.random.default_rng(0)
    lrn = osrl.Learner(3, 2, 0.002, robot="planar3",
                       config={"guards": {"warmup_samples": 50}}, seed=1)
    assert not lrn.ready and lrn.n_local_models == 0
    r = osrl.Robot.builtin("planar3")
    q, qd = r.q_start.copy(), np.zeros(3)
    prev = None
    for k in range(120):
        u = lrn.command(q, qd, np.zeros(2), explore=True)
        assert u.shape == (3,) and np.all(np.isfinite(u))
        u = u + rng.normal(0, 1.0, 3)
        qdd = r.aba(q, qd, u)
        x, J = r.fk(q)[r.task_axes], r.jacobian(q)[r.task_axes]
        cur = Measurement(k * 0.002, q.copy(), qd.copy(), x, J @ qd, J @ qdd, u)
        if prev is not None:
            lrn.learn(prev, cur)
        prev = cur
        qd = qd + 0.002 * qdd
        q = q + 0.002 * qd
    assert lrn.ready and lrn.n_local_models > 0
    assert lrn.stats["commands"] == 120
    with pytest.raises(ValueError, match="unknown field `warmup`"):
        osrl.Learner(3, 2, 0.002, robot="planar3", config={"guards": {"warmup": 5}})
    with pytest.raises(ValueError, match="xdd_ref: expected 2 values"):
        lrn.command(q, qd, np.zeros(3))
    with pytest.raises(ValueError, match=r"qd\[0\] = NaN"):
        lrn.command(q, np.array([np.nan, 0.0, 0.0]), np.zeros(2))
    assert lrn.stats["commands"] == 120
    with pytest.raises(ValueError, match=r"cur.u\[0\] = inf"):
        lrn.learn(prev, Measurement(1.0, q, qd, prev.x, prev.xd, prev.xdd, np.full(3, np.inf)))


def test_train_on_mujoco_returns_a_controller():
    pytest.importorskip("mujoco")
    from osrl.mujoco import MujocoRobot

    robot = MujocoRobot.builtin("planar3")
    c = osrl.train(robot, "figure8", minutes=0.05, seed=0,
                   config={"learner": {"guards": {"warmup_samples": 200}},
                           "train": {"babble": {"minutes": 0.03}, "eval_every_minutes": 0.0}})
    assert isinstance(c, osrl.LearnedController) and c.robot == "planar3"
    assert c.n_local_models > 0 and c.training["sim_training_minutes"] == pytest.approx(0.05)
    with pytest.raises(ValueError, match="unknown section 'sim'"):
        osrl.train(robot, minutes=0.01, config={"sim": {}})
    with pytest.raises(ValueError, match="osrl_name"):
        osrl.train(object(), minutes=0.01)


def test_train_raises_the_robots_exception():
    pytest.importorskip("mujoco")
    from osrl.mujoco import MujocoRobot

    class Failing:
        """A MuJoCo robot whose 100th step raises."""

        def __init__(self):
            self.inner, self.steps, self.osrl_name = MujocoRobot.builtin("planar3"), 0, "planar3"

        def __getattr__(self, name):
            return getattr(self.inner, name)

        def step(self, u):
            self.steps += 1
            if self.steps == 100:
                raise RuntimeError("boom at step 100")
            return self.inner.step(u)

    robot = Failing()
    with pytest.raises(RuntimeError, match="boom at step 100"):
        osrl.train(robot, minutes=0.05)
    assert robot.steps == 100
