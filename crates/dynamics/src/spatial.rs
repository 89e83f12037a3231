//! Spatial algebra on 3-vector pairs (Featherstone's notation, split into angular/linear parts).
//!
//! A motion `(ω, v)` is an angular velocity and the linear velocity of the point at the frame's
//! origin; a force `(n, f)` is a moment about the origin and a force. Everything is expressed in
//! one frame, named by the caller. These types are `Copy` and never allocate.

use nalgebra::{Matrix3, Vector3};
use serde::{Deserialize, Serialize};

/// Spatial motion vector: angular part `ang`, linear part `lin` (at the frame origin).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Motion {
    pub ang: Vector3<f64>,
    pub lin: Vector3<f64>,
}

/// Spatial force vector: moment `ang` about the frame origin, force `lin`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Force {
    pub ang: Vector3<f64>,
    pub lin: Vector3<f64>,
}

impl Motion {
    pub fn new(ang: Vector3<f64>, lin: Vector3<f64>) -> Self {
        Self { ang, lin }
    }
    /// Motion cross product `self ×ₘ m` (derivative of `m` in a frame moving with `self`).
    #[inline]
    pub fn cross_motion(&self, m: &Motion) -> Motion {
        Motion {
            ang: self.ang.cross(&m.ang),
            lin: self.ang.cross(&m.lin) + self.lin.cross(&m.ang),
        }
    }
    /// Force cross product `self ×_f f`.
    #[inline]
    pub fn cross_force(&self, f: &Force) -> Force {
        Force {
            ang: self.ang.cross(&f.ang) + self.lin.cross(&f.lin),
            lin: self.ang.cross(&f.lin),
        }
    }
    /// Power pairing `self · f`.
    #[inline]
    pub fn dot(&self, f: &Force) -> f64 {
        self.ang.dot(&f.ang) + self.lin.dot(&f.lin)
    }
}

impl std::ops::Add for Motion {
    type Output = Motion;
    fn add(self, o: Motion) -> Motion {
        Motion::new(self.ang + o.ang, self.lin + o.lin)
    }
}

impl std::ops::Add for Force {
    type Output = Force;
    fn add(self, o: Force) -> Force {
        Force {
            ang: self.ang + o.ang,
            lin: self.lin + o.lin,
        }
    }
}

impl std::ops::AddAssign for Force {
    fn add_assign(&mut self, o: Force) {
        self.ang += o.ang;
        self.lin += o.lin;
    }
}

/// Rigid transform of a child frame relative to its parent: the child's axes expressed in the
/// parent (`rot`) and the child's origin in parent coordinates (`trans`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    pub rot: Matrix3<f64>,
    pub trans: Vector3<f64>,
}

impl Default for Pose {
    fn default() -> Self {
        Self::identity()
    }
}

impl Pose {
    pub fn identity() -> Self {
        Self {
            rot: Matrix3::identity(),
            trans: Vector3::zeros(),
        }
    }
    pub fn new(rot: Matrix3<f64>, trans: Vector3<f64>) -> Self {
        Self { rot, trans }
    }
    /// `self ∘ child`: the child's pose in this pose's parent frame.
    #[inline]
    pub fn compose(&self, child: &Pose) -> Pose {
        Pose {
            rot: self.rot * child.rot,
            trans: self.trans + self.rot * child.trans,
        }
    }
    /// A point given in the child frame, expressed in the parent frame.
    #[inline]
    pub fn transform_point(&self, p: &Vector3<f64>) -> Vector3<f64> {
        self.trans + self.rot * p
    }
    /// A parent-frame motion seen in the child frame (`ᶜX_p m`).
    #[inline]
    pub fn motion_to_child(&self, m: &Motion) -> Motion {
        let rt = self.rot.transpose();
        Motion {
            ang: rt * m.ang,
            lin: rt * (m.lin + m.ang.cross(&self.trans)),
        }
    }
    /// A child-frame force seen in the parent frame (`ᵖX*_c f`).
    #[inline]
    pub fn force_to_parent(&self, f: &Force) -> Force {
        let lin = self.rot * f.lin;
        Force {
            ang: self.rot * f.ang + self.trans.cross(&lin),
            lin,
        }
    }
}

/// Skew-symmetric matrix `[v]×` with `[v]× w = v × w`.
#[inline]
pub fn skew(v: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

/// Rotation by angle `q` about the unit axis `axis` (Rodrigues), with the standard library's
/// sine: for building models (URDF origins, the built-in robots). Joint poses use
/// [`crate::sincos`] ([`rotate_about`]).
#[inline]
pub fn axis_angle(axis: &Vector3<f64>, q: f64) -> Matrix3<f64> {
    axis_rotation(axis, q.sin_cos())
}

/// Rotation about the unit axis `axis` by the angle with sine and cosine `(s, c)` (Rodrigues).
#[inline]
pub fn axis_rotation(axis: &Vector3<f64>, (s, c): (f64, f64)) -> Matrix3<f64> {
    let k = skew(axis);
    Matrix3::identity() + k * s + k * k * (1.0 - c)
}

/// `o · Rot(axis, q)` for a unit `axis`, with `(sin q, cos q)` from [`crate::sincos`]
/// ([`rotate_about_sc`]).
#[inline]
pub fn rotate_about(o: &Matrix3<f64>, axis: &Vector3<f64>, q: f64) -> Matrix3<f64> {
    rotate_about_sc(o, axis, crate::sincos::sin_cos(q))
}

/// `o · Rot(axis, q)` for a unit `axis`, given `(sin q, cos q)`. For an axis along ±x, ±y or ±z
/// (most robots) only the two columns that turn are computed, with the values of the general
/// product `o ·` [`axis_rotation`]`(axis, (s, c))`: that rotation's entries are then exact (±s,
/// `1 − (1 − c)`, 1, 0), so each column of the product is a sum of two non-zero terms, which is
/// commutative.
#[inline]
pub fn rotate_about_sc(o: &Matrix3<f64>, axis: &Vector3<f64>, sc: (f64, f64)) -> Matrix3<f64> {
    let (a, sign) = match (axis.x, axis.y, axis.z) {
        (x, 0.0, 0.0) if x.abs() == 1.0 => (0, x),
        (0.0, y, 0.0) if y.abs() == 1.0 => (1, y),
        (0.0, 0.0, z) if z.abs() == 1.0 => (2, z),
        _ => return o * axis_rotation(axis, sc),
    };
    // One copy per axis, so that the column indices are constants.
    match a {
        0 => rotate_about_unit::<0>(o, sign, sc),
        1 => rotate_about_unit::<1>(o, sign, sc),
        _ => rotate_about_unit::<2>(o, sign, sc),
    }
}

/// [`rotate_about_sc`] for the axis `sign e_K` (`sign = ±1`), known to the caller
/// ([`crate::Model`] knows when every joint shares one): the same values without the test.
#[inline(always)]
pub(crate) fn rotate_about_unit<const K: usize>(
    o: &Matrix3<f64>,
    sign: f64,
    (s, c): (f64, f64),
) -> Matrix3<f64> {
    let s = sign * s;
    // Rodrigues' diagonal entry of the turning axes, as the general formula evaluates it.
    let cc = 1.0 + -(1.0 - c);
    match K {
        0 => turn_columns::<1, 2>(o, s, cc),
        1 => turn_columns::<2, 0>(o, s, cc),
        _ => turn_columns::<0, 1>(o, s, cc),
    }
}

/// `o` with columns `I` and `J` turned: `(c_i cc + c_j s, −c_i s + c_j cc)`.
#[inline(always)]
fn turn_columns<const I: usize, const J: usize>(o: &Matrix3<f64>, s: f64, cc: f64) -> Matrix3<f64> {
    let mut r = *o;
    for k in 0..3 {
        let (ci, cj) = (o[(k, I)], o[(k, J)]);
        r[(k, I)] = ci * cc + cj * s;
        r[(k, J)] = ci * -s + cj * cc;
    }
    r
}

/// Roll-pitch-yaw (URDF convention: `R = Rz(yaw) Ry(pitch) Rx(roll)`) to a rotation matrix.
pub fn rpy_to_matrix(r: f64, p: f64, y: f64) -> Matrix3<f64> {
    axis_angle(&Vector3::z(), y) * axis_angle(&Vector3::y(), p) * axis_angle(&Vector3::x(), r)
}

/// Rotation matrix to roll-pitch-yaw (inverse of [`rpy_to_matrix`]), exact away from pitch = ±π/2
/// and consistent (round-trips to the same matrix) at it.
pub fn matrix_to_rpy(m: &Matrix3<f64>) -> (f64, f64, f64) {
    let pitch = (-m[(2, 0)]).atan2((m[(0, 0)].powi(2) + m[(1, 0)].powi(2)).sqrt());
    if m[(0, 0)].abs() < 1e-12 && m[(1, 0)].abs() < 1e-12 {
        // Gimbal lock: put the whole rotation about z into roll (yaw = 0).
        let roll = if pitch > 0.0 {
            m[(0, 1)].atan2(m[(1, 1)])
        } else {
            (-m[(0, 1)]).atan2(m[(1, 1)])
        };
        (roll, pitch, 0.0)
    } else {
        (
            m[(2, 1)].atan2(m[(2, 2)]),
            pitch,
            m[(1, 0)].atan2(m[(0, 0)]),
        )
    }
}
