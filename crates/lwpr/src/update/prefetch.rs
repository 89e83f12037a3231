//! Software prefetches for step 3: the state of the RFs about to be updated, fetched while the
//! current one is updated (issue 31). An RF's state is spread over its [`Rf`] (in the
//! sub-model's list), about twenty heap vectors and its row of the centres and metrics; on the
//! SARCOS data (≈ 6,000–11,000 RFs, ≈ 30 updated per output and sample) their first reads were
//! cache misses that the update waited for. A prefetch changes no value.
//!
//! Three stages, because each level's addresses are in the level above: RF `a + 3`'s [`Rf`]
//! and its rows of `centers`, `ms`, `ds`; RF `a + 2`'s vectors and its [`Pls`] records (read
//! from the `Rf` fetched one RF earlier); RF `a + 1`'s PLS vectors. The activation pass
//! (`activation.rs`) fetches, for a diagonal metric, the centre and metric rows
//! [`PASS_AHEAD`] RFs ahead of the one it measures (the hardware's stream prefetch alone left
//! ≈ 4 % more time per update).

use crate::pls::Pls;
use crate::rf::{Rf, SubModel};

/// Prefetches for the update of `active[a]`: the stages above for `active[a + 1..=a + 3]`.
#[inline(always)]
pub(crate) fn ahead(
    sub: &SubModel,
    nk: usize,
    ml: usize,
    active: &[(usize, f64, f64, f64)],
    a: usize,
) {
    if let Some(&(i, ..)) = active.get(a + 3) {
        lines(std::slice::from_ref(&sub.rfs[i]));
        lines(&sub.centers[i * nk..(i + 1) * nk]);
        lines(&sub.ds[i * ml..(i + 1) * ml]);
        lines(&sub.ms[i * ml..(i + 1) * ml]);
    }
    if let Some(&(i, ..)) = active.get(a + 2) {
        let rf: &Rf = &sub.rfs[i];
        for v in [&rf.alpha, &rf.b, &rf.hm, &rf.mean_x, &rf.var_x] {
            lines(v);
        }
        lines(&rf.outs);
    }
    if let Some(&(i, ..)) = active.get(a + 1) {
        for out in &sub.rfs[i].outs {
            pls(out);
        }
    }
}

/// The vectors the PLS step of `out` reads and writes.
#[inline(always)]
fn pls(out: &Pls) {
    for v in [&out.u, &out.p, &out.sxy, &out.ssx] {
        lines(v);
    }
    let small = [
        &out.beta,
        &out.ss_s2,
        &out.ss_yres,
        &out.sum_w,
        &out.n_data,
        &out.lambda,
        &out.sum_e_cv2,
        &out.h_tr,
        &out.r_tr,
    ];
    for v in small {
        lines(v);
    }
}

/// How many RFs ahead the activation pass prefetches centres and metrics.
pub(crate) const PASS_AHEAD: usize = 8;

/// Prefetches every cache line of `v` into the L1 cache (x86-64; nothing elsewhere).
#[inline(always)]
pub(crate) fn lines<T>(v: &[T]) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        let (start, bytes) = (v.as_ptr().cast::<i8>(), std::mem::size_of_val(v));
        let mut off = 0;
        while off < bytes {
            // SAFETY: a prefetch never faults; the address lies inside `v` (SSE is part of
            // the x86-64 baseline).
            unsafe { _mm_prefetch::<_MM_HINT_T0>(start.add(off)) };
            off += 64;
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = v;
}
