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
