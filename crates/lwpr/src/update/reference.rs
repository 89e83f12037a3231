//! The reference stages (tests only): the update and the plain prediction computed by the code
//! of `update/` and `predict/blend.rs` alone, with the dimensions taken from the model and the
//! activation pass from the rows of every RF (no heads), to compare the fast path with.

use crate::params::Params;
use crate::pls::Pls;
use crate::predict::blend::{sub_sums, Want};
use crate::rf::SubModel;
use crate::scratch::Scratch;
use crate::update::activation::{pass_rows, Top2};
use crate::update::metric::{MetricAcc, MetricScratch};
use crate::update::metric_step::reference_step;
use crate::update::regression::PlsScratch;
use crate::update::rf::{output_step, update_active};
use crate::update::stages::{FullStep, Stages};

/// The reference: every stage by the code of `update/` (dimensions from the model); the
/// tests compare the fast path with it.
pub(crate) struct Reference;

impl Stages for Reference {
    const NK: usize = 0;
    const NR: usize = 0;
    const AVX: bool = false;
    const HEADS: bool = false;

    #[inline(always)]
    fn activations(p: &Params, sub: &SubModel, ws: &mut Scratch) -> Top2 {
        pass_rows::<0, false>(p, sub, ws)
    }

    #[inline(always)]
    fn update_active(p: &Params, sub: &mut SubModel, o0: usize, ws: &mut Scratch) -> f64 {
        update_active::<Self>(p, sub, o0, ws)
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
        output_step(p, out, nr, omega, y, w, acc, ws)
    }

    #[inline(always)]
    fn full_metric_step(nk: usize, p: &Params, s: FullStep<'_>, ws: &mut MetricScratch) {
        reference_step(nk, p, s, ws)
    }

    #[inline(always)]
    fn plain_sums(p: &Params, sub: &mut SubModel, o0: usize, ws: &mut Scratch) -> f64 {
        sub_sums::<Self>(p, sub, o0, ws, Want::Plain)
    }
}
