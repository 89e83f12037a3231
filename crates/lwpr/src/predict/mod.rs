//! Prediction `ŷ = Σ w ŷ_k / Σ w` over trustworthy RFs with `w > cutoff`, with optional
//! confidence bounds and Jacobian `∂ŷ/∂x` (`docs/lwpr.md`, "Prediction"): the public methods,
//! and the repeated-query cache. The computation is in `blend.rs`, run by the fast dispatch
//! (`fast/mod.rs`).

pub(crate) mod blend;
pub(crate) mod everywhere;
pub(crate) mod query;

pub use blend::Support;

use crate::error::{check_len, check_vec};
use crate::model::Lwpr;
use crate::scratch::same_bits;
use crate::LwprError;
use blend::Want;

impl Lwpr {
    /// Predicts `y` (length `n_out`) at `x` (length `n_in`).
    ///
    /// Fails with [`LwprError::NoActiveRf`] when, for some output, no trustworthy RF has
    /// `w > cutoff` (the model has no support there), and with
    /// [`LwprError::PredictionOverflow`] when the blend is not finite (coefficients out of
    /// range in a hand-made model file); `y` is then left untouched.
    pub fn predict(&mut self, x: &[f64], y: &mut [f64]) -> Result<Support, LwprError> {
        check_len("y", y.len(), self.p.n_out)?;
        let s = self.predict_impl(x, Want::Plain)?;
        y.copy_from_slice(&self.ws.y);
        Ok(s)
    }

    /// Like [`Lwpr::predict`], also writing a confidence bound per output into `conf`
    /// (the reference library's `sqrt(Σ w σ²_k + Σ w (ŷ_k − ŷ)²) / Σ w`, in output units).
    pub fn predict_conf(
        &mut self,
        x: &[f64],
        y: &mut [f64],
        conf: &mut [f64],
    ) -> Result<Support, LwprError> {
        check_len("y", y.len(), self.p.n_out)?;
        check_len("conf", conf.len(), self.p.n_out)?;
        let s = self.predict_impl(x, Want::Conf)?;
        y.copy_from_slice(&self.ws.y);
        conf.copy_from_slice(&self.ws.conf);
        Ok(s)
    }

    /// Like [`Lwpr::predict`], also writing the Jacobian `∂ŷ/∂x` (row-major, `n_out × n_in`,
    /// user units) into `jac`. RFs at `w ≤ cutoff` are left out, as in the reference library.
    pub fn predict_jacobian(
        &mut self,
        x: &[f64],
        y: &mut [f64],
        jac: &mut [f64],
    ) -> Result<Support, LwprError> {
        check_len("y", y.len(), self.p.n_out)?;
        check_len("jac", jac.len(), self.p.n_out * self.p.n_in)?;
        let s = self.predict_impl(x, Want::Jac)?;
        y.copy_from_slice(&self.ws.y);
        jac.copy_from_slice(&self.ws.jac);
        Ok(s)
    }

    /// Predicts every output it can: writes into `support` each output's total activation
    /// `Σ w`, and where that is 0 (no RF active) sets the output to 0 as the reference library
    /// does. Never fails with [`LwprError::NoActiveRf`].
    pub fn predict_with_support(
        &mut self,
        x: &[f64],
        y: &mut [f64],
        support: &mut [f64],
    ) -> Result<(), LwprError> {
        check_len("y", y.len(), self.p.n_out)?;
        check_len("support", support.len(), self.p.n_out)?;
        self.predict_impl_mode(x, Want::Plain, false)?;
        y.copy_from_slice(&self.ws.y);
        support.copy_from_slice(&self.ws.support);
        Ok(())
    }

    fn predict_impl(&mut self, x: &[f64], want: Want) -> Result<Support, LwprError> {
        self.predict_impl_mode(x, want, true)
    }

    fn predict_impl_mode(
        &mut self,
        x: &[f64],
        want: Want,
        strict: bool,
    ) -> Result<Support, LwprError> {
        check_vec("x", x, self.p.n_in)?;
        // A repeated query (same input bits, same kind) on an unchanged model: the results are
        // still in the buffers.
        let key = (want as u8, strict);
        if let Some((k, res)) = self.ws.pred_cache {
            if k == key && same_bits(x, &self.ws.pred_x) {
                return res
                    .map(|sum_w| Support { sum_w })
                    .map_err(|output| LwprError::NoActiveRf { output });
            }
        }
        let res = crate::fast::predict(&self.p, &mut self.subs, &mut self.ws, x, want, strict);
        self.ws.pred_cache = match &res {
            Ok(s) => Some((key, Ok(s.sum_w))),
            Err(LwprError::NoActiveRf { output }) => Some((key, Err(*output))),
            Err(_) => None,
        };
        self.ws.pred_x.copy_from_slice(x);
        res
    }
}
