//! What a training run reports while it runs: its phase and progress, to an observer (progress
//! bars, logs and plots stay with the caller).

use crate::eval::EvalResult;
use serde::{Deserialize, Serialize};
use std::fmt;

/// The phase of a training run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Phase {
    /// Motor babbling under joint PD control.
    #[serde(rename = "babbling")]
    Babbling,
    /// Learning while tracking the task with the learned controller.
    #[serde(rename = "on-policy")]
    OnPolicy,
}

impl fmt::Display for Phase {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Phase::Babbling => "babbling",
            Phase::OnPolicy => "on-policy",
        })
    }
}

/// What the observer sees after each evaluation and at the end of each episode.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Progress {
    pub sim_minutes: f64,
    pub phase: Phase,
    pub n_local_models: usize,
    pub n_trained: usize,
    pub episodes: u64,
    pub aborted_episodes: u64,
    /// Episodes ended early (braked) on a growing task error or a command jump (see
    /// [`CurriculumConfig::brake_error`](super::CurriculumConfig::brake_error) and `brake_step`).
    #[serde(default)]
    pub braked_episodes: u64,
    /// Of the braked episodes, those braked because a command would have jumped by more than
    /// `brake_step` (the rest braked on the task error).
    #[serde(default)]
    pub braked_on_step: u64,
    /// Last evaluation result, if any.
    pub eval: Option<EvalResult>,
    /// Largest change of the commanded torque between two consecutive on-policy steps (N·m).
    pub max_command_step: f64,
    /// The curriculum's stage (index into `curriculum.stages`) and the last episode, if any.
    #[serde(default)]
    pub stage: usize,
    #[serde(default)]
    pub last_episode: Option<EpisodeReport>,
}

/// How an on-policy episode went.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct EpisodeReport {
    /// Simulated seconds it ran, and whether it was aborted or braked.
    pub seconds: f64,
    pub aborted: bool,
    #[serde(default)]
    pub braked: bool,
    /// RMS of the task error over it (m), and its stage `[amplitude, speed]`.
    pub rms_error: f64,
    pub stage: [f64; 2],
}

/// How an on-policy episode ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum EpisodeOutcome {
    /// Ran to the end of its path (or of the run).
    Completed,
    /// Braked on the task error (`curriculum.brake_error`).
    BrakedOnError,
    /// Braked on a refused command jump (`curriculum.brake_step`).
    BrakedOnStep,
    /// Aborted at `reset_error`.
    Aborted,
}

/// One on-policy episode in the run's log (`TrainSummary::episode_log`, the training JSON's
/// `episode_log`): when it started, at which curriculum stage, how it ended.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct EpisodeRecord {
    /// Simulated minute of training at its start.
    pub start_minute: f64,
    /// The curriculum's stage index (into `curriculum.stages`).
    pub stage: usize,
    /// Simulated seconds it ran (the final stop and hold included when it ran to its end).
    pub seconds: f64,
    /// RMS of the task error over it (mm).
    pub rms_error_mm: f64,
    pub outcome: EpisodeOutcome,
    /// The joint whose refused command jumped first (braked on a step), else `None`.
    pub jump_joint: Option<usize>,
    /// Whether the learner was rolled back to its last checkpoint after this episode
    /// (`adaptation.rollback_after`).
    #[serde(default)]
    pub rolled_back: bool,
}

impl Progress {
    /// The progress of a run that has not started: babbling, nothing learned.
    pub fn start() -> Self {
        Self {
            sim_minutes: 0.0,
            phase: Phase::Babbling,
            n_local_models: 0,
            n_trained: 0,
            episodes: 0,
            aborted_episodes: 0,
            braked_episodes: 0,
            braked_on_step: 0,
            eval: None,
            max_command_step: 0.0,
            stage: 0,
            last_episode: None,
        }
    }
}

/// Receives a training run's progress.
pub trait Observer {
    /// After each evaluation (`progress.eval` is the new one).
    fn evaluated(&mut self, _progress: &Progress) {}
    /// At the end of each on-policy episode.
    fn episode_ended(&mut self, _progress: &Progress) {}
}

/// An observer that does nothing.
impl Observer for () {}

/// A closure as an observer of the evaluations.
pub struct OnEvaluation<F>(pub F);

impl<F: FnMut(&Progress)> Observer for OnEvaluation<F> {
    fn evaluated(&mut self, progress: &Progress) {
        (self.0)(progress)
    }
}
