//! The still samples of the current hold at a path posture, kept until the hold ends
//! (`null_gravity.rs`, `Learner::end_hold`).

/// The still samples of one hold: rows of `q0, q̇0, q1, q̇1`, the gravity error
/// `u − ĝ(q1)`, the load correction `c(q1)` and `ĝ(q1)` (n values each) and `dt`.
#[derive(Clone, Debug, Default)]
pub(crate) struct HoldBatch {
    pub(crate) rows: Vec<f64>,
}
