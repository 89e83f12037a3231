//! Running a model on a chosen path, for the tests that compare the paths: the reference
//! (`update::reference::Reference`), or the fast path with some specialisations off (flags of
//! `fast::Fast`); and a wrapper that counts the outputs updated with two PLS directions.

use crate::fast::update_sub_with;
use crate::model::{Lwpr, UpdateInfo};
use crate::params::Params;
use crate::pls::Pls;
use crate::predict::blend::{predict_core, Want};
use crate::rf::SubModel;
use crate::scratch::Scratch;
use crate::update::metric::{MetricAcc, MetricScratch};
use crate::update::reference::Reference;
use crate::update::regression::PlsScratch;
use crate::update::stages::{FullStep, Stages};
use crate::update::update_sub;
use std::cell::Cell;
use std::marker::PhantomData;

/// [`Lwpr::update`] by the reference stages.
pub(crate) fn update_reference(m: &mut Lwpr, x: &[f64], y: &[f64]) -> UpdateInfo {
    m.update_by(x, y, update_sub::<Reference>).unwrap()
}

/// [`Lwpr::update`] on the fast path with the specialisations of the flags `F`.
pub(crate) fn update_flags<const F: u8>(m: &mut Lwpr, x: &[f64], y: &[f64]) -> UpdateInfo {
    m.update_by(x, y, update_sub_with::<F>).unwrap()
}

/// [`Lwpr::predict`] by the reference stages (no cache); `None` without support.
pub(crate) fn predict_reference(m: &mut Lwpr, x: &[f64]) -> Option<Vec<f64>> {
    let Lwpr { p, subs, ws, .. } = m;
    predict_core::<Reference, true>(p, subs, ws, x, Want::Plain, true).ok()?;
    Some(ws.y.clone())
}

thread_local! {
    /// Output steps with two directions that [`Counting`] saw.
    pub(crate) static TWO_DIRECTION_STEPS: Cell<u64> = const { Cell::new(0) };
}

/// The stages of `S`, but the RFs updated one at a time (through this wrapper), counting the
/// output steps with two PLS directions in [`TWO_DIRECTION_STEPS`].
pub(crate) struct Counting<S>(PhantomData<S>);

impl<S: Stages> Stages for Counting<S> {
    const NK: usize = S::NK;
    const NR: usize = S::NR;
    const AVX: bool = S::AVX;
    const HEADS: bool = S::HEADS;

    fn activations(
        p: &Params,
        sub: &SubModel,
        ws: &mut Scratch,
    ) -> crate::update::activation::Top2 {
        S::activations(p, sub, ws)
    }

    fn update_active(p: &Params, sub: &mut SubModel, o0: usize, ws: &mut Scratch) -> f64 {
        crate::update::rf::update_active::<Self>(p, sub, o0, ws)
    }

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
        if out.n_reg == 2 {
            TWO_DIRECTION_STEPS.with(|n| n.set(n.get() + 1));
        }
        S::output_step(p, out, nr, omega, y, w, acc, ws)
    }

    fn full_metric_step(nk: usize, p: &Params, s: FullStep<'_>, ws: &mut MetricScratch) {
        S::full_metric_step(nk, p, s, ws)
    }

    fn plain_sums(p: &Params, sub: &mut SubModel, o0: usize, ws: &mut Scratch) -> f64 {
        S::plain_sums(p, sub, o0, ws)
    }
}
