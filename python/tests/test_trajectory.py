"""`osrl.Trajectory`: the path `osrl.train` follows, sampled from Python. It starts at the
home posture's task point, its velocity and acceleration are the derivatives of its position
(central differences), it is periodic after the start ramp, and bad arguments raise."""

import numpy as np
import pytest

import osrl


@pytest.mark.parametrize("name", ["planar3", "sarcos7"])
@pytest.mark.parametrize("kind", ["figure8", "circle", "min_jerk"])
def test_starts_at_home_and_is_consistent(name, kind):
    traj = osrl.Trajectory(name, kind)
    r = osrl.Robot.builtin(name)
    assert traj.task_axes == r.task_axes
    x0, xd0, _ = traj.sample(0.0)
    assert np.allclose(x0, r.fk(traj.home)[r.task_axes], atol=1e-6)  # at rest on the start
    assert np.allclose(xd0, 0.0, atol=1e-12)
    h = 1e-5
    for t in np.linspace(0.1, 2.5 * traj.period, 23):
        x, xd, xdd = traj.sample(t)
        xm, xdm, _ = traj.sample(t - h)
        xp, xdp, _ = traj.sample(t + h)
        assert np.allclose((xp - xm) / (2 * h), xd, atol=1e-6)
        # 1e-4: min_jerk's jerk jumps at its points (an O(h) error of the difference there)
        assert np.allclose((xdp - xdm) / (2 * h), xdd, atol=1e-4)
    t = traj.ramp + 0.3
    for a, b in zip(traj.sample(t), traj.sample(t + traj.period)):
        assert np.allclose(a, b, atol=1e-9)


def test_same_path_as_train_config():
    small = osrl.Trajectory("planar3", "circle", config={"radius": 0.05})
    big = osrl.Trajectory("planar3", "circle")
    t = small.ramp + 0.25 * small.period
    c = small.sample(t)[0]
    r_small = np.linalg.norm(c - small.sample(t + 0.5 * small.period)[0]) / 2
    assert r_small == pytest.approx(0.05, rel=1e-9)
    assert not np.allclose(big.sample(t)[0], c)


def test_bad_arguments_raise():
    with pytest.raises(ValueError, match="trajectory 'square'"):
        osrl.Trajectory("planar3", "square")
    with pytest.raises(ValueError, match="bogus"):
        osrl.Trajectory("planar3", config={"bogus": 1})
    with pytest.raises(ValueError):
        osrl.Trajectory("no_such_robot")
    traj = osrl.Trajectory("planar3")
    with pytest.raises(ValueError, match="finite"):
        traj.sample(float("nan"))


def test_kind_from_the_config_is_used():
    # The keyword's default used to override the config's kind (a figure-8 for "circle").
    from_config = osrl.Trajectory("planar3", config={"kind": "circle"})
    circle, figure8 = osrl.Trajectory("planar3", "circle"), osrl.Trajectory("planar3")
    t = circle.ramp + 0.3 * circle.period
    assert np.array_equal(from_config.sample(t)[0], circle.sample(t)[0])
    assert not np.allclose(figure8.sample(t)[0], circle.sample(t)[0])
    same = osrl.Trajectory("planar3", "circle", config={"kind": "circle"})
    assert np.array_equal(same.sample(t)[0], circle.sample(t)[0])
    with pytest.raises(ValueError, match=r"kind=\"figure8\" and config\['kind'\] = \"circle\" "
                                         r"disagree"):
        osrl.Trajectory("planar3", "figure8", config={"kind": "circle"})
