//! One learning step and one command of the [`Learner`](super::Learner).

use super::Learner;
use crate::config::{CostKind, ExplorationKind};
use crate::error::{LearnError, Result};
use lwpr::RfEvent;
use osrl_dynamics::Measurement;
use rand::Rng;
use rand_distr::{Distribution, StandardNormal};

/// What produced a command.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CommandSource {
    /// The blend of the trained local controllers (eq. 34).
    Learned,
    /// No trained controller active above the cutoff: the blend of the nearest ones (any
    /// activation above 1e-12).
    Extrapolated,
    /// No trained controller anywhere near: the nominal `u0`.
    Fallback,
}

/// Activation cutoff of the extrapolating blend.
const EXTRAPOLATION_CUTOFF: f64 = 1e-12;

impl Learner {
    /// The nominal behaviour `u0 = ĝ(q) − K_Dq q̇ − K_Pq (q − q_rest)` into `u0` (`ĝ = 0` until
    /// the gravity model has support). Once `ĝ` is frozen, the static gravity model gives `ĝ`
    /// where it has support. Returns whether `ĝ` had support.
    pub fn nominal(&mut self, q: &[f64], qd: &[f64], u0: &mut [f64]) -> Result<bool> {
        let from_static = match self.gravity_static.as_mut() {
            Some(g) if self.gravity_frozen => g.predict(q, u0)?,
            _ => false,
        };
        let known = from_static
            || match self.gravity.as_mut() {
                Some(g) => g.predict(q, u0)?,
                None => {
                    u0.fill(0.0);
                    false
                }
            };
        let nom = &self.cfg.nominal;
        for i in 0..self.n {
            u0[i] -= nom.kd[i] * qd[i] + nom.kp[i] * (q[i] - nom.q_rest[i]);
        }
        Ok(known)
    }

    /// The learned command (eq. 34) for the reference acceleration `xdd_ref` at `(q, q̇)` into `u`,
    /// plus Gaussian exploration noise of the blended `σ` when `rng` is given, clipped to the
    /// torque limits (counted). Falls back to `u0` (counted) where no trained local controller
    /// is active. Does not allocate.
    pub fn command<R: Rng + ?Sized>(
        &mut self,
        q: &[f64],
        qd: &[f64],
        xdd_ref: &[f64],
        rng: Option<&mut R>,
        u: &mut [f64],
    ) -> Result<CommandSource> {
        let mut source = self.unclipped_command(q, qd, xdd_ref, rng, u)?;
        // Guard: a non-finite blend (a diverged local model) falls back to u0, counted.
        if u.iter().any(|v| !v.is_finite()) {
            self.stats.non_finite += 1;
            source = self.fallback(q, qd, u)?;
            if u.iter().any(|v| !v.is_finite()) {
                return Err(LearnError::NonFinite("the nominal command u0"));
            }
        }
        let mut clipped = false;
        for (v, lim) in u.iter_mut().zip(&self.cfg.torque_limits) {
            let c = v.clamp(-lim, *lim);
            clipped |= c != *v;
            *v = c;
        }
        self.stats.clipped += clipped as u64;
        Ok(source)
    }

    /// [`Learner::command`] before the torque limits.
    fn unclipped_command<R: Rng + ?Sized>(
        &mut self,
        q: &[f64],
        qd: &[f64],
        xdd_ref: &[f64],
        rng: Option<&mut R>,
        u: &mut [f64],
    ) -> Result<CommandSource> {
        let (n, m) = (self.n, self.m);
        if q.len() != n || qd.len() != n || u.len() != n || xdd_ref.len() != m {
            return Err(LearnError::Dimension {
                what: "command arguments",
                expected: n,
                got: q.len(),
            });
        }
        self.stats.commands += 1;
        let cutoff = self.cfg.activation_cutoff;
        let Some(fwd) = self.forward.as_mut() else {
            return self.fallback(q, qd, u);
        };
        // φ = [ẍ_refᵀ, q̇ᵀ, (q − c_i)ᵀ, 1] (eq. 31, with the optional position features).
        let phi = &mut self.ws.phi;
        phi[..m].copy_from_slice(xdd_ref);
        phi[m..m + n].copy_from_slice(qd);
        let last = phi.len() - 1;
        phi[last] = 1.0;
        // Blend the trained controllers active above the cutoff; if there are none, those with
        // any activation at all (extrapolation from the nearest ones), counted.
        let mut source = CommandSource::Learned;
        let (mut sum_w, mut sigma) = (0.0, 0.0);
        for cut in [cutoff, EXTRAPOLATION_CUTOFF] {
            fwd.activations(q, qd, cut, &mut self.ws.acts)?;
            u.fill(0.0);
            for a in &self.ws.acts {
                let Some(local) = self.locals.map.get(&a.id) else {
                    continue;
                };
                if local.ess < self.cfg.min_ess {
                    continue;
                }
                if self.cfg.position_features {
                    for i in 0..n {
                        phi[m + n + i] = q[i] - local.center[i];
                    }
                }
                local.rwr.mean_into(phi, &mut self.ws.ui)?;
                for (o, v) in u.iter_mut().zip(&self.ws.ui) {
                    *o += a.w * v;
                }
                sum_w += a.w;
                sigma += a.w * local.rwr.sigma();
            }
            if sum_w > 0.0 {
                break;
            }
            source = CommandSource::Extrapolated;
        }
        if sum_w <= 0.0 {
            return self.fallback(q, qd, u);
        }
        if source == CommandSource::Extrapolated {
            self.stats.extrapolations += 1;
        }
        let sigma = self.cfg.exploration_scale * sigma / sum_w;
        for v in u.iter_mut() {
            *v /= sum_w;
        }
        if self.cfg.residual {
            let mut u0 = std::mem::take(&mut self.ws.u0);
            self.nominal(q, qd, &mut u0)?;
            for (v, o) in u.iter_mut().zip(&u0) {
                *v += o;
            }
            self.ws.u0 = u0;
        }
        if let Some(rng) = rng {
            let cap = self.cfg.exploration_cap;
            if self.cfg.exploration == ExplorationKind::NullSpace {
                // z ~ N(0, σ² I) projected onto the null space of Â: z − Âᵀ (Â Âᵀ)⁻¹ Â z.
                let known = blended_gain(&self.locals, &self.ws.acts, q, n, m, &mut self.ws.a_hat);
                let ws = &mut self.ws;
                let ns_cap = self.cfg.null_space_cap.unwrap_or(f64::INFINITY);
                for (z, scale) in ws.du.iter_mut().zip(&self.torque_scale) {
                    let s: f64 = StandardNormal.sample(rng);
                    *z = sigma.min(ns_cap * scale) * s;
                }
                if known && project_null(&ws.a_hat, &mut ws.du, m, &mut ws.y, &mut ws.s) {
                    for (v, z) in u.iter_mut().zip(&ws.du) {
                        *v += z;
                    }
                }
            }
            for (v, s) in u.iter_mut().zip(&self.torque_scale) {
                let z: f64 = StandardNormal.sample(rng);
                *v += sigma.min(cap * s) * z;
            }
        }
        Ok(source)
    }

    /// The nominal `u0` as the command where no trained controller is near (counted).
    fn fallback(&mut self, q: &[f64], qd: &[f64], u: &mut [f64]) -> Result<CommandSource> {
        self.stats.fallbacks += 1;
        self.nominal(q, qd, u)?;
        Ok(CommandSource::Fallback)
    }

    /// Once per second of learning (`prune_untrained_after`): removes from the partition the
    /// fields whose controller is not trained and that were idle for too long; their `Pruned`
    /// events then drop the controllers.
    fn prune_idle_untrained(&mut self) -> Result<()> {
        let (Some(after), Some(fwd)) = (self.cfg.prune_untrained_after, self.forward.as_mut())
        else {
            return Ok(());
        };
        let per_second = (1.0 / self.dt).round().max(1.0) as u64;
        let idle = (after / self.dt).ceil() as u64;
        let now = self.stats.samples;
        if !now.is_multiple_of(per_second) || now <= idle {
            return Ok(());
        }
        self.ws.stale.clear();
        self.locals
            .stale_untrained(self.cfg.min_ess, now - idle, &mut self.ws.stale);
        for id in &self.ws.stale {
            self.stats.pruned_untrained += fwd.remove(*id)? as u64;
        }
        Ok(())
    }

    /// Learning from a checked transition once the models exist.
    pub(crate) fn learn_ready(&mut self, prev: &Measurement, cur: &Measurement) -> Result<()> {
        let (n, m) = (self.n, self.m);
        let (q, qd, u) = (cur.q.as_slice(), cur.qd.as_slice(), cur.u.as_slice());
        self.stats.samples += 1;
        // Supervised models: gravity (inverse dynamics) and the forward model (the partition).
        let dt = cur.t - prev.t;
        if dt > 0.0 && !self.gravity_frozen {
            let g = self.gravity.as_mut().expect("models exist");
            g.learn(prev.q.as_slice(), prev.qd.as_slice(), q, qd, u, dt)?;
            if let Some(g) = self.gravity_static.as_mut() {
                g.learn(prev.q.as_slice(), prev.qd.as_slice(), q, qd, u, dt)?;
            }
        }
        let fwd = self.forward.as_mut().expect("models exist");
        if self
            .stats
            .samples
            .is_multiple_of(self.cfg.forward_every as u64)
        {
            fwd.learn(q, qd, u, cur.xdd.as_slice())?;
        }
        self.prune_idle_untrained()?;
        let fwd = self.forward.as_mut().expect("models exist");
        self.ws.events.clear();
        fwd.drain_events(&mut self.ws.events);
        // Follow the partition: new RFs get a controller, pruned ones lose theirs.
        let mut u0 = std::mem::take(&mut self.ws.u0);
        self.nominal(q, qd, &mut u0)?;
        let p = super::n_features(&self.cfg, n, m);
        let init: &[f64] = if self.cfg.residual {
            &self.ws.target[..0]
        } else {
            u
        };
        for k in 0..self.ws.events.len() {
            match self.ws.events[k] {
                RfEvent::Added {
                    id, copied_from, ..
                } => {
                    let fwd = self.forward.as_ref().expect("models exist");
                    let center = fwd.center(id).unwrap_or_else(|| [q, qd].concat());
                    self.locals.add(
                        id,
                        center,
                        copied_from,
                        init,
                        n,
                        m,
                        p,
                        &self.cfg.rwr,
                        self.cfg.min_ess,
                        crate::local::DynamicsSpec {
                            features: crate::local::dynamics_features(
                                n,
                                self.cfg.dynamics_bilinear,
                            ),
                            forgetting: self.cfg.dynamics_forgetting,
                        },
                    )?;
                    if let Some(l) = self.locals.map.get_mut(&id) {
                        l.last_active = self.stats.samples;
                    }
                }
                RfEvent::Pruned { id, .. } => self.locals.remove(id),
            }
        }
        // The cost of the executed command (N = I), full or its avoidable part.
        for i in 0..n {
            self.ws.du[i] = u[i] - u0[i];
            // The regression target: the command itself or its deviation from u0.
            self.ws.target[i] = if self.cfg.residual {
                self.ws.du[i]
            } else {
                u[i]
            };
        }
        self.ws.u0 = u0;
        // Hindsight sample φ = [ẍ_measured, q̇, (q − c), 1] → u (or u − u0), weighted by each
        // RF's activation.
        let fwd = self.forward.as_mut().expect("models exist");
        fwd.activations(q, qd, self.cfg.activation_cutoff, &mut self.ws.acts)?;
        let full: f64 = self.ws.du.iter().map(|v| v * v).sum();
        let known = blended_gain(&self.locals, &self.ws.acts, q, n, m, &mut self.ws.a_hat);
        // Hindsight null-space shrinkage of the target (κ = 0: the paper's relabelling).
        let kappa = self.cfg.null_space_shrink;
        if kappa > 0.0 && known && self.cfg.residual {
            let ws = &mut self.ws;
            ws.z.copy_from_slice(&ws.du);
            if project_null(&ws.a_hat, &mut ws.z, m, &mut ws.y, &mut ws.s) {
                for (t, z) in ws.target.iter_mut().zip(&ws.z) {
                    *t -= kappa * z;
                }
            }
        }
        let r = match self.cfg.cost {
            _ if !self.cfg.reward_weighting => 0.0,
            CostKind::Full => full,
            CostKind::NullSpace => {
                if known {
                    null_space_cost(
                        &self.ws.a_hat,
                        &self.ws.du,
                        m,
                        &mut self.ws.y,
                        &mut self.ws.s,
                    )
                    .unwrap_or(full)
                } else {
                    full
                }
            }
        };
        let phi = &mut self.ws.phi;
        phi[..m].copy_from_slice(cur.xdd.as_slice());
        phi[m..m + n].copy_from_slice(qd);
        let last = phi.len() - 1;
        phi[last] = 1.0;
        // Features of the local dynamics regression: [u, q̇, q − c, 1] → ẍ.
        let phi_d = &mut self.ws.phi_d;
        phi_d[..n].copy_from_slice(u);
        phi_d[n..2 * n].copy_from_slice(qd);
        phi_d[3 * n] = 1.0;
        let dyn_every = self.cfg.dynamics_every as u64;
        let dyn_now = self.stats.samples.is_multiple_of(dyn_every);
        for a in &self.ws.acts {
            let Some(local) = self.locals.map.get_mut(&a.id) else {
                continue;
            };
            local.last_active = self.stats.samples;
            if dyn_now {
                for i in 0..n {
                    phi_d[2 * n + i] = q[i] - local.center[i];
                }
                // Bilinear features u_j (q_k − c_k), if any.
                if phi_d.len() > 3 * n + 1 {
                    for j in 0..n {
                        for k in 0..n {
                            phi_d[3 * n + 1 + j * n + k] = u[j] * phi_d[2 * n + k];
                        }
                    }
                }
                local
                    .dynamics
                    .observe(phi_d, cur.xdd.as_slice(), 0.0, a.w)?;
            }
            if self.cfg.position_features {
                for i in 0..n {
                    phi[m + n + i] = q[i] - local.center[i];
                }
            }
            local.rwr.observe(phi, &self.ws.target, r, a.w)?;
            local.pending += 1;
            if local.pending >= self.cfg.update_every {
                local.pending = 0;
                if local.updates % self.cfg.dynamics_solve_every as u64 == 0
                    && local.dynamics.update().is_ok()
                {
                    local.dynamics_updates += 1;
                }
                match local.rwr.update() {
                    Ok(info) => {
                        local.ess = info.ess;
                        local.updates += 1;
                        self.stats.m_steps += 1;
                    }
                    Err(_) => self.stats.failed_m_steps += 1,
                }
            }
        }
        Ok(())
    }
}

/// `r_null = ‖du‖² − duᵀ Âᵀ (Â Âᵀ)⁻¹ Â du`, the part of `‖du‖²` in the null space of `Â` (m×n,
/// row-major). `None` if `Â Âᵀ` is not positive definite.
pub(crate) fn null_space_cost(
    a: &[f64],
    du: &[f64],
    m: usize,
    y: &mut [f64],
    s: &mut [f64],
) -> Option<f64> {
    if !gain_system(a, du, m, y, s) {
        return None;
    }
    // yᵀ S⁻¹ y = ‖L⁻¹ y‖², and y now holds L⁻¹ Â du.
    let quad: f64 = y[..m].iter().map(|v| v * v).sum();
    let full: f64 = du.iter().map(|v| v * v).sum();
    Some((full - quad).max(0.0))
}

/// `z ← z − Âᵀ (Â Âᵀ)⁻¹ Â z` (Â m×n row-major); `false` (z unchanged) if `Â Âᵀ` is singular.
pub(crate) fn project_null(
    a: &[f64],
    z: &mut [f64],
    m: usize,
    y: &mut [f64],
    s: &mut [f64],
) -> bool {
    if !gain_system(a, z, m, y, s) {
        return false;
    }
    // Back substitution: y ← L⁻ᵀ L⁻¹ Â z = S⁻¹ Â z.
    for k in (0..m).rev() {
        let mut v = y[k];
        for j in k + 1..m {
            v -= s[j * m + k] * y[j];
        }
        y[k] = v / s[k * m + k];
    }
    let n = z.len();
    for j in 0..n {
        z[j] -= (0..m).map(|k| a[k * n + j] * y[k]).sum::<f64>();
    }
    true
}

/// Forms `S = Â Âᵀ` (m×m) and `y = Â v`, factors `S = L Lᵀ` in place and sets `y ← L⁻¹ y`;
/// `false` if `S` is not positive definite.
fn gain_system(a: &[f64], v: &[f64], m: usize, y: &mut [f64], s: &mut [f64]) -> bool {
    let n = v.len();
    for k in 0..m {
        y[k] = (0..n).map(|j| a[k * n + j] * v[j]).sum();
        for l in 0..m {
            s[k * m + l] = (0..n).map(|j| a[k * n + j] * a[l * n + j]).sum();
        }
    }
    if !cholesky(s, m) {
        return false;
    }
    for k in 0..m {
        let mut w = y[k];
        for j in 0..k {
            w -= s[k * m + j] * y[j];
        }
        y[k] = w / s[k * m + k];
    }
    true
}

/// In-place Cholesky factor (lower triangle) of the small m×m matrix `s`; `false` if not
/// positive definite.
fn cholesky(s: &mut [f64], m: usize) -> bool {
    let scale = (0..m).map(|k| s[k * m + k]).fold(0.0, f64::max);
    for k in 0..m {
        let mut d = s[k * m + k];
        for j in 0..k {
            d -= s[k * m + j] * s[k * m + j];
        }
        if !(d > 1e-12 * scale) {
            return false;
        }
        let d = d.sqrt();
        s[k * m + k] = d;
        for i in k + 1..m {
            let mut v = s[i * m + k];
            for j in 0..k {
                v -= s[i * m + j] * s[k * m + j];
            }
            s[i * m + k] = v / d;
        }
    }
    true
}

/// `Â = Σ w_i Â_i / Σ w_i` (m×n row-major) over the active receptive fields whose local dynamics
/// regression has been fitted; `false` if there is none.
pub(crate) fn blended_gain(
    locals: &crate::local::LocalControllers,
    acts: &[lwpr::Activation],
    q: &[f64],
    n: usize,
    m: usize,
    a: &mut [f64],
) -> bool {
    a.fill(0.0);
    let mut sum_w = 0.0;
    for act in acts {
        let Some(local) = locals.map.get(&act.id) else {
            continue;
        };
        if local.dynamics_updates == 0 {
            continue;
        }
        let theta = local.dynamics.theta();
        // With bilinear features, Â(q) = Θ_u + Σ_k (q_k − c_k) Θ_{u_j q_k}.
        let bilinear = theta.nrows() > 3 * n + 1;
        for k in 0..m {
            for j in 0..n {
                let mut g = theta[(j, k)];
                if bilinear {
                    for i in 0..n {
                        g += (q[i] - local.center[i]) * theta[(3 * n + 1 + j * n + i, k)];
                    }
                }
                a[k * n + j] += act.w * g;
            }
        }
        sum_w += act.w;
    }
    if sum_w <= 0.0 {
        return false;
    }
    a.iter_mut().for_each(|v| *v /= sum_w);
    true
}

#[cfg(test)]
mod tests {
    use super::{null_space_cost, project_null};

    #[test]
    fn projection_removes_the_task_part_and_the_cost_is_its_complement() {
        // Â (2×3) and a vector: after the projection Â z = 0, and r_null(du) = ‖P du‖².
        let a = [1.0, -2.0, 0.5, 0.3, 0.7, -17.0];
        let du = [0.4, -1.1, 2.0];
        let (mut y, mut s) = ([0.0; 2], [0.0; 4]);
        let mut z = du;
        assert!(project_null(&a, &mut z, 2, &mut y, &mut s));
        for k in 0..2 {
            let az: f64 = (0..3).map(|j| a[k * 3 + j] * z[j]).sum();
            assert!(az.abs() < 1e-12, "Â z = {az}");
        }
        let p2: f64 = z.iter().map(|v| v * v).sum();
        let r = null_space_cost(&a, &du, 2, &mut y, &mut s).unwrap();
        assert!((r - p2).abs() < 1e-12, "{r} vs {p2}");
        // A rank-deficient Â is refused, leaving z unchanged.
        let flat = [1.0, 2.0, 3.0, 2.0, 4.0, 6.0];
        let mut z2 = du;
        assert!(!project_null(&flat, &mut z2, 2, &mut y, &mut s));
        assert_eq!(z2, du);
        assert!(null_space_cost(&flat, &du, 2, &mut y, &mut s).is_none());
    }
}
