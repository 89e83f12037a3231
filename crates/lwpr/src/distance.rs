//! The distance of an input to a receptive field's centre, `q = (x − c)ᵀ D (x − c)`, which the
//! kernel turns into the RF's activation: for the update's activation pass, predictions and
//! activation queries.

/// `q = (x − c)ᵀ D (x − c)`: from the diagonal of `D`, or as `‖M (x − c)‖²` with the
/// upper-triangular `M` (row-major); `dx` is scratch of length `x.len()`.
///
/// The sum runs over non-negative terms, so its partial values never decrease (also in
/// floating point): once a partial sum reaches `bound`, the RF cannot matter to the caller and
/// that partial sum (`≥ bound`) is returned early. Below `bound` the result is the full sum,
/// bit for bit the same as without a bound (same terms, same order). Pass `f64::INFINITY` for
/// the exact value. `avx` (the same bits; a constant after inlining) may be set only where the CPU has AVX2, checked at
/// run time by the caller (`fast::has_avx2`): above 4 dimensions the full metric's row sums
/// then run in one AVX2 register (`fast/dot.rs`).
#[inline(always)]
pub(crate) fn quad(
    avx: bool,
    diag: bool,
    c: &[f64],
    md: &[f64],
    x: &[f64],
    dx: &mut [f64],
    bound: f64,
) -> f64 {
    if diag {
        quad_diag(c, md, x, bound)
    } else {
        match x.len() {
            1 => quad_full_n::<1>(c, md, x, bound),
            2 => quad_full_n::<2>(c, md, x, bound),
            3 => quad_full_n::<3>(c, md, x, bound),
            4 => quad_full_n::<4>(c, md, x, bound),
            _ => quad_full(avx, c, md, x, dx, bound),
        }
    }
}

/// Diagonal metric: `Σ_i D_i (x_i − c_i)²`, the terms of whole groups of 8 and then of one
/// group of 4 in four interleaved partial sums (lane `i mod 4`), the last `< 4` terms in order,
/// checking the bound after every 8 terms. Each lane only grows, and so does their
/// combination, so a partial value never exceeds the full sum.
#[inline(always)]
fn quad_diag(c: &[f64], d: &[f64], x: &[f64], bound: f64) -> f64 {
    let n = x.len();
    let (c, d) = (&c[..n], &d[..n]);
    let mut l = [0.0; 4];
    let mut i = 0;
    while i + 8 <= n {
        let (xs, cs, ds) = (&x[i..i + 8], &c[i..i + 8], &d[i..i + 8]);
        for j in 0..8 {
            let t = xs[j] - cs[j];
            l[j % 4] += ds[j] * t * t;
        }
        let q = (l[0] + l[1]) + (l[2] + l[3]);
        if q >= bound {
            return q;
        }
        i += 8;
    }
    if i + 4 <= n {
        let (xs, cs, ds) = (&x[i..i + 4], &c[i..i + 4], &d[i..i + 4]);
        for j in 0..4 {
            let t = xs[j] - cs[j];
            l[j] += ds[j] * t * t;
        }
        i += 4;
    }
    let mut q = (l[0] + l[1]) + (l[2] + l[3]);
    for k in i..n {
        let t = x[k] - c[k];
        q += d[k] * t * t;
    }
    q
}

/// Full metric, `N` known at compile time (small input spaces). Up to 2-D the bound is not
/// checked: the full sum costs less than a mispredicted branch (and a value `≥ bound` is
/// never used beyond the test against it).
#[inline(always)]
pub(crate) fn quad_full_n<const N: usize>(c: &[f64], m: &[f64], x: &[f64], bound: f64) -> f64 {
    let (c, m, x) = (&c[..N], &m[..N * N], &x[..N]);
    let mut dx = [0.0; N];
    for i in 0..N {
        dx[i] = x[i] - c[i];
    }
    let mut q = 0.0;
    for n in 0..N {
        let mut v = 0.0;
        for i in n..N {
            v += m[n * N + i] * dx[i];
        }
        q += v * v;
        if N > 2 && q >= bound {
            return q;
        }
    }
    q
}

/// `numeric::dot(row, dx)`, on AVX2 when `avx` (see [`quad`]; the same bits).
#[inline(always)]
fn row_dot(avx: bool, row: &[f64], dx: &[f64]) -> f64 {
    #[cfg(target_arch = "x86_64")]
    if avx {
        // SAFETY: `avx` is set only where the CPU has AVX2 (see `quad`).
        return unsafe { crate::fast::dot::dot_avx2(row, dx) };
    }
    let _ = avx;
    crate::numeric::dot(row, dx)
}

/// Full metric, any size: `Σ_n (Σ_{i≥n} M_ni dx_i)²` (the inner sums by [`crate::numeric::dot`]),
/// checking the bound after each row; with `avx` (see [`quad`]) by `fast::dot::dot_avx2`.
#[inline(always)]
fn quad_full(avx: bool, c: &[f64], m: &[f64], x: &[f64], dx: &mut [f64], bound: f64) -> f64 {
    let nk = x.len();
    let (c, m, dx) = (&c[..nk], &m[..nk * nk], &mut dx[..nk]);
    for i in 0..nk {
        dx[i] = x[i] - c[i];
    }
    let mut q = 0.0;
    for n in 0..nk {
        let (row, dxn) = (&m[n * nk + n..(n + 1) * nk], &dx[n..]);
        let v = row_dot(avx, row, dxn);
        q += v * v;
        if q >= bound {
            return q;
        }
    }
    q
}
