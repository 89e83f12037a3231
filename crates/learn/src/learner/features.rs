//! The feature layouts of the learner: `φ` of the local controllers (eq. 31) and `φ_d` of the
//! local dynamics regressions (`docs/learner.md`, "Features"). One type owns both, so the command,
//! the hindsight update and the gain `Â(q)` read the same positions.

use nalgebra::DMatrix;

/// Joints up to which [`Features::add_gain`] keeps its sums on the stack.
const SMALL_N: usize = 16;

/// Where each part of the two feature vectors lives, for `n` joints and `m` task dimensions.
///
/// - controller `φ = [ẍᵀ, q̇ᵀ, (q − c)ᵀ?, 1, (ẍ_j (q_k − c_k))?]` (eq. 31; `ẍ` is `ẍ_ref` when
///   commanding and the measured `ẍ` in hindsight; the position part and the bilinear part are
///   optional);
/// - local dynamics `φ_d = [uᵀ, q̇ᵀ, (q − c)ᵀ, 1, (u_j (q_k − c_k))?]`, regressed on `ẍ`; its `u`
///   rows (and the bilinear ones) give `Â(q) = ∂ẍ/∂u`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Features {
    n: usize,
    m: usize,
    position: bool,
    bilinear: bool,
    controller_bilinear: bool,
}

impl Features {
    pub fn new(n: usize, m: usize, position: bool, bilinear: bool) -> Self {
        Self {
            n,
            m,
            position,
            bilinear,
            controller_bilinear: false,
        }
    }

    /// The same layout with (or without) the controllers' bilinear part `ẍ_j (q_k − c_k)`.
    pub fn with_controller_bilinear(self, on: bool) -> Self {
        Self {
            controller_bilinear: on,
            ..self
        }
    }

    /// Joints `n` and task dimensions `m` of the layout.
    pub fn dims(&self) -> (usize, usize) {
        (self.n, self.m)
    }

    /// Rows of the controller's position part `q − c`, if the layout has it.
    pub fn controller_q_rows(&self) -> Option<std::ops::Range<usize>> {
        let start = self.m + self.n;
        self.position.then(|| start..start + self.n)
    }

    /// Row of the controller's constant feature.
    pub fn controller_constant(&self) -> usize {
        self.m + self.n + self.controller_q_rows().map_or(0, |r| r.len())
    }

    /// Rows of the controller's bilinear part, `ẍ_j (q_k − c_k)` at `start + j n + k`, if the
    /// layout has it.
    pub fn controller_bilinear_rows(&self) -> Option<std::ops::Range<usize>> {
        let start = self.controller_constant() + 1;
        self.controller_bilinear
            .then(|| start..start + self.m * self.n)
    }

    /// Length of the controller features `φ`.
    pub fn controller_len(&self) -> usize {
        self.controller_constant()
            + 1
            + if self.controller_bilinear {
                self.m * self.n
            } else {
                0
            }
    }

    /// Length of the local dynamics features `φ_d`.
    pub fn dynamics_len(&self) -> usize {
        3 * self.n + 1 + if self.bilinear { self.n * self.n } else { 0 }
    }

    /// The parts of `φ` shared by every receptive field: `ẍ`, `q̇` and the constant.
    pub fn controller_common(&self, phi: &mut [f64], xdd: &[f64], qd: &[f64]) {
        let (n, m) = (self.n, self.m);
        phi[..m].copy_from_slice(xdd);
        phi[m..m + n].copy_from_slice(qd);
        phi[self.controller_constant()] = 1.0;
    }

    /// Moves a controller's coefficients `beta` (`φ`-rows × n) from the centre `from` to `to`
    /// so that it gives the same command at every `q` and `ẍ`: the constant takes up the
    /// position part's `β_qᵀ (to − from)`, each `ẍ_j` row the bilinear part's
    /// `Σ_k β_{jk} (to_k − from_k)`. Without a position part there is nothing to move.
    pub fn recentre(&self, beta: &mut DMatrix<f64>, from: &[f64], to: &[f64]) {
        let Some(q_rows) = self.controller_q_rows() else {
            return;
        };
        let (n, m) = (self.n, self.m);
        let (last, products) = (self.controller_constant(), self.controller_bilinear_rows());
        for k in 0..beta.ncols() {
            let shift: f64 = (q_rows.clone())
                .enumerate()
                .map(|(i, r)| beta[(r, k)] * (to[i] - from[i]))
                .sum();
            beta[(last, k)] += shift;
            if let Some(rows) = &products {
                for j in 0..m {
                    let shift: f64 = (0..n)
                        .map(|i| beta[(rows.start + j * n + i, k)] * (to[i] - from[i]))
                        .sum();
                    beta[(j, k)] += shift;
                }
            }
        }
    }

    /// The parts of `φ` of the field centred at `center` (`q − c` and `ẍ_j (q_k − c_k)`), if
    /// the layout has them. Reads `ẍ` from `φ`: call after [`Self::controller_common`].
    pub fn controller_local(&self, phi: &mut [f64], q: &[f64], center: &[f64]) {
        let (n, m) = (self.n, self.m);
        if let Some(rows) = self.controller_q_rows() {
            for ((o, q), c) in phi[rows].iter_mut().zip(q).zip(center) {
                *o = q - c;
            }
        }
        if let Some(rows) = self.controller_bilinear_rows() {
            let (head, bilinear) = phi.split_at_mut(rows.start);
            for (j, row) in bilinear[..m * n].chunks_exact_mut(n).enumerate() {
                for (k, o) in row.iter_mut().enumerate() {
                    *o = head[j] * (q[k] - center[k]);
                }
            }
        }
    }

    /// The parts of `φ_d` shared by every receptive field: `u`, `q̇` and the constant.
    pub fn dynamics_common(&self, phi_d: &mut [f64], u: &[f64], qd: &[f64]) {
        let n = self.n;
        phi_d[..n].copy_from_slice(u);
        phi_d[n..2 * n].copy_from_slice(qd);
        phi_d[3 * n] = 1.0;
    }

    /// The parts of `φ_d` of the field centred at `center`: `q − c` and the bilinear terms.
    pub fn dynamics_local(&self, phi_d: &mut [f64], q: &[f64], u: &[f64], center: &[f64]) {
        let n = self.n;
        for i in 0..n {
            phi_d[2 * n + i] = q[i] - center[i];
        }
        if self.bilinear {
            let (dq, block) = phi_d[2 * n..].split_at_mut(n + 1);
            let block = &mut block[..n * n];
            for (row, &uj) in block.chunks_exact_mut(n).zip(&u[..n]) {
                for (o, &dqk) in row.iter_mut().zip(&dq[..n]) {
                    *o = uj * dqk;
                }
            }
        }
    }

    /// The shared parts of the difference form of `φ_d` (`DynamicsRegression::Difference`):
    /// `Δu/Δt`, `Δq̇/Δt` and 0 for the constant, from the previous transition's `u0, q̇0`.
    pub fn dynamics_common_difference(
        &self,
        phi_d: &mut [f64],
        (u, u0): (&[f64], &[f64]),
        (qd, qd0): (&[f64], &[f64]),
        inv_dt: f64,
    ) {
        let n = self.n;
        for i in 0..n {
            phi_d[i] = (u[i] - u0[i]) * inv_dt;
            phi_d[n + i] = (qd[i] - qd0[i]) * inv_dt;
        }
        phi_d[3 * n] = 0.0;
    }

    /// The field's parts of the difference form of `φ_d`: `Δq/Δt` and the change of the
    /// bilinear terms `u_j (q_k − c_k)` over `Δt`, from the previous transition's `q0, u0`.
    pub fn dynamics_local_difference(
        &self,
        phi_d: &mut [f64],
        (q, q0): (&[f64], &[f64]),
        (u, u0): (&[f64], &[f64]),
        center: &[f64],
        inv_dt: f64,
    ) {
        let n = self.n;
        for i in 0..n {
            phi_d[2 * n + i] = (q[i] - q0[i]) * inv_dt;
        }
        if self.bilinear {
            // Row `j` of the block: on slices, without index checks, so the row vectorises (every
            // subtraction and product as written, in this order).
            let (q, q0, c) = (&q[..n], &q0[..n], &center[..n]);
            let block = &mut phi_d[3 * n + 1..3 * n + 1 + n * n];
            for ((row, &uj), &u0j) in block.chunks_exact_mut(n).zip(&u[..n]).zip(&u0[..n]) {
                for (((o, &qk), &q0k), &ck) in row.iter_mut().zip(q).zip(q0).zip(c) {
                    let now = uj * (qk - ck);
                    let before = u0j * (q0k - ck);
                    *o = (now - before) * inv_dt;
                }
            }
        }
    }

    /// Adds `w · Â_i(q)` (m×n, row-major into `a`) of one field's dynamics coefficients `theta`
    /// (`φ_d`-rows × m): `Â_i(q) = Θ_u + Σ_k (q_k − c_k) Θ_{u_j q_k}`.
    pub fn add_gain(&self, theta: &DMatrix<f64>, q: &[f64], center: &[f64], w: f64, a: &mut [f64]) {
        let n = self.n;
        let rows = theta.nrows();
        let (q, center) = (&q[..n], &center[..n]);
        if self.bilinear && n <= SMALL_N {
            // The same sums, every `j` at once (independent chains, each still in order of `i`).
            let mut dq = [0.0; SMALL_N];
            for i in 0..n {
                dq[i] = q[i] - center[i];
            }
            for k in 0..self.m {
                let col = &theta.as_slice()[k * rows..(k + 1) * rows];
                let mut g = [0.0; SMALL_N];
                g[..n].copy_from_slice(&col[..n]);
                for i in 0..n {
                    for j in 0..n {
                        g[j] += dq[i] * col[3 * n + 1 + j * n + i];
                    }
                }
                for j in 0..n {
                    a[k * n + j] += w * g[j];
                }
            }
            return;
        }
        self.add_gain_columns(theta, q, center, w, a);
    }

    /// The coefficients of `Â_i(q)` from `theta` in the order [`Self::add_gain_table`] reads
    /// them, into `table` (resized; no allocation once it has the capacity): per task row `k`,
    /// `Θ_u[·, k]` (n values), then for each `i` the column `Θ_{u_j q_i}[·, k]` over `j` (n
    /// values each). Empty (and `false`) without the bilinear terms or above 16 joints, where
    /// [`Self::add_gain`] reads `Θ` directly.
    pub fn gain_table(&self, theta: &DMatrix<f64>, table: &mut Vec<f64>) -> bool {
        let n = self.n;
        if !(self.bilinear && n <= SMALL_N) {
            table.clear();
            return false;
        }
        let rows = theta.nrows();
        table.resize(self.m * (n + n * n), 0.0);
        for (k, out) in table.chunks_exact_mut(n + n * n).enumerate() {
            let col = &theta.as_slice()[k * rows..(k + 1) * rows];
            out[..n].copy_from_slice(&col[..n]);
            for i in 0..n {
                for j in 0..n {
                    out[n + i * n + j] = col[3 * n + 1 + j * n + i];
                }
            }
        }
        true
    }

    /// [`Self::add_gain`] from a table of [`Self::gain_table`]: the same sums in the same
    /// order (the same bits), read contiguously; for 2–8 joints with the sums in registers.
    pub fn add_gain_table(&self, table: &[f64], q: &[f64], center: &[f64], w: f64, a: &mut [f64]) {
        match self.n {
            2 => gain_table_n::<2>(table, q, center, w, a),
            3 => gain_table_n::<3>(table, q, center, w, a),
            4 => gain_table_n::<4>(table, q, center, w, a),
            5 => gain_table_n::<5>(table, q, center, w, a),
            6 => gain_table_n::<6>(table, q, center, w, a),
            7 => gain_table_n::<7>(table, q, center, w, a),
            8 => gain_table_n::<8>(table, q, center, w, a),
            _ => self.add_gain_table_any(table, q, center, w, a),
        }
    }

    /// [`Self::add_gain_table`] into two blends at once: `Â_i(q)` is formed once and added with
    /// weight `w1` into `a1` and `w2` into `a2` (each only if its weight is > 0): the bits of two
    /// calls of [`Self::add_gain_table`].
    pub fn add_gain_table_pair(
        &self,
        table: &[f64],
        q: &[f64],
        center: &[f64],
        (w1, a1): (f64, &mut [f64]),
        (w2, a2): (f64, &mut [f64]),
    ) {
        match self.n {
            2 => gain_table_pair_n::<2>(table, q, center, (w1, a1), (w2, a2)),
            3 => gain_table_pair_n::<3>(table, q, center, (w1, a1), (w2, a2)),
            4 => gain_table_pair_n::<4>(table, q, center, (w1, a1), (w2, a2)),
            5 => gain_table_pair_n::<5>(table, q, center, (w1, a1), (w2, a2)),
            6 => gain_table_pair_n::<6>(table, q, center, (w1, a1), (w2, a2)),
            7 => gain_table_pair_n::<7>(table, q, center, (w1, a1), (w2, a2)),
            8 => gain_table_pair_n::<8>(table, q, center, (w1, a1), (w2, a2)),
            _ => {
                if w1 > 0.0 {
                    self.add_gain_table_any(table, q, center, w1, a1);
                }
                if w2 > 0.0 {
                    self.add_gain_table_any(table, q, center, w2, a2);
                }
            }
        }
    }

    /// [`Self::add_gain_table`] for any number of joints (up to 16).
    fn add_gain_table_any(&self, table: &[f64], q: &[f64], center: &[f64], w: f64, a: &mut [f64]) {
        let n = self.n;
        let mut dq = [0.0; SMALL_N];
        for i in 0..n {
            dq[i] = q[i] - center[i];
        }
        for (k, rowk) in table.chunks_exact(n + n * n).enumerate() {
            let mut g = [0.0; SMALL_N];
            g[..n].copy_from_slice(&rowk[..n]);
            for (i, t) in rowk[n..].chunks_exact(n).enumerate() {
                for (gj, tj) in g[..n].iter_mut().zip(t) {
                    *gj += dq[i] * tj;
                }
            }
            for (aj, gj) in a[k * n..(k + 1) * n].iter_mut().zip(&g[..n]) {
                *aj += w * gj;
            }
        }
    }

    /// [`Features::add_gain`] one entry at a time (any number of joints).
    fn add_gain_columns(
        &self,
        theta: &DMatrix<f64>,
        q: &[f64],
        center: &[f64],
        w: f64,
        a: &mut [f64],
    ) {
        let n = self.n;
        let rows = theta.nrows();
        let (q, center) = (&q[..n], &center[..n]);
        for k in 0..self.m {
            // Column k of Θ (contiguous), and row k of Â.
            let col = &theta.as_slice()[k * rows..(k + 1) * rows];
            let out = &mut a[k * n..(k + 1) * n];
            for (j, o) in out.iter_mut().enumerate() {
                let mut g = col[j];
                if self.bilinear {
                    let t = &col[3 * n + 1 + j * n..][..n];
                    for ((qi, ci), ti) in q.iter().zip(center).zip(t) {
                        g += (qi - ci) * ti;
                    }
                }
                *o += w * g;
            }
        }
    }
}

/// [`Features::add_gain_table`] for `N` joints: the sums of each task row in registers.
#[inline(always)]
fn gain_table_n<const N: usize>(table: &[f64], q: &[f64], center: &[f64], w: f64, a: &mut [f64]) {
    let mut dq = [0.0; N];
    for i in 0..N {
        dq[i] = q[i] - center[i];
    }
    for (rowk, ak) in table.chunks_exact(N + N * N).zip(a.chunks_exact_mut(N)) {
        let g = gain_row::<N>(rowk, &dq);
        for j in 0..N {
            ak[j] += w * g[j];
        }
    }
}

/// One task row of `Â_i(q)` from its table row: `Θ_u` plus `Σ_i dq_i Θ_{u q_i}`, in order of `i`
/// (the sums in registers).
#[inline(always)]
fn gain_row<const N: usize>(rowk: &[f64], dq: &[f64; N]) -> [f64; N] {
    let mut g = [0.0; N];
    g.copy_from_slice(&rowk[..N]);
    for i in 0..N {
        let t = &rowk[N + i * N..N + (i + 1) * N];
        for j in 0..N {
            g[j] += dq[i] * t[j];
        }
    }
    g
}

/// [`Features::add_gain_table_pair`] for `N` joints: each task row of `Â_i(q)` summed once
/// (as [`gain_table_n`] sums it), then added to both blends.
#[inline(always)]
fn gain_table_pair_n<const N: usize>(
    table: &[f64],
    q: &[f64],
    center: &[f64],
    (w1, a1): (f64, &mut [f64]),
    (w2, a2): (f64, &mut [f64]),
) {
    let mut dq = [0.0; N];
    for i in 0..N {
        dq[i] = q[i] - center[i];
    }
    let rows = table.chunks_exact(N + N * N);
    for ((rowk, a1k), a2k) in rows.zip(a1.chunks_exact_mut(N)).zip(a2.chunks_exact_mut(N)) {
        let g = gain_row::<N>(rowk, &dq);
        if w1 > 0.0 {
            for j in 0..N {
                a1k[j] += w1 * g[j];
            }
        }
        if w2 > 0.0 {
            for j in 0..N {
                a2k[j] += w2 * g[j];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Features;
    use nalgebra::DMatrix;

    #[test]
    fn layouts_have_the_documented_lengths_and_positions() {
        let f = Features::new(3, 2, true, true);
        assert_eq!(f.controller_len(), 2 + 3 + 3 + 1);
        assert_eq!(f.dynamics_len(), 3 * 3 + 1 + 9);
        assert_eq!(Features::new(3, 2, false, false).controller_len(), 6);
        assert_eq!(Features::new(3, 2, false, false).dynamics_len(), 10);
        let mut phi = vec![f64::NAN; f.controller_len()];
        f.controller_common(&mut phi, &[1.0, 2.0], &[3.0, 4.0, 5.0]);
        f.controller_local(&mut phi, &[1.0, 1.0, 1.0], &[0.5, 0.0, 2.0]);
        assert_eq!(phi, [1.0, 2.0, 3.0, 4.0, 5.0, 0.5, 1.0, -1.0, 1.0]);
        let mut d = vec![f64::NAN; f.dynamics_len()];
        f.dynamics_common(&mut d, &[1.0, 2.0, 3.0], &[4.0, 5.0, 6.0]);
        f.dynamics_local(&mut d, &[1.0, 1.0, 1.0], &[1.0, 2.0, 3.0], &[0.0, 1.0, 2.0]);
        assert_eq!(
            &d[..10],
            &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 1.0, 0.0, -1.0, 1.0]
        );
        // u_j (q_k − c_k), row j.
        assert_eq!(&d[10..], &[1.0, 0.0, -1.0, 2.0, 0.0, -2.0, 3.0, 0.0, -3.0]);
    }

    /// The controllers' bilinear part: `ẍ_j (q_k − c_k)` after the constant, row `j`.
    #[test]
    fn the_controller_bilinear_part_follows_the_constant() {
        let f = Features::new(3, 2, true, true).with_controller_bilinear(true);
        assert_eq!(f.controller_len(), 2 + 3 + 3 + 1 + 2 * 3);
        assert_eq!(f.controller_bilinear_rows(), Some(9..15));
        let mut phi = vec![f64::NAN; f.controller_len()];
        f.controller_common(&mut phi, &[1.0, 2.0], &[3.0, 4.0, 5.0]);
        f.controller_local(&mut phi, &[1.0, 1.0, 1.0], &[0.5, 0.0, 2.0]);
        let want = [1.0, 2.0, 3.0, 4.0, 5.0, 0.5, 1.0, -1.0, 1.0];
        assert_eq!(&phi[..9], &want);
        assert_eq!(&phi[9..], &[0.5, 1.0, -1.0, 1.0, 2.0, -2.0]);
        let off = Features::new(3, 2, true, true).with_controller_bilinear(false);
        assert_eq!(off, Features::new(3, 2, true, true));
        assert_eq!(off.controller_bilinear_rows(), None);
    }

    /// A controller moved to another centre by `recentre` commands the same `u` at every `q`,
    /// `q̇` and `ẍ`, with and without the bilinear part; without position features it is
    /// unchanged.
    #[test]
    fn a_recentred_controller_commands_the_same() {
        for bilinear in [false, true] {
            let f = Features::new(3, 2, true, true).with_controller_bilinear(bilinear);
            let p = f.controller_len();
            let beta = DMatrix::from_fn(p, 3, |r, c| ((r * 7 + c * 3) as f64 * 0.913).sin());
            let (from, to) = ([0.1, -0.4, 0.7], [0.35, -0.1, 0.2]);
            let mut moved = beta.clone();
            f.recentre(&mut moved, &from, &to);
            assert_ne!(moved, beta);
            for t in 0..5 {
                let t = t as f64;
                let xdd = [(t * 1.1).sin(), (t * 0.7).cos()];
                let qd = [0.3 * t, -0.2, (t * 0.4).sin()];
                let q = [(t * 0.5).cos(), 0.2 * t - 0.5, (t * 1.7).sin()];
                let command = |beta: &DMatrix<f64>, c: &[f64]| {
                    let mut phi = vec![f64::NAN; p];
                    f.controller_common(&mut phi, &xdd, &qd);
                    f.controller_local(&mut phi, &q, c);
                    beta.tr_mul(&nalgebra::DVector::from_vec(phi))
                };
                let (a, b) = (command(&beta, &from), command(&moved, &to));
                assert!((&a - &b).amax() < 1e-12, "bilinear {bilinear}: {a} vs {b}");
            }
        }
        let f = Features::new(3, 2, false, true).with_controller_bilinear(false);
        let beta = DMatrix::from_fn(f.controller_len(), 3, |r, c| (r + c) as f64);
        let mut moved = beta.clone();
        f.recentre(&mut moved, &[0.0; 3], &[1.0; 3]);
        assert_eq!(moved, beta);
    }

    /// The gain from a table of `gain_table` is `add_gain`'s, bit for bit, for 3 task rows and
    /// 3, 7 (in registers) and 10 joints (on the stack); without the bilinear terms there is no
    /// table.
    #[test]
    fn the_gain_table_gives_the_same_bits_as_theta() {
        for n in [3, 7, 10] {
            let f = Features::new(n, 3, true, true);
            let theta = DMatrix::from_fn(f.dynamics_len(), 3, |r, c| {
                ((r * 31 + c * 17) as f64 * 0.7351).sin() * 10f64.powi((r % 5) as i32 - 2)
            });
            let q: Vec<f64> = (0..n).map(|i| (i as f64 * 1.3).cos()).collect();
            let c: Vec<f64> = (0..n).map(|i| 0.1 * i as f64 - 0.3).collect();
            let mut table = Vec::new();
            assert!(f.gain_table(&theta, &mut table));
            let (mut a, mut b) = (vec![0.25; 3 * n], vec![0.25; 3 * n]);
            f.add_gain(&theta, &q, &c, 0.37, &mut a);
            f.add_gain_table(&table, &q, &c, 0.37, &mut b);
            let same = a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits());
            assert!(same, "{n} joints: {a:?}\n{b:?}");
            assert!(!Features::new(n, 3, true, false).gain_table(&theta, &mut table));
            assert!(table.is_empty());
        }
    }

    /// The difference form of `φ_d` is the change of the levels over `Δt`, with 0 for the
    /// constant (`DynamicsRegression::Difference`).
    #[test]
    fn the_difference_form_is_the_change_of_the_levels() {
        let f = Features::new(3, 2, true, true);
        let c = [0.1, -0.2, 0.3];
        let (q0, q1) = ([0.2, 0.4, -0.1], [0.25, 0.35, -0.05]);
        let (qd0, qd1) = ([1.0, -2.0, 0.5], [1.5, -1.0, 0.0]);
        let (u0, u1) = ([3.0, -1.0, 2.0], [2.0, 0.5, 2.5]);
        let level = |q: &[f64], qd: &[f64], u: &[f64]| {
            let mut d = vec![f64::NAN; f.dynamics_len()];
            f.dynamics_common(&mut d, u, qd);
            f.dynamics_local(&mut d, q, u, &c);
            d
        };
        let (a, b) = (level(&q0, &qd0, &u0), level(&q1, &qd1, &u1));
        let mut d = vec![f64::NAN; f.dynamics_len()];
        f.dynamics_common_difference(&mut d, (&u1, &u0), (&qd1, &qd0), 500.0);
        f.dynamics_local_difference(&mut d, (&q1, &q0), (&u1, &u0), &c, 500.0);
        for k in 0..d.len() {
            let want = if k == 9 { 0.0 } else { (b[k] - a[k]) * 500.0 };
            assert!(
                (d[k] - want).abs() <= 1e-9 * want.abs().max(1.0),
                "{k}: {}",
                d[k]
            );
        }
    }

    /// The stack path of `add_gain` gives the bits of the entry-by-entry one.
    #[test]
    fn the_gain_on_the_stack_has_the_bits_of_the_entry_by_entry_sums() {
        for (n, m) in [(7, 3), (3, 2), (1, 1), (16, 6)] {
            let f = Features::new(n, m, true, true);
            let theta =
                DMatrix::from_fn(f.dynamics_len(), m, |r, k| ((r * 7 + k * 3) as f64).sin());
            let q: Vec<f64> = (0..n).map(|i| (i as f64 * 1.3).cos()).collect();
            let c: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).sin()).collect();
            let (mut a, mut b) = (vec![0.25; n * m], vec![0.25; n * m]);
            f.add_gain(&theta, &q, &c, 0.37, &mut a);
            f.add_gain_columns(&theta, &q, &c, 0.37, &mut b);
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&a), bits(&b), "n = {n}");
        }
    }

    #[test]
    fn the_gain_is_linear_in_q_and_equals_the_u_rows_at_the_centre() {
        // With φ_d · Θ the dynamics, ∂ẍ_k/∂u_j at q equals Θ[j,k] + Σ_i (q_i − c_i) Θ[bilinear].
        let f = Features::new(2, 1, false, true);
        let theta = DMatrix::from_fn(f.dynamics_len(), 1, |r, _| 0.1 * r as f64 + 0.3);
        let c = [0.2, -0.1];
        let mut a = [0.0; 2];
        f.add_gain(&theta, &c, &c, 1.0, &mut a);
        assert_eq!(a, [theta[(0, 0)], theta[(1, 0)]]);
        // Finite difference of the prediction φ_d(u) · Θ in u, at another q.
        let q = [0.5, 0.4];
        let predict = |u: [f64; 2]| {
            let mut d = vec![0.0; f.dynamics_len()];
            f.dynamics_common(&mut d, &u, &[0.0, 0.0]);
            f.dynamics_local(&mut d, &q, &u, &c);
            (0..d.len()).map(|r| d[r] * theta[(r, 0)]).sum::<f64>()
        };
        let mut a = [0.0; 2];
        f.add_gain(&theta, &q, &c, 2.0, &mut a);
        for j in 0..2 {
            let mut u = [0.3, -0.7];
            let base = predict(u);
            u[j] += 1.0;
            assert!((predict(u) - base - a[j] / 2.0).abs() < 1e-12);
        }
    }
}
