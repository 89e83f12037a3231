//! The heads of diagonal-metric RFs: each RF's first [`HEAD`] centre coordinates in single
//! precision and metric diagonals rounded down to bfloat16, a copy of its rows of `SubModel::centers` and `SubModel::ds`
//! kept in step with them (issue 31).
//!
//! The activation pass measures every RF, and with thousands of RFs of 21 dimensions (the
//! SARCOS data) their centres and metrics stream from beyond the core's caches. A head gives a
//! lower bound of the RF's distance `q` ([`Heads::bounds`]); where the bound already reaches
//! the pass's cutoff, the RF cannot matter and its rows are not read. The heads change no
//! value: every RF they do not exclude is measured from its rows as before (`docs/lwpr.md`,
//! "The fast path").
//!
//! The heads of [`LANES`] consecutive RFs lie transposed in one [`Block`] (dimension by
//! dimension, the RFs side by side), so that the bounds of a block are computed together,
//! one vector lane per RF, without a horizontal sum per RF.

use crate::params::Params;

/// How many leading dimensions a head holds.
pub(crate) const HEAD: usize = 24;
/// How many RFs' heads a [`Block`] holds side by side.
pub(crate) const LANES: usize = 8;

/// The heads of [`LANES`] consecutive RFs: per dimension `j`, their centre coordinates `c[j]`
/// rounded to single precision and metric diagonals `d[j]` rounded down to bfloat16 (18 cache
/// lines); zeros beyond the kernel dimension and in the lanes past the last RF.
#[derive(Clone, Debug, Default, PartialEq)]
#[repr(C, align(64))]
pub(crate) struct Block {
    /// The centres' first coordinates, one lane per RF.
    c: [[f32; LANES]; HEAD],
    /// The metric diagonals' first entries, one lane per RF, as the upper halves of their
    /// single-precision values (rounded down to 8 significant bits: bfloat16).
    d: [[u16; LANES]; HEAD],
}

/// Every RF's head, in blocks of [`LANES`]; a pure function of the RFs' rows (the same
/// whether built RF by RF or at once).
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Heads {
    blocks: Vec<Block>,
    len: usize,
    /// Per dimension, the largest `|c_j|` in single precision over the heads: the scale of
    /// the distances' slack ([`Probe`]).
    c_max: [f32; HEAD],
}

/// An input's first [`HEAD`] coordinates rounded as a head's, with the slack of each
/// dimension's distance: `e_j = 2^-20·(|x_j| + max |c_j|) + 2^-120`.
#[derive(Clone, Debug)]
pub(crate) struct Probe {
    x: [f32; HEAD],
    e: [f32; HEAD],
    /// The dimensions the heads hold: `min(nk, HEAD)`.
    n: usize,
}

impl Heads {
    /// The number of heads (RFs).
    pub fn len(&self) -> usize {
        self.len
    }

    /// Removes every head.
    pub fn clear(&mut self) {
        *self = Heads::default();
    }

    /// Appends the head of an RF whose centre row is `c` and metric diagonal row `d`.
    pub fn push(&mut self, c: &[f64], d: &[f64]) {
        if self.len.is_multiple_of(LANES) {
            self.blocks.push(Block::default());
        }
        self.len += 1;
        self.set(self.len - 1, c, d);
    }

    /// Rewrites RF `i`'s head from its rows (after a metric step; the centre does not move).
    /// A metric entry is held below its value: rounded to single precision, beyond its range
    /// as its largest number, below `2^-100` as 0, and rounded down to 8 significant bits.
    pub fn set(&mut self, i: usize, c: &[f64], d: &[f64]) {
        let (b, l) = (i / LANES, i % LANES);
        let blk = &mut self.blocks[b];
        for j in 0..HEAD.min(c.len()) {
            let dj = if d[j] < D_TINY {
                0
            } else {
                ((d[j] as f32).min(f32::MAX).to_bits() >> 16) as u16
            };
            (blk.c[j][l], blk.d[j][l]) = (c[j] as f32, dj);
            self.c_max[j] = self.c_max[j].max((c[j] as f32).abs());
        }
    }

    /// Removes RF `i`'s head, moving the last one into its place (as the rows).
    pub fn swap_remove(&mut self, i: usize) {
        let last = self.len - 1;
        let (bl, ll) = (last / LANES, last % LANES);
        for j in 0..HEAD {
            let (c, d) = (self.blocks[bl].c[j][ll], self.blocks[bl].d[j][ll]);
            let blk = &mut self.blocks[i / LANES];
            (blk.c[j][i % LANES], blk.d[j][i % LANES]) = (c, d);
            let blk = &mut self.blocks[bl];
            (blk.c[j][ll], blk.d[j][ll]) = (0.0, 0);
        }
        self.len = last;
        if ll == 0 {
            self.blocks.pop();
        }
        // The largest centre coordinates of the heads that remain.
        self.c_max = [0.0; HEAD];
        for i in 0..self.len {
            let blk = &self.blocks[i / LANES];
            for j in 0..HEAD {
                self.c_max[j] = self.c_max[j].max(blk.c[j][i % LANES].abs());
            }
        }
    }

    /// The number of blocks.
    pub fn blocks(&self) -> usize {
        self.blocks.len()
    }

    /// The input `x` (kernel coordinates) rounded as the heads, with each dimension's slack.
    pub fn probe(&self, x: &[f64]) -> Probe {
        let mut pr = Probe {
            x: [0.0; HEAD],
            e: [0.0; HEAD],
            n: HEAD.min(x.len()),
        };
        for j in 0..pr.n {
            let xj = x[j] as f32;
            pr.x[j] = xj;
            pr.e[j] = SLACK * (xj.abs() + self.c_max[j]) + SLACK_ABS;
        }
        pr
    }

    /// Lower bounds of `q = Σ_j d_j (x_j − c_j)²` over all dimensions of the RFs of block
    /// `b`, at the input of probe `pr`, one per lane (0 in the lanes past the last RF).
    ///
    /// Each term's distance `|x_j − c_j|` is reduced by the probe's slack `e_j`, at least
    /// `2^-20·(|x_j| + |c_j|) + 2^-120`: more than the error of rounding `x_j`, `c_j` and their
    /// difference to single precision (relative `2^-22` of it at most, absolute `2^-148` among
    /// subnormal numbers). A reduced distance that is NaN (an input or a centre beyond single
    /// precision's range, or `|x_j| + max |c_j|` beyond it) or negative counts as 0, and none is
    /// infinite (`|x_j − c_j| ≤ |x_j| + max |c_j|`, rounded alike). The metric entries are
    /// normal numbers at most `2^-24` above their value ([`Heads::set`]). So the sum of at most
    /// 24 non-negative terms, whose multiplications and additions round by a factor within
    /// `1 ± 2^-19` and by `2^-143` at most among subnormal numbers, capped at single
    /// precision's largest number, scaled by `1 − 2^-10` and lowered by `2^-130`, is below the
    /// exact sum of the head's terms, and with them below `q` (every term is non-negative),
    /// also as the update computes `q` in double precision (relative error below `2^-45` for
    /// up to 1,000 terms).
    #[inline(always)]
    pub fn bounds(&self, avx: bool, b: usize, pr: &Probe) -> [f64; LANES] {
        let blk = &self.blocks[b];
        let s = sums(avx, blk, pr);
        let mut lb = [0.0; LANES];
        for l in 0..LANES {
            let v = f64::from(s[l].min(f32::MAX)) * (1.0 - 1.0 / 1024.0) - SUM_ABS;
            lb[l] = v.max(0.0);
        }
        lb
    }

    /// RF `i`'s lower bound of `q` (see [`Heads::bounds`]; the portable sums).
    #[cfg(test)]
    pub fn bound(&self, i: usize, pr: &Probe) -> f64 {
        self.bounds(false, i / LANES, pr)[i % LANES]
    }

    /// A walk over the RFs in index order that tells which ones the heads put beyond a
    /// bound, where the model keeps heads ([`in_use`]); else `None` (every RF is measured).
    /// `avx` may be set only where the CPU has AVX2, checked at run time (`fast::has_avx2`).
    #[inline(always)]
    pub fn walk(&self, avx: bool, p: &Params, x: &[f64]) -> Option<Walk<'_>> {
        in_use(p).then(|| Walk {
            avx,
            heads: self,
            probe: self.probe(x),
            lb: [0.0; LANES],
        })
    }
}

/// The heads' bounds RF by RF, a block at a time ([`Heads::walk`]).
pub(crate) struct Walk<'a> {
    avx: bool,
    heads: &'a Heads,
    probe: Probe,
    lb: [f64; LANES],
}

impl Walk<'_> {
    /// Whether RF `i`'s head puts it at `q ≥ qb`. Called for every RF in index order, from 0.
    #[inline(always)]
    pub fn beyond(&mut self, i: usize, qb: f64) -> bool {
        if i.is_multiple_of(LANES) {
            self.lb = self.heads.bounds(self.avx, i / LANES, &self.probe);
        }
        self.lb[i % LANES] >= qb
    }
}

/// Per lane, the sum of the block's terms (see [`Heads::bounds`]): in one AVX2 register where
/// `avx` is set (the same values, `fast/head_avx.rs`).
#[inline(always)]
fn sums(avx: bool, blk: &Block, pr: &Probe) -> [f32; LANES] {
    #[cfg(target_arch = "x86_64")]
    if avx {
        // SAFETY: `avx` is set only after the run-time check of the CPU; `pr.n ≤ HEAD`.
        return unsafe { crate::fast::head_avx::sums(&blk.c, &blk.d, &pr.x, &pr.e, pr.n) };
    }
    let _ = avx;
    let mut s = [0.0f32; LANES];
    for j in 0..pr.n {
        let (x, e, c, d) = (pr.x[j], pr.e[j], &blk.c[j], &blk.d[j]);
        for l in 0..LANES {
            let t = (x - c[l]).abs() - e;
            let t = if t > 0.0 { t } else { 0.0 };
            s[l] += f32::from_bits(u32::from(d[l]) << 16) * t * t;
        }
    }
    s
}

/// The relative reduction of a head's distances (`2^-20`).
const SLACK: f32 = 1.0 / (1u32 << 20) as f32;
/// The absolute reduction of a head's distances (`2^-120`, a normal number in single
/// precision, so that the arithmetic stays off the CPU's slow subnormal path).
const SLACK_ABS: f32 = 1.0 / (1u64 << 20) as f32 / (1u128 << 100) as f32;
/// The absolute reduction of the sum (`2^-130`).
const SUM_ABS: f64 = 1.0 / (1u128 << 100) as f64 / (1u64 << 30) as f64;
/// Metric entries below this (`2^-100`) are held as 0 (see [`Heads::set`]).
const D_TINY: f64 = 1.0 / (1u128 << 100) as f64;

/// Whether a model keeps heads: a diagonal metric over more than 8 kernel dimensions.
#[inline(always)]
pub(crate) fn in_use(p: &Params) -> bool {
    p.cfg.diag_only && p.nk() > 8
}
