"""Training against MuJoCo equals training against osrl's own simulator: `osrl.train` on
`MujocoRobot.builtin("planar3")` and `osrl train` (the CLI, osrl's simulator) with the same
defaults and seed learn from measurements that differ by MuJoCo's rounding only (the models
agree to 1e-12, the trajectories to 1e-9: test_mujoco.py), so the learned controllers'
evaluations agree to far better than a learning difference would allow. One simulated minute
of seed 3 (babbling; about 10 s), whose evaluated controller never falls back to the nominal
command: where the early learned controller switches between the two (after half a minute,
or seed 0), the discrete switches amplify the 1e-9 differences to 1e-4–5 % of the tracking
error. python/README.md has the 30-minute runs, which agree to 1e-9–1e-3 relative over their
whole learning curves."""

import json

import pytest

import osrl

pytest.importorskip("mujoco")
from osrl.mujoco import MujocoRobot  # noqa: E402

MINUTES = 1.0


def test_mujoco_training_equals_osrl_simulator_training(cargo, tmp_path):
    mj = osrl.train(MujocoRobot.builtin("planar3"), "figure8", minutes=MINUTES, seed=3)
    out = cargo("--", "train", "--robot", "planar3", "--trajectory", "figure8", "--minutes",
                str(MINUTES), "--seed", "3", "--out", str(tmp_path / "p3.model"), "--json")
    ref = json.loads(out.strip().splitlines()[-1])
    got = mj.training
    assert got["n_local_models"] == ref["n_local_models"] > 0
    assert got["stats"]["samples"] == ref["counters"]["samples"]
    ours, theirs = got["learning_curve"][-1][1], ref["learning_curve"][-1]
    assert got["learning_curve"][-1][0] == theirs["sim_minutes"] == MINUTES
    for key in ("tracking_rms_mm", "command_nmse"):
        assert ours[key] == pytest.approx(theirs[key], rel=1e-6), key
    assert ours["fallback_share"] == ref["fallback_share"] == 0.0  # the final evaluation's
    # Not trivially equal: another seed learns another controller.
    out = cargo("--", "train", "--robot", "planar3", "--trajectory", "figure8", "--minutes",
                str(MINUTES), "--seed", "4", "--out", str(tmp_path / "p3b.model"), "--json")
    other = json.loads(out.strip().splitlines()[-1])["learning_curve"][-1]
    assert other["tracking_rms_mm"] != pytest.approx(ours["tracking_rms_mm"], rel=1e-3)

