//! The nominal behaviour `u0` (paper eq. 6 plus gravity compensation, `docs/learner.md`, "Conventions and the target"):
//! `u0 = g(q) − K_Dq q̇ − K_Pq (q − q_rest)`.

use osrl_dynamics::Model;

/// `u0 = g − s·(K_Dq q̇ + K_Pq (q − q_rest))` into `out` (N·m), with the joint PD gains `kp`, `kd`
/// and rest posture `q_rest` of `model`'s spec scaled by `scale`, and the gravity torques `g`
/// supplied by the caller (the model's `g(q)` for the analytical controller, a learned `ĝ(q)` for
/// the learned one). Panics if a slice is shorter than the number of joints.
#[inline]
pub fn nominal_command(
    model: &Model,
    scale: f64,
    g: &[f64],
    q: &[f64],
    qd: &[f64],
    out: &mut [f64],
) {
    let spec = model.spec();
    for i in 0..model.nq() {
        out[i] = g[i] - scale * (spec.kd[i] * qd[i] + spec.kp[i] * (q[i] - spec.q_rest[i]));
    }
}
