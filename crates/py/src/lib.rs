//! Python bindings of osrl: the native module `osrl._osrl` behind the `osrl` package
//! (`python/`, built by maturin as an abi3 wheel; `python/README.md` is the user's guide).
//!
//! - [`lwpr::PyLwpr`] (`osrl.Lwpr`): the `lwpr` crate's model on numpy arrays;
//! - [`robot::PyRobot`] (`osrl.Robot`): the `osrl-dynamics` model of a built-in robot or a URDF;
//! - [`controller::PyLearnedController`] (`osrl.LearnedController`), [`learner::PyLearner`]
//!   (`osrl.Learner`) and [`train::train`] (`osrl.train`): the learned controller of
//!   `osrl-learn`, stepped from Python and trained on a Python robot by the Rust trainer;
//! - [`trajectory::PyTrajectory`] (`osrl.Trajectory`): the task-space path training follows.
//!
//! Conventions shared by every method: inputs are float64 numpy arrays (or lists of numbers);
//! a wrong shape, a wrong dtype or a non-finite value raises `ValueError` before anything
//! changes ([`arrays`]); results are new numpy arrays. Calls that take long (batches, files)
//! release the GIL.

// The #[pymethods] signatures are Python's: `&mut self` methods that PyO3 wraps, and
// `PyResult` everywhere.
#![allow(clippy::useless_conversion)]

mod args;
mod arrays;
mod config;
mod controller;
mod errors;
mod learner;
mod lwpr;
mod meas;
mod pybot;
mod robot;
mod train;
mod trajectory;

use pyo3::prelude::*;

/// The native part of the `osrl` package (import `osrl`, not this module).
#[pymodule]
fn _osrl(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<lwpr::PyLwpr>()?;
    m.add_class::<robot::PyRobot>()?;
    m.add_class::<controller::PyLearnedController>()?;
    m.add_class::<learner::PyLearner>()?;
    m.add_function(wrap_pyfunction!(train::train, m)?)?;
    m.add_class::<trajectory::PyTrajectory>()?;
    m.add(
        "NoSupportError",
        m.py().get_type::<errors::NoSupportError>(),
    )?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("MAX_NORMALISED", ::lwpr::MAX_NORMALISED)?;
    m.add("MAX_BATCH_VALUES", arrays::MAX_BATCH_VALUES)?;
    Ok(())
}
