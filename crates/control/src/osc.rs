//! The analytical operational space controllers: eq. 7 (corrected: the crate README, "Choices") for any
//! positive-definite metric `N`, and eq. 4 as its special case `N = M⁻¹`, `u0 = 0`.

use crate::config::{Law, MetricKind, OscConfig};
use crate::controller::TaskController;
use crate::damping::damping;
use crate::error::{check, ControlError, Result};
use crate::linalg::{cholesky_in_place, cholesky_solve_columns};
use crate::nominal::nominal_command;
use crate::reference::reference_acceleration;
use crate::trajectory::Target;
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};
use osrl_dynamics::{compute_all, Data, Measurement, Model};

/// What one command of [`Osc`] did at the singularity guard.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CommandInfo {
    /// Damping `λ²` that was added to `A Aᵀ` (0 away from singularities).
    pub lambda2: f64,
    /// `σ_min(A) / σ_max(A)`, the inverse condition number of `A = J M⁻¹ N^(−1/2)`.
    pub sigma_ratio: f64,
}

/// Preallocated buffers of one command.
#[derive(Clone, Debug)]
struct Workspace {
    data: Data,
    /// Cholesky factor of `M` (lower triangle).
    lm: DMatrix<f64>,
    /// `Bᵀ = M⁻¹ Jᵀ` (n×3; the first `m` columns are used).
    bt: DMatrix<f64>,
    /// `W = N⁻¹ Bᵀ` (n×3).
    w: DMatrix<f64>,
    /// `h − u0` (n).
    v: DVector<f64>,
}

/// An analytical operational space controller reading its own robot model (which may differ from
/// the simulated robot: see [`crate::ModelError`]). Create once; every command reuses the
/// preallocated workspace and does not allocate.
///
/// Eq. 7 minimises `(u − u0)ᵀ N (u − u0)` subject to `J M⁻¹ (u − h) + J̇ q̇ = ẍ_ref`. With
/// `N = L Lᵀ` (Cholesky; `N^(1/2) := Lᵀ`), `A = J M⁻¹ N^(−1/2)` and
/// `b = ẍ_ref − J̇ q̇ + J M⁻¹ h` its solution is
///
/// `u* = N^(−1/2) A⁺ b + N^(−1/2) (I − A⁺A) N^(1/2) u0`,
///
/// which does not depend on the choice of square root (the minimiser is unique). It is computed
/// in the equivalent weighted form `u* = u0 + N⁻¹ Bᵀ (B N⁻¹ Bᵀ + λ²I)⁻¹ (b − B u0)` with
/// `B = J M⁻¹` (since `N^(−1/2) Aᵀ = N⁻¹ Bᵀ` and `A Aᵀ = B N⁻¹ Bᵀ`), so no matrix square root is
/// ever formed; `λ²` comes from the damping rule [`damping`] (0 away from singularities). With
/// damping, `u*` minimises `‖J M⁻¹(u − h) + J̇q̇ − ẍ_ref‖² + λ² (u − u0)ᵀ N (u − u0)`.
/// For `N = M⁻¹` the weight is `N⁻¹ Bᵀ = Jᵀ` and with `u0 = 0` this is eq. 4,
/// `u = Jᵀ (J M⁻¹ Jᵀ)⁻¹ b`.
#[derive(Clone, Debug)]
pub struct Osc {
    model: Model,
    cfg: OscConfig,
    metric: MetricKind,
    /// Cholesky factor of a constant metric (0×0 otherwise).
    ln: DMatrix<f64>,
    ws: Workspace,
    u0: DVector<f64>,
    xdd_ref: [f64; 3],
    last: CommandInfo,
}

impl Osc {
    /// A controller for `model` with settings `cfg`. Fails on an invalid config, or a constant
    /// metric that is not n×n, not finite, not symmetric or not positive definite (its Cholesky
    /// factorisation fails).
    pub fn new(model: Model, cfg: OscConfig) -> Result<Self> {
        cfg.validate()?;
        let n = model.nq();
        let metric = match cfg.law {
            Law::Eq4 => MetricKind::InverseMass,
            Law::Eq7 => cfg.metric,
        };
        let ln = if metric == MetricKind::Matrix {
            metric_factor(&cfg.metric_matrix, n)?
        } else {
            DMatrix::zeros(0, 0)
        };
        let ws = Workspace {
            data: model.data(),
            lm: DMatrix::zeros(n, n),
            bt: DMatrix::zeros(n, 3),
            w: DMatrix::zeros(n, 3),
            v: DVector::zeros(n),
        };
        Ok(Self {
            model,
            cfg,
            metric,
            ln,
            ws,
            u0: DVector::zeros(n),
            xdd_ref: [0.0; 3],
            last: CommandInfo::default(),
        })
    }

    /// The controller's model.
    pub fn model(&self) -> &Model {
        &self.model
    }
    pub fn config(&self) -> &OscConfig {
        &self.cfg
    }
    /// Dynamics of the controller's model at the state of the last call.
    pub fn data(&self) -> &Data {
        &self.ws.data
    }
    /// Singularity guard of the last command.
    pub fn last_info(&self) -> CommandInfo {
        self.last
    }
    /// The nominal `u0` of the last [`TaskController::command`] (zeros for eq. 4).
    pub fn last_u0(&self) -> &[f64] {
        self.u0.as_slice()
    }

    /// The nominal behaviour `u0 = g(q) − s (K_Dq q̇ + K_Pq (q − q_rest))` (eq. 6 plus gravity, the
    /// model's `g`) into `u0`. Fails on a wrong length or a non-finite state.
    pub fn nominal(&mut self, q: &[f64], qd: &[f64], u0: &mut [f64]) -> Result<()> {
        out_len(u0, self.model.nq())?;
        check("qd", qd, self.model.nq())?;
        let g = osrl_dynamics::gravity(&self.model, &mut self.ws.data, q)?;
        nominal_command(&self.model, self.cfg.nominal_scale, g.as_slice(), q, qd, u0);
        Ok(())
    }

    /// The eq. 7 command `u*` (N·m) for the metric of the config, at state `(q, q̇)`, for the
    /// reference acceleration `xdd_ref` (m/s², one entry per task axis) and nominal `u0` (N·m; pass
    /// zeros for eq. 4). Fails — leaving `u` unchanged — on wrong lengths, non-finite inputs, a
    /// mass matrix that is not positive definite, or a singular task system with damping off.
    pub fn solve(
        &mut self,
        q: &[f64],
        qd: &[f64],
        xdd_ref: &[f64],
        u0: &[f64],
        u: &mut [f64],
    ) -> Result<CommandInfo> {
        let (n, m) = (self.model.nq(), self.model.task_dim());
        check("xdd_ref", xdd_ref, m)?;
        check("u0", u0, n)?;
        out_len(u, n)?;
        compute_all(&self.model, &mut self.ws.data, q, qd)?;
        self.solve_loaded(xdd_ref, u0, u)
    }

    fn solve_loaded(&mut self, xdd_ref: &[f64], u0: &[f64], u: &mut [f64]) -> Result<CommandInfo> {
        let info = eq7(
            &self.model,
            self.metric,
            &self.ln,
            self.cfg.damping_threshold,
            &mut self.ws,
            xdd_ref,
            u0,
            u,
        )?;
        self.last = info;
        Ok(info)
    }
}

fn out_len(u: &[f64], n: usize) -> Result<()> {
    if u.len() == n {
        Ok(())
    } else {
        Err(ControlError::Dimension {
            what: "u",
            expected: n,
            got: u.len(),
        })
    }
}

impl TaskController for Osc {
    /// Eq. 2 from the measured task state and `target`, `u0` from [`Osc::nominal`] (eq. 7) or 0
    /// (eq. 4), then [`Osc::solve`]; reads `q, q̇, x, ẋ` of the measurement.
    fn command(&mut self, meas: &Measurement, target: &Target, u: &mut [f64]) -> Result<()> {
        let (n, m) = (self.model.nq(), self.model.task_dim());
        let (q, qd) = (meas.q.as_slice(), meas.qd.as_slice());
        check("x", meas.x.as_slice(), m)?;
        check("xd", meas.xd.as_slice(), m)?;
        out_len(u, n)?;
        compute_all(&self.model, &mut self.ws.data, q, qd)?;
        let axes = self.model.spec().task_axes.as_slice();
        let xr = &mut self.xdd_ref[..m];
        reference_acceleration(
            &self.cfg.gains,
            target,
            axes,
            meas.x.as_slice(),
            meas.xd.as_slice(),
            xr,
        );
        match self.cfg.law {
            Law::Eq4 => self.u0.fill(0.0),
            Law::Eq7 => {
                let g = self.ws.data.g.as_slice();
                let u0 = self.u0.as_mut_slice();
                nominal_command(&self.model, self.cfg.nominal_scale, g, q, qd, u0);
            }
        }
        let info = eq7(
            &self.model,
            self.metric,
            &self.ln,
            self.cfg.damping_threshold,
            &mut self.ws,
            &self.xdd_ref[..m],
            self.u0.as_slice(),
            u,
        )?;
        self.last = info;
        Ok(())
    }
}

/// Cholesky factor of a constant metric given as rows; checks size, finiteness, symmetry and
/// definiteness.
fn metric_factor(rows: &[Vec<f64>], n: usize) -> Result<DMatrix<f64>> {
    let bad = |m: String| Err(ControlError::MetricNotPositiveDefinite(m));
    if rows.len() != n || rows.iter().any(|r| r.len() != n) {
        return bad(format!("metric_matrix must be {n}×{n}"));
    }
    let nm = DMatrix::from_fn(n, n, |i, j| rows[i][j]);
    if nm.iter().any(|v| !v.is_finite()) {
        return bad("metric_matrix has a non-finite entry".into());
    }
    if (&nm - nm.transpose()).amax() > 1e-9 * nm.amax().max(1e-300) {
        return bad("metric_matrix is not symmetric".into());
    }
    let mut l = nm;
    match cholesky_in_place(&mut l) {
        Ok(()) => Ok(l),
        Err(k) => bad(format!("Cholesky factorisation fails at pivot {k}")),
    }
}

/// The eq. 7 solve on dynamics already in `ws.data` (see [`Osc`] for the maths).
#[allow(clippy::too_many_arguments)]
fn eq7(
    model: &Model,
    metric: MetricKind,
    ln: &DMatrix<f64>,
    threshold: f64,
    ws: &mut Workspace,
    xdd_ref: &[f64],
    u0: &[f64],
    u: &mut [f64],
) -> Result<CommandInfo> {
    let (n, axes) = (model.nq(), model.task_axes());
    let m = axes.len();
    let d = &ws.data;
    ws.lm.copy_from(&d.mass);
    cholesky_in_place(&mut ws.lm).map_err(ControlError::MassNotPositiveDefinite)?;
    // Bᵀ = M⁻¹ Jᵀ, column k from the task row axes[k] of the world Jacobian.
    for (k, &a) in axes.iter().enumerate() {
        for i in 0..n {
            ws.bt[(i, k)] = d.jac[(a, i)];
        }
    }
    cholesky_solve_columns(&ws.lm, &mut ws.bt, m);
    // W = N⁻¹ Bᵀ.
    match metric {
        MetricKind::Identity => ws.w.copy_from(&ws.bt),
        MetricKind::Mass => {
            ws.w.copy_from(&ws.bt);
            cholesky_solve_columns(&ws.lm, &mut ws.w, m);
        }
        MetricKind::InverseMass => {
            for (k, &a) in axes.iter().enumerate() {
                for i in 0..n {
                    ws.w[(i, k)] = d.jac[(a, i)];
                }
            }
        }
        MetricKind::Matrix => {
            ws.w.copy_from(&ws.bt);
            cholesky_solve_columns(ln, &mut ws.w, m);
        }
    }
    // G = B N⁻¹ Bᵀ = A Aᵀ, and r = b − B u0 = ẍ_ref − J̇q̇ + B (h − u0).
    for (v, (h, u0)) in ws.v.iter_mut().zip(d.h.iter().zip(u0)) {
        *v = h - u0;
    }
    let mut g = Matrix3::zeros();
    let mut r = Vector3::zeros();
    for k in 0..m {
        for l in 0..=k {
            let mut s = 0.0;
            for i in 0..n {
                s += ws.bt[(i, k)] * ws.w[(i, l)];
            }
            g[(k, l)] = s;
            g[(l, k)] = s;
        }
        let mut s = xdd_ref[k] - d.jdot_qd[axes[k]];
        for i in 0..n {
            s += ws.bt[(i, k)] * ws.v[i];
        }
        r[k] = s;
    }
    let (lambda2, sigma_ratio) = damping(&g, m, threshold);
    for k in 0..3 {
        g[(k, k)] = if k < m { g[(k, k)] + lambda2 } else { 1.0 };
    }
    let Some(chol) = g.cholesky() else {
        return Err(ControlError::Singular(format!(
            "A Aᵀ + λ²I is not positive definite (σ_min/σ_max = {sigma_ratio:.2e}, λ² = {lambda2:.2e})"
        )));
    };
    let y = chol.solve(&r);
    // u = u0 + W y, assembled in the scratch vector so that a failure leaves `u` unchanged.
    for (i, v) in ws.v.iter_mut().enumerate() {
        *v = u0[i] + (0..m).map(|k| ws.w[(i, k)] * y[k]).sum::<f64>();
    }
    if ws.v.iter().any(|v| !v.is_finite()) {
        return Err(ControlError::Singular(format!(
            "the command is not finite (σ_min/σ_max = {sigma_ratio:.2e}, λ² = {lambda2:.2e})"
        )));
    }
    u.copy_from_slice(ws.v.as_slice());
    Ok(CommandInfo {
        lambda2,
        sigma_ratio,
    })
}
