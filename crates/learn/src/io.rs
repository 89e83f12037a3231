//! Serialisation helpers (LWPR models as their own versioned byte format).

/// Serde adapter storing an [`lwpr::Lwpr`] as the bytes of [`lwpr::Lwpr::to_bytes`].
pub mod lwpr_bytes {
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    pub fn serialize<S: Serializer>(m: &lwpr::Lwpr, s: S) -> Result<S::Ok, S::Error> {
        serde_bytes_vec(&m.to_bytes()).serialize(s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<lwpr::Lwpr, D::Error> {
        let bytes = Vec::<u8>::deserialize(d)?;
        lwpr::Lwpr::from_bytes(&bytes).map_err(serde::de::Error::custom)
    }

    fn serde_bytes_vec(b: &[u8]) -> Vec<u8> {
        b.to_vec()
    }
}

use crate::config::LearnerConfig;
use crate::error::{LearnError, Result};
use crate::learner::{Learner, LearnerStats, LoadCorrection, Models, State};
use osrl_dynamics::Measurement;
use serde::{Deserialize, Serialize};

/// First bytes of a saved learned controller.
pub const MAGIC: &[u8; 8] = b"OSRLLC\0\0";
/// Version of the saved format; files of another version are refused. 10: the cost metric `N`
/// estimated in the warm-up is saved with the models (before, a loaded learner used `N = I`).
/// 11: the static gravity model's samples per posture (`StaticGate::max_samples_per_posture`).
/// 12: the null-space correction's model (`gravity.null_correction`). 13: its global scale
/// (`gravity.null_scale`). 14: each regression's external weights' sums, whether its
/// statistics have forgotten, and `min_ess_share` (`rwr::OnlineRwr`).
pub const FORMAT_VERSION: u32 = 14;

/// Everything a learner is, as stored (the config as JSON text, so its untagged enums survive).
#[derive(Serialize, Deserialize)]
struct Saved {
    config_json: String,
    n: usize,
    m: usize,
    dt: f64,
    warm_up: Vec<Measurement>,
    models: Option<Models>,
    stats: LearnerStats,
    gravity_frozen: bool,
    /// The load correction (`learner/load.rs`).
    load: LoadCorrection,
}

/// FNV-1a over the payload: detects corruption that would still parse.
fn checksum(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| {
        (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)
    })
}

impl Learner {
    /// The whole learner (models, local controllers, counters, config) as bytes:
    /// `MAGIC`, format version, payload length, FNV-1a checksum, postcard payload.
    pub fn to_bytes(&self) -> Result<Vec<u8>> {
        let saved = Saved {
            config_json: serde_json::to_string(&self.cfg)
                .map_err(|e| LearnError::Load(e.to_string()))?,
            n: self.n,
            m: self.m,
            dt: self.dt,
            warm_up: match &self.state {
                State::WarmUp(w) => w.clone(),
                State::Ready(_) => Vec::new(),
            },
            models: self.state.models().cloned(),
            stats: self.stats,
            gravity_frozen: self.gravity_frozen,
            load: self.load.clone(),
        };
        let payload = postcard::to_allocvec(&saved).map_err(|e| LearnError::Load(e.to_string()))?;
        let mut out = Vec::with_capacity(payload.len() + 28);
        out.extend_from_slice(MAGIC);
        out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
        out.extend_from_slice(&(payload.len() as u64).to_le_bytes());
        out.extend_from_slice(&checksum(&payload).to_le_bytes());
        out.extend_from_slice(&payload);
        Ok(out)
    }

    /// A learner from [`Learner::to_bytes`]. Fails on a foreign, truncated, corrupted or
    /// other-version file; nothing else is touched.
    pub fn from_bytes(bytes: &[u8]) -> Result<Learner> {
        let bad = |m: String| LearnError::Load(m);
        if bytes.len() < 28 || &bytes[..8] != MAGIC {
            return Err(bad("not an osrl learned-controller file".into()));
        }
        let version = u32::from_le_bytes(bytes[8..12].try_into().expect("4 bytes"));
        if version != FORMAT_VERSION {
            let older = match version < FORMAT_VERSION {
                true => " (saved by an older build: train it again with `osrl train`)",
                false => "",
            };
            return Err(bad(format!(
                "format version {version}, this build reads {FORMAT_VERSION}{older}"
            )));
        }
        let len = u64::from_le_bytes(bytes[12..20].try_into().expect("8 bytes")) as usize;
        let sum = u64::from_le_bytes(bytes[20..28].try_into().expect("8 bytes"));
        let payload = &bytes[28..];
        if payload.len() != len {
            return Err(bad(format!(
                "truncated or padded: {} payload bytes, header says {len}",
                payload.len()
            )));
        }
        if checksum(payload) != sum {
            return Err(bad("checksum mismatch: the file is corrupted".into()));
        }
        let s: Saved =
            postcard::from_bytes(payload).map_err(|e| bad(format!("malformed payload: {e}")))?;
        let cfg: LearnerConfig =
            serde_json::from_str(&s.config_json).map_err(|e| bad(format!("config: {e}")))?;
        let mut learner = Learner::new(s.n, s.m, s.dt, cfg)?;
        learner.state = match s.models {
            Some(mut models) => {
                models.restore_buffers();
                models.check_loaded()?;
                State::Ready(Box::new(models))
            }
            None => State::WarmUp(s.warm_up),
        };
        learner.stats = s.stats;
        learner.gravity_frozen = s.gravity_frozen;
        learner.load = s.load;
        Ok(learner)
    }

    /// Writes [`Learner::to_bytes`] to `path` by [`osrl_files::write_atomic`] (only over a
    /// regular file or a missing path; a failure or crash leaves any old file whole and no
    /// temporary file).
    pub fn save(&self, path: &std::path::Path) -> Result<()> {
        let bytes = self.to_bytes()?;
        Ok(osrl_files::write_atomic(path, &bytes)?)
    }

    /// Reads a learner saved by [`Learner::save`].
    pub fn load(path: &std::path::Path) -> Result<Learner> {
        let bytes = osrl_files::read_limited(path, crate::saved::MAX_MODEL_BYTES)?;
        Learner::from_bytes(&bytes)
            .map_err(|e| LearnError::Load(format!("{}: {e}", path.display())))
    }
}

#[cfg(test)]
mod tests {
    use crate::learner::fixture;
    use crate::Learner;
    use lwpr::{Activation, RfId};

    /// The load correction is saved and read back.
    #[test]
    fn the_load_correction_round_trips() {
        let (mut learner, _, _) = fixture::ready(fixture::config(), 200, 50);
        let back = Learner::from_bytes(&learner.to_bytes().unwrap()).unwrap();
        assert!(back.load_correction().is_empty());
        let acts = [Activation {
            id: RfId(3),
            w: 1.0,
        }];
        learner
            .load
            .learn(&acts, &[0.0; 3], &[1.5, -0.5, 0.25], 1.0);
        assert_eq!(learner.load_correction().len(), 1);
        let back = Learner::from_bytes(&learner.to_bytes().unwrap()).unwrap();
        assert_eq!(back.load_correction(), learner.load_correction());
        assert_eq!(back.load_correction().max_abs(), 1.5);
    }
}
