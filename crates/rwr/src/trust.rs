//! The trust region of an M-step (a proximal step, not in the paper): the new mean action
//! `θ_newᵀφ` may differ from the old one by at most `δ` in weighted RMS over the samples of the
//! step; a larger step is shrunk along the line from the old to the new `θ`, so one M-step cannot
//! make a jump.

use nalgebra::DMatrix;

/// The weighted RMS `sqrt(Σ_k Δ_kᵀ (G/Σw) Δ_k)` of the change `Δ = new − old` of the mean action
/// over the samples of `gram` (`Σ w φφᵀ`, lower triangle) and `sw` (`Σ w`).
pub(crate) fn rms_change(
    gram: &DMatrix<f64>,
    sw: f64,
    old: &DMatrix<f64>,
    new: &DMatrix<f64>,
) -> f64 {
    let p = gram.nrows();
    let g = gram.as_slice();
    let mut quad = 0.0;
    for k in 0..new.ncols() {
        let (a, b) = (
            &old.as_slice()[k * p..(k + 1) * p],
            &new.as_slice()[k * p..(k + 1) * p],
        );
        for j in 0..p {
            let dj = b[j] - a[j];
            let mut below = 0.0;
            for i in j + 1..p {
                below += g[j * p + i] * (b[i] - a[i]);
            }
            quad += dj * (g[j * p + j] * dj + 2.0 * below);
        }
    }
    (quad.max(0.0) / sw).sqrt()
}

/// Shrinks `new` towards `old` so that [`rms_change`] is at most `delta`; returns the factor
/// applied (1: unchanged).
pub(crate) fn shrink(
    gram: &DMatrix<f64>,
    sw: f64,
    old: &DMatrix<f64>,
    new: &mut DMatrix<f64>,
    delta: f64,
) -> f64 {
    let rms = rms_change(gram, sw, old, new);
    if rms.is_nan() || rms <= delta {
        return 1.0;
    }
    let f = delta / rms;
    for (n, o) in new.iter_mut().zip(old.iter()) {
        *n = o + f * (*n - o);
    }
    f
}
