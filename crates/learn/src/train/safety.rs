//! The learning-safety record of a training run (`docs/learner.md`, "Safe learning"): the
//! largest change of the command between consecutive on-policy commands, over the whole run and
//! per bin of simulated time, so that a report can draw it over training time next to the
//! analytical controller's level.

use crate::eval::max_abs_diff;
use serde::{Deserialize, Serialize};

/// Length of a bin of the command-step curve (simulated seconds).
pub const STEP_BIN_SECONDS: f64 = 15.0;

/// The largest on-policy command step within one bin of simulated time.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct StepPoint {
    /// Simulated training minutes at the end of the bin.
    pub minutes: f64,
    /// Largest per-joint change of the command between two consecutive on-policy commands in
    /// the bin (N·m).
    pub max_command_step: f64,
}

/// Follows the commands sent in the on-policy phase. Allocation-free after construction.
#[derive(Clone, Debug)]
pub(crate) struct StepMonitor {
    last: Vec<f64>,
    has_last: bool,
    /// Largest step of the run so far (N·m).
    pub max_step: f64,
    bin_steps: u64,
    bin_max: f64,
    bin_used: bool,
    pub curve: Vec<StepPoint>,
}

impl StepMonitor {
    /// A monitor for `n` joints at control period `dt` (s).
    pub fn new(n: usize, dt: f64) -> Self {
        Self {
            last: vec![0.0; n],
            has_last: false,
            max_step: 0.0,
            bin_steps: ((STEP_BIN_SECONDS / dt).round() as u64).max(1),
            bin_max: 0.0,
            bin_used: false,
            curve: Vec::new(),
        }
    }

    /// Records an on-policy command `u` (the first one of the run has no step).
    pub fn sent(&mut self, u: &[f64]) {
        if self.has_last {
            let d = max_abs_diff(&self.last, u);
            self.max_step = self.max_step.max(d);
            self.bin_max = self.bin_max.max(d);
            self.bin_used = true;
        }
        self.last.copy_from_slice(u);
        self.has_last = true;
    }

    /// The first joint `j` that `u` moves by more than `limits[j]` (N·m) from the last command
    /// sent, if any.
    pub fn jump(&self, u: &[f64], limits: &[f64]) -> Option<usize> {
        if !self.has_last {
            return None;
        }
        u.iter()
            .zip(&self.last)
            .zip(limits)
            .position(|((a, b), l)| (a - b).abs() > *l)
    }

    /// Moves each joint of `u` to within `limit` (N·m) of the last command sent; whether any
    /// joint moved.
    pub fn limit_step(&self, u: &mut [f64], limit: f64) -> bool {
        if !self.has_last {
            return false;
        }
        let mut limited = false;
        for (v, l) in u.iter_mut().zip(&self.last) {
            let c = v.clamp(l - limit, l + limit);
            limited |= c != *v;
            *v = c;
        }
        limited
    }

    /// The last command sent, into `u` (unchanged if none was).
    pub fn repeat_last(&self, u: &mut [f64]) {
        if self.has_last {
            u.copy_from_slice(&self.last);
        }
    }

    /// After control step `steps` of the run (`per_min` steps a minute): closes a bin at its end.
    pub fn tick(&mut self, steps: u64, per_min: u64) {
        if steps.is_multiple_of(self.bin_steps) {
            self.close(steps, per_min);
        }
    }

    /// Closes the current bin, if it saw an on-policy step (at the end of the run, too).
    pub fn close(&mut self, steps: u64, per_min: u64) {
        if self.bin_used {
            self.curve.push(StepPoint {
                minutes: steps as f64 / per_min as f64,
                max_command_step: self.bin_max,
            });
        }
        self.bin_max = 0.0;
        self.bin_used = false;
    }
}

#[cfg(test)]
mod tests {
    use super::StepMonitor;

    /// The overall and per-bin maxima follow their definitions; bins without on-policy
    /// commands are not drawn.
    #[test]
    fn steps_are_binned_by_simulated_time() {
        // 15 s bins at dt = 5 s: three steps per bin, 12 steps per minute.
        let mut m = StepMonitor::new(2, 5.0);
        let mut steps = 0;
        // Babbling: nothing sent on-policy, no bin drawn.
        for _ in 0..3 {
            steps += 1;
            m.tick(steps, 12);
        }
        for u in [[0.0, 1.0], [0.5, 1.0], [0.5, 0.2]] {
            m.sent(&u);
            steps += 1;
            m.tick(steps, 12);
        }
        m.sent(&[0.6, 0.2]);
        steps += 1;
        m.close(steps, 12);
        assert_eq!(m.curve.len(), 2, "{:?}", m.curve);
        assert!((m.curve[0].minutes - 0.5).abs() < 1e-12);
        assert!((m.curve[0].max_command_step - 0.8).abs() < 1e-12);
        assert!((m.curve[1].max_command_step - 0.1).abs() < 1e-12);
        assert!((m.max_step - 0.8).abs() < 1e-12);
    }

    /// `limit_step` moves every joint to within the limit of the last command sent (and says
    /// so), leaves a command within it unchanged, and does nothing before the first command.
    #[test]
    fn a_limited_step_never_exceeds_its_bound() {
        let mut m = StepMonitor::new(2, 0.002);
        let mut u = [5.0, -5.0];
        assert!(!m.limit_step(&mut u, 0.03));
        assert_eq!(u, [5.0, -5.0]);
        m.sent(&u);
        let mut v = [5.5, -5.01];
        assert!(m.limit_step(&mut v, 0.03));
        assert!((v[0] - 5.03).abs() < 1e-12 && v[1] == -5.01, "{v:?}");
        m.sent(&v);
        let mut w = [5.04, -5.0];
        assert!(!m.limit_step(&mut w, 0.03));
        assert_eq!(w, [5.04, -5.0]);
    }
}
