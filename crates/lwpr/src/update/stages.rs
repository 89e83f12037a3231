//! The stages of an update (and of a plain prediction) that the fast code computes in other
//! ways: the seams between the reference code of `update/` and the specialisations of `fast/`.
//!
//! The reference update is written once, generic over a [`Stages`] type: the reference
//! (`update::Reference`) fills each stage with the code of `update/`, the fast path
//! (`fast::Fast`) with its specialisations where they apply (and the reference code where not).

use crate::params::Params;
use crate::pls::Pls;
use crate::rf::SubModel;
use crate::scratch::Scratch;
use crate::update::activation::Top2;
use crate::update::metric::{MetricAcc, MetricScratch};
use crate::update::regression::PlsScratch;

/// How each replaceable stage is computed. Every implementation gives the reference's results
/// bit for bit, but for the fast full-metric step above 4 dimensions (`fast/wide.rs`).
pub(crate) trait Stages {
    /// The kernel dimension as a compile-time constant, or 0 (taken from the model).
    const NK: usize;
    /// The regression dimension as a compile-time constant, or 0 (taken from the model).
    const NR: usize;
    /// Whether the code runs on AVX2 (set only after the run-time check of the CPU).
    const AVX: bool;
    /// Whether the activation passes skip the RFs that their heads exclude (`head/`), where
    /// the model keeps heads.
    const HEADS: bool;

    /// Step 2: queues the RFs to update in `ws.active`, with the kernel's derivatives, and
    /// returns the two nearest (`update/activation.rs`).
    fn activations(p: &Params, sub: &SubModel, ws: &mut Scratch) -> Top2;

    /// Step 3 for every RF in `ws.active` (outputs `o0..` of `ws.yn`): blends the trustworthy
    /// RFs' predictions into `ws.yacc` and returns the sum of their weights; the ids of RFs
    /// whose state diverged go to `ws.diverged` (`update/rf.rs`).
    fn update_active(p: &Params, sub: &mut SubModel, o0: usize, ws: &mut Scratch) -> f64;

    /// Steps (b), the metric's cost terms into `acc`, (e) and (f) of one output's PLS model
    /// `out` at sample `(x̃ = ws.xmz, y)`, weight `w`, `ω` (`omega`): returns the RF's
    /// prediction and the PLS step's guard sum (`update/rf.rs`).
    #[allow(clippy::too_many_arguments)]
    fn output_step(
        p: &Params,
        out: &mut Pls,
        nr: usize,
        omega: f64,
        y: f64,
        w: f64,
        acc: &mut MetricAcc,
        ws: &mut PlsScratch,
    ) -> (f64, f64);

    /// Step (d) of one RF with a full metric, `ws.dx = x − c` (`update/metric_step.rs`).
    fn full_metric_step(nk: usize, p: &Params, s: FullStep<'_>, ws: &mut MetricScratch);

    /// The sums of a plain prediction over sub-model `sub` (outputs `o0..`): `Σ w ŷ_k` into
    /// `ws.yacc`; returns `Σ w` (`predict/blend.rs`).
    fn plain_sums(p: &Params, sub: &mut SubModel, o0: usize, ws: &mut Scratch) -> f64;
}

/// The kernel and regression dimensions of a model `p` under `S`: its constants, or the model's.
#[inline(always)]
pub(crate) fn dims<S: Stages>(p: &Params) -> (usize, usize) {
    let nk = if S::NK > 0 { S::NK } else { p.nk() };
    let nr = if S::NR > 0 { S::NR } else { p.nr() };
    (nk, nr)
}

/// One RF's metric state — `M`, `D`, `α`, `b = ln α`, the IDBD memory `hm`, updated in place —
/// with the output sums `acc` and the kernel derivatives `dwdq`, `ddwdqdq` at the sample: what
/// step (d) of one RF reads.
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
