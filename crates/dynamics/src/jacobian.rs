//! The end-effector point Jacobian `J(q) = ∂x/∂q` in the world frame.

use crate::data::Data;
use crate::error::Result;
use crate::kinematics::forward_kinematics;
use crate::model::{JointKind, Model};

/// Fills `data.jac` (3×n) with the world-frame Jacobian of the end-effector point at `q`
/// (and, as a by-product, the forward kinematics). Column `i` is `a_i × (x − p_i)` for a revolute
/// joint and `a_i` for a prismatic one, with `a_i` the joint axis and `p_i` the joint origin in
/// the world.
pub fn jacobian(model: &Model, data: &mut Data, q: &[f64]) -> Result<()> {
    forward_kinematics(model, data, q)?;
    jacobian_from_fk(model, data);
    Ok(())
}

/// The Jacobian from the world poses already in `data` (after [`forward_kinematics`] or
/// [`crate::kinematics`]).
#[inline]
pub fn jacobian_from_fk(model: &Model, data: &mut Data) {
    for (i, l) in model.links().iter().enumerate() {
        let pose = &data.world_pose[i];
        let axis = pose.rot * l.axis;
        let col = match l.kind {
            JointKind::Revolute => axis.cross(&(data.ee_pos - pose.trans)),
            JointKind::Prismatic => axis,
        };
        data.jac.set_column(i, &col);
    }
}
