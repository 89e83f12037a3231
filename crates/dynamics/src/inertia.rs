//! Spatial inertias: the rigid-body inertia of one link and the articulated-body inertia of ABA.

use crate::spatial::{skew, Force, Motion, Pose};
use nalgebra::{Matrix3, Vector3};
use serde::{Deserialize, Serialize};

/// Rigid-body inertia of a link in its own frame: mass `mass` (kg), first moment `h = m·c`
/// (kg·m, `c` the centre of mass) and rotational inertia `inertia` about the frame **origin**
/// (kg·m²). Keeping `h` rather than `c` allows the zero-mass links of identified base parameters.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Inertia {
    pub mass: f64,
    pub h: Vector3<f64>,
    pub inertia: Matrix3<f64>,
}

impl Default for Inertia {
    fn default() -> Self {
        Self::zero()
    }
}

impl Inertia {
    /// A massless, inertia-less body.
    pub fn zero() -> Self {
        Self {
            mass: 0.0,
            h: Vector3::zeros(),
            inertia: Matrix3::zeros(),
        }
    }
    /// From mass, centre of mass `com` (m) and inertia about the centre of mass (kg·m²).
    pub fn from_com(mass: f64, com: Vector3<f64>, inertia_com: Matrix3<f64>) -> Self {
        // Parallel axis theorem: I_o = I_c + m (|c|² I − c cᵀ).
        let i_o =
            inertia_com + (Matrix3::identity() * com.norm_squared() - com * com.transpose()) * mass;
        Self {
            mass,
            h: com * mass,
            inertia: i_o,
        }
    }
    /// From mass, first moment `mcm = m·c` (kg·m) and inertia about the frame origin (kg·m²).
    pub fn from_origin(mass: f64, mcm: Vector3<f64>, inertia_origin: Matrix3<f64>) -> Self {
        Self {
            mass,
            h: mcm,
            inertia: inertia_origin,
        }
    }
    /// Centre of mass (m), or the origin for a massless body.
    pub fn com(&self) -> Vector3<f64> {
        if self.mass > 0.0 {
            self.h / self.mass
        } else {
            Vector3::zeros()
        }
    }
    /// Rotational inertia about the centre of mass (kg·m²); about the origin if massless.
    pub fn inertia_com(&self) -> Matrix3<f64> {
        let c = self.com();
        self.inertia - (Matrix3::identity() * c.norm_squared() - c * c.transpose()) * self.mass
    }
    /// Momentum `I v` of the body moving with `v` (same frame).
    #[inline]
    pub fn mul_motion(&self, v: &Motion) -> Force {
        Force {
            ang: self.inertia * v.ang + self.h.cross(&v.lin),
            lin: v.lin * self.mass - self.h.cross(&v.ang),
        }
    }
    /// This inertia (given in a child frame) expressed in the parent frame of `pose`.
    ///
    /// `I_p = R I Rᵀ − [Rh]×[p]× − [p]×[Rh]× − m [p]×[p]×`, expanded with
    /// `[a]×[b]× = b aᵀ − (a·b) 1`; the result is symmetric, so only its upper triangle is
    /// computed and mirrored (CRBA's main cost).
    #[inline(always)]
    pub fn to_parent(&self, pose: &Pose) -> Inertia {
        let r = &pose.rot;
        let p = &pose.trans;
        let hr = r * self.h;
        let ri = r * self.inertia;
        let diag = 2.0 * hr.dot(p) + self.mass * p.norm_squared();
        let entry = |a: usize, b: usize| {
            let rir = ri[(a, 0)] * r[(b, 0)] + ri[(a, 1)] * r[(b, 1)] + ri[(a, 2)] * r[(b, 2)];
            let cross = p[a] * hr[b] + hr[a] * p[b];
            rir - cross - p[a] * p[b] * self.mass
        };
        let (xx, yy, zz) = (entry(0, 0) + diag, entry(1, 1) + diag, entry(2, 2) + diag);
        let (xy, xz, yz) = (entry(0, 1), entry(0, 2), entry(1, 2));
        Inertia {
            mass: self.mass,
            h: hr + p * self.mass,
            inertia: Matrix3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz),
        }
    }
    /// Sum of two inertias in the same frame.
    pub fn add(&self, o: &Inertia) -> Inertia {
        Inertia {
            mass: self.mass + o.mass,
            h: self.h + o.h,
            inertia: self.inertia + o.inertia,
        }
    }
}

/// Relative tolerance of [`Inertia::unphysical`] (against the trace): published files round their
/// values.
pub const INERTIA_TOLERANCE: f64 = 1e-6;

/// Absolute tolerance of [`Inertia::unphysical`] (kg·m², added to the relative one): a gram at
/// 30 µm. A point mass written with round-off in its products of inertia (iCub's `head`: every
/// moment 0, `ixz` 2.4e-35) has principal moments of ±that size and a trace of 0, which no
/// relative tolerance accepts.
pub const INERTIA_FLOOR: f64 = 1e-12;

impl Inertia {
    /// Why the rotational inertia `ic` about a body's centre of mass is one no rigid body can
    /// have, or `None`: a principal moment below zero, or principal moments violating the
    /// triangle inequality `I₁ + I₂ ≥ I₃`, each by more than [`INERTIA_TOLERANCE`] × `scale`
    /// (kg·m²; the trace for a file's values) + [`INERTIA_FLOOR`]. Point masses and thin rods
    /// (zero moments) pass.
    pub fn unphysical(ic: &Matrix3<f64>, scale: f64) -> Option<String> {
        let mut e = nalgebra::SymmetricEigen::new(*ic).eigenvalues;
        e.as_mut_slice().sort_by(f64::total_cmp);
        let tol = INERTIA_TOLERANCE * scale + INERTIA_FLOOR;
        let moments = format!("{:.3e}, {:.3e}, {:.3e} kg·m²", e[0], e[1], e[2]);
        if !e.iter().all(|x| x.is_finite()) {
            Some("the inertia is not finite".into())
        } else if e[0] < -tol {
            Some(format!(
                "the inertia is not positive semi-definite (principal moments {moments})"
            ))
        } else if e[0] + e[1] < e[2] - tol {
            Some(format!(
                "the principal moments {moments} violate the triangle inequality (no mass \
                 distribution has them)"
            ))
        } else {
            None
        }
    }
}

/// Articulated-body inertia, a symmetric 6×6 map from motion to force kept in 3×3 blocks:
/// `n = A ω + B v`, `f = Bᵀ ω + C v`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArticulatedInertia {
    pub a: Matrix3<f64>,
    pub b: Matrix3<f64>,
    pub c: Matrix3<f64>,
}

impl Default for ArticulatedInertia {
    fn default() -> Self {
        Self {
            a: Matrix3::zeros(),
            b: Matrix3::zeros(),
            c: Matrix3::zeros(),
        }
    }
}

impl ArticulatedInertia {
    /// The rigid inertia as a 6×6 block matrix.
    #[inline]
    pub fn from_rigid(i: &Inertia) -> Self {
        Self {
            a: i.inertia,
            b: skew(&i.h),
            c: Matrix3::identity() * i.mass,
        }
    }
    #[inline]
    pub fn mul_motion(&self, v: &Motion) -> Force {
        Force {
            ang: self.a * v.ang + self.b * v.lin,
            lin: self.b.tr_mul(&v.ang) + self.c * v.lin,
        }
    }
    /// `self − U Uᵀ / d` with `U = (ua, ul)`: removes the joint's own degree of freedom.
    #[inline]
    pub fn sub_rank1(&mut self, ua: &Vector3<f64>, ul: &Vector3<f64>, inv_d: f64) {
        self.a -= ua * ua.transpose() * inv_d;
        self.b -= ua * ul.transpose() * inv_d;
        self.c -= ul * ul.transpose() * inv_d;
    }
    #[inline]
    pub fn add_assign(&mut self, o: &ArticulatedInertia) {
        self.a += o.a;
        self.b += o.b;
        self.c += o.c;
    }
    /// This inertia (given in a child frame) expressed in the parent frame of `pose`:
    /// `ᵖX*_c I ᶜX_p`, computed as a rotation followed by a shift with `P = [p]×`.
    ///
    /// The products are written out ([`rotate`], [`skew_mul`], [`mul_skew`]) in the order of
    /// nalgebra's, with `P`'s zero entries left out: the same values as the matrix expression
    /// `(R A Rᵀ) − B' P − (B' P)ᵀ − (P C') P` (test `to_parent_equals_the_matrix_products`), in a
    /// third fewer operations (ABA's pass 2, the simulator's main cost).
    #[inline]
    pub fn to_parent(&self, pose: &Pose) -> ArticulatedInertia {
        let r = &pose.rot;
        let a = rotate(r, &self.a);
        let b = rotate(r, &self.b);
        let c = rotate(r, &self.c);
        let p = &pose.trans;
        let pc = skew_mul(p, &c);
        let bp = mul_skew(&b, p);
        ArticulatedInertia {
            a: a - bp - bp.transpose() - mul_skew(&pc, p),
            b: b + pc,
            c,
        }
    }
}

/// `(R X) Rᵀ`, each entry summed over `k = 0, 1, 2` in turn as nalgebra's product does.
#[inline(always)]
fn rotate(r: &Matrix3<f64>, x: &Matrix3<f64>) -> Matrix3<f64> {
    let rx = Matrix3::from_fn(|i, j| {
        r[(i, 0)] * x[(0, j)] + r[(i, 1)] * x[(1, j)] + r[(i, 2)] * x[(2, j)]
    });
    Matrix3::from_fn(|i, j| {
        rx[(i, 0)] * r[(j, 0)] + rx[(i, 1)] * r[(j, 1)] + rx[(i, 2)] * r[(j, 2)]
    })
}

/// `[p]× X` without the zero terms: row `i` is `Σ_k P_ik X_kj` over the two `k ≠ i`, in order.
#[inline(always)]
fn skew_mul(p: &Vector3<f64>, x: &Matrix3<f64>) -> Matrix3<f64> {
    Matrix3::from_fn(|i, j| match i {
        0 => -p.z * x[(1, j)] + p.y * x[(2, j)],
        1 => p.z * x[(0, j)] + -p.x * x[(2, j)],
        _ => -p.y * x[(0, j)] + p.x * x[(1, j)],
    })
}

/// `X [p]×` without the zero terms: column `j` is `Σ_k X_ik P_kj` over the two `k ≠ j`, in order.
#[inline(always)]
fn mul_skew(x: &Matrix3<f64>, p: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::from_fn(|i, j| match j {
        0 => x[(i, 1)] * p.z + x[(i, 2)] * -p.y,
        1 => x[(i, 0)] * -p.z + x[(i, 2)] * p.x,
        _ => x[(i, 0)] * p.y + x[(i, 1)] * -p.x,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spatial::axis_angle;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The written-out products give the values of the matrix expression they replace, on
    /// random inertias and poses and on poses with zero offsets (the built-in arms have them).
    #[test]
    fn to_parent_equals_the_matrix_products() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let m3 = |rng: &mut ChaCha8Rng| Matrix3::from_fn(|_, _| rng.random_range(-3.0..3.0));
        for k in 0..2000 {
            let ia = ArticulatedInertia {
                a: m3(&mut rng),
                b: m3(&mut rng),
                c: m3(&mut rng),
            };
            let axis = Vector3::new(rng.random(), rng.random(), rng.random::<f64>()).normalize();
            let mut trans = Vector3::from_fn(|_, _| rng.random_range(-1.0..1.0));
            if k % 4 == 0 {
                trans[k / 4 % 3] = 0.0;
            }
            if k % 7 == 0 {
                trans.fill(0.0);
            }
            let pose = Pose {
                rot: axis_angle(&axis, rng.random_range(-3.0..3.0)),
                trans,
            };
            let (r, rt, p) = (pose.rot, pose.rot.transpose(), skew(&pose.trans));
            let (a, b, c) = (r * ia.a * rt, r * ia.b * rt, r * ia.c * rt);
            let (pc, bp) = (p * c, b * p);
            let got = ia.to_parent(&pose);
            assert_eq!(got.a, a - bp - bp.transpose() - pc * p, "a, draw {k}");
            assert_eq!(got.b, b + pc, "b, draw {k}");
            assert_eq!(got.c, c, "c, draw {k}");
        }
    }
}
