"""The MuJoCo model of a built-in robot is osrl's robot (mass matrix, gravity, Coriolis,
friction, task point, Jacobian at random states; trajectories against osrl's dynamics
integrated the same way), and MujocoRobot measures it from MuJoCo's state as the protocol says."""

import re

import numpy as np
import pytest

import osrl

mujoco = pytest.importorskip("mujoco")
from osrl.mujoco import INERTIAL_PREFIX, MujocoRobot, builtin_mjcf, load_model  # noqa: E402

NAMES = osrl.Robot.builtins()


def random_state(r, rng):
    lo, hi = np.maximum(r.q_min, -3.0), np.minimum(r.q_max, 3.0)
    return rng.uniform(lo, hi), rng.normal(size=r.dof)


@pytest.mark.parametrize("name", NAMES)
def test_model_equals_osrl_at_random_states(name):
    r = osrl.Robot.builtin(name)
    m = load_model(builtin_mjcf(name))
    d = mujoco.MjData(m)
    site = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_SITE, "ee_link")
    rng = np.random.default_rng(0)
    full, jac = np.zeros((m.nv, m.nv)), np.zeros((3, m.nv))
    for _ in range(50):
        q, qd = random_state(r, rng)
        d.qpos[:], d.qvel[:] = q, 0.0
        mujoco.mj_forward(m, d)
        mujoco.mj_fullM(m, d, full)
        g = r.gravity(q)
        assert np.allclose(full, r.mass_matrix(q), rtol=1e-12, atol=1e-14 * np.abs(full).max())
        assert np.allclose(d.qfrc_bias, g, rtol=1e-12, atol=1e-12 * np.abs(g).max())
        assert np.allclose(d.site_xpos[site], r.fk(q), atol=1e-14)
        mujoco.mj_jacSite(m, d, jac, None, site)
        assert np.allclose(jac, r.jacobian(q), atol=1e-14)
        d.qvel[:] = qd
        mujoco.mj_forward(m, d)
        bias = r.rnea(q, qd, np.zeros(r.dof))  # C q̇ + g
        assert np.allclose(d.qfrc_bias, bias, rtol=1e-12, atol=1e-12 * np.abs(bias).max())
        # MuJoCo's joint damping is osrl's viscous friction (the built-ins have no Coulomb term).
        assert np.allclose(-d.qfrc_passive, r.friction(qd), rtol=1e-12, atol=1e-15)


def test_exact_inertials_where_mujoco_refuses_them():
    sarcos = builtin_mjcf("sarcos7")
    assert sarcos.count(f'<numeric name="{INERTIAL_PREFIX}') == 7  # every identified link
    with pytest.raises(ValueError, match="inertia"):  # MuJoCo's own URDF import refuses them
        mujoco.MjModel.from_xml_string(osrl.Robot.builtin("sarcos7").to_urdf())
    assert INERTIAL_PREFIX not in builtin_mjcf("planar3")  # physical links: plain MJCF
    m = mujoco.MjModel.from_xml_string(builtin_mjcf("planar3"))
    r = osrl.Robot.builtin("planar3")
    assert np.isclose(m.body_mass.sum(), r.total_mass, rtol=1e-15)


def rk4_osrl(r, q, qd, u, h, steps):
    """osrl's forward dynamics (friction included) by classical RK4, the command held."""
    for _ in range(steps):
        f = lambda q_, v_: (v_, r.forward_dynamics(q_, v_, u))
        k1 = f(q, qd)
        k2 = f(q + h / 2 * k1[0], qd + h / 2 * k1[1])
        k3 = f(q + h / 2 * k2[0], qd + h / 2 * k2[1])
        k4 = f(q + h * k3[0], qd + h * k3[1])
        q = q + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        qd = qd + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
    return q, qd


@pytest.mark.parametrize("name", NAMES)
def test_trajectory_equals_osrl_dynamics(name):
    """0.4 s under varying torques, joint limits off (MuJoCo's are soft constraints, osrl's
    simulator has hard stops): MuJoCo's RK4 and osrl's dynamics by RK4 agree to 1e-9."""
    r = osrl.Robot.builtin(name)
    robot = MujocoRobot.builtin(name, joint_limits=False)
    meas = robot.reset()
    q, qd = meas.q, meas.qd
    rng = np.random.default_rng(1)
    for k in range(200):
        u = r.gravity(meas.q) + rng.normal(size=r.dof) * 0.2 * np.minimum(r.tau_max, 10)
        meas = robot.step(u)
        q, qd = rk4_osrl(r, q, qd, meas.u, 0.001, robot.substeps)
        assert np.allclose(meas.q, q, atol=1e-9) and np.allclose(meas.qd, qd, atol=1e-8), k
    assert np.isclose(meas.t, 0.4)


@pytest.mark.parametrize("name", NAMES)
def test_measurements(name):
    """x, ẋ, ẍ are osrl's kinematics of MuJoCo's state (ẍ = J q̈ + J̇ q̇ with q̈ MuJoCo's
    acceleration under the held command); ẍ is also the derivative of ẋ (central differences
    over the control period, to 1 %: sarcos7's light wrist moves fast, the difference's error
    is of order dt²; gravity in ẍ, or a sign error, would be off by far more)."""
    r = osrl.Robot.builtin(name)
    robot = MujocoRobot.builtin(name, joint_limits=False)
    assert isinstance(robot, osrl.RobotProtocol)
    assert robot.dof == r.dof and robot.task_dim == r.task_dim
    assert np.array_equal(robot.torque_limits, r.tau_max)
    limited = MujocoRobot.builtin(name).joint_limits
    assert all(np.array_equal(a, b) for a, b in zip(limited, (r.q_min, r.q_max)))
    assert (robot.joint_limits[0] == -np.inf).all() and (robot.joint_limits[1] == np.inf).all()
    ax = r.task_axes
    rng = np.random.default_rng(2)
    meas = [robot.reset()]
    assert np.array_equal(meas[0].q, r.q_start) and meas[0].t == 0.0
    u = r.gravity(meas[0].q) + rng.normal(size=r.dof)
    for _ in range(100):
        meas.append(robot.step(u))
    for m in meas:
        x, xd, jdot_qd = r.kinematics(m.q, m.qd)
        xdd = r.jacobian(m.q) @ r.forward_dynamics(m.q, m.qd, m.u) + jdot_qd
        assert np.allclose(m.x, x[ax], atol=1e-14) and np.allclose(m.xd, xd[ax], atol=1e-13)
        assert np.allclose(m.xdd, xdd[ax], rtol=1e-10, atol=1e-10)
    dt = robot.control_period
    for a, b, c in zip(meas[1:], meas[2:], meas[3:]):
        fd = (c.xd - a.xd) / (2 * dt)
        assert np.allclose(b.xdd, fd, atol=1e-2 * (1 + np.abs(fd).max()))


def test_step_and_reset_errors_change_nothing():
    robot = MujocoRobot.builtin("sarcos7")
    before = robot.step(np.ones(7))
    for bad, text in [(np.ones(6), "shape (7,)"), (np.full(7, np.nan), "u[0] is not finite"),
                      (np.ones(7, dtype=np.float32), "float32")]:
        with pytest.raises(ValueError, match=re.escape(text)):
            robot.step(bad)
    assert robot.measurement() is before and robot.data.time == before.t
    with pytest.raises(ValueError):
        robot.reset(q=np.zeros(3))
    assert robot.measurement() is before
    clipped = robot.step(np.full(7, 1e6))
    assert np.array_equal(clipped.u, np.full(7, 100.0))
    with pytest.raises(ValueError, match="exactly one"):
        MujocoRobot(robot.model)
    with pytest.raises(ValueError, match="no site 'hand'"):
        MujocoRobot(robot.model, site="hand")
    with pytest.raises(ValueError, match="whole number"):
        MujocoRobot(robot.model, site="ee_link", control_period=0.0015)
    with pytest.raises(ValueError, match="task_axes"):
        MujocoRobot(robot.model, site="ee_link", task_axes=(0, 0))


def test_body_point_and_mjcf_text():
    """A body's frame origin is the task point as the site at that frame is; the MJCF text can
    be given directly (compiled by load_model)."""
    xml = builtin_mjcf("sarcos7")
    a = MujocoRobot(xml, body="WAA", control_period=0.002)
    b = MujocoRobot(xml, site="WAA", control_period=0.002)
    for robot in (a, b):
        robot.reset(q=osrl.Robot.builtin("sarcos7").q_start)
        for _ in range(10):
            last = robot.step(np.full(7, 0.5))
    ma, mb = a.measurement(), b.measurement()
    for f in ("q", "x", "xd", "xdd"):
        assert np.allclose(getattr(ma, f), getattr(mb, f), atol=1e-14), f


def test_not_a_torque_robot():
    xml = """<mujoco><worldbody><body><joint type="hinge"/><inertial pos="0 0 0" mass="1"
    diaginertia="1 1 1"/><site name="s"/></body></worldbody><actuator><position joint="0" kp="1"/>
    </actuator></mujoco>""".replace('joint="0"', 'joint="j"').replace('type="hinge"', 'name="j" type="hinge"')
    with pytest.raises(ValueError, match="not a motor"):
        MujocoRobot(mujoco.MjModel.from_xml_string(xml), site="s")
