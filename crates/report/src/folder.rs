//! The report folder of an `osrl reproduce` run: the data it holds (`results.json`,
//! `figures.json`, the time series as CSV, each analytical run's metrics and config) and the
//! page drawn from them (every figure as SVG and PNG, `index.html`). [`Page`] is what the
//! page is drawn from, in memory after a run or read back from a folder, so the page can be
//! drawn again without running anything ([`Page::load`], `osrl report --from`).

use crate::error::{create_dir, write, ReportError, Result};
use crate::figures::{commands, learned, path, safety, toy};
use crate::page::{self, Fig};
use crate::plot;
use crate::series;
use osrl_control::{ModelError, OscConfig, TrajectoryConfig};
use osrl_dynamics::SimConfig;
use osrl_experiments::analytical::{self, AnalyticalRun, ROBOTS};
use osrl_experiments::stats::Outcome;
use osrl_experiments::{FigureInputs, Reproduction, Results, Setup};
use osrl_learn::eval::EvalSeries;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::Path;

/// Everything the page is drawn from.
#[derive(Clone, Debug, PartialEq)]
pub struct Page {
    pub results: Results,
    pub figures: FigureInputs,
    /// Each analytical run's series, by its folder ([`Case::dir`]), in the order of
    /// [`analytical::cases`].
    pub analytical: Vec<(String, osrl_control::Series)>,
    /// Per robot, seed 0's evaluation series of the learned controller.
    pub learned: BTreeMap<String, EvalSeries>,
}

/// The file of a robot's learned evaluation series.
fn learned_csv(robot: &str) -> String {
    format!("E3/{robot}_learned.csv")
}

/// The `osrl simulate --config` file that repeats an analytical run.
#[derive(Serialize)]
struct CaseConfig<'a> {
    robot: &'a str,
    trajectory: &'a TrajectoryConfig,
    controller: OscConfig,
    sim: &'a SimConfig,
    model_error: &'a ModelError,
    simulate: Seconds,
}

#[derive(Serialize)]
struct Seconds {
    seconds: f64,
}

/// Writes an analytical run's folder: `simulate.csv`, `metrics.json`, `config.toml` (the
/// figure comes with the page).
fn write_case(out: &Path, a: &AnalyticalRun, setup: &Setup) -> Result<()> {
    let dir = out.join(a.case.dir());
    create_dir(&dir)?;
    series::write_run(
        &dir.join("simulate.csv"),
        &a.run.series,
        setup.model().task_axes(),
    )?;
    let metrics = serde_json::to_string_pretty(&serde_json::to_value(&a.row)?)?;
    write(&dir.join("metrics.json"), &metrics)?;
    let cfg = CaseConfig {
        robot: a.case.robot,
        trajectory: setup.trajectory_config(),
        controller: a.case.osc(),
        sim: setup.sim(),
        model_error: &a.case.error,
        simulate: Seconds {
            seconds: a.case.seconds,
        },
    };
    write(&dir.join("config.toml"), &toml::to_string(&cfg)?)
}

impl Page {
    /// The page of a finished run (its data copied).
    pub fn of(rep: &Reproduction) -> Self {
        Self {
            results: rep.results.clone(),
            figures: rep.figures.clone(),
            analytical: (rep.analytical.iter())
                .map(|a| (a.case.dir(), a.run.series.clone()))
                .collect(),
            learned: rep.learned.clone(),
        }
    }

    /// The page of the report folder `dir`, read from its data files.
    ///
    /// # Errors
    /// A missing or malformed `results.json`, `figures.json` or time series.
    pub fn load(dir: &Path) -> Result<Self> {
        let results = Results::load(&dir.join("results.json"))?;
        let fpath = dir.join("figures.json");
        let text = crate::error::read_text(&fpath)?;
        let figures: FigureInputs = serde_json::from_str(&text)
            .map_err(|e| ReportError::Folder(format!("{}: {e}", fpath.display())))?;
        let sizes = &results.config.sizes;
        let analytical = analytical::cases(sizes.payload_kg, sizes.analytical_seconds)?
            .iter()
            .map(|c| {
                let d = c.dir();
                Ok((
                    d.clone(),
                    series::read_run(&dir.join(&d).join("simulate.csv"))?,
                ))
            })
            .collect::<Result<_>>()?;
        let mut learned = BTreeMap::new();
        for robot in ROBOTS {
            if results.e4.get(robot).and_then(Outcome::done).is_some() {
                let es = series::read_eval(&dir.join(learned_csv(robot)))?;
                learned.insert(robot.to_string(), es);
            }
        }
        Ok(Self {
            results,
            figures,
            analytical,
            learned,
        })
    }

    /// The series of the analytical run in folder `dir`.
    fn run(&self, dir: &str) -> Option<&osrl_control::Series> {
        self.analytical
            .iter()
            .find(|(d, _)| d == dir)
            .map(|(_, s)| s)
    }
}

/// Writes a finished run's data into `out`: `results.json`, `figures.json`, `E1/toy.json`, the
/// analytical runs' folders and the learned evaluation series (not the saved models).
///
/// # Errors
/// An I/O error.
pub fn write_data(out: &Path, rep: &Reproduction) -> Result<()> {
    create_dir(out)?;
    rep.results.save(&out.join("results.json"))?;
    let figs = serde_json::to_string_pretty(&rep.figures)?;
    write(&out.join("figures.json"), &(figs + "\n"))?;
    create_dir(&out.join("E1"))?;
    write(
        &out.join("E1").join("toy.json"),
        &(serde_json::to_string(&rep.results.e1)? + "\n"),
    )?;
    let setups = setups(&rep.figures)?;
    for a in &rep.analytical {
        write_case(out, a, setup(&setups, a.case.robot)?)?;
    }
    for (robot, es) in &rep.learned {
        let model = setup(&setups, robot)?.model();
        series::write_eval(
            &out.join(learned_csv(robot)),
            es,
            model.nq(),
            model.task_axes(),
        )?;
    }
    Ok(())
}

fn setups(f: &FigureInputs) -> Result<Vec<(&'static str, Setup)>> {
    ROBOTS.iter().map(|&r| Ok((r, f.setup(r)?))).collect()
}

fn setup<'a>(setups: &'a [(&'static str, Setup)], robot: &str) -> Result<&'a Setup> {
    (setups.iter().find(|(r, _)| *r == robot))
        .map(|(_, s)| s)
        .ok_or_else(|| ReportError::Folder(format!("no set-up for robot {robot}")))
}

/// Draws every figure of `page` into `out` and writes `out/index.html`.
///
/// # Errors
/// A figure that cannot be drawn, an I/O error.
pub fn render(out: &Path, page: &Page) -> Result<()> {
    create_dir(out)?;
    let setups = setups(&page.figures)?;
    let mut figs = toy_figures(out, page)?;
    figs.extend(path_figures(out, page, &setups)?);
    figs.extend(learned_figures(out, page, &setups)?);
    figs.extend(ablation_figures(out, page)?);
    figs.extend(change_figures(out, page)?);
    figs.extend(
        (crate::family::figures(out, &page.results)?.into_iter())
            .map(|(file, caption)| Fig { file, caption }),
    );
    write(
        &out.join("index.html"),
        &page::html(out, &page.results, &figs)?,
    )
}

/// Writes a finished run's folder: [`write_data`], then [`render`] of its [`Page`].
///
/// # Errors
/// As those.
pub fn write_report(out: &Path, rep: &Reproduction) -> Result<()> {
    write_data(out, rep)?;
    render(out, &Page::of(rep))
}

fn toy_figures(out: &Path, page: &Page) -> Result<Vec<Fig>> {
    let dir = out.join("E1");
    toy::fig1(&page.figures.toy, &dir)?;
    toy::iterations(&page.figures.toy.config, &page.results.e1, &dir)?;
    Ok(vec![
        Fig {
            file: "E1/fig1_toy.svg".into(),
            caption: "E1 (paper Fig. 1): transformed reward and policy mean over EM iterations, fixed vs adaptive τ.".into(),
        },
        Fig {
            file: "E1/toy_iterations.svg".into(),
            caption: "E1 (paper Fig. 1): EM iterations to converge vs initial τ (median, quartiles), adaptive vs fixed.".into(),
        },
    ])
}

/// The path figure of every analytical run (E2's on the page, E7's in their folders).
fn path_figures(out: &Path, page: &Page, setups: &[(&'static str, Setup)]) -> Result<Vec<Fig>> {
    let sizes = &page.results.config.sizes;
    let mut figs = Vec::new();
    for case in analytical::cases(sizes.payload_kg, sizes.analytical_seconds)? {
        let dir = case.dir();
        let s = page
            .run(&dir)
            .ok_or_else(|| ReportError::Folder(format!("no time series of {dir}")))?;
        let axes = setup(setups, case.robot)?.model().task_axes();
        plot::save(&path::path_figure(s, axes), &out.join(&dir), "path")?;
        if case.error_key == "none" {
            figs.push(Fig {
                file: format!("{dir}/path.svg"),
                caption: format!("E2 (baseline): {}, analytical {} with the true model — desired vs actual figure-8 and the error over time.", case.robot, case.law_name()),
            });
        }
    }
    Ok(figs)
}

/// E3 (tracking, arm), E4 (commands) and E5 (curves) of each robot.
fn learned_figures(out: &Path, page: &Page, setups: &[(&'static str, Setup)]) -> Result<Vec<Fig>> {
    let r = &page.results;
    let mut figs = Vec::new();
    for robot in ROBOTS {
        let setup = setup(setups, robot)?;
        let fig = if robot == "planar3" { 2 } else { 3 };
        let eq7 = page.run(&format!("E2/{robot}_eq7"));
        if let (Some(s), Some(a), Some(e3)) = (
            page.learned.get(robot),
            eq7,
            r.e3.get(robot).and_then(Outcome::done),
        ) {
            figs.extend(e3_e4(out, setup, s, a, e3, r, fig)?);
        }
        if let Some(c) = r.e5.get(robot).and_then(Outcome::done) {
            let reference = r.e3.get(robot).and_then(Outcome::done);
            let title = format!(
                "{robot}: learning curves (mean, min–max over {} seeds)",
                c.seeds
            );
            let runs = [("learned (RWR)".to_string(), c.clone())];
            let f = learned::curves(
                &title,
                &runs,
                reference.and_then(|v| v.analytical_eq7_tracking_rms_mm),
                r.config.sizes.robot(robot).minutes,
            );
            plot::save(&f, &out.join("E5"), &format!("{robot}_curves"))?;
            figs.push(Fig {
                file: format!("E5/{robot}_curves.svg"),
                caption: format!("E5 (paper Sec. V): {robot} tracking error, command nMSE against u* and command cost vs simulated training minutes, mean with min–max over seeds."),
            });
        }
        if let Some(e3) = r.e3.get(robot).and_then(Outcome::done) {
            let s = &e3.summary;
            let f = safety::command_steps(
                robot,
                &s.safety,
                &r.seeds,
                s.max_command_step_analytical.max,
                setup.sim().control_period,
                r.config.sizes.robot(robot).minutes,
            );
            plot::save(&f, &out.join("E5"), &format!("{robot}_steps"))?;
            figs.push(Fig {
                file: format!("E5/{robot}_steps.svg"),
                caption: format!("E5, learning safety: {robot}, the largest change of the command between consecutive on-policy commands in each 15 s of simulated training (exploration, switches and returns home included), per seed, next to the largest step of eq. 7's optimal command u* in the final evaluations (dashed)."),
            });
        }
    }
    Ok(figs)
}

fn e3_e4(
    out: &Path,
    setup: &Setup,
    s: &EvalSeries,
    a: &osrl_control::Series,
    e3: &osrl_experiments::results::LearnedRow,
    r: &Results,
    fig: u8,
) -> Result<Vec<Fig>> {
    let robot = setup.robot();
    let (dir, per, n) = (out.join("E3"), setup.steps_per_period(), setup.model().nq());
    plot::save(
        &learned::tracking(setup, s, a),
        &dir,
        &format!("{robot}_tracking"),
    )?;
    let mut figs = vec![Fig {
        file: format!("E3/{robot}_tracking.svg"),
        caption: format!("E3 (paper Fig. {fig}b): {robot} figure-8 with the learned controller (seed 0) and analytical eq. 7 — path and tracking error."),
    }];
    // The arm drawing needs a whole cycle: the learned run's if it did not diverge.
    let learned_ok = e3.summary.per_seed.first().is_some_and(|e| !e.diverged);
    let arm = if learned_ok {
        learned::ArmSeries {
            t: &s.t,
            q: &s.q,
            x_d: &s.x_d,
            who: "learned",
        }
    } else {
        learned::ArmSeries {
            t: &a.t,
            q: &a.q,
            x_d: &a.x_d,
            who: "analytical eq. 7",
        }
    };
    let k = r.config.sizes.arm_instants;
    plot::save(
        &learned::arm(setup, &arm, per, k)?,
        &dir,
        &format!("{robot}_arm"),
    )?;
    figs.push(Fig {
        file: format!("E3/{robot}_arm.svg"),
        caption: format!("E3 (paper Fig. {fig}a): {robot} posture at {k} instants of one figure-8 cycle under the {} controller, the first at the path start (links from forward kinematics; large dots: the desired point at the same instant){}.",
            arm.who,
            if learned_ok { "" } else { " — the learned controller's evaluation diverged, so the analytical run is drawn" }),
    });
    let title = format!("{robot}: learned vs analytical optimal commands over one cycle");
    plot::save(
        &commands::commands_figure(s, n, per, &title),
        &out.join("E4"),
        &format!("{robot}_commands"),
    )?;
    figs.push(Fig {
        file: format!("E4/{robot}_commands.svg"),
        caption: format!("E4 (paper Fig. 2c): {robot}, per joint, the learned command and the analytical optimum u* (eq. 7, N = I, true model) at the same states over one cycle."),
    });
    Ok(figs)
}

/// E8: each robot's timelines of a changing robot.
fn change_figures(out: &Path, page: &Page) -> Result<Vec<Fig>> {
    let mut figs = Vec::new();
    for robot in ROBOTS {
        let Some(rows) = page.results.e8.get(robot).filter(|r| !r.is_empty()) else {
            continue;
        };
        let f = crate::figures::change::timelines(robot, rows);
        plot::save(&f, &out.join("E8"), &format!("{robot}_change"))?;
        figs.push(Fig {
            file: format!("E8/{robot}_change.svg"),
            caption: format!("E8 (issue 26): {robot}, a learned controller trained on the unchanged arm (seed 0) while the robot changes — re-adapting on-policy, frozen, and analytical eq. 7 with the stale model; tracking RMS of each evaluation (the frozen and eq. 7 lines are their evaluations on the robot as it is)."),
        });
    }
    Ok(figs)
}

/// E6: each robot's variants' learning curves.
fn ablation_figures(out: &Path, page: &Page) -> Result<Vec<Fig>> {
    let r = &page.results;
    let mut figs = Vec::new();
    for robot in ROBOTS {
        let plotted = page
            .figures
            .ablation
            .get(robot)
            .cloned()
            .unwrap_or_default();
        let reference = r.e2.get(&format!("{robot}_eq7")).map(|v| v.tracking_rms_mm);
        let title = format!("{robot}: ablation — reward weighting, cost, localisation");
        let t_max = r.config.sizes.robot(robot).minutes;
        let f = learned::curves(&title, &plotted, reference, t_max);
        plot::save(&f, &out.join("E6"), &format!("{robot}_ablation"))?;
        figs.push(Fig {
            file: format!("E6/{robot}_ablation.svg"),
            caption: format!("E6 (paper Sec. II, IV): {robot}, RWR vs unweighted (supervised) inverse learning, RWR as in the paper (full cost, no shrinkage), and a global unweighted inverse model — tracking, command error against u*, command cost over training."),
        });
    }
    Ok(figs)
}
