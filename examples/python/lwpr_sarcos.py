"""Fits osrl.Lwpr on the SARCOS inverse-dynamics split (real robot data: 21 inputs q, q̇, q̈ →
7 joint torques) and prints the test nMSE per joint, as `osrl lwpr fit` does with
crates/lwpr/examples/sarcos.toml (inputs and outputs divided by the training data's standard
deviation, init_d 0.3, init_alpha 250, w_gen 0.2, meta learning; a fresh shuffled order per
epoch; a test row without support predicts 0, as the reference library does).

    python examples/python/lwpr_sarcos.py [--data DIR] [--epochs 3] [--seed 0]

(DIR defaults to $OSRL_SHARED/data/sarcos, OSRL_SHARED to ../shared beside the repository.)

The shuffles come from numpy, not from the CLI's ChaCha8, so the numbers are close to the
CLI's (crates/lwpr/README.md: mean nMSE 0.091, 0.093, 0.087 at 3 epochs, seeds 0-2), not equal.
"""

import argparse
import os
import time
from pathlib import Path

import numpy as np

import osrl

REPO = Path(__file__).resolve().parents[2]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    shared = Path(os.environ.get("OSRL_SHARED", REPO.parent / "shared"))
    ap.add_argument("--data", type=Path, default=shared / "data" / "sarcos")
    ap.add_argument("--epochs", type=int, default=3)
    ap.add_argument("--seed", type=int, default=0)
    a = ap.parse_args()
    load = lambda f: np.loadtxt(a.data / f, delimiter=",", skiprows=1)
    train, test = load("parity_train.csv"), load("parity_test.csv")
    x, y = train[:, :21], train[:, 21:]
    x_test, y_test = test[:, :21], test[:, 21:]
    std = lambda v: np.where(v.std(axis=0) > 1e-12, v.std(axis=0), 1.0).tolist()
    model = osrl.Lwpr(21, 7, norm_in=std(x), norm_out=std(y), init_d=0.3, init_alpha=250.0,
                      w_gen=0.2, meta=True)
    rng = np.random.default_rng(a.seed)
    t0 = time.perf_counter()
    for _ in range(a.epochs):
        order = rng.permutation(len(x))
        model.update_batch(x[order], y[order])
    seconds = time.perf_counter() - t0
    pred = model.predict_batch(x_test, strict=False)
    nmse = ((pred - y_test) ** 2).mean(axis=0) / y_test.var(axis=0)
    print(f"{len(x)} training rows × {a.epochs} epochs in {seconds:.1f} s; "
          f"receptive fields per joint {model.n_rfs}")
    for j, v in enumerate(nmse):
        print(f"tau{j + 1}: nMSE {v:.4f}")
    print(f"mean nMSE {nmse.mean():.4f}")


if __name__ == "__main__":
    main()
