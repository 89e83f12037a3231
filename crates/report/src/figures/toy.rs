//! The two figures of E1 (`osrl toy`): iterations to converge against the initial `τ`, and
//! the paper's Fig. 1.

use crate::error::Result;
use crate::plot::{self, Contours, Figure, HeatMap, Legend, Panel, Rgb, Series, Style, PALETTE};
use osrl_experiments::toy::{Fig1, FIG1_STEPS, FIG1_TAU0};
use rwr::toy::{Report, ToyConfig, Variant};
use std::path::{Path, PathBuf};

const RED: Rgb = Rgb(200, 30, 30);

/// Iterations to converge (median, IQR bars) vs initial τ: one panel per σ setting.
pub fn iterations(cfg: &ToyConfig, report: &Report, out: &Path) -> Result<Vec<PathBuf>> {
    let mut panels = Vec::new();
    for sigma_update in [false, true] {
        let title = if sigma_update {
            "σ updated (eq. 24)"
        } else {
            "σ fixed"
        };
        let mut p = Panel::new(title, "initial τ", "EM iterations to ‖θ − θ*‖ < ε");
        p.log_x = true;
        p.log_y = true;
        p.legend = Legend::UpperRight;
        let (x0, x1) = cfg
            .tau0s
            .iter()
            .fold((f64::INFINITY, 0.0f64), |a, &t| (a.0.min(t), a.1.max(t)));
        p.x_range = Some((x0 / 2.0, x1 * 2.0));
        p.y_range = Some((0.7, cfg.max_iters as f64 * 2.0));
        // Fixed first and wider, so adaptive stays visible where the two coincide.
        for (i, variant) in [Variant::Fixed, Variant::Adaptive].into_iter().enumerate() {
            let rows: Vec<_> = report
                .results
                .iter()
                .filter(|r| r.variant == variant && r.sigma_update == sigma_update)
                .collect();
            let pts = rows
                .iter()
                .map(|r| (r.tau0, r.median_iters.max(1.0)))
                .collect();
            let bars = rows
                .iter()
                .map(|r| (r.q25_iters.max(1.0), r.q75_iters.max(1.0)))
                .collect();
            let label = if variant == Variant::Adaptive {
                "adaptive τ (eq. 28)"
            } else {
                "fixed τ"
            };
            let s = Series::line(label, pts)
                .style(Style::LineMarkers)
                .color(PALETTE[1 - i]);
            p.series.push(s.errors(bars).width(3 - i as u32));
        }
        let budget = vec![
            (x0 / 2.0, cfg.max_iters as f64),
            (x1 * 2.0, cfg.max_iters as f64),
        ];
        p.series.push(
            Series::line("iteration budget", budget)
                .dashed()
                .color(Rgb(120, 120, 120))
                .width(1),
        );
        panels.push(p);
    }
    let mut fig = Figure::grid(panels, 2);
    fig.title = Some(format!(
        "Median iterations (bars: 25–75%) over {} seeds; never-converged runs count as {}",
        report.seeds, cfg.max_iters
    ));
    plot::save(&fig, out, "toy_iterations")
}

/// Fig. 1 of the paper: the policy (mean, ±σ) over the transformed reward `exp(−τ r)` in the
/// (s, a) plane at several iterations, fixed (top row) vs adaptive (bottom row) `τ`,
/// initial τ = 0.1, σ updated, seed 0.
pub fn fig1(fig: &Fig1, out: &Path) -> Result<Vec<PathBuf>> {
    const STEPS: [usize; 6] = FIG1_STEPS;
    let (cfg, tau0) = (&fig.config, FIG1_TAU0);
    let (s_max, a_lo, a_hi) = (cfg.s_max, -2.5, 3.5);
    let xs: Vec<f64> = (0..=60)
        .map(|i| -s_max + 2.0 * s_max * i as f64 / 60.0)
        .collect();
    let ys: Vec<f64> = (0..=90)
        .map(|i| a_lo + (a_hi - a_lo) * i as f64 / 90.0)
        .collect();
    let star = cfg.theta_star();
    let mut panels = Vec::new();
    for variant in [Variant::Fixed, Variant::Adaptive] {
        let tr = match variant {
            Variant::Fixed => &fig.fixed,
            Variant::Adaptive => &fig.adaptive,
        };
        for &k in &STEPS {
            let Some(&st) = tr.get(k) else {
                return Err(crate::ReportError::Folder(format!(
                    "Fig. 1 needs EM iteration {k}, the trace has {}",
                    tr.len()
                )));
            };
            let name = if variant == Variant::Adaptive {
                "adaptive"
            } else {
                "fixed"
            };
            let title = format!("{name}, step {k}: τ = {:.3}, σ = {:.2}", st.tau, st.sigma);
            let mut p = Panel::new(&title, "state s", "action a");
            // exp(−τ r) relative to its maximum over the window (the max is at r = 0, so 1).
            let z: Vec<Vec<f64>> = ys
                .iter()
                .map(|&a| {
                    xs.iter()
                        .map(|&s| (-st.tau * cfg.cost(s, a)).exp())
                        .collect()
                })
                .collect();
            p.heat = Some(HeatMap {
                xs: xs.clone(),
                ys: ys.clone(),
                z: z.clone(),
                range: Some((0.0, 1.0)),
            });
            p.contours.push(Contours {
                xs: xs.clone(),
                ys: ys.clone(),
                z,
                levels: vec![0.25, 0.5, 0.75, 0.9],
                color: Rgb(255, 255, 255),
                dashed: true,
                label: Some("exp(−τ r) = .25/.5/.75/.9".into()),
            });
            let line = |off: f64| {
                vec![
                    (-s_max, st.theta[0] * -s_max + st.theta[1] + off),
                    (s_max, st.theta[0] * s_max + st.theta[1] + off),
                ]
            };
            p.series.push(
                Series::line(
                    "optimal θ*",
                    vec![(-s_max, -star[0] * s_max), (s_max, star[0] * s_max)],
                )
                .color(Rgb(0, 0, 0))
                .dashed()
                .width(2),
            );
            p.series
                .push(Series::line("policy mean", line(0.0)).color(RED).width(3));
            p.series.push(
                Series::line("mean ± σ", line(st.sigma))
                    .color(RED)
                    .dashed()
                    .width(2),
            );
            p.series.push(
                Series::line("", line(-st.sigma))
                    .color(RED)
                    .dashed()
                    .width(2),
            );
            p.x_range = Some((-s_max, s_max));
            p.y_range = Some((a_lo, a_hi));
            p.legend = if k == 0 && variant == Variant::Fixed {
                Legend::LowerLeft
            } else {
                Legend::None
            };
            panels.push(p);
        }
    }
    let mut fig = Figure::grid(panels, STEPS.len());
    fig.panel_size = (400, 340);
    fig.title = Some(format!(
        "Fig. 1: policy N(a | θ1 s + θ2, σ²) under the transformed reward exp(−τ r), r = {}, initial τ = {tau0}, σ updated — top: fixed τ, bottom: adaptive τ",
        cost_text(cfg.q)
    ));
    plot::save(&fig, out, "fig1_toy")
}

/// `q1 a² + q2 a s + q3 s²` with signs and unit coefficients written the usual way.
fn cost_text(q: [f64; 3]) -> String {
    let mut out = String::new();
    for (c, m) in q.iter().zip(["a²", "a s", "s²"]) {
        if *c == 0.0 {
            continue;
        }
        let sign = if *c < 0.0 {
            "−"
        } else if out.is_empty() {
            ""
        } else {
            "+"
        };
        let mag = if c.abs() == 1.0 {
            String::new()
        } else {
            format!("{} ", c.abs())
        };
        let sep = if out.is_empty() { "" } else { " " };
        let gap = if out.is_empty() || sign.is_empty() {
            ""
        } else {
            " "
        };
        out += &format!("{sep}{sign}{gap}{mag}{m}");
    }
    out
}

#[cfg(test)]
mod tests {
    #[test]
    fn cost_text_reads_naturally() {
        assert_eq!(super::cost_text([1.0, -1.0, 0.5]), "a² − a s + 0.5 s²");
        assert_eq!(super::cost_text([2.0, 0.0, -3.0]), "2 a² − 3 s²");
    }
}
