//! Gimbal lock of a ball joint written as three revolute joints on massless links.
//!
//! A URDF often models a ball joint (a human shoulder, a spherical wrist of a humanoid) as three
//! revolute joints whose axes meet in one point, with massless links between them. Only the third
//! link has inertia, and it turns with angular velocity `ω = a q̇₁ + b q̇₂ + c q̇₃`. Where the first
//! and the third axis coincide (Euler angles' gimbal lock: the middle joint at `θ*`, e.g. ±π/2 for
//! Z-X-Y axes), `q̇₁ = −q̇₃` (or `+`) moves no mass: the mass matrix `M(q)` is singular there, and
//! near it one eigenvalue shrinks as the square of the distance `δ` to `θ*` (the human's right
//! shoulder: 1.5e-4 kg·m² at δ = 0.1 rad). The held command of the 2 ms control period then drives
//! that mode unstably (any joint damping `K_D` with `K_D Δt > 2 λ_min`), the velocities grow to
//! 1e9 rad/s and the state becomes non-finite. A real ball joint has no such point; the three-angle
//! model does, so the simulator refuses a model whose limits let the middle joint reach `θ*`,
//! naming the joints and the angle ([`check`]).
//!
//! With `a`, `b` the first two axes and `c` the third, all in the middle joint's child frame, the
//! axes are dependent where `det[a, b, c] = a(θ) · (b × c) = 0`; `a(θ) = Rot(b, −θ) p` with
//! `p = Rᵀ a₀` (`R` the middle joint's origin rotation), so with `n = b × c ⟂ b`,
//! `det = cos θ (p · n) + sin θ (p · (b × n))`: zero at `θ* = atan2(A, −B) + kπ` for
//! `A = p · n`, `B = p · (b × n)` (closed form, no search).

use crate::error::{DynamicsError, Result};
use crate::model::{JointKind, Link, Model};

/// Relative size below which an origin offset, a mass or an inertia counts as zero.
const ZERO: f64 = 1e-12;

/// A gimbal (three revolute joints about one point through two massless links) whose singular
/// angle lies within the middle joint's limits.
#[derive(Clone, Debug, PartialEq)]
pub struct Gimbal {
    /// Indices of the three joints, base to tip.
    pub joints: [usize; 3],
    /// Middle-joint positions (rad) within its limits at which the first and third axes coincide.
    pub singular_at: Vec<f64>,
}

fn massless(l: &Link) -> bool {
    l.inertia.mass <= ZERO && l.inertia.inertia.amax() <= ZERO
}

/// Every gimbal of `model` whose singular angle lies within the middle joint's limits (bounds
/// included). Joints through massive links, offset origins or prismatic joints are never one.
pub fn gimbals(model: &Model) -> Vec<Gimbal> {
    let links = model.links();
    let mut out = Vec::new();
    for i in 0..links.len().saturating_sub(2) {
        let (l1, l2, l3) = (&links[i], &links[i + 1], &links[i + 2]);
        if [l1, l2, l3].iter().any(|l| l.kind != JointKind::Revolute)
            || !massless(l1)
            || !massless(l2)
            || l2.origin.trans.norm() > ZERO
            || l3.origin.trans.norm() > ZERO
        {
            continue;
        }
        let p = l2.origin.rot.transpose() * l1.axis;
        let b = l2.axis;
        let c = l3.origin.rot * l3.axis;
        let n = b.cross(&c);
        let (a_cos, b_sin) = (p.dot(&n), p.dot(&b.cross(&n)));
        let (lo, hi) = (l2.limits.q_min, l2.limits.q_max);
        let singular_at = if a_cos.hypot(b_sin) <= ZERO {
            // Dependent at every angle: M is singular everywhere (also caught by the ABA).
            vec![lo.max(-std::f64::consts::PI)]
        } else {
            let theta = a_cos.atan2(-b_sin);
            let pi = std::f64::consts::PI;
            // Every θ* + kπ within [lo, hi] (a few at most: the limits are finite or the joint
            // turns freely, in which case one period suffices).
            let (lo_c, hi_c) = (lo.max(-2.0 * pi), hi.min(2.0 * pi));
            let k0 = ((lo_c - theta) / pi).ceil() as i64;
            (k0..)
                .map(|k| theta + k as f64 * pi)
                .take_while(|t| *t <= hi_c + 1e-9)
                .filter(|t| *t >= lo_c - 1e-9)
                .collect()
        };
        if !singular_at.is_empty() {
            out.push(Gimbal {
                joints: [i, i + 1, i + 2],
                singular_at,
            });
        }
    }
    out
}

/// Refuses a model with a gimbal inside its limits ([`gimbals`]), naming the joints, the middle
/// joint's limits and the singular angle, and what to change.
pub fn check(model: &Model) -> Result<()> {
    let Some(g) = gimbals(model).into_iter().next() else {
        return Ok(());
    };
    let links = model.links();
    let name = |k: usize| links[g.joints[k]].joint_name.as_str();
    let mid = &links[g.joints[1]].limits;
    let at: Vec<String> = g.singular_at.iter().map(|t| format!("{t:.4}")).collect();
    Err(DynamicsError::InvalidModel(format!(
        "joints '{}', '{}', '{}' turn one body about one point through massless links (a ball \
         joint written as three angles); at '{}' = {} rad, inside its limits [{:.4}, {:.4}], the \
         axes of '{}' and '{}' coincide and the mass matrix is singular (gimbal lock), which the \
         simulation cannot follow: narrow the <limit> of '{}' to exclude it (the smallest \
         eigenvalue of M shrinks as the square of the distance), or lock one of the three joints",
        name(0),
        name(1),
        name(2),
        name(1),
        at.join(", "),
        mid.q_min,
        mid.q_max,
        name(0),
        name(2),
        name(1)
    )))
}
