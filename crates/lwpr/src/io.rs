//! Saving and loading models.
//!
//! File layout: the magic bytes `OSRLLWPR`, the format version (u32, little-endian), the
//! payload length (u64 LE), the payload (the model in `postcard` encoding, so every `f64` is
//! stored bit-exactly), and an FNV-1a 64-bit checksum of the payload (u64 LE). Loading checks all
//! of these and the model's internal consistency, so a truncated or corrupted file is an error.

use crate::model::Lwpr;
use crate::params::Params;
use crate::rf::SubModel;
use crate::scratch::Scratch;
use crate::LwprError;
use std::path::Path;

/// File magic.
pub const MAGIC: &[u8; 8] = b"OSRLLWPR";
/// Current format version.
pub const FORMAT_VERSION: u32 = 1;

fn fnv1a(data: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in data {
        h ^= b as u64;
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

fn fmt(msg: impl Into<String>) -> LwprError {
    LwprError::Format(msg.into())
}

/// Largest model file [`Lwpr::load`] reads (1 GiB).
pub const MAX_MODEL_BYTES: u64 = 1 << 30;

impl Lwpr {
    /// The model as bytes (see the module docs for the layout).
    pub fn to_bytes(&self) -> Vec<u8> {
        let payload = postcard::to_allocvec(self).expect("serialising to memory cannot fail");
        let mut out = Vec::with_capacity(payload.len() + 28);
        out.extend_from_slice(MAGIC);
        out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
        out.extend_from_slice(&(payload.len() as u64).to_le_bytes());
        out.extend_from_slice(&payload);
        out.extend_from_slice(&fnv1a(&payload).to_le_bytes());
        out
    }

    /// A model from [`Lwpr::to_bytes`] output. Fails on a wrong magic or version, a truncated
    /// or corrupted payload, or a model whose parts are inconsistent.
    pub fn from_bytes(bytes: &[u8]) -> Result<Lwpr, LwprError> {
        if bytes.len() < 20 || &bytes[..8] != MAGIC {
            return Err(fmt("not an osrl LWPR model (bad magic)"));
        }
        let version = u32::from_le_bytes(bytes[8..12].try_into().expect("4 bytes"));
        if version != FORMAT_VERSION {
            return Err(fmt(format!(
                "format version {version}, this build reads {FORMAT_VERSION}"
            )));
        }
        let len = u64::from_le_bytes(bytes[12..20].try_into().expect("8 bytes"));
        if bytes.len() as u64 != 20 + len.saturating_add(8) {
            return Err(fmt(format!(
                "file is {} bytes, header says {}",
                bytes.len(),
                20u64.saturating_add(len).saturating_add(8)
            )));
        }
        let payload = &bytes[20..20 + len as usize];
        let sum = u64::from_le_bytes(bytes[20 + len as usize..].try_into().expect("8 bytes"));
        if sum != fnv1a(payload) {
            return Err(fmt("checksum mismatch (corrupted file)"));
        }
        let mut m: Lwpr = postcard::from_bytes(payload).map_err(|e| fmt(e.to_string()))?;
        m.check_consistent().map_err(fmt)?;
        for s in &mut m.subs {
            s.rebuild_heads(&m.p);
        }
        m.ws = Scratch::new(&m.p, m.subs.iter().map(|s| s.rfs.len()).max().unwrap_or(0));
        m.events = Vec::with_capacity(64);
        Ok(m)
    }

    /// Writes the model to `path` by [`osrl_files::write_atomic`] (only over a regular file or a
    /// missing path): a failure leaves any file at `path` as it
    /// was, and no temporary file behind.
    pub fn save(&self, path: impl AsRef<Path>) -> Result<(), LwprError> {
        Ok(osrl_files::write_atomic(path.as_ref(), &self.to_bytes())?)
    }

    /// Reads a model saved by [`Lwpr::save`]. Any model in memory is unaffected by a failure.
    pub fn load(path: impl AsRef<Path>) -> Result<Lwpr, LwprError> {
        let bytes = osrl_files::read_limited_if_starts(path.as_ref(), MAX_MODEL_BYTES, &[MAGIC])?;
        Lwpr::from_bytes(&bytes)
    }

    /// Checks sizes, finiteness and ids after decoding.
    fn check_consistent(&self) -> Result<(), String> {
        let p = &self.p;
        let again = Params::from_config(&p.cfg, p.n_in, p.n_out).map_err(|e| e.to_string())?;
        if &again != p {
            return Err("stored parameters do not match their config".into());
        }
        if self.subs.len() != p.n_sub() {
            return Err("wrong number of sub-models".into());
        }
        let mut ids: Vec<u64> = Vec::new();
        for s in &self.subs {
            check_sub(p, s)?;
            ids.extend(s.rfs.iter().map(|r| r.id));
        }
        ids.sort_unstable();
        if ids.windows(2).any(|w| w[0] == w[1]) || ids.last().is_some_and(|&l| l >= self.next_id) {
            return Err("receptive field ids are not unique".into());
        }
        Ok(())
    }
}

fn check_sub(p: &Params, s: &SubModel) -> Result<(), String> {
    let (nk, nr, ml, ny) = (p.nk(), p.nr(), p.mlen(), p.n_local_out());
    let n = s.rfs.len();
    let finite = |v: &[f64]| v.iter().all(|a| a.is_finite());
    if s.centers.len() != n * nk || s.ms.len() != n * ml || s.ds.len() != n * ml {
        return Err("receptive field arrays have inconsistent sizes".into());
    }
    if !(finite(&s.centers) && finite(&s.ms) && finite(&s.ds)) {
        return Err("non-finite centre or metric".into());
    }
    for rf in &s.rfs {
        let sizes = [rf.alpha.len(), rf.b.len(), rf.hm.len()];
        if sizes.iter().any(|&l| l != ml) || rf.mean_x.len() != nr || rf.var_x.len() != nr {
            return Err("receptive field has inconsistent sizes".into());
        }
        if rf.outs.len() != ny {
            return Err("receptive field has the wrong number of outputs".into());
        }
        for o in &rf.outs {
            let r = o.n_reg;
            if r == 0 || r > nr || o.slope.len() != nr {
                return Err("PLS model has a bad number of directions".into());
            }
            let mats = [o.u.len(), o.p.len(), o.sxy.len(), o.ssx.len()];
            let vecs = [
                o.beta.len(),
                o.ss_s2.len(),
                o.ss_yres.len(),
                o.sum_w.len(),
                o.n_data.len(),
                o.lambda.len(),
                o.sum_e_cv2.len(),
                o.h_tr.len(),
                o.r_tr.len(),
            ];
            if mats.iter().any(|&l| l != r * nr) || vecs.iter().any(|&l| l != r) {
                return Err("PLS model has inconsistent sizes".into());
            }
            if !(o.predictors_finite() && finite(&o.slope)) {
                return Err("PLS model has non-finite values".into());
            }
        }
    }
    Ok(())
}
