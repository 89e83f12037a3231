//! A family training run traced episode by episode (`docs/family.md`): each drawn path (kind,
//! size, speed, peak acceleration against the base figure-8's), how its episode went (stage,
//! seconds run, braked, RMS error) and each evaluation on the base figure-8. Saves the model
//! like `osrl train --out`, so `e9_models` can evaluate it.
//!
//! ```sh
//! cargo run --release -p osrl-cli --example family_trace -- planar3 30 2 OUT.osrl [F.toml]
//! ```
//!
//! `F.toml` may hold `[trajectory]` (with `kind = "family"` and `[trajectory.family]`),
//! `[train]` and `[learner]` sections; the rest are the defaults.

use anyhow::{bail, Context, Result};
use osrl_control::family::FamilySampler;
use osrl_control::{Trajectory, TrajectoryConfig, TrajectoryKind};
use osrl_dynamics::{SimConfig, SimRobot};
use osrl_experiments::family::label;
use osrl_experiments::Setup;
use osrl_learn::train::{Observer, PathSource, Progress, TrainConfig, Trainer};
use osrl_learn::{LearnError, Learner, LearnerConfig};
use std::cell::RefCell;
use std::rc::Rc;

#[derive(serde::Deserialize, Default)]
#[serde(default)]
struct File {
    trajectory: Option<TrajectoryConfig>,
    train: Option<TrainConfig>,
    learner: Option<LearnerConfig>,
}

/// The family's paths, each printed as it is drawn.
struct Logged {
    sampler: FamilySampler,
    base: Trajectory,
    base_every: u64,
    episodes: u64,
    base_peak: f64,
    drawn: Rc<RefCell<Vec<String>>>,
}

impl PathSource for Logged {
    fn next_path(&mut self) -> osrl_learn::Result<Trajectory> {
        // As `FamilySampler::next_training_path`, with the drawn path's description.
        let k = self.base_every;
        self.episodes += 1;
        if k > 0 && (self.episodes - 1).is_multiple_of(k) {
            self.drawn.borrow_mut().push("base figure-8".into());
            return Ok(self.base.clone());
        }
        let p = self.sampler.draw().map_err(LearnError::Control)?;
        let speed = peak_speed(&p.path);
        self.drawn.borrow_mut().push(format!(
            "{:48} peak ẍ {:.2}× base, peak ẋ {:.3} m/s, torque share {:.2}",
            label(&p),
            p.peak_acceleration / self.base_peak,
            speed,
            p.torque_share
        ));
        Ok(p.approached)
    }
}

/// Prints each episode (with the path it ran) and each evaluation.
struct Trace(Rc<RefCell<Vec<String>>>);

impl Observer for Trace {
    fn evaluated(&mut self, p: &Progress) {
        if let Some(e) = &p.eval {
            println!(
                "   eval {:5.1} min: figure-8 {:.3} mm nMSE {:.4} ({} local models, {} trained)",
                p.sim_minutes, e.tracking_rms_mm, e.command_nmse, p.n_local_models, p.n_trained
            );
        }
    }

    fn episode_ended(&mut self, p: &Progress) {
        let Some(e) = &p.last_episode else { return };
        let d = self.0.borrow();
        println!(
            "ep {:3} {:5.1} min stage {} [{:.2},{:.2}] {:5.1} s {} rms {:6.3} mm | {}",
            p.episodes,
            p.sim_minutes,
            p.stage,
            e.stage[0],
            e.stage[1],
            e.seconds,
            if e.braked {
                "BRAKED "
            } else if e.aborted {
                "ABORTED"
            } else {
                "       "
            },
            1e3 * e.rms_error,
            d.last().map(String::as_str).unwrap_or("")
        );
    }
}

fn peak_speed(t: &Trajectory) -> f64 {
    let span = t.lead() + t.ramp() + t.period();
    (0..=2000)
        .map(|k| t.sample(span * k as f64 / 2000.0).xd.norm())
        .fold(0.0, f64::max)
}

fn peak_acc(t: &Trajectory) -> f64 {
    let span = t.lead() + t.ramp() + t.period();
    (0..=2000)
        .map(|k| t.sample(span * k as f64 / 2000.0).xdd.norm())
        .fold(0.0, f64::max)
}

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (robot, minutes, seed, out, file) = match args.as_slice() {
        [r, m, s, o] => (r, m, s, o, None),
        [r, m, s, o, f] => (r, m, s, o, Some(f)),
        _ => bail!("usage: family_trace ROBOT MINUTES SEED OUT [CONFIG.toml]"),
    };
    let minutes: f64 = minutes.parse().context("MINUTES")?;
    let seed: u64 = seed.parse().context("SEED")?;
    let file: File = match file {
        Some(f) => toml::from_str(&std::fs::read_to_string(f).context("config")?)?,
        None => File::default(),
    };
    let traj = file.trajectory.unwrap_or(TrajectoryConfig {
        kind: TrajectoryKind::Family,
        ..TrajectoryConfig::default()
    });
    let mut setup = Setup::along(robot, traj)?;
    let mut train = file.train.unwrap_or_default();
    train.minutes = minutes;
    train.seed = seed;
    if let Some(l) = file.learner {
        setup = setup.with_learner(l)?;
    }
    let setup = setup.with_train(train)?;
    let truth = setup.model().clone();
    let base_peak = peak_acc(setup.trajectory());
    println!(
        "base figure-8: peak ẍ {base_peak:.3} m/s², peak ẋ {:.3} m/s",
        peak_speed(setup.trajectory())
    );
    let sim_cfg = SimConfig {
        seed,
        ..setup.sim().clone()
    };
    let mut sim = SimRobot::new(truth.clone(), sim_cfg)?;
    sim.reset(setup.home(), &vec![0.0; truth.nq()])?;
    let (n, m) = (truth.nq(), truth.task_dim());
    let mut learner = Learner::new(
        n,
        m,
        setup.sim().control_period,
        setup.training_learner_config(),
    )?;
    let mut ev = setup.evaluator(&truth)?;
    let mut evaluate = |l: &mut Learner| ev.evaluate(l);
    let drawn = Rc::new(RefCell::new(Vec::new()));
    let mut observer = Trace(drawn.clone());
    let mut src = Logged {
        sampler: setup.family_sampler(seed)?,
        base: setup.trajectory().clone(),
        base_every: setup.trajectory_config().family.base_every as u64,
        episodes: 0,
        base_peak,
        drawn,
    };
    let cfg = setup.train_config().clone();
    let trainer = Trainer::new(
        &mut sim,
        &mut learner,
        setup.trajectory(),
        truth.task_axes(),
        &cfg,
        &mut evaluate,
        &mut observer,
    )?;
    let summary = trainer.with_paths(&mut src).run()?;
    let last = summary.learning_curve.last().map(|(_, e)| e.clone());
    if let Some(e) = last {
        println!(
            "final: figure-8 {:.3} mm nMSE {:.4}; {} episodes, {} braked, {} aborted",
            e.tracking_rms_mm,
            e.command_nmse,
            summary.episodes,
            summary.braked_episodes,
            summary.aborted_episodes
        );
    }
    let bytes = setup.saved(learner, &summary)?.to_bytes()?;
    std::fs::write(out, bytes).context("OUT")?;
    Ok(())
}
