//! Samples held back from `Σ w φφᵀ` and `Σ w φ uᵀ` and folded in a block of rows at a time
//! ([`Stats::push`], [`Stats::flush`]).
//!
//! [`Stats::add`] loads and stores every entry of the lower triangle of `G` once per sample;
//! with a few dozen receptive fields their statistics do not fit the L1 cache, and the learner
//! spent most of its time there. Holding up to [`HELD_MAX`] samples and folding them in one
//! block of [`LANES`] rows at a time keeps each block in registers through all held samples:
//! one load and one store per entry per flush instead of per sample. Each entry receives the
//! same operations in the same order as `scale` and `add` one sample at a time — the same bits.

use crate::stats::Stats;

/// Samples that [`Stats::push`] holds before it folds them in by itself.
pub(crate) const HELD_MAX: usize = 32;

/// Features from which [`Stats::push`] holds samples; below, it adds them at once (the
/// blocks' overhead outweighs the saving): 24 with the AVX-512 kernels (planar3's 9 and 19
/// features ran 5 % slower held), 16 with the AVX2 ones (planar3's 19 held: its training 6 %
/// faster on an AMD EPYC, `docs/decisions.md`, D51) and the portable ones.
#[inline]
pub(crate) fn held_min_features() -> usize {
    #[cfg(target_arch = "x86_64")]
    if crate::simd::avx512() {
        return 24;
    }
    16
}

/// Rows per block (two AVX2 registers of f64).
pub(crate) const LANES: usize = 8;

/// Blocks folded together: independent chains through the held samples, so that each add's
/// latency hides behind the others (8 blocks: 16 of the 32 AVX-512 registers).
pub(crate) const GROUP: usize = 8;

/// Zeros after each held `φ`, so that a block of rows can always be read whole.
pub(crate) const PAD: usize = LANES;

/// Samples not yet in `gram` and `cross`: per sample the factor the statistics were scaled by
/// just before it (1: none), `φ` (followed by [`PAD`] zeros), its weight `w` and `u`. The
/// kernels form `w φ` as they go (the same product, the same bits): holding it as well doubled
/// the held samples' bytes, which then no longer fit the L1 cache beside the statistics.
/// Preallocated.
#[derive(Debug, PartialEq)]
pub(crate) struct Held {
    pub scale: Vec<f64>,
    pub phi: Vec<f64>,
    pub w: Vec<f64>,
    pub u: Vec<f64>,
}

impl Held {
    pub fn new(p: usize, d: usize) -> Self {
        Self {
            scale: Vec::with_capacity(HELD_MAX),
            phi: Vec::with_capacity(HELD_MAX * (p + PAD)),
            w: Vec::with_capacity(HELD_MAX),
            u: Vec::with_capacity(HELD_MAX * d),
        }
    }

    /// Samples held.
    pub fn len(&self) -> usize {
        self.scale.len()
    }

    fn clear(&mut self) {
        self.scale.clear();
        self.phi.clear();
        self.w.clear();
        self.u.clear();
    }
}

impl Clone for Held {
    /// With the full capacity (a clone that learns does not allocate either).
    fn clone(&self) -> Self {
        let mut c = Self {
            scale: Vec::with_capacity(HELD_MAX),
            phi: Vec::with_capacity(self.phi.capacity()),
            w: Vec::with_capacity(HELD_MAX),
            u: Vec::with_capacity(self.u.capacity()),
        };
        c.scale.extend_from_slice(&self.scale);
        c.phi.extend_from_slice(&self.phi);
        c.w.extend_from_slice(&self.w);
        c.u.extend_from_slice(&self.u);
        c
    }
}

/// [`GROUP`] blocks of one matrix: per block the offset of its first entry in the matrix, its
/// column (of `G`: that `φ` index; of `C`: that `u` index), its first row, and its rows
/// (1..=[`LANES`]). Only the first `n` are stored back; the others repeat block 0.
pub(crate) struct Group {
    pub off: [usize; GROUP],
    pub col: [usize; GROUP],
    pub row: [usize; GROUP],
    pub len: [usize; GROUP],
    pub n: usize,
}

impl Group {
    fn new() -> Self {
        Self {
            off: [0; GROUP],
            col: [0; GROUP],
            row: [0; GROUP],
            len: [0; GROUP],
            n: 0,
        }
    }

    /// Adds a block; `true` when the group is full.
    fn push(&mut self, off: usize, col: usize, row: usize, len: usize) -> bool {
        let n = self.n;
        (self.off[n], self.col[n], self.row[n], self.len[n]) = (off, col, row, len);
        self.n += 1;
        self.n == GROUP
    }

    /// Fills the unused slots with block 0.
    fn fill(&mut self) {
        for g in self.n..GROUP {
            (self.off[g], self.col[g], self.row[g], self.len[g]) =
                (self.off[0], self.col[0], self.row[0], self.len[0]);
        }
    }
}

/// A kernel folding the held samples into one group of blocks of `G` or `C` (the matrix as a
/// column-major slice; `p` features, `d` outputs).
pub(crate) type Kernel = fn(&Group, &Held, usize, usize, &mut [f64]);

impl Stats {
    /// [`Stats::scale`] by `f` (unless `None`) followed by [`Stats::add`]: the scalar sums at
    /// once, `gram` and `cross` at the next [`Stats::flush`] (run here once [`HELD_MAX`]
    /// samples are held). Lengths are the caller's responsibility. Does not allocate.
    pub fn push(&mut self, f: Option<f64>, w: f64, phi: &[f64], u: &[f64], r: f64) {
        if self.gram.nrows() < held_min_features() {
            if let Some(f) = f {
                self.scale(f);
            }
            self.add(w, phi, u, r);
            return;
        }
        if self.held.len() >= HELD_MAX {
            self.flush();
        }
        if let Some(f) = f {
            self.yy *= f;
            self.sw *= f;
            self.swr *= f;
            self.sw2 *= f * f;
        }
        let h = &mut self.held;
        h.scale.push(f.unwrap_or(1.0));
        h.phi.extend_from_slice(phi);
        h.phi.extend_from_slice(&[0.0; PAD]);
        h.w.push(w);
        h.u.extend_from_slice(u);
        self.yy += w * u.iter().map(|x| x * x).sum::<f64>();
        self.sw += w;
        self.swr += w * r;
        self.sw2 += w * w;
    }

    /// Folds the held samples into `gram` and `cross` (see the module). Runs the AVX2 kernels
    /// where the CPU has them (the same operations: the same bits).
    pub fn flush(&mut self) {
        #[cfg(target_arch = "x86_64")]
        if crate::simd::avx2() {
            let (gram, cross) = crate::held_x86::kernels();
            self.flush_with(gram, cross);
            return;
        }
        self.flush_body();
    }

    /// [`Stats::flush`] with the portable kernels.
    pub(crate) fn flush_body(&mut self) {
        self.flush_with(gram_group, cross_group);
    }

    /// Folds the held samples in with the given kernels.
    pub(crate) fn flush_with(&mut self, gram: Kernel, cross: Kernel) {
        let (p, d, h) = (self.gram.nrows(), self.cross.ncols(), &self.held);
        if h.len() == 0 {
            return;
        }
        let n = h.len();
        assert!(h.phi.len() == n * (p + PAD) && h.w.len() == n && h.u.len() == n * d);
        let mut group = Group::new();
        // The lower triangle of G, column by column, in blocks of rows.
        let m = self.gram.as_mut_slice();
        for j in 0..p {
            for i0 in (j..p).step_by(LANES) {
                if group.push(j * p + i0, j, i0, (p - i0).min(LANES)) {
                    gram(&group, h, p, d, m);
                    group.n = 0;
                }
            }
        }
        if group.n > 0 {
            group.fill();
            gram(&group, h, p, d, m);
            group.n = 0;
        }
        let m = self.cross.as_mut_slice();
        for k in 0..d {
            for i0 in (0..p).step_by(LANES) {
                if group.push(k * p + i0, k, i0, (p - i0).min(LANES)) {
                    cross(&group, h, p, d, m);
                    group.n = 0;
                }
            }
        }
        if group.n > 0 {
            group.fill();
            cross(&group, h, p, d, m);
        }
        self.held.clear();
    }
}

/// The portable kernel for `G`: entry `(i, j)` gains `(w φ_j) φ_i` per held sample, after that
/// sample's rescaling (as in [`Stats::add_body`]).
fn gram_group(t: &Group, h: &Held, p: usize, _d: usize, m: &mut [f64]) {
    for g in 0..t.n {
        let (off, col, row, len) = (t.off[g], t.col[g], t.row[g], t.len[g]);
        let acc = &mut m[off..off + len];
        let samples = h.phi.chunks_exact(p + PAD).zip(&h.w);
        for ((phi, &w), &f) in samples.zip(&h.scale) {
            let wj = w * phi[col];
            for (a, x) in acc.iter_mut().zip(&phi[row..row + len]) {
                *a = *a * f + wj * x;
            }
        }
    }
}

/// The portable kernel for `C`: entry `(i, k)` gains `(w φ_i) u_k` per held sample, after that
/// sample's rescaling (as in [`Stats::add_body`]).
fn cross_group(t: &Group, h: &Held, p: usize, d: usize, m: &mut [f64]) {
    for g in 0..t.n {
        let (off, col, row, len) = (t.off[g], t.col[g], t.row[g], t.len[g]);
        let acc = &mut m[off..off + len];
        let samples = h
            .phi
            .chunks_exact(p + PAD)
            .zip(&h.w)
            .zip(h.u.chunks_exact(d));
        for (((phi, &w), u), &f) in samples.zip(&h.scale) {
            for (a, x) in acc.iter_mut().zip(&phi[row..row + len]) {
                let wx = w * x;
                *a = *a * f + wx * u[col];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::HELD_MAX;
    use crate::stats::Stats;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Asserts the same bits everywhere (naming the first entry that differs).
    fn same(a: &Stats, b: &Stats, what: &str, p: usize) {
        let first = bits(a).iter().zip(bits(b)).position(|(x, y)| *x != y);
        assert_eq!(
            first, None,
            "{what} kernels, p = {p}: first differing entry"
        );
    }

    /// Folds in with the AVX2 kernels where the CPU has them, else with the portable ones.
    fn flush_avx2(s: &mut Stats) {
        #[cfg(target_arch = "x86_64")]
        if crate::simd::avx2() {
            let (gram, cross) = crate::held_x86::kernels_avx2();
            s.flush_with(gram, cross);
        }
        s.flush_body();
    }

    /// Every number of the statistics, as bits (so that `-0.0` differs from `0.0`).
    fn bits(s: &Stats) -> Vec<u64> {
        let sums = [s.yy, s.sw, s.swr, s.sw2];
        let all = s.gram.iter().chain(s.cross.iter()).chain(&sums);
        all.map(|x| x.to_bits()).collect()
    }

    /// Held samples folded in by `flush` (the dispatched kernels, the AVX2 kernels where the
    /// CPU has them, and the portable ones) give the bits of `scale` and `add_body` one sample
    /// at a time: at the learner's sizes (71 and 19 features; below `held_min_features()`
    /// it adds at once, 16 or 24) and others, in random runs of held samples ended by the holding limit,
    /// an `add`, a `scale` or a `flush`, with random rescalings (some by 0 and 1), and through
    /// the serialised form.
    #[test]
    fn held_samples_give_the_bits_of_adding_one_at_a_time() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        for (p, d) in [
            (71, 3),
            (19, 3),
            (16, 2),
            (24, 2),
            (25, 7),
            (33, 1),
            (40, 3),
            (48, 2),
        ] {
            let mut eager = Stats::new(p, d);
            let (mut held, mut base) = (Stats::new(p, d), Stats::new(p, d));
            let mut avx2 = Stats::new(p, d);
            for n in 0..(6 * HELD_MAX + 7) {
                let phi: Vec<f64> = (0..p).map(|_| rng.random_range(-2.0..2.0)).collect();
                let u: Vec<f64> = (0..d).map(|_| rng.random_range(-5.0..5.0)).collect();
                let (w, r) = (rng.random_range(0.0..1.0), rng.random_range(0.0..3.0));
                let f = match rng.random_range(0..20) {
                    0..=3 => Some(rng.random_range(0.0..1.0)),
                    4 => Some(1.0),
                    5 if n % 3 == 0 => Some(0.0),
                    _ => None,
                };
                match rng.random_range(0..40) {
                    // An eager `add` between held samples (it flushes first).
                    0 => {
                        eager.add_body(w, &phi, &u, r);
                        held.add(w, &phi, &u, r);
                        base.flush_body();
                        base.add_body(w, &phi, &u, r);
                        flush_avx2(&mut avx2);
                        avx2.add_body(w, &phi, &u, r);
                        continue;
                    }
                    1 => {
                        held.flush();
                        base.flush_body();
                        flush_avx2(&mut avx2);
                    }
                    _ => {}
                }
                if let Some(f) = f {
                    eager.scale(f);
                }
                eager.add_body(w, &phi, &u, r);
                held.push(f, w, &phi, &u, r);
                base.push(f, w, &phi, &u, r);
                avx2.push(f, w, &phi, &u, r);
                assert_eq!((eager.sw, eager.sw2), (held.sw, held.sw2));
            }
            let json = serde_json::to_string(&held).unwrap();
            held.flush();
            base.flush_body();
            flush_avx2(&mut avx2);
            same(&eager, &held, "dispatched", p);
            same(&eager, &base, "portable", p);
            same(&eager, &avx2, "AVX2", p);
            let back: Stats = serde_json::from_str(&json).unwrap();
            same(&eager, &back, "serialised", p);
            assert_eq!(json, serde_json::to_string(&eager).unwrap());
        }
    }
}
