//! Step (d): the first and second derivatives of the activation `w` and of the penalty
//! `J2 = (γ/n) Σ D_ij²` with respect to the free elements of the metric's factor `M`
//! (`D = MᵀM`, `M` upper-triangular; `docs/lwpr.md`, "The distance metric").

use crate::numeric::dot;
use crate::update::metric::MetricScratch;

/// First and second derivatives of `w` and of the penalty `J2 = (γ/n) Σ D_ij²` with respect to
/// each free element of `M`, at `dx = x − c` (`pen` = γ/n). Second derivatives only with `meta`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn derivatives(
    nk: usize,
    diag: bool,
    meta: bool,
    m: &[f64],
    d: &[f64],
    dwdq: f64,
    ddwdqdq: f64,
    pen: f64,
    ws: &mut MetricScratch,
) {
    let dx = &ws.dx[..nk];
    if diag {
        for n in 0..nk {
            let aux = 2.0 * m[n];
            let dqdm = dx[n] * dx[n] * aux;
            ws.dwdm[n] = dqdm * dwdq;
            ws.dj2[n] = 2.0 * pen * d[n] * aux;
            if meta {
                ws.ddw[n] = ddwdqdq * dqdm * dqdm + 2.0 * dwdq * dx[n] * dx[n];
                ws.ddj2[n] = 2.0 * pen * (2.0 * d[n] + aux * aux);
            }
        }
        return;
    }
    let (m, d) = (&m[..nk * nk], &d[..nk * nk]);
    let dx = &dx[..nk];
    for n in 0..nk {
        let mrow = &m[n * nk + n..(n + 1) * nk];
        ws.mdx[n] = dot(mrow, &dx[n..]);
    }
    // ∂J2/∂M_nm = 4 pen Σ_{i≥n} M_ni D_im (m ≥ n): row n of M·D, accumulated over the rows i
    // of D (the same terms in the same order as a dot product).
    let pen4 = 4.0 * pen;
    for n in 0..nk {
        let row = &mut ws.row[n..nk];
        row.iter_mut().for_each(|v| *v = 0.0);
        for i in n..nk {
            let a = m[n * nk + i];
            for (o, &dv) in row.iter_mut().zip(&d[i * nk + n..(i + 1) * nk]) {
                *o += a * dv;
            }
        }
        let dst = &mut ws.dj2[n * nk + n..(n + 1) * nk];
        for (o, &v) in dst.iter_mut().zip(&ws.row[n..nk]) {
            *o = v * pen4;
        }
    }
    for n in 0..nk {
        let k0 = n * nk + n;
        let len = nk - n;
        let mdx_n = ws.mdx[n];
        let dxr = &dx[n..];
        let dwdm = &mut ws.dwdm[k0..k0 + len];
        for (o, &x) in dwdm.iter_mut().zip(dxr) {
            *o = 2.0 * x * mdx_n * dwdq;
        }
        if meta {
            let mrow = &m[k0..k0 + len];
            let ss: f64 = mrow.iter().map(|v| v * v).sum();
            let ddw = &mut ws.ddw[k0..k0 + len];
            for (o, &x) in ddw.iter_mut().zip(dxr) {
                let dqdm = 2.0 * x * mdx_n;
                *o = ddwdqdq * dqdm * dqdm + 2.0 * dwdq * x * x;
            }
            let ddj2 = &mut ws.ddj2[k0..k0 + len];
            for (j, (o, &mv)) in ddj2.iter_mut().zip(mrow).enumerate() {
                let mm = n + j;
                *o = 4.0 * pen * (d[mm * nk + mm] + ss + mv * mv);
            }
        }
    }
}
