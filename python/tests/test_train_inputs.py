"""`osrl.train`, `osrl.Learner` and `osrl.LearnedController` on hostile inputs: robots whose
attributes or measurements are wrong, configs that disagree with the keywords, arguments out of
range. Each error names what was wrong; nothing is silently ignored. The robot is a pure-Python
one on `osrl.Robot`'s dynamics (no MuJoCo needed), and the trainings last a few simulated
seconds."""

import copy
import dataclasses
import warnings

import numpy as np
import pytest

import osrl
from osrl import Measurement

QUICK = {"learner": {"guards": {"warmup_samples": 200}},
         "train": {"babble": {"minutes": 0.03}, "eval_every_minutes": 0.0}}


class SimBot:
    """A robot of ROBOT_PROTOCOL.md on osrl's dynamics of a built-in robot (RK4, 2 substeps)."""

    def __init__(self, name="planar3", dt=0.002):
        self.r = osrl.Robot.builtin(name)
        self.osrl_name = name
        self.dof, self.task_dim, self.control_period = self.r.dof, self.r.task_dim, dt
        self.torque_limits = self.r.tau_max
        self.joint_limits = (self.r.q_min, self.r.q_max)
        self.reset()

    def measurement(self):
        x, xd, jdqd = self.r.kinematics(self.q, self.qd)
        xdd = self.r.jacobian(self.q) @ self.r.forward_dynamics(self.q, self.qd, self.u) + jdqd
        a = self.r.task_axes
        return Measurement(self.t, self.q.copy(), self.qd.copy(), x[a], xd[a], xdd[a],
                           self.u.copy())

    def reset(self, q=None, qd=None):
        self.q = np.array(self.r.q_start if q is None else q, float)
        self.qd = np.zeros(self.dof) if qd is None else np.array(qd, float)
        self.u, self.t = np.zeros(self.dof), 0.0
        return self.measurement()

    def step(self, u):
        lim = np.minimum(self.torque_limits, self.r.tau_max)
        self.u = np.clip(np.asarray(u, float), -lim, lim)
        f = lambda q, qd: (qd, self.r.forward_dynamics(q, qd, self.u))
        h = self.control_period / 2
        for _ in range(2):
            q, qd = self.q, self.qd
            k1 = f(q, qd)
            k2 = f(q + h / 2 * k1[0], qd + h / 2 * k1[1])
            k3 = f(q + h / 2 * k2[0], qd + h / 2 * k2[1])
            k4 = f(q + h * k3[0], qd + h * k3[1])
            self.q = q + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
            self.qd = qd + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        self.t += self.control_period
        return self.measurement()


class Bad(SimBot):
    """A SimBot whose measurements go wrong from its 10th step on: `field` replaced by `value`,
    or (value None) a measurement whose `q` property raises."""

    def __init__(self, field, value=None):
        super().__init__()
        self.field, self.value, self.steps = field, value, 0

    def step(self, u):
        self.steps += 1
        m = super().step(u)
        if self.steps < 10:
            return m
        if self.value is None:
            return RaisingQ(m)
        return dataclasses.replace(m, **{self.field: np.full(len(getattr(m, self.field)),
                                                             self.value)})


class RaisingQ:
    """A measurement whose `q` property raises ZeroDivisionError."""

    def __init__(self, m):
        self._m = m

    def __getattr__(self, name):
        return getattr(self._m, name)

    @property
    def q(self):
        return 1 / 0


def robot_with(**attrs):
    bot = SimBot()
    for k, v in attrs.items():
        setattr(bot, k, v)
    return bot


def train(bot, **kw):
    kw.setdefault("minutes", 0.05)
    kw.setdefault("config", QUICK)
    return osrl.train(bot, **kw)


def probe(ctrl):
    """The controller's command at a fixed state and target, as bytes."""
    meas = Measurement(0.0, ctrl.home, np.zeros(3), np.array([0.6, 0.3]), np.zeros(2),
                       np.zeros(2), np.zeros(3))
    return ctrl.command(meas, np.array([0.6, 0.3]), np.zeros(2), np.zeros(2)).tobytes()


# --- the config's values are not overridden by the keywords' defaults (finding 7) ------------

def test_config_values_are_used_and_must_agree_with_keywords():
    cfg = copy.deepcopy(QUICK)
    cfg["trajectory"] = {"kind": "circle"}
    cfg["train"].update(minutes=0.04, seed=7)
    from_config = osrl.train(SimBot(), config=cfg)
    from_keywords = osrl.train(SimBot(), "circle", minutes=0.04, seed=7, config=QUICK)
    both = osrl.train(SimBot(), "circle", minutes=0.04, seed=7, config=cfg)
    # These used to train a figure-8 for 30 (or the keyword's) minutes with seed 0.
    assert from_config.sim_training_minutes == pytest.approx(0.04)
    assert np.array_equal(from_config.home, osrl.Trajectory("planar3", "circle").home)
    assert not np.allclose(from_config.home, osrl.Trajectory("planar3", "figure8").home)
    assert probe(from_config) == probe(from_keywords) == probe(both)
    seed0 = osrl.train(SimBot(), "circle", minutes=0.04, seed=0, config=QUICK)
    assert probe(seed0) != probe(from_config)
    for kw, text in [(dict(minutes=0.05), r"minutes=0.05 and config\['train'\]\['minutes'\] = 0.04"),
                     (dict(seed=1), r"seed=1 and config\['train'\]\['seed'\] = 7"),
                     (dict(trajectory="figure8"),
                      r"trajectory=\"figure8\" and config\['trajectory'\]\['kind'\] = \"circle\"")]:
        with pytest.raises(ValueError, match=text + " disagree"):
            osrl.train(SimBot(), config=cfg, **kw)


# --- the robot's attributes are checked and named (findings 9, 16) -----------------------------

@pytest.mark.parametrize("attrs, exc, text", [
    (dict(torque_limits=-np.ones(3)), ValueError, r"robot.torque_limits\[0\] = -1: .* must be > 0"),
    (dict(torque_limits=np.array([60.0, 0.0, 20.0])), ValueError,
     r"robot.torque_limits\[1\] = 0: .* must be > 0"),
    (dict(torque_limits=np.full(3, -np.inf)), ValueError, r"robot.torque_limits\[0\] = -inf"),
    (dict(torque_limits=None), ValueError, r"robot.torque_limits: expected 3 numbers .* NoneType"),
    (dict(torque_limits=np.ones(2)), ValueError, r"robot.torque_limits: expected 3 numbers .* got 2"),
    (dict(joint_limits=(np.ones(3), -np.ones(3))), ValueError,
     r"robot.joint_limits: joint 0 has q_min = 1 ≥ q_max = -1"),
    (dict(joint_limits=(np.full(3, np.inf), np.full(3, -np.inf))), ValueError,
     r"robot.joint_limits: joint 0 has q_min = inf ≥ q_max = -inf"),
    (dict(joint_limits=np.ones(3)), ValueError, r"robot.joint_limits: expected a pair"),
    (dict(joint_limits=(np.full(3, np.nan), np.ones(3))), ValueError,
     r"robot.joint_limits\[0\] \(q_min\)\[0\] is NaN"),
    (dict(dof=-1), ValueError, r"robot.dof = -1: expected an integer ≥ 0"),
    (dict(dof=3.0), TypeError, r"robot.dof: expected an integer, got float"),
    (dict(dof=7), ValueError, r"robot.dof = 7 and robot.task_dim = 2, but osrl's model planar3"),
    (dict(task_dim=None), TypeError, r"robot.task_dim: expected an integer, got NoneType"),
    (dict(control_period=1e300), ValueError, r"robot.control_period = 1e300 s: must be within"),
    (dict(control_period="0.002"), TypeError, r"robot.control_period: expected a number"),
])
def test_robot_attributes_are_checked_and_named(attrs, exc, text):
    with pytest.raises(exc, match=text):
        train(robot_with(**attrs))


def test_missing_robot_and_bad_arguments_are_named():
    with pytest.raises(TypeError, match=r"^robot: expected a robot .* got None"):
        osrl.train(None)
    bot = SimBot()
    del bot.torque_limits
    with pytest.raises(ValueError, match=r"robot.torque_limits: the robot \(SimBot\) has no") as e:
        train(bot)
    assert isinstance(e.value.__cause__, AttributeError)
    with pytest.raises(ValueError, match=r"seed = -1: expected an integer in \[0, 2\*\*64\)"):
        train(SimBot(), seed=-1)
    # Unlimited joints and motors (inf, as ROBOT_PROTOCOL.md allows) still train.
    free = robot_with(torque_limits=np.full(3, np.inf),
                      joint_limits=(np.full(3, -np.inf), np.full(3, np.inf)))
    assert train(free).n_local_models > 0


# --- the robot's measurements (findings 10, 15, 17) --------------------------------------------

def test_absurd_measured_command_is_named():
    bot = Bad("u", 1e300)
    with pytest.raises(ValueError, match=r"robot.step\(\).u\[0\] = 1e300 N·m: beyond 10 × the "
                                         r"joint's torque limit \(60 N·m"):
        train(bot)
    assert bot.steps == 10


def test_training_that_learns_nothing_raises_or_warns():
    # Every measurement after the 10th rejected by the learner's guards: it used to return a
    # controller without local models, silently.
    with pytest.raises(ValueError, match=r"learned nothing: the learner rejected \d+ of the "
                                         r"robot's \d+ measurements .* accepted \d+"):
        train(Bad("qd", 1e300))
    # Too short for the warm-up: a warning, and the (untrained) controller.
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        c = train(SimBot(), minutes=0.001)
    assert c.n_local_models == 0
    assert any("fewer than its warm-up needs" in str(x.message) for x in w)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert train(SimBot()).n_local_models > 0


def test_exceptions_of_measurement_attributes_propagate():
    with pytest.raises(ZeroDivisionError):
        train(Bad("q"))
    lrn = osrl.Learner(3, 2, 0.002, robot="planar3")
    m = SimBot().reset()
    with pytest.raises(ZeroDivisionError):
        lrn.learn(m, RaisingQ(m))
    with pytest.raises(ValueError, match="cur: expected an osrl.Measurement, it has no `q`") as e:
        lrn.learn(m, object())
    assert isinstance(e.value.__cause__, AttributeError)
    ctrl = train(SimBot())
    with pytest.raises(ZeroDivisionError):
        ctrl.command(RaisingQ(m), np.zeros(2), np.zeros(2), np.zeros(2))


# --- the learner (findings 1, 11, 12, 16) ------------------------------------------------------

def _meas(t):
    r = osrl.Robot.builtin("planar3")
    q = r.q_start
    return Measurement(t, q, np.zeros(3), r.fk(q)[r.task_axes], np.zeros(2), np.zeros(2),
                       np.zeros(3))


def test_learn_needs_consecutive_measurements():
    lrn = osrl.Learner(3, 2, 0.002, robot="planar3", config={"guards": {"warmup_samples": 50}})
    m0, m1 = _meas(0.0), _meas(0.002)
    before = lrn.stats
    for prev, cur, text in [(m1, m1, "time does not advance"), (m1, m0, "time does not advance"),
                            (m0, _meas(0.004), "2.000 control periods apart"),
                            (m0, _meas(0.0009), "0.450 control periods apart")]:
        with pytest.raises(ValueError, match=r"learn\(prev, cur\): cur.t − prev.t = .*" + text
                                             + r".*; nothing was learned$"):
            lrn.learn(prev, cur)
    assert lrn.stats == before
    # Consecutive measurements with timing jitter within half a period are learned from.
    jitter = np.random.default_rng(0).uniform(-0.0004, 0.0004, 80)  # gaps 1.6–2.4 ms
    times = 0.002 * np.arange(80) + jitter
    for t0, t1 in zip(times[:-1], times[1:]):
        lrn.learn(_meas(t0), _meas(t1))
    assert lrn.ready and lrn.stats["samples"] > 0


@pytest.mark.parametrize("dt", [5e-324, 1e-300, 0.0, 5e-5, 0.2, 1e300])
def test_learner_control_period_range(dt):
    with pytest.raises(ValueError, match=r"control_period = .* s: must be within \[0.0001, 0.1\]"):
        osrl.Learner(3, 2, dt, robot="planar3")


def test_learner_arguments_are_checked_at_construction():
    for section in ("partition", "gravity"):
        # Accepted before, failing a warm-up later with another message.
        with pytest.raises(ValueError, match=rf"invalid learner config: {section}.lwpr: .*init_d"):
            osrl.Learner(3, 2, 0.002, robot="planar3", config={section: {"lwpr": {"init_d": -1.0}}})
    assert osrl.Learner(3, 2, 0.002, robot="planar3",
                        config={"partition": {"lwpr": {"init_d": 30.0}}}).dof == 3
    with pytest.raises(ValueError, match=r"^dof = -1: expected an integer ≥ 0"):
        osrl.Learner(-1, 2, 0.002)
    with pytest.raises(ValueError, match=r"^task_dim = -2"):
        osrl.Learner(3, -2, 0.002)
    with pytest.raises(ValueError, match=r"^seed = 18446744073709551616: expected an integer"):
        osrl.Learner(3, 2, 0.002, robot="planar3", seed=2**64)
    lrn = osrl.Learner(3, 2, 0.002, robot="planar3", seed=np.uint64(5))
    with pytest.raises(ValueError, match=r"^seed = -1"):
        lrn.command(np.zeros(3), np.zeros(3), np.zeros(2), seed=-1)
    cyclic = {}
    cyclic["guards"] = cyclic
    with pytest.raises(ValueError, match=r"^learner config.guards.guards.*nested more than 64"):
        osrl.Learner(3, 2, 0.002, robot="planar3", config=cyclic)
    with pytest.raises(ValueError, match=r"^trajectory config.x.x.*nested more than 64"):
        osrl.Trajectory("planar3", config=_cyclic("x"))
    with pytest.raises(ValueError, match=r"^learner config.learner.*nested more than 64"):
        osrl.train(SimBot(), config=_cyclic("learner"))


def _cyclic(key):
    d = {}
    d[key] = d
    return d
