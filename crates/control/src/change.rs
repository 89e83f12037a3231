//! A change of the robot itself (`osrl adapt --change`, `osrl train --change`): the grammar of
//! [`crate::ModelError`] (`mass=1.3,com=0.02,friction=off,payload=0.5,seed=7`), applied to the
//! simulated robot — the truth — instead of to a controller's model; `friction` may also be a
//! factor (`friction=2`: doubled).

use crate::error::{ControlError, Result};
use crate::ik::{solve_ik, IkOptions};
use crate::spec::num;
use crate::trajectory::Trajectory;
use osrl_dynamics::Model;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// How the robot changes (all defaults: no change).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RobotChange {
    /// Factor on every link's mass and rotational inertia about its centre of mass (`mass=`,
    /// > 0). Default 1.
    pub mass_scale: f64,
    /// Distance (m) each massive link's centre of mass moves, in a random direction per link
    /// drawn from `seed` (`com=`, ≥ 0). Default 0.
    pub com_shift: f64,
    /// Factor on every joint's viscous and Coulomb friction (`friction=` a number ≥ 0, or `on`
    /// = 1, `off` = 0). Default 1.
    pub friction_scale: f64,
    /// Point mass (kg) attached at the end-effector (`payload=`, ≥ 0). Default 0.
    pub payload: f64,
    /// Seed of the centre-of-mass shift directions (`seed=`). Default 0.
    pub seed: u64,
}

impl Default for RobotChange {
    fn default() -> Self {
        Self {
            mass_scale: 1.0,
            com_shift: 0.0,
            friction_scale: 1.0,
            payload: 0.0,
            seed: 0,
        }
    }
}

fn spec_error(spec: &str, reason: String) -> ControlError {
    ControlError::ChangeSpec {
        spec: spec.to_string(),
        reason,
    }
}

impl RobotChange {
    /// Checks the ranges ([`crate::MASS_SCALE_RANGE`] and the bounds beside it).
    ///
    /// # Errors
    /// [`ControlError::ChangeSpec`] naming the field, its value and its range.
    pub fn validate(&self) -> Result<()> {
        crate::spec::check_ranges(
            self.mass_scale,
            self.com_shift,
            self.payload,
            self.friction_scale,
        )
        .map_err(|reason| spec_error(&self.to_string(), reason))
    }

    /// Whether nothing changes.
    pub fn is_none(&self) -> bool {
        *self
            == Self {
                seed: self.seed,
                ..Self::default()
            }
    }

    /// The changed robot: `truth` with the payload on its last link (at the end-effector), its
    /// masses and inertias scaled, centres of mass shifted and friction scaled. Zero-mass links
    /// (identified base parameters) keep their inertia. The same seed gives the same model.
    ///
    /// # Errors
    /// An invalid change, or a model the dynamics refuse.
    pub fn apply(&self, truth: &Model) -> Result<Model> {
        self.validate()?;
        let mut spec = truth.spec().clone();
        crate::spec::perturb_links(
            &mut spec,
            self.seed,
            self.mass_scale,
            self.com_shift,
            self.friction_scale,
        );
        if self.payload > 0.0 {
            crate::spec::add_payload(&mut spec, self.payload);
        }
        Ok(Model::new(spec)?)
    }

    /// Refuses a change under which the arm cannot hold itself on the path: at `samples` points
    /// of one cycle of `traj` (postures by IK from `q_start`), the gravity torque of every joint
    /// of the changed robot must stay within its torque limit.
    ///
    /// # Errors
    /// [`ControlError::ChangeSpec`] naming the joint, the torque needed, its limit and where on
    /// the path; or the errors of [`RobotChange::apply`] and the IK.
    pub fn check_holdable(
        &self,
        truth: &Model,
        traj: &Trajectory,
        q_start: &[f64],
        samples: usize,
    ) -> Result<()> {
        let changed = self.apply(truth)?;
        let limits: Vec<f64> = changed.tau_max().collect();
        let mut data = changed.data();
        let mut q = q_start.to_vec();
        let opts = IkOptions::default();
        let samples = samples.max(1);
        for k in 0..=samples {
            let t = if k == 0 {
                0.0
            } else {
                traj.ramp() + traj.period() * k as f64 / samples as f64
            };
            solve_ik(&changed, &mut data, &traj.sample(t).x, &mut q, &opts)?;
            let g = osrl_dynamics::gravity(&changed, &mut data, &q)?;
            if let Some((j, tau)) = g.iter().enumerate().find(|(j, tau)| tau.abs() > limits[*j]) {
                return Err(spec_error(
                    &self.to_string(),
                    format!(
                        "the changed arm cannot hold itself on the path: joint {j} ('{}') needs \
                         {:.1} N·m against gravity at t = {t:.2} s, its torque limit is {:.1} N·m",
                        changed.links()[j].joint_name,
                        tau.abs(),
                        limits[j]
                    ),
                ));
            }
        }
        Ok(())
    }
}

impl fmt::Display for RobotChange {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_none() {
            return write!(f, "none");
        }
        let d = Self::default();
        let mut parts = Vec::new();
        if self.mass_scale != d.mass_scale {
            parts.push(format!("mass={}", num(self.mass_scale)));
        }
        if self.com_shift != d.com_shift {
            parts.push(format!("com={},seed={}", num(self.com_shift), self.seed));
        }
        if self.friction_scale != d.friction_scale {
            parts.push(format!("friction={}", num(self.friction_scale)));
        }
        if self.payload != d.payload {
            parts.push(format!("payload={}", num(self.payload)));
        }
        write!(f, "{}", parts.join(","))
    }
}

impl FromStr for RobotChange {
    type Err = ControlError;

    /// Parses `none` or comma-separated `key=value` pairs with keys `mass`, `com`, `friction`
    /// (`on`, `off` or a factor), `payload`, `seed`; unnamed keys keep their defaults. Unknown
    /// keys, malformed numbers and out-of-range values are refused.
    fn from_str(spec: &str) -> Result<Self> {
        let err = |reason: String| spec_error(spec, reason);
        let v = crate::spec::parse(spec).map_err(err)?;
        let mut c = RobotChange::default();
        c.mass_scale = v.mass.unwrap_or(c.mass_scale);
        c.com_shift = v.com.unwrap_or(c.com_shift);
        c.payload = v.payload.unwrap_or(c.payload);
        c.seed = v.seed.unwrap_or(c.seed);
        if let Some(f) = v.friction {
            c.friction_scale = match f {
                "on" | "true" => 1.0,
                "off" | "false" => 0.0,
                _ => f
                    .parse::<f64>()
                    .map_err(|_| err(format!("friction: '{f}' is not on, off or a factor")))?,
            };
        }
        c.validate().map_err(|e| match e {
            ControlError::ChangeSpec { reason, .. } => err(reason),
            e => e,
        })?;
        Ok(c)
    }
}

#[cfg(test)]
mod tests {
    use super::RobotChange;
    use crate::TrajectoryConfig;
    use osrl_dynamics::robots;

    /// The grammar: keys parse, friction takes on/off/factors, bad specs are refused by name.
    #[test]
    fn specs_parse_and_bad_ones_are_refused() {
        let c: RobotChange = "mass=1.3,friction=2,payload=0.5".parse().unwrap();
        assert_eq!((c.mass_scale, c.friction_scale, c.payload), (1.3, 2.0, 0.5));
        assert_eq!(c.to_string(), "mass=1.3,friction=2,payload=0.5");
        assert_eq!(
            "friction=off"
                .parse::<RobotChange>()
                .unwrap()
                .friction_scale,
            0.0
        );
        assert!("none".parse::<RobotChange>().unwrap().is_none());
        for (bad, word) in [
            ("mass=-1.3", "mass"),
            ("weight=2", "unknown key 'weight'"),
            ("payload=abc", "payload"),
            ("payload=-0.5", "payload"),
            ("friction=sticky", "friction"),
            ("mass=nan", "mass"),
            ("payload", "key=value"),
        ] {
            let e = bad.parse::<RobotChange>().unwrap_err().to_string();
            assert!(e.contains(word), "{bad}: {e}");
        }
    }

    /// The payload adds its mass to the robot; masses scale; gravity torques grow accordingly.
    #[test]
    fn the_change_goes_into_the_robot() {
        let truth = robots::planar3();
        let total =
            |m: &osrl_dynamics::Model| m.links().iter().map(|l| l.inertia.mass).sum::<f64>();
        let loaded = "payload=0.5"
            .parse::<RobotChange>()
            .unwrap()
            .apply(&truth)
            .unwrap();
        assert!((total(&loaded) - total(&truth) - 0.5).abs() < 1e-12);
        let heavy = "mass=1.3"
            .parse::<RobotChange>()
            .unwrap()
            .apply(&truth)
            .unwrap();
        assert!((total(&heavy) - 1.3 * total(&truth)).abs() < 1e-9);
        let q = truth.spec().q_rest.clone();
        let (mut d0, mut d1) = (truth.data(), heavy.data());
        let g0 = osrl_dynamics::gravity(&truth, &mut d0, &q).unwrap().clone();
        let g1 = osrl_dynamics::gravity(&heavy, &mut d1, &q).unwrap().clone();
        assert!((g1 - g0 * 1.3).amax() < 1e-9);
    }

    /// A payload the arm can hold passes; one beyond its torque limits is refused, naming the
    /// joint and its limit.
    #[test]
    fn a_payload_beyond_the_torque_limits_is_refused() {
        let truth = robots::planar3();
        let traj = TrajectoryConfig::default().build(&truth).unwrap();
        let q0 = truth.spec().q_rest.clone();
        let ok: RobotChange = "payload=0.5".parse().unwrap();
        ok.check_holdable(&truth, &traj, &q0, 16).unwrap();
        let heavy: RobotChange = "payload=500".parse().unwrap();
        let e = heavy
            .check_holdable(&truth, &traj, &q0, 16)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("cannot hold") && e.contains("torque limit"),
            "{e}"
        );
    }
}
