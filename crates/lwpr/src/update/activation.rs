//! Step 2 of an update, the activation pass: the distance `q` of every RF to the input, the
//! RFs to update (activation above `W_UPDATE`, with the kernel's derivatives), and the two
//! nearest, for the add and prune tests of step 5.

use crate::distance::quad;
use crate::head;
use crate::params::{Params, W_UPDATE};
use crate::rf::SubModel;
use crate::scratch::Scratch;

/// The activation pass: queues in `ws.active` every RF whose activation exceeds the update
/// threshold, with the kernel's derivatives, and returns the two nearest RFs. `NK > 0` fixes
/// the kernel dimension at compile time (0: taken from `p`); `AVX` is set only after the
/// run-time check of the CPU (`distance::quad`). Where the model keeps heads (`head/`) by
/// [`pass_heads`], else by [`pass_rows`]: the same results.
#[inline(always)]
pub(crate) fn pass<const NK: usize, const AVX: bool>(
    p: &Params,
    sub: &SubModel,
    ws: &mut Scratch,
) -> Top2 {
    if head::in_use(p) {
        pass_heads::<AVX>(p, sub, ws)
    } else {
        pass_rows::<NK, AVX>(p, sub, ws)
    }
}

/// [`pass`] from every RF's rows of the centres and metrics.
#[inline(always)]
pub(crate) fn pass_rows<const NK: usize, const AVX: bool>(
    p: &Params,
    sub: &SubModel,
    ws: &mut Scratch,
) -> Top2 {
    let nk = if NK > 0 { NK } else { p.nk() };
    let (ml, diag, qb) = (p.mlen(), p.cfg.diag_only, ws.qb_update);
    let mut top = Top2::new();
    ws.active.clear();
    let kern = if diag { &sub.ds } else { &sub.ms };
    // Centres and metrics by chunks (no index arithmetic or bounds checks per RF).
    let rf_chunks = sub.centers.chunks_exact(nk).zip(kern.chunks_exact(ml));
    for (i, (c, md)) in rf_chunks.enumerate() {
        // Diagonal metrics (SARCOS: thousands of RFs, not in the caches): the rows ahead.
        let ahead = i + crate::update::prefetch::PASS_AHEAD;
        if let (true, Some(c), Some(md)) = (
            diag,
            sub.centers.get(ahead * nk..(ahead + 1) * nk),
            kern.get(ahead * ml..(ahead + 1) * ml),
        ) {
            crate::update::prefetch::lines(c);
            crate::update::prefetch::lines(md);
        }
        // An RF at q ≥ max(qb, q2) is neither updated nor among the two most active.
        let q = quad(
            AVX,
            diag,
            c,
            md,
            &ws.xk[..nk],
            &mut ws.met.dx,
            qb.max(top.q2),
        );
        top.visit(p, qb, i, q, &mut ws.active);
    }
    top
}

/// [`pass`] over the heads (`head/`; a diagonal metric over many dimensions): an RF whose
/// head's lower bound of `q` reaches the pass's bound (it would be neither updated nor among
/// the two nearest) is skipped; the others are measured from their rows as by [`pass_rows`].
/// The same results as [`pass_rows`], tested against it (`tests/heads.rs`).
#[inline(always)]
pub(crate) fn pass_heads<const AVX: bool>(p: &Params, sub: &SubModel, ws: &mut Scratch) -> Top2 {
    let (nk, qb, n) = (p.nk(), ws.qb_update, sub.rfs.len());
    let mut top = Top2::new();
    ws.active.clear();
    debug_assert_eq!(sub.heads.len(), n);
    let x = &ws.xk[..nk];
    let Some(mut heads) = sub.heads.walk(AVX, p, x) else {
        unreachable!("the pass over heads runs where the model keeps them")
    };
    for i in 0..n {
        let bound = qb.max(top.q2);
        if heads.beyond(i, bound) {
            continue;
        }
        let (c, d) = (&sub.centers[i * nk..][..nk], &sub.ds[i * nk..][..nk]);
        let q = quad(false, true, c, d, x, &mut [], bound);
        top.visit(p, qb, i, q, &mut ws.active);
    }
    top
}

/// The activation pass's state: the two RFs of smallest `q` (largest activation) so far, with
/// their activations where already computed (`q < qb`), for the add/prune tests.
pub(crate) struct Top2 {
    pub q1: f64,
    pub i1: usize,
    pub w1: Option<f64>,
    pub q2: f64,
    pub i2: usize,
    pub w2: Option<f64>,
}

impl Top2 {
    pub fn new() -> Top2 {
        Top2 {
            q1: f64::INFINITY,
            i1: usize::MAX,
            w1: None,
            q2: f64::INFINITY,
            i2: usize::MAX,
            w2: None,
        }
    }

    /// The nearest RF's activation, 0 when there is none (taken from the pass when it
    /// computed it, else from the kernel).
    #[inline(always)]
    pub fn w_max(&self, p: &Params) -> f64 {
        Self::w(p, self.i1, self.q1, self.w1)
    }

    /// The second-nearest RF's activation, 0 when there is none.
    #[inline(always)]
    pub fn w_sec(&self, p: &Params) -> f64 {
        Self::w(p, self.i2, self.q2, self.w2)
    }

    /// The activation of RF `i` at distance `q`, `w` if the pass computed it; 0 for no RF.
    #[inline(always)]
    fn w(p: &Params, i: usize, q: f64, w: Option<f64>) -> f64 {
        if i < usize::MAX {
            w.unwrap_or_else(|| p.kernel(q).0)
        } else {
            0.0
        }
    }

    /// Visits RF `i` at distance `q`: queues it for the update if its activation exceeds
    /// `W_UPDATE` (`q < qb` first, so that far RFs cost no exponential), and keeps the two
    /// nearest.
    #[inline(always)]
    pub fn visit(
        &mut self,
        p: &Params,
        qb: f64,
        i: usize,
        q: f64,
        active: &mut Vec<(usize, f64, f64, f64)>,
    ) {
        let mut wq = None;
        if q < qb {
            let (w, dw, ddw) = p.kernel(q);
            if w > W_UPDATE {
                active.push((i, w, dw, ddw));
            }
            wq = Some(w);
        }
        if q < self.q2 {
            if q < self.q1 {
                (self.q2, self.i2, self.w2) = (self.q1, self.i1, self.w1);
                (self.q1, self.i1, self.w1) = (q, i, wq);
            } else {
                (self.q2, self.i2, self.w2) = (q, i, wq);
            }
        }
    }
}
