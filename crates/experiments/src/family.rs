//! Training over a family of paths and evaluating on held-out ones (`docs/family.md`, E9): the
//! family sampler of a set-up, its paths as the training driver's path source, and the
//! evaluation of a learned controller on any drawn path.

use crate::error::Result;
use crate::Setup;
use osrl_control::family::{FamilyPath, FamilySampler};
use osrl_control::{Trajectory, TrajectoryConfig, TrajectoryKind};
use osrl_dynamics::Model;
use osrl_learn::eval::{EvalResult, Evaluator};
use osrl_learn::train::PathSource;
use osrl_learn::{LearnError, Learner};

/// The seed of the held-out paths (E9, `osrl eval` examples): no training run draws its family
/// with it (training draws with its training seed, 0, 1, 2, …).
pub const HELD_OUT_SEED: u64 = 0x27_0000_0000;

/// The seed of the validation paths ([`validation`]): neither a training seed nor
/// [`HELD_OUT_SEED`].
pub const VALIDATION_SEED: u64 = 0x27_5000_0000;

/// The family's drawn paths, approached from home, one per episode.
pub struct FamilySource(pub FamilySampler);

impl PathSource for FamilySource {
    fn next_path(&mut self) -> osrl_learn::Result<Trajectory> {
        self.0.next_training_path().map_err(LearnError::Control)
    }
}

impl Setup {
    /// The family of this set-up's `[trajectory]`: itself when `kind = "family"`, otherwise
    /// the default family around its figure-8 (the same centre, plane and size).
    pub fn family_config(&self) -> TrajectoryConfig {
        let mut cfg = self.trajectory_config().clone();
        if cfg.kind != TrajectoryKind::Family {
            cfg.kind = TrajectoryKind::Family;
        }
        cfg
    }

    /// A sampler of [`Setup::family_config`] on this robot from this home, seeded with `seed`.
    ///
    /// # Errors
    /// A family config out of range.
    pub fn family_sampler(&self, seed: u64) -> Result<FamilySampler> {
        Ok(FamilySampler::new(
            self.model(),
            &self.family_config(),
            self.home(),
            seed,
        )?)
    }

    /// `n` paths of the family drawn with `seed` ([`HELD_OUT_SEED`] for held-out ones).
    ///
    /// # Errors
    /// As [`FamilySampler::draw`].
    pub fn draw_paths(&self, n: usize, seed: u64) -> Result<Vec<FamilyPath>> {
        let mut s = self.family_sampler(seed)?;
        (0..n).map(|_| Ok(s.draw()?)).collect()
    }

    /// Evaluates `learner` on `truth` along `path` as training runs it: from rest at this
    /// set-up's home, behind the approach to the path's start (not evaluated), then
    /// [`Setup::eval_periods`] periods after a warm-up one, with this set-up's task gains. (From
    /// rest on the path's own start instead, as `osrl eval --config` starts, a redundant arm
    /// starts in the null-space posture eq. 7 settles in there, which training need not have
    /// visited.)
    ///
    /// # Errors
    /// As [`Evaluator::evaluate`].
    pub fn evaluate_path(
        &self,
        truth: &Model,
        learner: &mut Learner,
        path: &FamilyPath,
    ) -> Result<EvalResult> {
        let mut ev = Evaluator::new(
            truth.clone(),
            self.sim().clone(),
            path.approached.clone(),
            self.home().to_vec(),
            self.train_config().gains,
            self.eval_periods(),
        )?;
        Ok(ev.evaluate(learner)?)
    }
}

/// E9's held-out paths of `setup`'s family: `per_kind` of each kind of the family, drawn with
/// [`HELD_OUT_SEED`] (plus the kind's index), each from its own sampler.
///
/// # Errors
/// As [`FamilySampler::draw`].
pub fn held_out(setup: &Setup, per_kind: usize) -> Result<Vec<FamilyPath>> {
    drawn_per_kind(setup, per_kind, HELD_OUT_SEED)
}

/// Validation paths: drawn as [`held_out`]'s, with [`VALIDATION_SEED`] in place of
/// [`HELD_OUT_SEED`], so that a setting can be chosen on them without looking at the held-out
/// paths (`docs/family.md`).
///
/// # Errors
/// As [`FamilySampler::draw`].
pub fn validation(setup: &Setup, per_kind: usize) -> Result<Vec<FamilyPath>> {
    drawn_per_kind(setup, per_kind, VALIDATION_SEED)
}

/// `per_kind` paths of each kind of `setup`'s family, the kind `i`'s drawn with `seed + i`.
fn drawn_per_kind(setup: &Setup, per_kind: usize, seed: u64) -> Result<Vec<FamilyPath>> {
    let base = setup.family_config();
    let mut paths = Vec::new();
    for (i, kind) in base.family.kinds.iter().enumerate() {
        let mut cfg = base.clone();
        cfg.family.kinds = vec![*kind];
        let seed = seed + i as u64;
        let mut s = FamilySampler::new(setup.model(), &cfg, setup.home(), seed)?;
        for _ in 0..per_kind {
            paths.push(s.draw()?);
        }
    }
    Ok(paths)
}

/// A short description of a drawn path: kind, size, speed and centre.
pub fn label(p: &FamilyPath) -> String {
    let c = &p.config;
    let centre = c
        .centre
        .map(|x| format!(" at ({:.2}, {:.2}, {:.2}) m", x[0], x[1], x[2]))
        .unwrap_or_default();
    match c.kind {
        TrajectoryKind::Circle => format!(
            "circle r {:.0} mm, {:.1} s{centre}",
            1e3 * c.radius.unwrap_or(0.0),
            c.period
        ),
        TrajectoryKind::MinJerk => format!(
            "min-jerk {} points, {:.1} s moves",
            c.points.len(),
            c.move_time
        ),
        _ => format!(
            "figure-8 {:.0}×{:.0} mm, {:.1} s{centre}",
            2e3 * c.a.unwrap_or(0.0),
            2e3 * c.b.unwrap_or(0.0),
            c.period
        ),
    }
}
