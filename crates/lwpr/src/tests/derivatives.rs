//! Every derivative used by the metric update against central finite differences.

use crate::config::{Kernel, LwprConfig, MetricInit};
use crate::params::Params;
use crate::update::metric::MetricScratch;
use crate::update::metric_derivatives::derivatives;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// `D = MᵀM` in the storage layout.
fn d_of(diag: bool, nk: usize, m: &[f64]) -> Vec<f64> {
    if diag {
        return m.iter().map(|v| v * v).collect();
    }
    let mut d = vec![0.0; nk * nk];
    for i in 0..nk {
        for j in 0..nk {
            d[i * nk + j] = (0..nk).map(|k| m[k * nk + i] * m[k * nk + j]).sum();
        }
    }
    d
}

fn q_of(diag: bool, nk: usize, m: &[f64], dx: &[f64]) -> f64 {
    let d = d_of(diag, nk, m);
    if diag {
        (0..nk).map(|i| d[i] * dx[i] * dx[i]).sum()
    } else {
        (0..nk)
            .flat_map(|i| (0..nk).map(move |j| (i, j)))
            .map(|(i, j)| dx[i] * d[i * nk + j] * dx[j])
            .sum()
    }
}

fn j2_of(diag: bool, nk: usize, m: &[f64], pen: f64) -> f64 {
    pen * d_of(diag, nk, m).iter().map(|v| v * v).sum::<f64>()
}

fn params(kernel: Kernel, diag: bool) -> Params {
    let cfg = LwprConfig {
        kernel,
        diag_only: diag,
        init_d: MetricInit::Scalar(1.0),
        ..Default::default()
    };
    cfg.validate(4, 1).unwrap()
}

fn check(kernel: Kernel, diag: bool, seed: u64) {
    let nk = 4;
    let p = params(kernel, diag);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let ml = if diag { nk } else { nk * nk };
    let mut m = vec![0.0; ml];
    for n in 0..nk {
        for k in n..nk {
            let idx = if diag { n } else { n * nk + k };
            if diag && k != n {
                continue;
            }
            m[idx] = if k == n {
                rng.random_range(0.5..1.5)
            } else {
                rng.random_range(-0.4..0.4)
            };
        }
    }
    let dx: Vec<f64> = (0..nk).map(|_| rng.random_range(-0.6..0.6)).collect();
    let pen = 0.37; // large, so the penalty terms are well above rounding
    let q = q_of(diag, nk, &m, &dx);
    let (_w, dwdq, ddwdqdq) = p.kernel(q);
    let mut ws = MetricScratch::new(nk, ml, 0);
    ws.dx.copy_from_slice(&dx);
    let d = d_of(diag, nk, &m);
    derivatives(nk, diag, true, &m, &d, dwdq, ddwdqdq, pen, &mut ws);
    let w_of = |m: &[f64]| p.kernel(q_of(diag, nk, m, &dx)).0;
    let h = 1e-4;
    for n in 0..nk {
        for k in if diag { n..n + 1 } else { n..nk } {
            let idx = if diag { n } else { n * nk + k };
            let (mut mp, mut mm) = (m.clone(), m.clone());
            mp[idx] += h;
            mm[idx] -= h;
            let (w0, wp, wm) = (w_of(&m), w_of(&mp), w_of(&mm));
            let fd1 = (wp - wm) / (2.0 * h);
            let fd2 = (wp - 2.0 * w0 + wm) / (h * h);
            let tol = |v: f64| 1e-5 * (1.0 + v.abs());
            assert!((ws.dwdm[idx] - fd1).abs() < tol(fd1), "dw/dM[{n},{k}]");
            assert!(
                (ws.ddw[idx] - fd2).abs() < 1e-3 * (1.0 + fd2.abs()),
                "d2w/dM2[{n},{k}]"
            );
            let (j0, jp, jm) = (
                j2_of(diag, nk, &m, pen),
                j2_of(diag, nk, &mp, pen),
                j2_of(diag, nk, &mm, pen),
            );
            let fd1 = (jp - jm) / (2.0 * h);
            let fd2 = (jp - 2.0 * j0 + jm) / (h * h);
            assert!((ws.dj2[idx] - fd1).abs() < tol(fd1), "dJ2/dM[{n},{k}]");
            assert!(
                (ws.ddj2[idx] - fd2).abs() < 1e-3 * (1.0 + fd2.abs()),
                "d2J2[{n},{k}]"
            );
        }
    }
}

#[test]
fn metric_derivatives_match_finite_differences() {
    for seed in 0..5 {
        for kernel in [Kernel::Gaussian, Kernel::Bisquare] {
            for diag in [true, false] {
                check(kernel, diag, seed);
            }
        }
    }
}

#[test]
fn kernel_derivatives_match_finite_differences() {
    for kernel in [Kernel::Gaussian, Kernel::Bisquare] {
        let p = params(kernel, true);
        for &q in &[0.1, 0.7, 2.0, 3.5] {
            let h = 1e-5;
            let (w, d1, d2) = p.kernel(q);
            let (wp, wm) = (p.kernel(q + h).0, p.kernel(q - h).0);
            assert!((d1 - (wp - wm) / (2.0 * h)).abs() < 1e-8);
            assert!((d2 - (wp - 2.0 * w + wm) / (h * h)).abs() < 1e-4);
        }
    }
}

/// `∂J1/∂w` without memory terms is the derivative of the running leave-one-out cost
/// `J1(w) = (E₀ + w e_cv²) / (W₀ + w)` at the current sample.
#[test]
fn loo_cost_derivative_matches_finite_differences() {
    use crate::pls::Pls;
    use crate::update::metric::{output_terms, MetricAcc};
    let p = params(Kernel::Gaussian, true);
    let (e0, w0, w, ecv) = (0.8, 20.0, 0.6, 0.5);
    let mut pls = Pls::new(&p, 1, 0.0);
    // State after the sample was included, memory traces zero, derivatives enabled.
    pls.sum_w[0] = w0 + w;
    pls.sum_e_cv2[0] = e0 + w * ecv * ecv;
    pls.sum_e2 = 1e3; // transient multiplier 1
    pls.n_data[0] = 1e3;
    pls.lambda[0] = 0.999;
    let mut acc = MetricAcc::default();
    output_terms::<0>(
        &mut pls,
        4,
        w,
        &[0.0],
        &mut [0.0],
        ecv,
        ecv,
        false,
        &mut acc,
    );
    let j1 = |w: f64| (e0 + w * ecv * ecv) / (w0 + w);
    let h = 1e-6;
    let fd = (j1(w + h) - j1(w - h)) / (2.0 * h);
    assert!((acc.b - fd).abs() < 1e-8, "{} vs {fd}", acc.b);
}
