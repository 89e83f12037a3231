//! The heads of diagonal-metric RFs: each RF's first [`HEAD`] centre coordinates and metric
//! diagonals in single precision, side by side in one cache-line-aligned record, a copy of its
//! rows of `SubModel::centers` and `SubModel::ds` kept in step with them (issue 31).
//!
//! The activation pass measures every RF, and with thousands of RFs of 21 dimensions (the
//! SARCOS data) their centres and metrics stream from beyond the core's caches. A head gives a
//! lower bound of the RF's distance `q` ([`lower_bound`]); where the bound already reaches the
//! pass's cutoff, the RF cannot matter and its rows are not read. The heads change no value:
//! every RF they do not exclude is measured from its rows as before (`docs/lwpr.md`, "The
//! fast path").

use crate::params::Params;

/// How many leading dimensions a head holds.
pub(crate) const HEAD: usize = 24;

/// One RF's first [`HEAD`] centre coordinates `c` and metric diagonals `d`, rounded to single
/// precision (three cache lines); zeros beyond the kernel dimension.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C, align(64))]
pub(crate) struct Head {
    /// The centre's first coordinates.
    pub c: [f32; HEAD],
    /// The metric diagonal's first entries.
    pub d: [f32; HEAD],
}

impl Head {
    /// The head of an RF whose centre row is `c` and metric diagonal row `d` (non-negative).
    /// A metric entry is held below its value where single precision cannot hold it within
    /// its relative rounding: beyond its range as its largest number, below `2^-100` as 0.
    pub fn of(c: &[f64], d: &[f64]) -> Head {
        let mut h = Head::default();
        for j in 0..HEAD.min(c.len()) {
            let dj = if d[j] < D_TINY {
                0.0
            } else {
                (d[j] as f32).min(f32::MAX)
            };
            (h.c[j], h.d[j]) = (c[j] as f32, dj);
        }
        h
    }
}

/// The input's head where the model keeps heads ([`in_use`]), for a pass over them; else
/// `None` (the pass reads every RF's rows).
#[inline(always)]
pub(crate) fn probe(p: &Params, x: &[f64]) -> Option<[f32; HEAD]> {
    in_use(p).then(|| input(x))
}

/// An input's first [`HEAD`] coordinates rounded as a head's (zeros beyond its length).
#[inline(always)]
pub(crate) fn input(x: &[f64]) -> [f32; HEAD] {
    let mut x32 = [0.0; HEAD];
    for j in 0..HEAD.min(x.len()) {
        x32[j] = x[j] as f32;
    }
    x32
}

/// A lower bound of `q = Σ_j d_j (x_j − c_j)²` over all dimensions of the RF of head `h`, at
/// the input whose head is `x32`.
///
/// Each term's distance `|x_j − c_j|` is reduced by `2^-20·(|x_j| + |c_j|) + 2^-120`, more
/// than the error of rounding `x_j`, `c_j` and their difference to single precision (relative
/// `2^-22` of it at most, absolute `2^-148` among subnormal numbers). The sum, whose terms and
/// additions round by a factor within `1 ± 2^-19` (the metric entries are normal numbers, see
/// [`Head::of`]) and by `2^-143` at most among subnormal numbers, is capped at single
/// precision's largest number, scaled by `1 − 2^-10` and lowered by `2^-130`. So the result is
/// below the exact sum of the head's terms, and with them below `q` (every term is
/// non-negative), also as the update computes `q` in double precision (relative error below
/// `2^-45` for up to 1,000 terms). Where an input or a centre overflows single precision, the
/// reduced distance is NaN or negative and counts as 0; a sum that overflows is capped: the
/// bound is then smaller, never larger.
#[inline(always)]
pub(crate) fn lower_bound(h: &Head, x32: &[f32; HEAD]) -> f64 {
    let mut s = [0.0f32; HEAD];
    for j in 0..HEAD {
        let (x, c) = (x32[j], h.c[j]);
        let t = (x - c).abs() - SLACK * (x.abs() + c.abs()) - SLACK_ABS;
        let t = if t > 0.0 { t } else { 0.0 };
        s[j] = h.d[j] * t * t;
    }
    // Folded onto 8 lanes, then a pairwise sum (vectorised the same on every target).
    const _: () = assert!(HEAD.is_multiple_of(8));
    for j in 8..HEAD {
        s[j % 8] += s[j];
    }
    let mut w = 8;
    while w > 1 {
        w /= 2;
        for j in 0..w {
            s[j] += s[j + w];
        }
    }
    let lb = f64::from(s[0].min(f32::MAX)) * (1.0 - 1.0 / 1024.0) - SUM_ABS;
    lb.max(0.0)
}

/// The relative reduction of a head's distances (`2^-20`).
const SLACK: f32 = 1.0 / (1u32 << 20) as f32;
/// The absolute reduction of a head's distances (`2^-120`, a normal number in single
/// precision, so that the arithmetic stays off the CPU's slow subnormal path).
const SLACK_ABS: f32 = 1.0 / (1u64 << 20) as f32 / (1u128 << 100) as f32;
/// The absolute reduction of the sum (`2^-130`).
const SUM_ABS: f64 = 1.0 / (1u128 << 100) as f64 / (1u64 << 30) as f64;
/// Metric entries below this (`2^-100`) are held as 0 (see [`Head::of`]).
const D_TINY: f64 = 1.0 / (1u128 << 100) as f64;

/// Whether a model keeps heads: a diagonal metric over more than 8 kernel dimensions.
#[inline(always)]
pub(crate) fn in_use(p: &Params) -> bool {
    p.cfg.diag_only && p.nk() > 8
}
