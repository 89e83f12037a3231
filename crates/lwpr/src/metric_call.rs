//! How the update calls the full-metric step: [`crate::metric_2d::step_2d`] for 2-D kernels
//! (a compile-time constant), [`full_step`] inlined for kernels of up to 4 dimensions; above,
//! [`crate::metric_wide::wide_step`] as a function of its own per constant dimension.

use crate::metric::{MetricAcc, MetricScratch};
use crate::metric_full::full_step;
use crate::params::Params;

/// The arguments of [`full_step`] that belong to one RF: its metric state — `M`, `D`, `α`,
/// `b = ln α`, the IDBD memory `hm`, updated in place — the output sums `acc` and the kernel
/// derivatives `dwdq`, `ddwdqdq` at the sample; what the update hands to [`full_step_call`].
/// [`full_step`] and its non-inlined copies take the fields as separate arguments: only then
/// does the compiler know that the slices do not overlap (taking the struct instead cost
/// 3.7 % more instructions on the 21-D test in the copies, 0.4–1 % in the inlined step).
pub(crate) struct FullStep<'a> {
    pub m: &'a mut [f64],
    pub d: &'a mut [f64],
    pub alpha: &'a mut [f64],
    pub b: &'a mut [f64],
    pub hm: &'a mut [f64],
    pub acc: MetricAcc,
    pub dwdq: f64,
    pub ddwdqdq: f64,
}

/// Calls [`full_step`] inlined up to 4-D; above, [`crate::metric_wide::wide_step`] as a
/// function of its own (generic in the constant dimension `NK`; AVX2 and FMA when the caller
/// is the AVX2 update, `AVX`), so that the metric step gets its own registers instead of
/// spilling inside the whole update.
#[inline(always)]
pub(crate) fn full_step_call<const NK: usize, const AVX: bool>(
    nk: usize,
    p: &Params,
    s: FullStep,
    ws: &mut MetricScratch,
) {
    let FullStep {
        m,
        d,
        alpha,
        b,
        hm,
        acc,
        dwdq,
        ddwdqdq,
    } = s;
    if NK == 2 && !crate::rf_update::general_only() {
        // Every dimension a constant, on fixed-size arrays (the same arithmetic).
        use crate::rf_update_2d::arr;
        let st = crate::metric_2d::MetricState {
            m: arr(m),
            d: arr(d),
            alpha: arr(alpha),
            b: arr(b),
            hm: arr(hm),
        };
        let dx = *arr::<2>(&mut ws.dx);
        return crate::metric_2d::step_2d(p, st, acc, dx, dwdq, ddwdqdq);
    }
    if nk <= 4 {
        return full_step(nk, p, m, d, alpha, b, hm, acc, dwdq, ddwdqdq, ws);
    }
    #[cfg(target_arch = "x86_64")]
    if AVX {
        // SAFETY: `AVX` is only set by the update's AVX2 entry point (after the CPU check,
        // which includes FMA).
        return unsafe { full_step_avx2::<NK>(nk, p, m, d, alpha, b, hm, acc, dwdq, ddwdqdq, ws) };
    }
    full_step_base::<NK>(nk, p, m, d, alpha, b, hm, acc, dwdq, ddwdqdq, ws)
}

/// Defines `$name`, `wide_step` as a function of its own with `nk = NK` when `NK > 0`
/// (one argument list for both copies; separate arguments, not a [`FullStep`], see there).
macro_rules! full_step_copy {
    ($(#[$attr:meta])* $name:ident $(, $unsafe:ident)?) => {
        $(#[$attr])*
        #[allow(clippy::too_many_arguments)]
        #[inline(never)]
        pub(crate) $($unsafe)? fn $name<const NK: usize>(
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
            crate::metric_wide::wide_step::<NK>(nk, p, m, d, alpha, b, hm, acc, dwdq, ddwdqdq, ws)
        }
    };
}

full_step_copy!(
    /// `wide_step` with AVX2 and FMA (same results, see `crate::metric_wide`).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    full_step_avx2, unsafe
);
full_step_copy!(
    /// `wide_step` for the baseline target (FMA in software).
    full_step_base
);
