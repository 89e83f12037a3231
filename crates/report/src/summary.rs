//! The page's opening table: each claim of the paper (Peters & Schaal 2007), in this project's
//! words, next to this run's number for it.

use crate::page::{escape, num, spread, table};
use osrl_experiments::results::{Results, RunsSummary};
use osrl_experiments::stats::{Outcome, Stat, Status};

/// A measured statistic with its unit, or why there is none.
fn val(s: &Stat, unit: &str) -> String {
    match s {
        Stat::Spread(v) => format!("{}{unit}", spread(v)),
        Stat::Missing(m) if m.status == Status::Diverged => "diverged (every seed)".into(),
        Stat::Missing(_) => "failed".into(),
    }
}

/// The runs summary of E3 for `robot`, if it ran.
fn e3<'a>(r: &'a Results, robot: &str) -> Option<&'a RunsSummary> {
    r.e3.get(robot).and_then(Outcome::done).map(|v| &v.summary)
}

/// `x` or `—`.
fn or_dash(s: Option<&RunsSummary>, f: impl Fn(&RunsSummary) -> String) -> String {
    s.map_or_else(|| num(None), f)
}

/// E1: the fixed/adaptive ratios of the median iterations for a mis-scaled initial `τ`.
fn toy(r: &Results) -> String {
    let c = rwr::toy::check_claims(&r.e1);
    let ratios: Vec<f64> = (c.speedups.iter())
        .filter(|s| s.tau0 <= 0.1)
        .map(|s| s.ratio)
        .collect();
    let lo = ratios.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = ratios.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let range = if ratios.is_empty() {
        num(None)
    } else {
        format!("{}–{}×", num(Some(lo)), num(Some(hi)))
    };
    format!(
        "fixed / adaptive median EM iterations with initial τ ≤ 0.1: {range}; adaptive never more \
         than 20 % slower: {} ({} seeds per case)",
        if c.never_20pct_slower { "yes" } else { "no" },
        r.e1.seeds
    )
}

fn tracking(r: &Results, robot: &str) -> String {
    let s = e3(r, robot);
    let eq7 = r.e3.get(robot).and_then(Outcome::done);
    format!(
        "{robot}: tracking RMS {} over {} seeds (eq. 7 with the true model: {} mm)",
        or_dash(s, |s| val(&s.tracking_rms_mm, " mm")),
        or_dash(s, |s| s.runs.to_string()),
        num(eq7.and_then(|v| v.analytical_eq7_tracking_rms_mm))
    )
}

fn commands(r: &Results, robot: &str) -> String {
    let s = e3(r, robot);
    format!(
        "{robot}: command nMSE against u* {}, command cost / that of u* {}",
        or_dash(s, |s| val(&s.command_nmse, "")),
        or_dash(s, |s| val(&s.command_cost_ratio, ""))
    )
}

fn training(r: &Results) -> String {
    let part = |robot: &str| {
        let s = e3(r, robot);
        format!(
            "{robot} {} simulated minutes at {}× real time",
            r.config.sizes.robot(robot).minutes,
            or_dash(s, |s| spread(&s.realtime_factor))
        )
    };
    format!("{}; {}", part("planar3"), part("sarcos7"))
}

fn ablation(r: &Results) -> String {
    let part = |robot: &str| {
        let row = |k: &str| {
            (r.e6.get(robot))
                .and_then(|m| m.get(k))
                .and_then(Outcome::done)
                .map_or_else(
                    || "failed".into(),
                    |v| val(&v.summary.tracking_rms_mm, " mm"),
                )
        };
        format!(
            "{robot} tracking without the command projection (as in the paper): RWR {}, \
             unweighted regression {}, global model {}; with it (the default since D32): RWR \
             {}, unweighted regression {}",
            row("rwr_unprojected"),
            row("unweighted"),
            row("global_unweighted"),
            row("rwr"),
            row("unweighted_projected")
        )
    };
    format!("{}; {}", part("planar3"), part("sarcos7"))
}

fn model_errors(r: &Results) -> String {
    let part = |robot: &str| {
        let rows = r.e7.get(robot);
        let wrong: Vec<f64> = rows
            .into_iter()
            .flatten()
            .filter(|(k, _)| k.as_str() != "none")
            .filter_map(|(_, v)| v.analytical_eq7_tracking_rms_mm)
            .collect();
        let lo = wrong.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = wrong.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let none = rows.and_then(|m| m.get("none"));
        format!(
            "{robot}: eq. 7 {} mm with the true model, {}–{} mm with a wrong one; learned {}",
            num(none.and_then(|v| v.analytical_eq7_tracking_rms_mm)),
            num((!wrong.is_empty()).then_some(lo)),
            num((!wrong.is_empty()).then_some(hi)),
            none.map_or_else(|| num(None), |v| val(&v.learned_tracking_rms_mm, " mm"))
        )
    };
    format!("{}; {}", part("planar3"), part("sarcos7"))
}

/// The summary table (HTML): one row per claim of the paper, with this run's numbers.
pub fn summary(r: &Results) -> String {
    let rows = [
        ("Fig. 1 (E1)", "Making the reward transformation adaptive speeds up reward-weighted regression on the 1-D toy problem about four-fold.", toy(r)),
        ("Fig. 2b (E3)", "The learned controller of the 3-DOF arm tracks the figure-8 almost perfectly.", tracking(r, "planar3")),
        ("Fig. 2c (E4)", "Its commands are nearly those of the analytical optimum u* (eq. 7).", commands(r, "planar3")),
        ("Fig. 3b (E3, E4)", "The 7-DOF SARCOS arm tracks nearly as well, its commands further from the optimum.", format!("{}; {}", tracking(r, "sarcos7"), commands(r, "sarcos7"))),
        ("Sec. V (E5)", "Training took about 2 hours of real time on the 3-DOF arm and 60 minutes on the 7-DOF arm.", training(r)),
        ("Sec. II, IV (E6)", "Learning the inverse model by plain supervised regression is ill-posed for a redundant arm; reward-weighted regression makes it well-posed.", ablation(r)),
        ("Sec. I (E7)", "Analytical operational space control degrades with errors in the robot's model; a learned controller needs no model.", model_errors(r)),
    ];
    let rows: Vec<Vec<String>> = rows
        .into_iter()
        .map(|(w, c, n)| vec![w.to_string(), c.to_string(), n])
        .collect();
    format!(
        "<h2>Summary</h2><p>{}</p>\n{}",
        escape(
            "The paper's claims, in our words, and this run's numbers (tables and figures below)."
        ),
        table(&["paper", "claim", "this run"], &rows).replacen(
            "<table>",
            "<table class=\"summary\">",
            1
        )
    )
}
