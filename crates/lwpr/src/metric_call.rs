//! How the update calls the full-metric step [`full_step`]:
//! inlined for small kernels, otherwise as a function of its own per constant dimension.

use crate::metric::{MetricAcc, MetricScratch};
use crate::metric_full::full_step;
use crate::params::Params;

/// Calls [`full_step`]: inlined up to 4-D; above, as a function of its own (generic in the
/// constant dimension `NK`; AVX2 when the caller is the AVX2 update, `AVX`), so that the
/// metric step gets its own registers instead of spilling inside the whole update.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn full_step_call<const NK: usize, const AVX: bool>(
    nk: usize,
    p: &Params,
    m: &mut [f64],
    d: &mut [f64],
    alpha: &mut [f64],
    b: &mut [f64],
    hm: &mut [f64],
    acc: MetricAcc,
    dwdq: f64,
    ddwdqdq: f64,
    ws: &mut MetricScratch,
) {
    if nk <= 4 {
        return full_step(nk, p, m, d, alpha, b, hm, acc, dwdq, ddwdqdq, ws);
    }
    #[cfg(target_arch = "x86_64")]
    if AVX {
        // SAFETY: `AVX` is only set by the update's AVX2 entry point (after the CPU check).
        return unsafe { full_step_avx2::<NK>(nk, p, m, d, alpha, b, hm, acc, dwdq, ddwdqdq, ws) };
    }
    full_step_base::<NK>(nk, p, m, d, alpha, b, hm, acc, dwdq, ddwdqdq, ws)
}

/// [`full_step`] with AVX2 (same results, see `crate::simd`).
#[cfg(target_arch = "x86_64")]
#[allow(clippy::too_many_arguments)]
#[target_feature(enable = "avx2")]
#[inline(never)]
unsafe fn full_step_avx2<const NK: usize>(
    nk: usize,
    p: &Params,
    m: &mut [f64],
    d: &mut [f64],
    alpha: &mut [f64],
    b: &mut [f64],
    hm: &mut [f64],
    acc: MetricAcc,
    dwdq: f64,
    ddwdqdq: f64,
    ws: &mut MetricScratch,
) {
    full_step_base_inl::<NK>(nk, p, m, d, alpha, b, hm, acc, dwdq, ddwdqdq, ws)
}

/// [`full_step`] for the baseline target.
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn full_step_base<const NK: usize>(
    nk: usize,
    p: &Params,
    m: &mut [f64],
    d: &mut [f64],
    alpha: &mut [f64],
    b: &mut [f64],
    hm: &mut [f64],
    acc: MetricAcc,
    dwdq: f64,
    ddwdqdq: f64,
    ws: &mut MetricScratch,
) {
    full_step_base_inl::<NK>(nk, p, m, d, alpha, b, hm, acc, dwdq, ddwdqdq, ws)
}

/// [`full_step`] with `nk = NK` when `NK > 0`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn full_step_base_inl<const NK: usize>(
    nk: usize,
    p: &Params,
    m: &mut [f64],
    d: &mut [f64],
    alpha: &mut [f64],
    b: &mut [f64],
    hm: &mut [f64],
    acc: MetricAcc,
    dwdq: f64,
    ddwdqdq: f64,
    ws: &mut MetricScratch,
) {
    let nk = if NK > 0 { NK } else { nk };
    full_step(nk, p, m, d, alpha, b, hm, acc, dwdq, ddwdqdq, ws)
}
