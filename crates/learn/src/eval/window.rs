//! The sums of an evaluation window and the metrics they give (`docs/learner.md`, "Evaluation").

use super::result::EvalResult;

/// Sums of one evaluation window.
pub(super) struct Acc {
    pub count: usize,
    e2: f64,
    emax: f64,
    du2: f64,
    c_l: f64,
    c_s: f64,
    pub null2: f64,
    pub nom2: f64,
    pub nom_null2: f64,
    pub gain_err: f64,
    pub gain_count: usize,
    pub floor_null2: f64,
    pub floor_count: usize,
    fall: usize,
    learned: usize,
    s1: Vec<f64>,
    s2: Vec<f64>,
}

impl Acc {
    pub fn new(n: usize) -> Self {
        Self {
            count: 0,
            e2: 0.0,
            emax: 0.0,
            du2: 0.0,
            c_l: 0.0,
            c_s: 0.0,
            null2: 0.0,
            nom2: 0.0,
            nom_null2: 0.0,
            gain_err: 0.0,
            gain_count: 0,
            floor_null2: 0.0,
            floor_count: 0,
            fall: 0,
            learned: 0,
            s1: vec![0.0; n],
            s2: vec![0.0; n],
        }
    }

    /// One step: task error `e` (m), whether the command fell back to `u0` or came from the
    /// trained fields (`learned`), the learned, optimal and nominal commands.
    pub fn add(
        &mut self,
        e: f64,
        (fallback, learned): (bool, bool),
        u: &[f64],
        u_star: &[f64],
        u0: &[f64],
    ) {
        self.count += 1;
        self.learned += learned as usize;
        self.e2 += e * e;
        self.emax = self.emax.max(e);
        self.fall += fallback as usize;
        for i in 0..u.len() {
            self.du2 += (u[i] - u_star[i]).powi(2);
            self.c_l += (u[i] - u0[i]).powi(2);
            self.c_s += (u_star[i] - u0[i]).powi(2);
            self.s1[i] += u_star[i];
            self.s2[i] += u_star[i] * u_star[i];
        }
    }

    pub fn result(&self, step_l: f64, step_a: f64, diverged: bool) -> EvalResult {
        let c = self.count.max(1) as f64;
        let var: f64 = (0..self.s1.len())
            .map(|i| self.s2[i] / c - (self.s1[i] / c).powi(2))
            .sum::<f64>()
            .max(1e-12);
        EvalResult {
            tracking_rms_mm: 1e3 * (self.e2 / c).sqrt(),
            tracking_max_mm: 1e3 * self.emax,
            command_nmse: self.du2 / c / var,
            command_cost_ratio: self.c_l / self.c_s.max(1e-12),
            command_nmse_null: self.null2 / c / var,
            nominal_nmse: self.nom2 / c / var,
            nominal_nmse_null: self.nom_null2 / c / var,
            u_star_variance: var,
            u_star_cost: self.c_s / c,
            gain_error: self.gain_err / self.gain_count.max(1) as f64,
            floor_nmse_null: self.floor_null2 / self.floor_count.max(1) as f64 / var,
            fallback_share: self.fall as f64 / c,
            support_share: self.learned as f64 / c,
            max_command_step: step_l,
            max_command_step_analytical: step_a,
            diverged,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Acc;

    /// The metrics of a window from its definition, on two steps by hand.
    #[test]
    fn window_metrics_follow_their_definitions() {
        let mut acc = Acc::new(2);
        acc.add(0.003, (false, true), &[1.0, 2.0], &[1.5, 2.0], &[0.0, 0.0]);
        acc.add(0.004, (true, false), &[3.0, 1.0], &[2.5, 1.0], &[1.0, 0.0]);
        let r = acc.result(0.7, 0.2, false);
        assert!((r.tracking_rms_mm - (12.5f64).sqrt()).abs() < 1e-12);
        assert!((r.tracking_max_mm - 4.0).abs() < 1e-12);
        // var(u*) = var(1.5, 2.5) + var(2, 1) = 0.25 + 0.25; mean ‖u − u*‖² = 0.25.
        assert!((r.command_nmse - 0.5).abs() < 1e-12, "{}", r.command_nmse);
        // Σ ‖u − u0‖² = 5 + 5 over Σ ‖u* − u0‖² = 6.25 + 3.25.
        assert!((r.command_cost_ratio - 10.0 / 9.5).abs() < 1e-12);
        assert_eq!((r.fallback_share, r.support_share), (0.5, 0.5));
        assert_eq!(
            (r.max_command_step, r.max_command_step_analytical),
            (0.7, 0.2)
        );
        assert!(!r.diverged);
    }
}
