//! The interface every task-space controller offers to the closed-loop driver.

use crate::error::Result;
use crate::trajectory::Target;
use osrl_dynamics::Measurement;

/// A controller that turns a measurement and a desired task state into joint torques. The
/// analytical [`crate::Osc`] implements it; so can a learned controller (it sees only the
/// measurement, never the robot's model).
pub trait TaskController {
    /// The command `u` (N·m, one per joint) for measurement `meas` and desired state `target`
    /// (world frame; the controller reads its task axes). An error leaves the robot untouched
    /// (the driver stops).
    fn command(&mut self, meas: &Measurement, target: &Target, u: &mut [f64]) -> Result<()>;
}

impl<C: TaskController + ?Sized> TaskController for &mut C {
    fn command(&mut self, meas: &Measurement, target: &Target, u: &mut [f64]) -> Result<()> {
        (**self).command(meas, target, u)
    }
}
