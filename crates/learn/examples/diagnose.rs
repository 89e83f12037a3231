//! Diagnostics of a learner after babbling: ĝ vs g, and the learned command vs u* along the
//! analytical controller's figure-8 run (off-policy), with the task acceleration it would give.
//! `cargo run -p osrl-learn --release --example diagnose -- [planar3|sarcos7] [babble minutes]`

use osrl_control::{check_reachable, run_closed_loop, IkOptions, Osc, OscConfig, TrajectoryConfig};
use osrl_dynamics::{robots, Robot, SimConfig, SimRobot};
use osrl_learn::train::{train, BabbleConfig, TrainConfig};
use osrl_learn::{Learner, LearnerConfig};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let robot = args.get(1).map_or("planar3", |s| s.as_str());
    let minutes: f64 = args.get(2).map_or(Ok(2.0), |s| s.parse())?;
    let model = robots::by_name(robot)?;
    let (n, m) = (model.nq(), model.task_dim());
    let traj = TrajectoryConfig::default().build(&model)?;
    let reach = check_reachable(&model, &traj, &IkOptions::default())?;
    let spec = model.spec();
    let mut sim = SimRobot::new(model.clone(), SimConfig::default())?;
    sim.reset(&reach.q_start, &vec![0.0; n])?;
    let mut lcfg = LearnerConfig::for_robot(
        &spec.kp,
        &spec.kd,
        &spec.q_rest,
        &model.tau_max().collect::<Vec<_>>(),
    );
    lcfg.position_features = std::env::var("POS").is_ok();
    lcfg.residual = std::env::var("NORES").is_err();
    lcfg.reward_weighting = std::env::var("NORW").is_err();
    // Numeric knobs: each environment variable, when set, overrides one setting.
    let num = |name: &str| -> Result<Option<f64>, Box<dyn std::error::Error>> {
        Ok(std::env::var(name).ok().map(|v| v.parse()).transpose()?)
    };
    if let Some(d) = num("INITD")? {
        lcfg.forward.init_d = lwpr::MetricInit::Scalar(d);
    }
    if let Some(d) = num("GINITD")? {
        lcfg.gravity.init_d = lwpr::MetricInit::Scalar(d);
    }
    for (name, field) in [
        ("FORGET", &mut lcfg.rwr.forgetting),
        ("ALPHA", &mut lcfg.forward.init_alpha),
        ("VS", &mut lcfg.velocity_scale),
        ("GADD", &mut lcfg.gravity.add_threshold),
        ("GWGEN", &mut lcfg.gravity.w_gen),
    ] {
        if let Some(v) = num(name)? {
            *field = v;
        }
    }
    if std::env::var("FWDUPD").is_ok() {
        lcfg.forward.update_d = true;
    }
    if std::env::var("NOPROD").is_ok() {
        lcfg.gravity_velocity_products = false;
    }
    let mut learner = Learner::new(n, m, 0.002, lcfg)?;
    let cfg = TrainConfig {
        minutes,
        babble: BabbleConfig {
            minutes,
            noise: std::env::var("BNOISE").map_or(Ok(0.02), |s| s.parse())?,
            spread: std::env::var("SPREAD")
                .ok()
                .map(|s| s.parse())
                .transpose()?,
            ..BabbleConfig::default()
        },
        eval_every_minutes: 0.0,
        seed: std::env::var("SEED").map_or(Ok(0), |s| s.parse())?,
        ..TrainConfig::default()
    };
    let axes = model.task_axes().to_vec();
    train(
        &mut sim,
        &mut learner,
        &traj,
        &axes,
        &cfg,
        &mut |_| Ok(Default::default()),
        &mut |_| {},
    )?;
    // The analytical run gives the states.
    let mut osc = Osc::new(model.clone(), OscConfig::default())?;
    let mut sim2 = SimRobot::new(model.clone(), SimConfig::default())?;
    sim2.reset(&reach.q_start, &vec![0.0; n])?;
    let run = run_closed_loop(&mut sim2, &mut osc, &traj, &axes, 8.0)?;
    let s = &run.series;
    let mut data = model.data();
    let (mut g_err, mut g_var, mut du2, mut us2, mut acc_err, mut fb) =
        (0.0, 0.0, 0.0, 0.0, 0.0, 0);
    let (mut u, mut u0, mut us, mut g_hat) =
        (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut xdd_ref = vec![0.0; m];
    let k_all = s.len();
    let mut sim3 = SimRobot::new(model.clone(), SimConfig::default())?;
    sim3.reset(&reach.q_start, &vec![0.0; n])?;
    let mut count = 0;
    let mut excursion: f64 = 0.0;
    let (mut a_err, mut a_count) = (0.0, 0);
    for k in (0..k_all).step_by(10) {
        // Reconstruct the state by replaying: cheaper to re-run the analytical controller.
        let _ = k;
        let meas = sim3.measurement().clone();
        let target = traj.sample(meas.t);
        osrl_control::reference_acceleration(
            &Default::default(),
            &target,
            &axes,
            meas.x.as_slice(),
            meas.xd.as_slice(),
            &mut xdd_ref,
        );
        let (q, qd) = (meas.q.as_slice(), meas.qd.as_slice());
        for (qi, q0) in q[..n].iter().zip(&reach.q_start[..n]) {
            excursion = excursion.max((qi - q0).abs());
        }
        let src = learner.command::<rand_chacha::ChaCha8Rng>(q, qd, &xdd_ref, None, &mut u)?;
        fb += (src == osrl_learn::CommandSource::Fallback) as usize;
        osc.nominal(q, qd, &mut u0)?;
        osc.solve(q, qd, &xdd_ref, &u0, &mut us)?;
        let g = osrl_dynamics::gravity(&model, &mut data, q)?.clone();
        learner.nominal(q, qd, &mut g_hat)?;
        for i in 0..n {
            let gh = g_hat[i] + spec.kd[i] * qd[i] + spec.kp[i] * (q[i] - spec.q_rest[i]);
            g_err += (gh - g[i]).powi(2);
            g_var += g[i].powi(2);
            du2 += (u[i] - us[i]).powi(2);
            us2 += (us[i] - u0[i]).powi(2);
        }
        let qdd = osrl_dynamics::forward_dynamics(&model, &mut data, q, qd, &u)?.clone();
        osrl_dynamics::compute_all(&model, &mut data, q, qd)?;
        let xdd = &data.jac * qdd + data.jdot_qd;
        acc_err += axes
            .iter()
            .enumerate()
            .map(|(j, &a)| (xdd[a] - xdd_ref[j]).powi(2))
            .sum::<f64>();
        // Â from the forward model against the true A = J M⁻¹ on the task rows.
        let mut a_hat = vec![0.0; m * n];
        if learner.input_gain(q, qd, &mut a_hat)? {
            let mass = osrl_dynamics::crba(&model, &mut data, q)?.clone();
            osrl_dynamics::jacobian(&model, &mut data, q)?;
            let minv = mass.try_inverse().unwrap();
            let a_true = &data.jac * minv;
            let (mut e, mut t) = (0.0, 0.0);
            for (j, &ax) in axes.iter().enumerate() {
                for i in 0..n {
                    e += (a_hat[j * n + i] - a_true[(ax, i)]).powi(2);
                    t += a_true[(ax, i)].powi(2);
                }
            }
            a_err += (e / t).sqrt();
            if a_count == 0 {
                println!("Â = {a_hat:?}");
                println!(
                    "A  = {:?}",
                    axes.iter()
                        .flat_map(|&ax| (0..n).map(move |i| (ax, i)))
                        .map(|(ax, i)| a_true[(ax, i)])
                        .collect::<Vec<_>>()
                );
            }
            a_count += 1;
        }
        count += 1;
        // Advance the analytical run 10 steps.
        for _ in 0..10 {
            let mm = sim3.measurement().clone();
            let mut ua = vec![0.0; n];
            osrl_control::TaskController::command(&mut osc, &mm, &traj.sample(mm.t), &mut ua)?;
            osrl_dynamics::Robot::step(&mut sim3, &ua)?;
        }
    }
    let c = count as f64;
    println!(
        "RFs {} (gravity {}), trained {}",
        learner.n_local_models(),
        learner.n_gravity_rfs(),
        learner.n_trained()
    );
    println!(
        "gravity: rms error {:.3} N·m vs rms g {:.3}",
        (g_err / c / n as f64).sqrt(),
        (g_var / c / n as f64).sqrt()
    );
    println!(
        "command: rms ‖u − u*‖ {:.3} N·m; rms ‖u* − u0‖ {:.3}; fallback {}/{}",
        (du2 / c).sqrt(),
        (us2 / c).sqrt(),
        fb,
        count
    );
    println!("largest joint excursion from the path start: {excursion:.3} rad");
    // ĝ inside the babbling box: random postures within ± spread/2 of home.
    {
        use rand::{RngExt, SeedableRng};
        let spread = cfg.babble.spread_for(n);
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let (mut e2, mut g2) = (0.0, 0.0);
        let zero = vec![0.0; n];
        for _ in 0..500 {
            let q: Vec<f64> = (0..n)
                .map(|i| reach.q_start[i] + r.random_range(-0.5 * spread..0.5 * spread))
                .collect();
            let g = osrl_dynamics::gravity(&model, &mut data, &q)?.clone();
            learner.nominal(&q, &zero, &mut g_hat)?;
            for i in 0..n {
                let gh = g_hat[i] + spec.kp[i] * (q[i] - spec.q_rest[i]);
                e2 += (gh - g[i]).powi(2);
                g2 += g[i].powi(2);
            }
        }
        println!(
            "gravity inside half the babbling box: rms error {:.3} N·m vs rms g {:.3}",
            (e2 / 500.0 / n as f64).sqrt(),
            (g2 / 500.0 / n as f64).sqrt()
        );
    }
    for (what, g) in [
        ("dynamic", learner.gravity_model()),
        ("static", learner.gravity_static_model()),
    ] {
        let Some(g) = g else { continue };
        let mut hist = std::collections::BTreeMap::new();
        for r in g.lwpr().rfs(0)?.map(|v| v.n_reg()[0]) {
            *hist.entry(r).or_insert(0) += 1;
        }
        println!("{what} gravity model PLS directions (count of RFs by R, output 0): {hist:?}");
    }
    if let Some(f) = learner.forward_model() {
        let regs: Vec<usize> = f.lwpr().rfs(0)?.map(|v| v.n_reg()[0]).collect();
        let mut hist = std::collections::BTreeMap::new();
        for r in regs {
            *hist.entry(r).or_insert(0) += 1;
        }
        println!("forward model PLS directions (count of RFs by R, output 0): {hist:?}");
    }
    println!(
        "Â relative error (Frobenius): mean {:.3} over {a_count} states",
        a_err / a_count.max(1) as f64
    );
    println!(
        "task acceleration error rms {:.3} m/s²",
        (acc_err / c).sqrt()
    );
    Ok(())
}
