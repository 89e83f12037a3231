//! Trains the learned controller on the figure-8 and prints the learning curve (Fig. 2b/3b, E3).
//! `cargo run -p osrl-learn --release --example learn_figure8 -- [planar3|sarcos7] [minutes] [seed]`

use osrl_control::{check_reachable, IkOptions, TrajectoryConfig};
use osrl_dynamics::{robots, SimConfig, SimRobot};
use osrl_learn::eval::Evaluator;
use osrl_learn::train::{train, TrainConfig};
use osrl_learn::{Learner, LearnerConfig};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let robot = args.get(1).map_or("planar3", |s| s.as_str());
    let minutes: f64 = args.get(2).map_or(Ok(10.0), |s| s.parse())?;
    let seed: u64 = args.get(3).map_or(Ok(0), |s| s.parse())?;
    let model = robots::by_name(robot)?;
    let traj = TrajectoryConfig::default().build(&model)?;
    let reach = check_reachable(&model, &traj, &IkOptions::default())?;
    let spec = model.spec();
    let mut sim = SimRobot::new(
        model.clone(),
        SimConfig {
            seed,
            ..SimConfig::default()
        },
    )?;
    sim.reset(&reach.q_start, &vec![0.0; model.nq()])?;
    let mut lcfg = LearnerConfig::for_robot(
        &spec.kp,
        &spec.kd,
        &spec.q_rest,
        &model.tau_max().collect::<Vec<_>>(),
    );
    if let Ok(c) = std::env::var("COST") {
        lcfg.cost = if c == "null" {
            osrl_learn::CostKind::NullSpace
        } else {
            osrl_learn::CostKind::Full
        };
    }
    lcfg.position_features = std::env::var("NOPOS").is_err();
    lcfg.residual = std::env::var("NORES").is_err();
    lcfg.reward_weighting = std::env::var("NORW").is_err();
    if let Ok(d) = std::env::var("INITD") {
        lcfg.forward.init_d = lwpr::MetricInit::Scalar(d.parse()?);
    }
    if let Ok(v) = std::env::var("VS") {
        lcfg.velocity_scale = v.parse()?;
    }
    if let Ok(v) = std::env::var("FORGET") {
        lcfg.rwr.forgetting = v.parse()?;
    }
    if let Ok(v) = std::env::var("PRIOR") {
        lcfg.rwr.ridge_to_previous = true;
        lcfg.rwr.ridge = v.parse()?;
    }
    if let Ok(v) = std::env::var("TAUMAX") {
        lcfg.rwr.tau_max = Some(v.parse()?);
    }
    if let Ok(v) = std::env::var("XSCALE") {
        lcfg.exploration_scale = v.parse()?;
    }
    lcfg.gravity_on_policy = std::env::var("GRAVON").is_ok();
    if let Ok(d) = std::env::var("GINITD") {
        lcfg.gravity.init_d = lwpr::MetricInit::Scalar(d.parse()?);
    }
    if std::env::var("NOPROD").is_ok() {
        lcfg.gravity_velocity_products = false;
    }
    if std::env::var("GNOUPD").is_ok() {
        lcfg.gravity.update_d = false;
    }
    if std::env::var("BILIN").is_ok() {
        lcfg.dynamics_bilinear = true;
    }
    if let Ok(v) = std::env::var("DFORGET") {
        lcfg.dynamics_forgetting = v.parse()?;
    }
    if std::env::var("FWDUPD").is_ok() {
        lcfg.forward.update_d = true;
    }
    if let Ok(v) = std::env::var("PENALTY") {
        lcfg.forward.penalty = v.parse()?;
    }
    if let Ok(v) = std::env::var("WGEN") {
        lcfg.forward.w_gen = v.parse()?;
    }
    if let Ok(v) = std::env::var("NSHRINK") {
        lcfg.null_space_shrink = v.parse()?;
    }
    if let Ok(v) = std::env::var("MINESS") {
        lcfg.min_ess = v.parse()?;
    }
    if let Ok(v) = std::env::var("DYNEVERY") {
        lcfg.dynamics_every = v.parse()?;
    }
    if let Ok(v) = std::env::var("DYNSOLVE") {
        lcfg.dynamics_solve_every = v.parse()?;
    }
    if let Ok(v) = std::env::var("FWDEVERY") {
        lcfg.forward_every = v.parse()?;
    }
    if let Ok(v) = std::env::var("UPDEVERY") {
        lcfg.update_every = v.parse()?;
    }
    if let Ok(v) = std::env::var("NSCAP") {
        lcfg.null_space_cap = Some(v.parse()?);
    }
    if std::env::var("NSX").is_ok() {
        lcfg.exploration = osrl_learn::ExplorationKind::NullSpace;
    }
    if std::env::var("ISO").is_ok() {
        lcfg.exploration = osrl_learn::ExplorationKind::Isotropic;
    }
    if let Ok(v) = std::env::var("PRUNE") {
        lcfg.prune_untrained_after = if v == "none" { None } else { Some(v.parse()?) };
    }
    if let Ok(v) = std::env::var("CAP") {
        lcfg.exploration_cap = v.parse()?;
    }
    let mut learner = Learner::new(model.nq(), model.task_dim(), 0.002, lcfg)?;
    let babble: f64 = std::env::var("BABBLE").map_or(Ok(4.0), |s| s.parse())?;
    let learn_every: usize = std::env::var("LEARN_EVERY").map_or(Ok(1), |s| s.parse())?;
    let cfg = TrainConfig {
        learn_every,
        minutes,
        seed,
        eval_every_minutes: 1.0,
        learn_on_policy: std::env::var("NOLEARN").is_err(),
        learn_returning_home: std::env::var("NOLEARN_HOME").is_err(),
        explore: std::env::var("NOEXPLORE").is_err(),
        babble: osrl_learn::train::BabbleConfig {
            minutes: babble,
            noise: std::env::var("BNOISE").map_or(Ok(0.02), |s| s.parse())?,
            spread: std::env::var("SPREAD")
                .ok()
                .map(|s| s.parse())
                .transpose()?,
            ..Default::default()
        },
        ..TrainConfig::default()
    };
    let mut cfg = cfg;
    if let Ok(v) = std::env::var("RESET") {
        cfg.reset_error = v.parse()?;
    }
    if let Ok(v) = std::env::var("KP") {
        let kp: f64 = v.parse()?;
        cfg.gains = osrl_control::TaskGains {
            kp,
            kd: 2.0 * kp.sqrt(),
        };
    }
    let mut ev = Evaluator::new(
        model.clone(),
        SimConfig::default(),
        traj.clone(),
        reach.q_start.clone(),
        cfg.gains,
        2,
    )?;
    let axes = model.task_axes().to_vec();
    let t0 = std::time::Instant::now();
    let summary = train(
        &mut sim,
        &mut learner,
        &traj,
        &axes,
        &cfg,
        &mut |l| ev.evaluate(l),
        &mut |p| {
            if let Some(e) = &p.eval {
                println!(
                "{:6.2} min {:10} rfs {:4} trained {:4} | track {:8.2} mm (max {:8.2}) nmse {:7.4} (null {:7.4} nom {:7.4}/{:7.4} Â {:5.3}) cost {:6.3} (var {:.3} c* {:.3}) fallback {:5.3} | episodes {} aborted {} | wall {:.0} s",
                p.sim_minutes, p.phase, p.n_local_models, p.n_trained, e.tracking_rms_mm, e.tracking_max_mm, e.command_nmse, e.command_nmse_null, e.nominal_nmse, e.nominal_nmse_null, e.gain_error, e.command_cost_ratio, e.u_star_variance, e.u_star_cost, e.fallback_share, p.episodes, p.aborted_episodes, t0.elapsed().as_secs_f64()
            );
            }
        },
    )?;
    let mut s = learner.local_summaries();
    let q = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        if v.is_empty() {
            vec![]
        } else {
            vec![
                v[0],
                v[v.len() / 4],
                v[v.len() / 2],
                v[3 * v.len() / 4],
                v[v.len() - 1],
            ]
        }
    };
    println!(
        "ess quantiles {:?}",
        q(&mut s.iter().map(|l| l.ess).collect())
    );
    println!(
        "sigma quantiles {:?}",
        q(&mut s.iter().map(|l| l.sigma).collect())
    );
    println!(
        "tau quantiles {:?}",
        q(&mut s.iter().map(|l| l.tau).collect())
    );
    s.clear();
    println!(
        "{}",
        serde_json::to_string(&serde_json::json!({
            "wall_seconds": summary.wall_seconds, "realtime_factor": summary.realtime_factor,
            "n_local_models": summary.n_local_models, "stats": summary.stats, "gravity_rfs": learner.n_gravity_rfs(),
            "max_command_step": summary.max_command_step,
        }))?
    );
    Ok(())
}
