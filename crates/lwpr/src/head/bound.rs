//! The heads' lower bound of an RF's distance `q` (`docs/lwpr.md`, "The fast path"): the
//! input's [`Probe`], the bounds of a block of heads at once, and the [`Walk`] over them RF
//! by RF.

use super::{in_use, Block, Heads, HEAD, LANES, SLACK, SLACK_ABS};
use crate::params::Params;

/// An input's first [`HEAD`] coordinates rounded as a head's, with the slack of each
/// dimension's distance: `e_j = 2^-20·(|x_j| + max |c_j|) + 2^-120`, the largest `|c_j|` over
/// the sub-model's heads.
#[derive(Clone, Debug)]
pub(crate) struct Probe {
    x: [f32; HEAD],
    e: [f32; HEAD],
    /// The dimensions the heads hold: `min(nk, HEAD)`.
    n: usize,
}

impl Heads {
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
    /// `2^-20·(|x_j| + |c_j|) + 2^-120`: more than the error of rounding `x_j`, `c_j` and
    /// their difference to single precision (relative `2^-22` of it at most, absolute
    /// `2^-148` among subnormal numbers). A reduced distance that is NaN (an input or a
    /// centre beyond single precision's range, or `|x_j| + max |c_j|` beyond it) or
    /// negative counts as 0, and none is infinite (`|x_j − c_j| ≤ |x_j| + max |c_j|`,
    /// rounded alike). The metric entries are normal numbers at most `2^-24` above their
    /// value ([`Heads::set_metric`]). So the sum of at most 24 non-negative terms, whose
    /// multiplications and additions round by a factor within `1 ± 2^-19` and by `2^-143`
    /// at most among subnormal numbers, capped at single precision's largest number, scaled
    /// by `1 − 2^-10` and lowered by `2^-130`, is below the exact sum of the head's terms,
    /// and with them below `q` (every term is non-negative), also as the update computes
    /// `q` in double precision (relative error below `2^-45` for up to 1,000 terms).
    #[inline(always)]
    pub fn bounds(&self, avx: bool, b: usize, pr: &Probe) -> [f64; LANES] {
        let blk = &self.blocks[b];
        let s = sums(avx, blk, pr);
        let mut lb = [0.0; LANES];
        for l in 0..LANES {
            // A NaN sum (none arises: every term is finite or capped) would count as 0, which
            // `clamp` would keep as NaN.
            #[allow(clippy::manual_clamp)]
            let sl = s[l].max(0.0).min(f32::MAX);
            let v = f64::from(sl) * (1.0 - 1.0 / 1024.0) - SUM_ABS;
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

/// The absolute reduction of the sum (`2^-130`).
const SUM_ABS: f64 = 1.0 / (1u128 << 100) as f64 / (1u64 << 30) as f64;
