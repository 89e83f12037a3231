//! The grammar shared by `--model-error` ([`crate::ModelError`]) and `--change`
//! ([`crate::RobotChange`]): `none`, or comma-separated `key=value` pairs with the keys `mass`,
//! `com`, `payload` (numbers), `friction` (a word or a number; each caller reads it) and `seed`
//! (an integer).

/// The values a spec names (`None`: not named, the caller's default).
#[derive(Debug, Default)]
pub(crate) struct SpecValues<'a> {
    pub mass: Option<f64>,
    pub com: Option<f64>,
    pub payload: Option<f64>,
    pub friction: Option<&'a str>,
    pub seed: Option<u64>,
}

/// Parses `spec`; the error says which part is wrong and why.
pub(crate) fn parse(spec: &str) -> Result<SpecValues<'_>, String> {
    let mut out = SpecValues::default();
    let spec = spec.trim();
    if spec.is_empty() || spec == "none" {
        return Ok(out);
    }
    for part in spec.split(',') {
        let (k, v) = part
            .split_once('=')
            .ok_or_else(|| format!("'{part}' is not key=value"))?;
        let (k, v) = (k.trim(), v.trim());
        let num = || {
            v.parse::<f64>()
                .map_err(|_| format!("{k}: '{v}' is not a number"))
        };
        match k {
            "mass" => out.mass = Some(num()?),
            "com" => out.com = Some(num()?),
            "payload" => out.payload = Some(num()?),
            "friction" => out.friction = Some(v),
            "seed" => {
                out.seed = Some(
                    v.parse()
                        .map_err(|_| format!("seed: '{v}' is not an integer"))?,
                )
            }
            _ => {
                return Err(format!(
                    "unknown key '{k}' (keys: mass, com, friction, payload, seed)"
                ))
            }
        }
    }
    Ok(out)
}

/// The link changes of the grammar, in place: every link with mass gets its mass and inertia
/// scaled by `mass_scale` and its centre of mass moved by `com_shift` (m) in a random direction
/// (one draw per link from `seed`, links in order); every joint's viscous and Coulomb friction is
/// scaled by `friction_scale`.
pub(crate) fn perturb_links(
    spec: &mut osrl_dynamics::ModelSpec,
    seed: u64,
    mass_scale: f64,
    com_shift: f64,
    friction_scale: f64,
) {
    use rand::SeedableRng;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    for l in spec.links.iter_mut() {
        let dir = osrl_dynamics::robots::random_unit_vector(&mut rng);
        let i = l.inertia;
        if i.mass > 0.0 {
            let com = i.com() + dir * com_shift;
            l.inertia = osrl_dynamics::Inertia::from_com(
                i.mass * mass_scale,
                com,
                i.inertia_com() * mass_scale,
            );
        }
        l.friction = osrl_dynamics::Friction {
            viscous: l.friction.viscous * friction_scale,
            coulomb: l.friction.coulomb * friction_scale,
            ..l.friction
        };
    }
}

/// A point mass of `kg` at the end-effector, added to the last link's inertia.
pub(crate) fn add_payload(spec: &mut osrl_dynamics::ModelSpec, kg: f64) {
    let last = spec.links.last_mut().expect("a model has links");
    let point = osrl_dynamics::Inertia::from_com(kg, spec.ee_offset, nalgebra::Matrix3::zeros());
    last.inertia = last.inertia.add(&point);
}

/// `x` as the grammar writes it: plain decimals for ordinary sizes (`1.3`, `0.02`), exponents
/// beyond them (`1e300`), so that a message about an absurd value stays one short line.
pub(crate) struct Num(pub f64);

impl std::fmt::Display for Num {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let a = self.0.abs();
        if a != 0.0 && a.is_finite() && !(1e-6..1e16).contains(&a) {
            write!(f, "{:e}", self.0)
        } else {
            write!(f, "{}", self.0)
        }
    }
}

/// Shorthand for [`Num`].
pub(crate) fn num(x: f64) -> Num {
    Num(x)
}

/// Range of the grammar's `mass` factor: a model a thousand times too light or too heavy is no
/// longer a model error, and larger factors only overflow the dynamics.
pub const MASS_SCALE_RANGE: (f64, f64) = (1e-3, 1e3);
/// Largest `com` shift (m): ten metres, several times the reach of any arm this crate loads.
pub const MAX_COM_SHIFT: f64 = 10.0;
/// Largest `payload` (kg): ten tonnes, beyond the payload of any serial arm.
pub const MAX_PAYLOAD: f64 = 1e4;
/// Largest `friction` factor.
pub const MAX_FRICTION_SCALE: f64 = 1e3;

/// Checks the grammar's numbers against their ranges ([`MASS_SCALE_RANGE`], [`MAX_COM_SHIFT`],
/// [`MAX_PAYLOAD`], [`MAX_FRICTION_SCALE`]; all finite, `com`, `payload` and `friction` ≥ 0).
///
/// # Errors
/// The first key out of range, its value and its range, as `"key = value: must be …"`.
pub(crate) fn check_ranges(mass: f64, com: f64, payload: f64, friction: f64) -> Result<(), String> {
    let (lo, hi) = MASS_SCALE_RANGE;
    for (key, v, lo, hi) in [
        ("mass", mass, lo, hi),
        ("com", com, 0.0, MAX_COM_SHIFT),
        ("payload", payload, 0.0, MAX_PAYLOAD),
        ("friction", friction, 0.0, MAX_FRICTION_SCALE),
    ] {
        if !(lo..=hi).contains(&v) {
            return Err(format!(
                "{key} = {}: must lie in [{}, {}]",
                num(v),
                num(lo),
                num(hi)
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_name_the_key_out_of_range() {
        assert_eq!(check_ranges(1.0, 0.0, 0.0, 1.0), Ok(()));
        assert_eq!(check_ranges(1e3, 10.0, 1e4, 1e3), Ok(()));
        for (args, key) in [
            ((1e300, 0.0, 0.0, 1.0), "mass = 1e300"),
            ((0.0, 0.0, 0.0, 1.0), "mass = 0: must lie in [0.001, 1000]"),
            ((f64::NAN, 0.0, 0.0, 1.0), "mass = NaN"),
            ((1.0, 1e300, 0.0, 1.0), "com = 1e300"),
            ((1.0, -0.1, 0.0, 1.0), "com = -0.1"),
            ((1.0, 0.0, f64::INFINITY, 1.0), "payload = inf"),
            ((1.0, 0.0, 0.0, 1e4), "friction = 10000"),
            (
                (1.0, 0.0, 1e17, 1.0),
                "payload = 1e17: must lie in [0, 10000]",
            ),
        ] {
            let e = check_ranges(args.0, args.1, args.2, args.3).unwrap_err();
            assert!(e.starts_with(key), "{e}");
        }
    }
}
