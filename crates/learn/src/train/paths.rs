//! Where the on-policy episodes' paths come from: the one task path, or a source that draws a
//! new path for each episode (a family of paths, `docs/family.md`). The source may read a model
//! to check its paths (it is the task's description, like the evaluation); the training driver
//! only runs them.

use crate::error::{LearnError, Result};
use osrl_control::Trajectory;

/// A source of one path per on-policy episode. Every path must start where the task path
/// starts (home's task point; the driver refuses any other), at rest.
pub trait PathSource {
    /// The path of the next episode.
    ///
    /// # Errors
    /// The source's failure (e.g. no path passed its checks).
    fn next_path(&mut self) -> Result<Trajectory>;
}

/// Checks that `path` starts at `start` on the task axes `axes` (within 1 µm).
pub(super) fn check_start(path: &Trajectory, start: &Trajectory, axes: &[usize]) -> Result<()> {
    let (a, b) = (path.start(), start.start());
    let off = axes
        .iter()
        .map(|&k| (a[k] - b[k]).abs())
        .fold(0.0, f64::max);
    if off <= 1e-6 {
        Ok(())
    } else {
        Err(LearnError::InvalidConfig(format!(
            "an episode's path starts {:.1} mm away from home's task point: every drawn path \
             must start there",
            off * 1e3
        )))
    }
}
