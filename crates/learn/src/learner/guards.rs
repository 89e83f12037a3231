//! The guards on every command sent: the torque limits and the torque-rate limit.

/// Limits the change of each joint's command between consecutive commands to `rate · dt`
/// (N·m), against the last command it let through. Allocation-free after construction.
#[derive(Clone, Debug, PartialEq)]
pub struct RateLimiter {
    /// Largest change per command of each joint (N·m).
    steps: Vec<f64>,
    prev: Vec<f64>,
    has_prev: bool,
}

impl RateLimiter {
    /// A limiter for one joint per entry of `rates` (N·m/s) at control period `dt` s, with no
    /// previous command (the first command passes unchanged).
    pub fn new(rates: &[f64], dt: f64) -> Self {
        Self {
            steps: rates.iter().map(|r| r * dt).collect(),
            prev: vec![0.0; rates.len()],
            has_prev: false,
        }
    }

    /// New per-joint limits (N·m/s) at period `dt` s; the last command is kept.
    pub fn set_rates(&mut self, rates: &[f64], dt: f64) {
        for (s, r) in self.steps.iter_mut().zip(rates) {
            *s = r * dt;
        }
    }

    /// The largest change per command of each joint (N·m).
    #[cfg(test)]
    pub fn steps(&self) -> &[f64] {
        &self.steps
    }

    /// Sets the command last sent (`None`: forget it, so the next command passes unchanged).
    pub fn reset(&mut self, prev: Option<&[f64]>) {
        match prev {
            Some(p) => {
                self.prev.copy_from_slice(p);
                self.has_prev = true;
            }
            None => self.has_prev = false,
        }
    }

    /// Sets the command last sent to `prev`, each joint clamped to `±limits`.
    pub fn reset_within(&mut self, prev: &[f64], limits: &[f64]) {
        for ((p, v), l) in self.prev.iter_mut().zip(prev).zip(limits) {
            *p = v.clamp(-l, *l);
        }
        self.has_prev = true;
    }

    /// Moves `u` to within the limit of the previous command, remembers it, and returns
    /// whether any joint was limited.
    pub fn apply(&mut self, u: &mut [f64]) -> bool {
        let mut limited = false;
        if self.has_prev {
            for ((v, p), s) in u.iter_mut().zip(&self.prev).zip(&self.steps) {
                let c = v.clamp(p - s, p + s);
                limited |= c != *v;
                *v = c;
            }
        }
        self.prev.copy_from_slice(u);
        self.has_prev = true;
        limited
    }
}

#[cfg(test)]
mod tests {
    use super::RateLimiter;

    #[test]
    fn consecutive_commands_change_by_at_most_the_rate_times_the_period() {
        let mut r = RateLimiter::new(&[1000.0; 2], 0.002);
        let mut u = [5.0, -3.0];
        assert!(!r.apply(&mut u));
        assert_eq!(u, [5.0, -3.0]);
        let mut v = [9.0, -3.5];
        assert!(r.apply(&mut v));
        assert_eq!(v, [7.0, -3.5]);
        let mut w = [7.5, -3.5];
        assert!(!r.apply(&mut w));
        r.reset(None);
        let mut x = [-100.0, 100.0];
        assert!(!r.apply(&mut x));
        r.reset(Some(&[0.0, 0.0]));
        assert!(r.apply(&mut x));
        assert_eq!(x, [-2.0, 2.0]);
    }
}
