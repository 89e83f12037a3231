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
