//! Forward kinematics of every link and of the end-effector point, its velocity and `J̇ q̇`.

use crate::data::{update_joint_poses, Data};
use crate::error::{check_vec, Result};
use crate::model::Model;
use crate::spatial::Motion;

/// Poses of every link in the world (`data.world_pose`) and the end-effector position
/// (`data.ee_pos`) at `q`. Fails on a wrong length or a non-finite entry.
pub fn forward_kinematics(model: &Model, data: &mut Data, q: &[f64]) -> Result<()> {
    check_vec("q", q, model.nq())?;
    update_joint_poses(model, data, q);
    fk_world(model, data);
    Ok(())
}

/// World poses from the joint poses already in `data`.
#[inline]
pub(crate) fn fk_world(model: &Model, data: &mut Data) {
    let n = model.nq();
    data.world_pose[0] = data.joint_pose[0];
    for i in 1..n {
        data.world_pose[i] = data.world_pose[i - 1].compose(&data.joint_pose[i]);
    }
    data.ee_pos = data.world_pose[n - 1].transform_point(&model.spec().ee_offset);
}

/// Forward kinematics plus link velocities, the end-effector velocity `ẋ = J q̇` (`data.ee_vel`)
/// and the bias acceleration `J̇ q̇` (`data.jdot_qd`, the end-effector's acceleration at `q̈ = 0`
/// without gravity), all in the world frame.
pub fn kinematics(model: &Model, data: &mut Data, q: &[f64], qd: &[f64]) -> Result<()> {
    check_vec("q", q, model.nq())?;
    check_vec("qd", qd, model.nq())?;
    update_joint_poses(model, data, q);
    fk_world(model, data);
    let mut v_parent = Motion::default();
    let mut a_parent = Motion::default();
    for (i, l) in model.links().iter().enumerate() {
        let x = &data.joint_pose[i];
        let vj = l.motion(qd[i]);
        let v = x.motion_to_child(&v_parent) + vj;
        // Spatial acceleration with q̈ = 0: transported parent acceleration plus v ×ₘ S q̇.
        let a = x.motion_to_child(&a_parent) + v.cross_motion(&vj);
        data.v[i] = v;
        data.a[i] = a;
        v_parent = v;
        a_parent = a;
    }
    // The end-effector point r in the last frame: classical velocity v + ω × r and classical
    // acceleration (a_lin + α × r) + ω × (v + ω × r).
    let n = model.nq();
    let r = model.spec().ee_offset;
    let (v, a) = (&data.v[n - 1], &data.a[n - 1]);
    let v_pt = v.lin + v.ang.cross(&r);
    let acc = a.lin + a.ang.cross(&r) + v.ang.cross(&v_pt);
    let rot = &data.world_pose[n - 1].rot;
    data.ee_vel = rot * v_pt;
    data.jdot_qd = rot * acc;
    Ok(())
}
