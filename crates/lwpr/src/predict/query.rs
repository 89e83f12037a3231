//! The activation query of `Lwpr::activations` (`partition.rs`): the activations above a
//! cutoff of every RF of one sub-model at an input, trustworthy or not.

use crate::distance::quad;
use crate::params::Params;
use crate::rf::{Activation, RfId, SubModel};
use crate::scratch::Scratch;

/// Writes into `out` (cleared first) the activations `w > cutoff` of the RFs of `s` at `x`;
/// `NK > 0` fixes the kernel dimension at compile time (0: taken from `p`); `AVX` is set only
/// after the run-time check of the CPU (`distance::quad`).
#[inline(always)]
pub(crate) fn activations_core<const NK: usize, const AVX: bool>(
    p: &Params,
    s: &SubModel,
    ws: &mut Scratch,
    x: &[f64],
    cutoff: f64,
    out: &mut Vec<Activation>,
) {
    ws.load_x(p, x);
    let (ml, diag) = (p.mlen(), p.cfg.diag_only);
    let nk = if NK > 0 { NK } else { p.nk() };
    let kern = if diag { &s.ds } else { &s.ms };
    let qb = p.q_bound(cutoff);
    out.clear();
    let rf_chunks = s.centers.chunks_exact(nk).zip(kern.chunks_exact(ml));
    // Where the model keeps heads, the RFs they put beyond `qb` are not measured (same result).
    let mut heads = s.heads.walk(AVX, p, &ws.xk[..nk]);
    for (i, (rf, (c, md))) in s.rfs.iter().zip(rf_chunks).enumerate() {
        if heads.as_mut().is_some_and(|h| h.beyond(i, qb)) {
            continue;
        }
        let q = quad(AVX, diag, c, md, &ws.xk[..nk], &mut ws.met.dx, qb);
        if q < qb {
            let w = p.kernel(q).0;
            if w > cutoff {
                out.push(Activation { id: RfId(rf.id), w });
            }
        }
    }
}
