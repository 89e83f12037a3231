//! Model errors: the analytical controller reads a robot model whose parameters differ from the
//! simulated robot's.

use crate::error::{ControlError, Result};
use crate::spec::num;
use osrl_dynamics::Model;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// How the controller's model differs from the truth (all defaults: no error). Written on the
/// command line as `key=value` pairs, e.g. `mass=1.3,com=0.02,friction=off,payload=0.5,seed=7`
/// (`none` for no error).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ModelError {
    /// Factor on every link's mass and rotational inertia (about its centre of mass) in the
    /// controller's model (`mass=`). Default 1.
    pub mass_scale: f64,
    /// Distance (m) by which the controller's model shifts each massive link's centre of mass, in
    /// a random direction per link drawn from `seed` (`com=`). Default 0.
    pub com_shift: f64,
    /// Whether the controller's model includes the joint friction (`friction=on|off`). Default
    /// true.
    pub friction: bool,
    /// Point mass (kg) at the end-effector of the simulated robot that the controller's model
    /// does not know (`payload=`). Default 0.
    pub payload: f64,
    /// Seed of the centre-of-mass shift directions (`seed=`). Default 0.
    pub seed: u64,
}

impl Default for ModelError {
    fn default() -> Self {
        Self {
            mass_scale: 1.0,
            com_shift: 0.0,
            friction: true,
            payload: 0.0,
            seed: 0,
        }
    }
}

impl ModelError {
    /// Checks the ranges ([`crate::MASS_SCALE_RANGE`] and the bounds beside it).
    ///
    /// # Errors
    /// [`ControlError::ModelErrorSpec`] naming the field, its value and its range.
    pub fn validate(&self) -> Result<()> {
        let friction = if self.friction { 1.0 } else { 0.0 };
        crate::spec::check_ranges(self.mass_scale, self.com_shift, self.payload, friction).map_err(
            |reason| ControlError::ModelErrorSpec {
                spec: self.to_string(),
                reason,
            },
        )
    }

    /// Whether the controller's model equals the truth.
    pub fn is_none(&self) -> bool {
        *self
            == Self {
                seed: self.seed,
                ..Self::default()
            }
    }

    /// `(simulated robot, controller's model)` from the true model: the payload goes into the
    /// simulated robot's last link; the scaled masses and inertias, shifted centres of mass and
    /// missing friction go into the controller's model. Zero-mass links (identified base
    /// parameters) keep their inertia unscaled and unshifted. The same seed gives the same models.
    pub fn apply(&self, truth: &Model) -> Result<(Model, Model)> {
        self.validate()?;
        let mut sim = truth.spec().clone();
        if self.payload > 0.0 {
            crate::spec::add_payload(&mut sim, self.payload);
        }
        let mut ctrl = truth.spec().clone();
        let friction = if self.friction { 1.0 } else { 0.0 };
        crate::spec::perturb_links(
            &mut ctrl,
            self.seed,
            self.mass_scale,
            self.com_shift,
            friction,
        );
        ctrl.name = format!("{} ({})", ctrl.name, self);
        Ok((Model::new(sim)?, Model::new(ctrl)?))
    }
}

impl fmt::Display for ModelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_none() {
            return write!(f, "none");
        }
        let on = if self.friction { "on" } else { "off" };
        write!(
            f,
            "mass={},com={},friction={on},payload={},seed={}",
            num(self.mass_scale),
            num(self.com_shift),
            num(self.payload),
            self.seed
        )
    }
}

impl FromStr for ModelError {
    type Err = ControlError;

    /// Parses `none` or comma-separated `key=value` pairs with keys `mass`, `com`, `friction`
    /// (`on`/`off`/`true`/`false`), `payload`, `seed`; unnamed keys keep their defaults.
    fn from_str(spec: &str) -> Result<Self> {
        let err = |reason: String| ControlError::ModelErrorSpec {
            spec: spec.to_string(),
            reason,
        };
        let v = crate::spec::parse(spec).map_err(err)?;
        let mut me = ModelError::default();
        me.mass_scale = v.mass.unwrap_or(me.mass_scale);
        me.com_shift = v.com.unwrap_or(me.com_shift);
        me.payload = v.payload.unwrap_or(me.payload);
        me.seed = v.seed.unwrap_or(me.seed);
        if let Some(f) = v.friction {
            me.friction = match f {
                "on" | "true" => true,
                "off" | "false" => false,
                _ => return Err(err(format!("friction: '{f}' is not on/off"))),
            };
        }
        me.validate().map_err(|e| match e {
            ControlError::ModelErrorSpec { reason, .. } => err(reason),
            e => e,
        })?;
        Ok(me)
    }
}
