//! The fast path: every speed specialisation of the update, the prediction and the activation
//! query, and this file, the one place that chooses among them.
//!
//! Each choice depends on the model's shape alone — its kernel and regression dimensions, its
//! metric (full or diagonal), its outputs per RF, an output's number of PLS directions — and on
//! the CPU (AVX2 and FMA, checked at run time). Every specialisation computes the reference's
//! results (`update/`, `predict/blend.rs`) bit for bit, tested against it, except one: the
//! full-metric step above 4 dimensions ([`wide`]) uses fused multiply-adds and other summation
//! orders, so it rounds differently (relative 1e-12 per step, tested; the same bits on every
//! CPU).
//!
//! | specialisation | applies to | file |
//! |---|---|---|
//! | compile-time dimensions | the shapes of [`SHAPES`] | this file |
//! | AVX2 entry points | every model, on CPUs with AVX2 and FMA | this file |
//! | two PLS directions as a constant | outputs with 2 directions, shapes of [`SHAPES`] | `update/regression.rs` at `R = 2` |
//! | 2-D PLS step | 2 regression inputs, 2 directions | [`plane_pls`] |
//! | 2-D metric step | 2-D full metric | [`plane_metric`] |
//! | distances four RFs at a time | 2-D full metric: activation pass, plain prediction | [`plane_quad`] |
//! | RF updates in groups of 2–3 | 2-D kernel and regression, full metric, one output per RF | [`group`] |
//! | fused full-metric step | full metric, up to 4 dimensions | [`fused`] |
//! | four-lane full-metric step | full metric, 5 dimensions or more | [`wide`] |
//! | its partial vectors, `max \|M\|` and row sums in AVX2 registers | the four-lane step on AVX2 | [`lanes_avx`] |
//! | distance rows in one AVX2 register | full metric, 5 dimensions or more: activation pass, predictions, activation queries | [`dot`] |
//! | the heads' bounds of eight RFs in one AVX2 register | diagonal metric over more than 8 dimensions, on AVX2 | [`head_avx`] |
//!
//! Tests run single specialisations off through the flags `F` of [`Fast`] (production runs
//! [`ALL`]) and compare with the reference.

pub(crate) mod dot;
pub(crate) mod fused;
pub(crate) mod group;
#[cfg(target_arch = "x86_64")]
pub(crate) mod head_avx;
pub(crate) mod lanes;
#[cfg(target_arch = "x86_64")]
pub(crate) mod lanes_avx;
pub(crate) mod plane_metric;
pub(crate) mod plane_pls;
pub(crate) mod plane_quad;
pub(crate) mod wide;

use crate::params::Params;
use crate::pls::Pls;
use crate::predict::blend::{predict_core, sub_sums, Support, Want};
use crate::predict::query::activations_core;
use crate::rf::{Activation, SubModel};
use crate::scratch::Scratch;
use crate::update::activation::{pass, Top2};
use crate::update::metric::{MetricAcc, MetricScratch};
use crate::update::metric_step::reference_step;
use crate::update::regression::{update_regression, PlsScratch};
use crate::update::rf::{after_pls, output_step, update_active};
use crate::update::stages::{dims, FullStep, Stages};
use crate::update::{update_sub as update_with, SubCtx, SubOutcome};
use crate::LwprError;

/// The shape table: the (kernel, regression) dimensions that get a copy of the update and of
/// the prediction with both as compile-time constants, so that the loops over them unroll (the
/// arithmetic is the same). A copy costs compile time and code size, so a shape is here when a
/// workload of that shape is measured faster with it: the 1-D and 2-D models, a kernel on all
/// 21 inputs, and kernels on 3, 6, 7 and 14 of 9 or 21 inputs (`docs/lwpr.md`, "Speed").
/// Other shapes take the dimensions from the model.
pub(crate) const SHAPES: [(usize, usize); 7] =
    [(1, 1), (2, 2), (14, 21), (7, 21), (6, 9), (3, 9), (21, 21)];

/// The kernel dimensions whose activation queries (`Lwpr::activations`) get a copy with the
/// dimension as a constant: those of [`SHAPES`] with a kernel on part of the inputs that are
/// queried at every step of a controller (6 and 14).
pub(crate) const QUERY_KERNEL_DIMS: [usize; 2] = [14, 6];

/// `$go!(S)` for the entry `S` of [`SHAPES`] that is `($nk, $nr)`, else `$go!((0, 0))`.
macro_rules! by_shape {
    ($nk:expr, $nr:expr, $go:ident) => {{
        // One arm per entry (a table of another length does not compile).
        const S: [(usize, usize); 7] = SHAPES;
        const S0: (usize, usize) = S[0];
        const S1: (usize, usize) = S[1];
        const S2: (usize, usize) = S[2];
        const S3: (usize, usize) = S[3];
        const S4: (usize, usize) = S[4];
        const S5: (usize, usize) = S[5];
        const S6: (usize, usize) = S[6];
        const OTHER: (usize, usize) = (0, 0);
        match ($nk, $nr) {
            S0 => $go!(S0),
            S1 => $go!(S1),
            S2 => $go!(S2),
            S3 => $go!(S3),
            S4 => $go!(S4),
            S5 => $go!(S5),
            S6 => $go!(S6),
            _ => $go!(OTHER),
        }
    }};
}

/// Flag of [`Fast`]: two PLS directions as a constant.
pub(crate) const TWO_DIRS: u8 = 1;
/// Flag of [`Fast`]: the 2-D code (PLS step, metric step, distances four at a time).
pub(crate) const PLANE: u8 = 2;
/// Flag of [`Fast`]: RF updates in groups.
pub(crate) const GROUPS: u8 = 4;
/// Flag of [`Fast`]: the fused full-metric step.
pub(crate) const FUSED: u8 = 8;
/// Flag of [`Fast`]: the four-lane full-metric step above 4 dimensions.
pub(crate) const WIDE: u8 = 16;
/// Every specialisation: what production runs.
pub(crate) const ALL: u8 = TWO_DIRS | PLANE | GROUPS | FUSED | WIDE;

/// The stages of the fast path for kernel and regression dimensions `K`, `R` (compile-time
/// constants, 0: from the model), compiled for AVX2 (`AVX`, set only after the CPU check) and
/// with the specialisations of the flags `F`.
pub(crate) struct Fast<const K: usize, const R: usize, const AVX: bool, const F: u8>;

/// Whether a sub-model of this shape updates its RFs in groups (`group.rs`).
#[inline(always)]
pub(crate) fn groups_apply(nk: usize, nr: usize, p: &Params) -> bool {
    nk == 2 && nr == 2 && !p.cfg.diag_only && p.n_local_out() == 1
}

impl<const K: usize, const R: usize, const AVX: bool, const F: u8> Stages for Fast<K, R, AVX, F> {
    const NK: usize = K;
    const NR: usize = R;
    const AVX: bool = AVX;
    const HEADS: bool = true;

    #[inline(always)]
    fn activations(p: &Params, sub: &SubModel, ws: &mut Scratch) -> Top2 {
        if !(K == 2 && !p.cfg.diag_only && F & PLANE != 0) {
            return pass::<K, AVX>(p, sub, ws);
        }
        let qb = ws.qb_update;
        let mut top = Top2::new();
        ws.active.clear();
        // Four RFs at a time; the same `q`s.
        let active = &mut ws.active;
        plane_quad::for_each_q::<AVX>(&sub.centers, &sub.ms, &ws.xk, |i, q| {
            top.visit(p, qb, i, q, active)
        });
        top
    }

    #[inline(always)]
    fn update_active(p: &Params, sub: &mut SubModel, o0: usize, ws: &mut Scratch) -> f64 {
        if F & GROUPS != 0 && groups_apply(K, R, p) {
            group::update_active_grouped::<Self>(p, sub, o0, ws)
        } else {
            update_active::<Self>(p, sub, o0, ws)
        }
    }

    #[inline(always)]
    fn output_step(
        p: &Params,
        out: &mut Pls,
        nr: usize,
        omega: f64,
        y: f64,
        w: f64,
        acc: &mut MetricAcc,
        ws: &mut PlsScratch,
    ) -> (f64, f64) {
        if !(R > 0 && out.n_reg == 2 && F & TWO_DIRS != 0) {
            return output_step(p, out, nr, omega, y, w, acc, ws);
        }
        // Two directions (the usual count at small dimensions) as a constant, so that the
        // loops over them unroll; in two inputs on fixed-size arrays.
        let r = if nr == 2 && F & PLANE != 0 {
            plane_pls::regression_2d(out, omega, y, w, ws)
        } else {
            update_regression::<2>(out, nr, omega, y, w, ws)
        };
        after_pls::<2>(p, out, nr, w, &r, acc, ws)
    }

    #[inline(always)]
    fn full_metric_step(nk: usize, p: &Params, s: FullStep<'_>, ws: &mut MetricScratch) {
        if K == 2 && F & PLANE != 0 {
            // Every dimension a constant, on fixed-size arrays.
            use plane_pls::arr;
            let st = plane_metric::MetricState {
                m: arr(s.m),
                d: arr(s.d),
                alpha: arr(s.alpha),
                b: arr(s.b),
                hm: arr(s.hm),
            };
            let dx = *arr::<2>(&mut ws.dx);
            return plane_metric::step_2d(p, st, s.acc, dx, s.dwdq, s.ddwdqdq);
        }
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
        if nk >= wide::MIN_DIMS && F & WIDE != 0 {
            // A function of its own (per constant dimension), so that the step gets its own
            // registers instead of spilling inside the whole update.
            #[cfg(target_arch = "x86_64")]
            if AVX {
                // SAFETY: `AVX` is only set by the AVX2 entry points (after the CPU check,
                // which includes FMA).
                return unsafe {
                    wide_avx2::<K>(nk, p, m, d, alpha, b, hm, acc, dwdq, ddwdqdq, ws)
                };
            }
            return wide_base::<K>(nk, p, m, d, alpha, b, hm, acc, dwdq, ddwdqdq, ws);
        }
        if F & FUSED != 0 {
            return fused::full_step(nk, p, m, d, alpha, b, hm, acc, dwdq, ddwdqdq, ws);
        }
        let s = FullStep {
            m,
            d,
            alpha,
            b,
            hm,
            acc,
            dwdq,
            ddwdqdq,
        };
        reference_step(nk, p, s, ws)
    }

    #[inline(always)]
    fn plain_sums(p: &Params, sub: &mut SubModel, o0: usize, ws: &mut Scratch) -> f64 {
        if K == 2 && !p.cfg.diag_only && F & PLANE != 0 {
            let nr = dims::<Self>(p).1;
            plane_quad::plain_sums_2d::<AVX>(p, sub, o0, ws, nr)
        } else {
            sub_sums::<Self>(p, sub, o0, ws, Want::Plain)
        }
    }
}

/// Updates sub-model `sub` with the sample in `ws` ([`crate::update::update_sub`]) on the fast
/// path.
pub(crate) fn update_sub(
    p: &Params,
    sub: &mut SubModel,
    ws: &mut Scratch,
    cx: SubCtx<'_>,
) -> SubOutcome {
    update_sub_with::<ALL>(p, sub, ws, cx)
}

/// [`update_sub`] with the specialisations of the flags `F`: compiled for the baseline target
/// and with AVX2 enabled (chosen at run time); vector instructions do the same IEEE operations
/// in the same order, so both give the same bits.
#[inline(always)]
pub(crate) fn update_sub_with<const F: u8>(
    p: &Params,
    sub: &mut SubModel,
    ws: &mut Scratch,
    cx: SubCtx<'_>,
) -> SubOutcome {
    #[cfg(target_arch = "x86_64")]
    if has_avx2() {
        // SAFETY: the CPU supports AVX2 (checked at run time).
        return unsafe { update_avx2::<F>(p, sub, ws, cx) };
    }
    update_shape::<false, F>(p, sub, ws, cx)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn update_avx2<const F: u8>(
    p: &Params,
    sub: &mut SubModel,
    ws: &mut Scratch,
    cx: SubCtx<'_>,
) -> SubOutcome {
    update_shape::<true, F>(p, sub, ws, cx)
}

#[inline(always)]
fn update_shape<const AVX: bool, const F: u8>(
    p: &Params,
    sub: &mut SubModel,
    ws: &mut Scratch,
    cx: SubCtx<'_>,
) -> SubOutcome {
    macro_rules! go {
        ($s:ident) => {
            update_with::<Fast<{ $s.0 }, { $s.1 }, AVX, F>>(p, sub, ws, cx)
        };
    }
    by_shape!(p.nk(), p.nr(), go)
}

/// Predicts at `x` into `ws` ([`predict_core`]) on the fast path: plain predictions get a copy
/// of their own, without the branches (and the registers) of the confidence and Jacobian code.
pub(crate) fn predict(
    p: &Params,
    subs: &mut [SubModel],
    ws: &mut Scratch,
    x: &[f64],
    want: Want,
    strict: bool,
) -> Result<Support, LwprError> {
    predict_with::<ALL>(p, subs, ws, x, want, strict)
}

/// [`predict`] with the specialisations of the flags `F`.
#[inline(always)]
pub(crate) fn predict_with<const F: u8>(
    p: &Params,
    subs: &mut [SubModel],
    ws: &mut Scratch,
    x: &[f64],
    want: Want,
    strict: bool,
) -> Result<Support, LwprError> {
    #[cfg(target_arch = "x86_64")]
    if has_avx2() {
        // SAFETY: the CPU supports AVX2 (checked at run time).
        return unsafe {
            match want {
                Want::Plain => predict_plain_avx2::<F>(p, subs, ws, x, strict),
                _ => predict_avx2::<F>(p, subs, ws, x, want, strict),
            }
        };
    }
    match want {
        Want::Plain => predict_shape::<true, false, F>(p, subs, ws, x, want, strict),
        _ => predict_shape::<false, false, F>(p, subs, ws, x, want, strict),
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline(never)]
unsafe fn predict_plain_avx2<const F: u8>(
    p: &Params,
    subs: &mut [SubModel],
    ws: &mut Scratch,
    x: &[f64],
    strict: bool,
) -> Result<Support, LwprError> {
    predict_shape::<true, true, F>(p, subs, ws, x, Want::Plain, strict)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline(never)]
unsafe fn predict_avx2<const F: u8>(
    p: &Params,
    subs: &mut [SubModel],
    ws: &mut Scratch,
    x: &[f64],
    want: Want,
    strict: bool,
) -> Result<Support, LwprError> {
    predict_shape::<false, true, F>(p, subs, ws, x, want, strict)
}

#[inline(always)]
fn predict_shape<const PLAIN: bool, const AVX: bool, const F: u8>(
    p: &Params,
    subs: &mut [SubModel],
    ws: &mut Scratch,
    x: &[f64],
    want: Want,
    strict: bool,
) -> Result<Support, LwprError> {
    macro_rules! go {
        ($s:ident) => {
            predict_core::<Fast<{ $s.0 }, { $s.1 }, AVX, F>, PLAIN>(p, subs, ws, x, want, strict)
        };
    }
    by_shape!(p.nk(), p.nr(), go)
}

/// The activation query ([`activations_core`]) on the fast path.
pub(crate) fn activations(
    p: &Params,
    s: &SubModel,
    ws: &mut Scratch,
    x: &[f64],
    cutoff: f64,
    out: &mut Vec<Activation>,
) {
    #[cfg(target_arch = "x86_64")]
    if has_avx2() {
        // SAFETY: the CPU supports AVX2 (checked at run time).
        unsafe { activations_avx2(p, s, ws, x, cutoff, out) };
        return;
    }
    activations_dims::<false>(p, s, ws, x, cutoff, out);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn activations_avx2(
    p: &Params,
    s: &SubModel,
    ws: &mut Scratch,
    x: &[f64],
    cutoff: f64,
    out: &mut Vec<Activation>,
) {
    activations_dims::<true>(p, s, ws, x, cutoff, out)
}

/// The kernel dimensions of [`QUERY_KERNEL_DIMS`] as constants (`AVX`: only after the CPU
/// check).
#[inline(always)]
fn activations_dims<const AVX: bool>(
    p: &Params,
    s: &SubModel,
    ws: &mut Scratch,
    x: &[f64],
    cutoff: f64,
    out: &mut Vec<Activation>,
) {
    const Q0: usize = QUERY_KERNEL_DIMS[0];
    const Q1: usize = QUERY_KERNEL_DIMS[1];
    match p.nk() {
        Q0 => activations_core::<Q0, AVX>(p, s, ws, x, cutoff, out),
        Q1 => activations_core::<Q1, AVX>(p, s, ws, x, cutoff, out),
        _ => activations_core::<0, AVX>(p, s, ws, x, cutoff, out),
    }
}

/// Defines `$name`, [`wide::wide_step`] as a function of its own with `nk = NK` when `NK > 0`.
/// It takes the fields of a [`FullStep`] as separate arguments: only then does the compiler
/// know that the slices do not overlap (taking the struct cost 3.7 % more instructions on the
/// 21-D test).
macro_rules! wide_copy {
    ($(#[$attr:meta])* $name:ident, $avx:expr $(, $unsafe:ident)?) => {
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
            wide::wide_step::<NK, $avx>(nk, p, m, d, alpha, b, hm, acc, dwdq, ddwdqdq, ws)
        }
    };
}

wide_copy!(
    /// `wide_step` with AVX2 and FMA (same results, see `wide.rs`).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    wide_avx2, true, unsafe
);
wide_copy!(
    /// `wide_step` for the baseline target (FMA in software).
    wide_base, false
);

/// Whether the CPU supports AVX2 and FMA (cached by the standard library after the first
/// query). The full-metric step above 4 dimensions uses FMA; every other AVX2 entry point only
/// AVX2.
#[cfg(target_arch = "x86_64")]
#[inline]
pub(crate) fn has_avx2() -> bool {
    std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma")
}
