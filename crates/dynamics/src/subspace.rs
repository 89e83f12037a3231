//! A joint's motion subspace `S` as the recursive algorithms use it ([`crate::crba`],
//! [`crate::aba`]): the general products of [`Link::motion`] and [`Link::project`], or, when every
//! joint is revolute about one `±e_K` ([`crate::Model`] knows), the same products without their
//! exact zero terms.
//!
//! Dropping a term `0 · x` changes no value but the sign of a zero result (`0 · x` is `±0`, and
//! `y + ±0 = y` for `y ≠ 0`), so both kinds give the same bits up to the sign of zeros (tests in
//! `crba.rs` and `aba.rs`).

use crate::inertia::{ArticulatedInertia, Inertia};
use crate::model::Link;
use crate::spatial::{Force, Motion};
use nalgebra::Vector3;

/// The operations with a joint's motion subspace `S` (one column: revolute or prismatic).
pub(crate) trait Subspace {
    /// `I S`: the column of the rigid or composite inertia `ic` that the joint of `link` moves.
    fn column(link: &Link, ic: &Inertia) -> Force;
    /// `Sᵀ f`: the part of the force `f` that the joint transmits.
    fn project(link: &Link, f: &Force) -> f64;
    /// `m + S x`: the joint's motion at rate `x` added to `m`.
    fn add_motion(link: &Link, m: Motion, x: f64) -> Motion;
    /// `v ×ₘ (S x)`: the velocity-product acceleration of the joint's motion at rate `x`.
    fn cross_joint(link: &Link, v: &Motion, x: f64) -> Motion;
    /// `U = I^A S` as angular and linear parts, and `d = Sᵀ U`.
    fn columns(link: &Link, ia: &ArticulatedInertia) -> (Vector3<f64>, Vector3<f64>, f64);
}

/// Revolute or prismatic about any axis: [`Inertia::mul_motion`], [`Link::project`] and
/// [`Link::motion`] as they are.
pub(crate) struct AnyAxis;

impl Subspace for AnyAxis {
    #[inline(always)]
    fn column(link: &Link, ic: &Inertia) -> Force {
        ic.mul_motion(&link.motion(1.0))
    }
    #[inline(always)]
    fn project(link: &Link, f: &Force) -> f64 {
        link.project(f)
    }
    #[inline(always)]
    fn add_motion(link: &Link, m: Motion, x: f64) -> Motion {
        m + link.motion(x)
    }
    #[inline(always)]
    fn cross_joint(link: &Link, v: &Motion, x: f64) -> Motion {
        v.cross_motion(&link.motion(x))
    }
    #[inline(always)]
    fn columns(link: &Link, ia: &ArticulatedInertia) -> (Vector3<f64>, Vector3<f64>, f64) {
        let s = &link.axis;
        match link.kind {
            crate::model::JointKind::Revolute => {
                let ua = ia.a * s;
                (ua, ia.b.tr_mul(s), s.dot(&ua))
            }
            crate::model::JointKind::Prismatic => {
                let ul = ia.c * s;
                (ia.b * s, ul, s.dot(&ul))
            }
        }
    }
}

/// Revolute about `s e_K` with `s = ±1`: `S = (s e_K, 0)`, so `I S = s (I_:K, −h × e_K)`,
/// `Sᵀ f = s n_K`, `v ×ₘ S x` has two non-zero entries per part, and `I^A S` is column `K` of
/// the articulated inertia's `A` and row `K` of its `B`.
pub(crate) struct UnitAxis<const K: usize>;

impl<const K: usize> UnitAxis<K> {
    /// The two other axes, in the cyclic order of the cross product.
    const K1: usize = (K + 1) % 3;
    const K2: usize = (K + 2) % 3;

    /// `a × (w e_K)`: entry `K1` is `a_K2 w`, entry `K2` is `−a_K1 w`, entry `K` zero.
    #[inline(always)]
    fn cross_axis(a: &Vector3<f64>, w: f64) -> Vector3<f64> {
        let mut r = Vector3::zeros();
        r[Self::K1] = a[Self::K2] * w;
        r[Self::K2] = -(a[Self::K1] * w);
        r
    }
}

impl<const K: usize> Subspace for UnitAxis<K> {
    #[inline(always)]
    fn column(link: &Link, ic: &Inertia) -> Force {
        let s = link.axis[K];
        let mut lin = Vector3::zeros();
        lin[Self::K1] = -(ic.h[Self::K2] * s);
        lin[Self::K2] = ic.h[Self::K1] * s;
        Force {
            ang: ic.inertia.column(K) * s,
            lin,
        }
    }
    #[inline(always)]
    fn project(link: &Link, f: &Force) -> f64 {
        link.axis[K] * f.ang[K]
    }
    #[inline(always)]
    fn add_motion(link: &Link, mut m: Motion, x: f64) -> Motion {
        m.ang[K] += link.axis[K] * x;
        m
    }
    #[inline(always)]
    fn cross_joint(link: &Link, v: &Motion, x: f64) -> Motion {
        let w = link.axis[K] * x;
        Motion {
            ang: Self::cross_axis(&v.ang, w),
            lin: Self::cross_axis(&v.lin, w),
        }
    }
    #[inline(always)]
    fn columns(link: &Link, ia: &ArticulatedInertia) -> (Vector3<f64>, Vector3<f64>, f64) {
        let s = link.axis[K];
        let ua = ia.a.column(K) * s;
        let ul = ia.b.row(K).transpose() * s;
        (ua, ul, s * ua[K])
    }
}

/// Models with every joint about one `±e_k`, for the tests that compare the unit-axis paths with
/// the general ones.
#[cfg(test)]
pub(crate) use test_models::unit_axis_models;

#[cfg(test)]
mod test_models {
    use crate::model::Model;
    use crate::robots;
    use nalgebra::Vector3;

    /// Models with every joint about one `±e_k`: `sarcos7` (`+z`), `planar3` (`−y`) and random
    /// arms of 3, 6, 7 and 8 joints turned about `±x`, `±y`, `±z`.
    pub(crate) fn unit_axis_models() -> Vec<Model> {
        let mut models = vec![robots::sarcos7(), robots::planar3()];
        for (seed, n) in [(0u64, 3), (1, 6), (2, 7), (3, 8), (4, 6), (5, 7)] {
            let mut spec = robots::random_arm(n, seed, false).spec().clone();
            for (i, l) in spec.links.iter_mut().enumerate() {
                l.axis = Vector3::zeros();
                l.axis[seed as usize % 3] = if (i as u64 + seed).is_multiple_of(3) {
                    -1.0
                } else {
                    1.0
                };
            }
            models.push(Model::new(spec).unwrap());
        }
        models
    }
}
