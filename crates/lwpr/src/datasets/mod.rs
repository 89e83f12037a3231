//! The reference library's accuracy benchmarks (`docs/lwpr.md`, "The cross tests"), for tests,
//! benchmarks and comparisons with other implementations: the 2-D "cross" function, its
//! training set and test grid, the 21-D version embedded by a random rotation, their model
//! configs, and a seeded train-and-test run that reports nMSE, RFs and µs per call.
//!
//! Behind the cargo feature `datasets` (off by default), which brings in the random-number
//! crates the data sets are drawn with.
//!
//! ```
//! use lwpr::datasets::{cross_config, cross_run};
//! // One seed of the standard test, with 2 epochs instead of 20.
//! let r = cross_run(&cross_config(), 0, 2)?;
//! assert!(r.nmse < 0.5 && r.n_rfs > 10);
//! # Ok::<(), lwpr::LwprError>(())
//! ```

mod cross;
mod run;

pub use cross::{
    cross, cross21_config, cross21_data, cross_config, cross_grid, cross_nd_data, cross_train,
    embed, rotation, Data, Embedding,
};
pub use run::{
    cross21_embedded_run, cross21_run, cross_nd_run, cross_run, fit, median, predict_conf_or_nan,
    predict_or_zero, run, test_nmse, RunResult,
};
