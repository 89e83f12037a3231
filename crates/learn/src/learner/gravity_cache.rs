//! The last `ĝ(q)` of `nominal::gravity_into` and what it depended on: the relabelling of a
//! transition and the next command ask for `ĝ` at the same measured `q`, with no gravity update
//! between them unless a still sample was learned (`docs/decisions.md`, D38). A hit returns the
//! stored bits, so the cache changes no result.

/// What a `ĝ(q)` depends on besides `q`: the `frozen` switch, the blend's settings and the update
/// counts of the dynamic and the static model (`u64::MAX` for no static model).
pub(crate) type GravityKey = [u64; 5];

/// One stored `ĝ(q)` (empty until the first; buffers sized at the first store).
#[derive(Clone, Debug, Default)]
pub(crate) struct GravityCache {
    key: Option<GravityKey>,
    q: Vec<f64>,
    g: Vec<f64>,
    known: bool,
}

impl GravityCache {
    /// Buffers for `n` joints (so storing does not allocate).
    pub fn with_joints(n: usize) -> Self {
        Self {
            key: None,
            q: vec![0.0; n],
            g: vec![0.0; n],
            known: false,
        }
    }

    /// The stored `ĝ` into `g` and whether it was known, if `key` and `q` (bit for bit) match.
    pub fn get(&self, key: &GravityKey, q: &[f64], g: &mut [f64]) -> Option<bool> {
        let same_q = self.q.len() == q.len()
            && self
                .q
                .iter()
                .zip(q)
                .all(|(a, b)| a.to_bits() == b.to_bits());
        if self.key.as_ref() != Some(key) || !same_q || self.g.len() != g.len() {
            return None;
        }
        g.copy_from_slice(&self.g);
        Some(self.known)
    }

    /// Stores `ĝ(q) = g` under `key`.
    pub fn put(&mut self, key: GravityKey, q: &[f64], g: &[f64], known: bool) {
        self.q.resize(q.len(), 0.0);
        self.g.resize(g.len(), 0.0);
        self.q.copy_from_slice(q);
        self.g.copy_from_slice(g);
        self.known = known;
        self.key = Some(key);
    }
}

#[cfg(test)]
mod tests {
    use super::GravityCache;

    /// A hit needs the same key and the same `q` bits; a hit returns what was stored.
    #[test]
    fn a_hit_needs_the_same_key_and_q() {
        let mut c = GravityCache::with_joints(2);
        let mut g = [0.0; 2];
        assert_eq!(c.get(&[0; 5], &[0.1, 0.2], &mut g), None);
        c.put([1, 0, 0, 7, 3], &[0.1, 0.2], &[4.0, -5.0], true);
        assert_eq!(c.get(&[1, 0, 0, 7, 3], &[0.1, 0.2], &mut g), Some(true));
        assert_eq!(g, [4.0, -5.0]);
        assert_eq!(c.get(&[1, 0, 0, 8, 3], &[0.1, 0.2], &mut g), None);
        assert_eq!(
            c.get(&[1, 0, 0, 7, 3], &[0.1, 0.2 + 1e-17], &mut g),
            Some(true)
        );
        assert_eq!(c.get(&[1, 0, 0, 7, 3], &[0.1, 0.2000000001], &mut g), None);
        assert_eq!(
            c.get(&[1, 0, 0, 7, 3], &[-0.0 + 0.1, 0.2], &mut g),
            Some(true)
        );
    }
}
