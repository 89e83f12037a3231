//! The heads of diagonal-metric RFs: each RF's first [`HEAD`] centre coordinates in single
//! precision and metric diagonals rounded down to bfloat16, a copy of its rows of
//! `SubModel::centers` and `SubModel::ds` kept in step with them (issue 31); the bound they
//! give: `bound.rs`.
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

mod bound;

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
    /// the distances' slack ([`bound::Probe`]).
    c_max: [f32; HEAD],
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
        let i = self.len;
        self.len += 1;
        let blk = &mut self.blocks[i / LANES];
        for j in 0..HEAD.min(c.len()) {
            let cj = c[j] as f32;
            blk.c[j][i % LANES] = cj;
            self.c_max[j] = self.c_max[j].max(cj.abs());
        }
        self.set_metric(i, d);
    }

    /// Rewrites RF `i`'s metric diagonals from its row `d` (after a metric step; the centre
    /// does not move). An entry is held at most `2^-24` above its value (its rounding to
    /// single precision), and below it where that cannot hold it: beyond its range as its
    /// largest number, below `2^-100` (or NaN) as 0, and rounded down to 8 significant bits.
    pub fn set_metric(&mut self, i: usize, d: &[f64]) {
        let blk = &mut self.blocks[i / LANES];
        for j in 0..HEAD.min(d.len()) {
            blk.d[j][i % LANES] = if d[j] >= D_TINY {
                ((d[j] as f32).min(f32::MAX).to_bits() >> 16) as u16
            } else {
                0
            };
        }
    }

    /// Removes RF `i`'s head, moving the last one into its place (as the rows).
    pub fn swap_remove(&mut self, i: usize) {
        let last = self.len - 1;
        let (bl, ll) = (last / LANES, last % LANES);
        let (bi, li) = (i / LANES, i % LANES);
        // The dimensions where the removed head held the largest centre coordinate.
        let mut rescan = [false; HEAD];
        for j in 0..HEAD {
            rescan[j] = self.blocks[bi].c[j][li].abs() >= self.c_max[j];
            let (c, d) = (self.blocks[bl].c[j][ll], self.blocks[bl].d[j][ll]);
            let blk = &mut self.blocks[bi];
            (blk.c[j][li], blk.d[j][li]) = (c, d);
            let blk = &mut self.blocks[bl];
            (blk.c[j][ll], blk.d[j][ll]) = (0.0, 0);
        }
        self.len = last;
        if ll == 0 {
            self.blocks.pop();
        }
        for j in (0..HEAD).filter(|&j| rescan[j]) {
            self.c_max[j] = (0..self.len)
                .map(|k| self.blocks[k / LANES].c[j][k % LANES].abs())
                .fold(0.0, f32::max);
        }
    }

    /// The number of blocks.
    #[cfg(test)]
    pub fn blocks(&self) -> usize {
        self.blocks.len()
    }
}

/// The relative reduction of a head's distances (`2^-20`).
const SLACK: f32 = 1.0 / (1u32 << 20) as f32;
/// The absolute reduction of a head's distances (`2^-120`, a normal number in single
/// precision, so that the arithmetic stays off the CPU's slow subnormal path).
const SLACK_ABS: f32 = 1.0 / (1u64 << 20) as f32 / (1u128 << 100) as f32;
/// Metric entries below this (`2^-100`) are held as 0 (see [`Heads::set_metric`]).
const D_TINY: f64 = 1.0 / (1u128 << 100) as f64;

/// Whether a model keeps heads: a diagonal metric over more than 8 kernel dimensions.
#[inline(always)]
pub(crate) fn in_use(p: &Params) -> bool {
    p.cfg.diag_only && p.nk() > 8
}
