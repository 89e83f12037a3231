//! Trains a built-in robot on its default figure-8 and prints every evaluation in full (one JSON
//! line each: simulated minutes and all metrics of `EvalResult`), then the training summary.
//!
//! `cargo run --release -p osrl-learn --example learning_curve -- ROBOT MINUTES [SEED]
//! [EVAL_EVERY] [LEARNER_JSON]` (LEARNER_JSON: a `LearnerConfig` as JSON, fields as in
//! `osrl train`'s `[learner]` section; the robot's data sheet fills the rest). With `EPISODES` set in
//! the environment, each on-policy episode's report goes to stderr.

use osrl_control::{check_reachable, IkOptions, TrajectoryConfig};
use osrl_dynamics::robots;
use osrl_learn::train::{train_simulated, TrainConfig};
use osrl_learn::LearnerConfig;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let robot = args.first().map_or("planar3", String::as_str);
    let minutes: f64 = args.get(1).map_or(Ok(10.0), |s| s.parse())?;
    let seed: u64 = args.get(2).map_or(Ok(0), |s| s.parse())?;
    let every: f64 = args.get(3).map_or(Ok(1.0), |s| s.parse())?;
    let model = robots::by_name(robot)?;
    let traj = TrajectoryConfig::default().build(&model)?;
    let home = check_reachable(&model, &traj, &IkOptions::default())?.q_start;
    let mut lcfg: LearnerConfig = match args.get(4).filter(|s| !s.is_empty()) {
        Some(text) => serde_json::from_str(text)?,
        None => LearnerConfig::default(),
    };
    let spec = model.spec();
    let tau: Vec<f64> = model.tau_max().collect();
    lcfg.fill_data_sheet(&spec.kp, &spec.kd, &spec.q_rest, &tau);
    let cfg = TrainConfig {
        minutes,
        seed,
        eval_every_minutes: every,
        ..TrainConfig::default()
    };
    struct Print(bool);
    impl osrl_learn::train::Observer for Print {
        fn evaluated(&mut self, p: &osrl_learn::train::Progress) {
            let e = p.eval.as_ref().map(serde_json::to_value);
            println!(
                "{}",
                serde_json::json!({"sim_minutes": p.sim_minutes, "aborted": p.aborted_episodes,
                                   "episodes": p.episodes, "local_models": p.n_local_models,
                                   "eval": e.transpose().ok().flatten()})
            );
        }
        fn episode_ended(&mut self, p: &osrl_learn::train::Progress) {
            if self.0 {
                eprintln!("{:.3} min {:?}", p.sim_minutes, p.last_episode);
            }
        }
    }
    let mut print = Print(std::env::var("EPISODES").is_ok());
    let (mut learner, summary) = train_simulated(&model, &traj, &home, lcfg, &cfg, 1, &mut print)?;
    if let Some(path) = args.get(5) {
        // The final evaluation's time series: t, then per joint u and u*.
        let mut ev = osrl_learn::eval::Evaluator::new(
            model.clone(),
            Default::default(),
            traj.clone(),
            home.clone(),
            cfg.gains,
            1,
        )?;
        ev.keep_series = true;
        ev.evaluate(&mut learner)?;
        let s = &ev.series;
        let n = model.nq();
        let mut out = String::new();
        for k in 0..s.t.len() {
            let u = &s.u[k * n..(k + 1) * n];
            let us = &s.u_star[k * n..(k + 1) * n];
            let row: Vec<String> = std::iter::once(s.t[k])
                .chain(u.iter().copied())
                .chain(us.iter().copied())
                .map(|v| v.to_string())
                .collect();
            out += &(row.join(",") + "\n");
        }
        std::fs::write(path, out)?;
    }
    let mut s = serde_json::to_value(&summary)?;
    s.as_object_mut().map(|o| o.remove("learning_curve"));
    println!("{s}");
    Ok(())
}
