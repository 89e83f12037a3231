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
