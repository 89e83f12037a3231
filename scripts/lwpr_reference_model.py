"""The independent LWPR of scripts/lwpr_reference.py: the model alone (see that file).

One output, no normalisation, Gaussian kernel, full metric with meta learning: the settings of
the two cross tests of issue 4. Written from the written LWPR description of the project's
background notes (LWPR.md, not in this repository; docs/lwpr.md explains the same steps under the
same letters) and from the behaviour of the reference C library (lwpr_aux.c, v1.2); shares no
code with the crate. Where LWPR.md and the C library differ or LWPR.md is silent, this follows
the C library, as the crate does:
- the prune rule removes the wider of the two RFs (smaller trace of D; LWPR.md says narrower);
- a PLS direction's metric terms count only when n_data_j (1 - lambda_0) > 0.1 (lambda of the
  first direction for every j);
- a new RF's mean starts at 0 (the C library's zeroed allocation; it is replaced by the first
  sample it learns from, whose weight dwarfs the 1e-10 of the empty statistics);
- the confidence bound reads sum_e_cv2 and sum_w of the last direction the RF predicts with
  (LWPR.md writes R, the last direction, even while it does not predict yet).
Where the crate deviates from the C library on purpose, so does this, switchable:
- the leverage guard (Config.guard, on by default): the metric terms of a sample with leverage
  h >= 1 are skipped, where the C library divides by 1 - h <= 0;
- Model.update returns NaN, not 0, when no trustworthy RF took part.
"""

import math

import numpy as np

CASES = ("cross2", "cross21", "cross21diag")


class Config:
    """The cross tests' configs (lwpr::datasets::cross_config, cross21_config, and the latter
    with a diagonal metric, `cross21diag`)."""

    def __init__(self, case):
        if case not in CASES:
            raise ValueError(f"unknown case '{case}': one of {', '.join(CASES)}")
        self.n = 2 if case == "cross2" else 21
        init_d, self.w_prune = (25.0, 1.0) if case == "cross2" else (0.25, 0.7)
        n = self.n
        self.init_D = np.eye(n) * init_d
        self.init_M = np.eye(n) * math.sqrt(init_d)  # upper triangular, D = M^T M
        self.init_alpha = np.full((n, n), 250.0)
        self.w_gen, self.meta_rate, self.penalty = 0.2, 250.0, 1e-6
        self.init_lambda, self.final_lambda, self.tau_lambda = 0.999, 0.99999, 0.9999
        self.init_s2, self.add_threshold = 1e-10, 0.5
        # The free elements of M: its upper triangle, or its diagonal (diag_only).
        diag = case == "cross21diag"
        self.free = np.eye(n, dtype=bool) if diag else np.triu(np.ones((n, n), dtype=bool))
        self.guard = True


class RF:
    """A receptive field; `tmpl` (the nearest trustworthy RF) lends D, M, alpha, beta0, R."""

    def __init__(self, cfg, x, y, tmpl=None):
        n = cfg.n
        src = tmpl
        self.D = (cfg.init_D if src is None else src.D).copy()
        self.M = (cfg.init_M if src is None else src.M).copy()
        self.alpha = (cfg.init_alpha if src is None else src.alpha).copy()
        self.beta0 = y if src is None else src.beta0
        self.R = 2 if src is None else src.R
        self.c = x.copy()
        self.b = np.log(self.alpha + 1e-10)  # meta learning: alpha = exp(b)
        self.hm = np.zeros((n, n))  # meta learning memory
        self.mean_x = np.zeros(n)
        self.trust = False
        self.sum_e2 = self.SSp = 0.0
        # PLS state, room for n directions; the first R are in use.
        self.U, self.P = np.eye(n), np.eye(n)
        self.SXresYres, self.SSXres = np.zeros((n, n)), np.zeros((n, n))
        z = lambda: np.zeros(n)  # noqa: E731
        self.SSs2, self.SSYres, self.beta, self.s = z(), z(), z(), z()
        self.sum_w, self.n_data, self.lam = z(), z(), z()
        self.H, self.r, self.sum_e_cv2 = z(), z(), z()
        self.SSs2[:] = cfg.init_s2
        self.sum_w[:] = 1e-10
        self.n_data[: self.R] = 1e-10
        self.lam[:] = cfg.init_lambda


def project(rf, x, R):
    """The PLS projections s_1..s_R of x (each direction on the residual of the previous)."""
    s = np.zeros(R)
    xres = x.copy()
    for j in range(R):
        s[j] = rf.U[:, j] @ xres
        xres = xres - rf.P[:, j] * s[j]
    return s


def update_regression(cfg, rf, x, y, w):
    """docs/lwpr.md (b) on the centred sample; returns the RF's prediction, e_cv of the last
    trusted direction and the residual e with the new projections."""
    n, R = cfg.n, rf.R
    # Projections and residual inputs with the old directions.
    xres = np.zeros((R, n))
    s = np.zeros(R)
    xres[0] = x
    for j in range(R):
        s[j] = rf.U[:, j] @ xres[j]
        if j + 1 < R:
            xres[j + 1] = xres[j] - rf.P[:, j] * s[j]
    e_cv = y - np.cumsum(rf.beta[:R] * s)
    rf.sum_w[:R] = rf.sum_w[:R] * rf.lam[:R] + w
    target = np.concatenate([[y], e_cv[: R - 1]])
    ws2 = 0.0
    for j in range(R):
        slow = 0.9 + 0.1 * rf.lam[j]
        rf.SXresYres[:, j] = rf.SXresYres[:, j] * slow + w * target[j] * xres[j]
        norm2 = rf.SXresYres[:, j] @ rf.SXresYres[:, j]
        if norm2 > 1e-24:
            rf.U[:, j] = rf.SXresYres[:, j] / math.sqrt(norm2)
        ws = w * s[j]
        rf.SSs2[j] = rf.lam[j] * rf.SSs2[j] + s[j] * ws
        rf.SSYres[j] = rf.lam[j] * rf.SSYres[j] + target[j] * ws
        rf.SSXres[:, j] = rf.lam[j] * rf.SSXres[:, j] + ws * xres[j]
        rf.beta[j] = rf.SSYres[j] / rf.SSs2[j]
        rf.P[:, j] = rf.SSXres[:, j] / rf.SSs2[j]
        ws2 += ws * ws / rf.SSs2[j]
    rf.SSp = rf.lam[R - 1] * rf.SSp + ws2
    # The new projections; the last direction counts once it has seen 2n samples.
    rf.s[:] = 0.0
    rf.s[:R] = project(rf, x, R)
    used = R if rf.n_data[R - 1] > 2.0 * n else R - 1
    ypred = rf.beta[:used] @ rf.s[:used]
    e = y - ypred
    if rf.n_data[0] * (1.0 - rf.lam[0]) > 0.1:
        rf.sum_e2 = rf.sum_e2 * rf.lam[R - 1] + w * e * e
        rf.sum_e_cv2[:R] = rf.sum_e_cv2[:R] * rf.lam[:R] + w * e_cv * e_cv
    if rf.n_data[0] > 2.0 * n:
        rf.trust = True
    return ypred + rf.beta0, e_cv[used - 1], e


def update_metric(cfg, rf, w, e_cv, e, x, stats):
    """docs/lwpr.md (d): one gradient step on M, with IDBD meta learning of its rates."""
    n, R = cfg.n, rf.R
    dwdq, ddwdqdq = -0.5 * w, 0.25 * w
    ok = rf.n_data[:R] * (1.0 - rf.lam[0]) > 0.1
    if not ok[0]:
        return
    s = rf.s[:R]
    ss = rf.SSs2[:R]
    h = w * np.sum(np.where(ok, s * s / ss, 0.0))  # leverage
    if cfg.guard and not h < 1.0:
        stats["guard"] += 1
        return
    W = rf.sum_w[0]
    E = rf.sum_e_cv2[R - 1] if rf.n_data[R - 1] > 2 * n else rf.sum_e_cv2[R - 2]
    T = rf.sum_e2 / (E + 1e-10)
    T = min((T * T) * (T * T), 1.0)  # transient multiplier
    Ps = np.where(ok, s / ss, 0.0)
    Pse = e * Ps
    dJ1dw = (-E / W + e_cv**2 - np.sum(2.0 * Pse * rf.H[:R] + 2.0 * Ps * Ps * rf.r[:R])) / W
    # Derivatives with respect to every element of M (only the free elements are used).
    dx = x - rf.c
    M, D = rf.M, rf.D
    pen = cfg.penalty / n
    dqdM = 2.0 * np.outer(M @ dx, dx)
    dwdM = dwdq * dqdM
    ddwdMdM = ddwdqdq * dqdM**2 + 2.0 * dwdq * (dx * dx)[None, :]
    dJ2dM = 4.0 * pen * (M @ D)
    row2 = np.sum(M * M, axis=1)  # sum over the row of M, M being upper triangular
    ddJ2dMdM = 4.0 * pen * (np.diag(D)[None, :] + row2[:, None] + M * M)
    dJdM = (w / W) * dJ2dM + dJ1dw * dwdM
    up = cfg.free
    max_m = np.max(np.abs(M[up]))
    # IDBD: the rates follow the correlation of successive gradients.
    dd = (
        2.0 * (e * e * h / w - e_cv**2 / W)
        + E / (W * W)
        + np.sum(4.0 * (Pse / W + Ps * (s @ Pse)) * rf.H[:R])
    ) / W
    ddJdMdM = (w / W) * ddJ2dMdM + dJ1dw * ddwdMdM + dd * dwdM * dwdM
    b = np.clip(rf.b - np.clip(cfg.meta_rate * T * dJdM * rf.hm, -0.1, 0.1), -10.0, 10.0)
    rf.b = np.where(up, b, rf.b)
    rf.alpha = np.where(up, np.exp(rf.b), rf.alpha)
    hm = rf.hm * np.maximum(1.0 - rf.alpha * ddJdMdM * T, 0.0) - rf.alpha * T * dJdM
    rf.hm = np.where(up, hm, rf.hm)
    # The step; an element whose step would exceed a tenth of max |M| halves its rate instead.
    dM = rf.alpha * T * dJdM
    big = up & (dM > 0.1 * max_m)
    stats["halved"] += int(np.sum(big))
    rf.alpha = np.where(big, 0.5 * rf.alpha, rf.alpha)
    rf.M = np.where(up & ~big, M - dM, M)
    rf.D = rf.M.T @ rf.M
    # Memory traces of the leave-one-out cost.
    H = rf.lam[:R] * rf.H[:R] + (w / (1.0 - h)) * s * e_cv * T
    r = rf.lam[:R] * rf.r[:R] + (w * w * e_cv**2 / (1.0 - h)) * s * s * T
    rf.H[:R] = np.where(ok, H, rf.H[:R])
    rf.r[:R] = np.where(ok, r, rf.r[:R])


def grow(cfg, rf, stats):
    """docs/lwpr.md (e): adds a PLS direction when the last one still halves the error."""
    n, R = cfg.n, rf.R
    if R >= n:
        return
    mse = rf.sum_e_cv2[R - 2 : R] / rf.sum_w[R - 2 : R] + 1e-10
    if (
        mse[1] < cfg.add_threshold * mse[0]
        and rf.n_data[R - 1] > 0.99 * rf.n_data[0]
        and rf.n_data[R - 1] * (1.0 - rf.lam[R - 1]) > 0.5
    ):
        rf.R = R + 1
        rf.SSp = 0.0
        stats["grown"] += 1


class Model:
    def __init__(self, cfg):
        self.cfg = cfg
        self.rfs = []
        self.stats = dict(added=0, templated=0, pruned=0, grown=0, halved=0, guard=0)

    def activation(self, rf, x):
        dx = x - rf.c
        return math.exp(-0.5 * (dx @ rf.D @ dx))

    def update(self, x, y):
        """One sample; returns the prediction before learning (NaN if no trusted RF)."""
        cfg = self.cfg
        w1 = w2 = 0.0
        i1 = i2 = -1
        yp = sw = 0.0
        for k, rf in enumerate(self.rfs):
            w = self.activation(rf, x)
            if w > w2:
                if w > w1:
                    i2, w2, i1, w1 = i1, w1, k, w
                else:
                    i2, w2 = k, w
            if w <= 0.001:
                continue
            keep = rf.sum_w[0] * rf.lam[0]
            rf.mean_x = (keep * rf.mean_x + w * x) / (keep + w)
            rf.beta0 = (keep * rf.beta0 + w * y) / (keep + w)
            yk, e_cv, e = update_regression(cfg, rf, x - rf.mean_x, y - rf.beta0, w)
            if rf.trust:
                yp += w * yk
                sw += w
            update_metric(cfg, rf, w, e_cv, e, x, self.stats)
            grow(cfg, rf, self.stats)
            R = rf.R
            rf.n_data[:R] = rf.n_data[:R] * rf.lam[:R] + 1.0
            rf.lam[:R] = cfg.tau_lambda * rf.lam[:R] + cfg.final_lambda * (1.0 - cfg.tau_lambda)
        if w1 <= cfg.w_gen:
            tmpl = self.rfs[i1] if w1 > 0.1 * cfg.w_gen and self.rfs[i1].trust else None
            self.rfs.append(RF(cfg, x, y, tmpl))
            self.stats["added"] += 1
            self.stats["templated"] += tmpl is not None
        elif w2 > cfg.w_prune:
            # The reference C library removes the wider of the two (smaller trace of D).
            k = i1 if np.trace(self.rfs[i1].D) < np.trace(self.rfs[i2].D) else i2
            last = self.rfs.pop()
            if k < len(self.rfs):
                self.rfs[k] = last
            self.stats["pruned"] += 1
        return yp / sw if sw > 0 else math.nan

    def predict(self, x, cutoff=0.001):
        """The prediction and its confidence bound (docs/lwpr.md, "Prediction"); 0
        and NaN where no trusted RF is active."""
        yp = sw = wyy = wconf = 0.0
        for rf in self.rfs:
            w = self.activation(rf, x)
            if w > cutoff and rf.trust:
                R = rf.R if rf.n_data[rf.R - 1] > 2 * self.cfg.n else rf.R - 1
                s = project(rf, x - rf.mean_x, R)
                yk = rf.beta0 + rf.beta[:R] @ s
                # The RF's variance, from the last direction it predicts with.
                sigma2 = rf.sum_e_cv2[R - 1] / (rf.sum_w[R - 1] - rf.SSp)
                wconf += w * sigma2 * (1.0 + w * np.sum(s * s / rf.SSs2[:R]))
                yp += w * yk
                wyy += w * yk * yk
                sw += w
        if sw <= 0:
            return 0.0, math.nan
        y = yp / sw
        return y, math.sqrt(abs(wconf + wyy - yp * y)) / sw
