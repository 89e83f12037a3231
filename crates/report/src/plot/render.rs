//! Drawing a [`Figure`] with plotters onto SVG and PNG backends.

use super::series::{draw_lines, draw_series};
use super::{contour_lines, viridis, Figure, Legend, Panel, Rgb, Series, Style, PALETTE};
use crate::error::{ReportError, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

const FONT: &str = "sans-serif";
const TITLE_H: u32 = 44;
const MARGIN: u32 = 12;
const X_AREA: u32 = 48;
const Y_AREA: u32 = 70;
const CAPTION: u32 = 32;

pub(super) fn err<E: std::fmt::Debug>(e: E) -> ReportError {
    ReportError::Draw(format!("{e:?}"))
}

fn size(fig: &Figure) -> (u32, u32) {
    let rows = fig.panels.len().div_ceil(fig.columns) as u32;
    let title = if fig.title.is_some() { TITLE_H } else { 0 };
    (
        fig.columns as u32 * fig.panel_size.0,
        rows * fig.panel_size.1 + title,
    )
}

pub(super) fn to_svg(fig: &Figure, path: &Path) -> Result<()> {
    let root = SVGBackend::new(path, size(fig)).into_drawing_area();
    draw(fig, &root)?;
    root.present().map_err(err)
}

pub(super) fn to_png(fig: &Figure, path: &Path) -> Result<()> {
    let root = BitMapBackend::new(path, size(fig)).into_drawing_area();
    draw(fig, &root)?;
    root.present().map_err(err)
}

fn draw<DB: DrawingBackend>(fig: &Figure, root: &DrawingArea<DB, Shift>) -> Result<()> {
    root.fill(&WHITE).map_err(err)?;
    let area = match &fig.title {
        Some(t) => root.titled(t, (FONT, 26)).map_err(err)?,
        None => root.clone(),
    };
    let rows = fig.panels.len().div_ceil(fig.columns);
    for (panel, cell) in fig
        .panels
        .iter()
        .zip(area.split_evenly((rows, fig.columns)).iter())
    {
        draw_panel(panel, cell)?;
    }
    Ok(())
}

fn rgb(c: Rgb) -> RGBColor {
    RGBColor(c.0, c.1, c.2)
}

/// Axis transform: log10 on log axes; `None` for values that cannot be shown.
fn tf(v: f64, log: bool) -> Option<f64> {
    let t = if log {
        (v > 0.0).then(|| v.log10())?
    } else {
        v
    };
    t.is_finite().then_some(t)
}

/// Tick label: plain numbers; on log axes spanning `span` decades, the decades only, or every
/// tick when the axis spans less than 1.5 decades and might show no decade at all, with enough
/// significant digits (at least 2) that neighbouring ticks (about a tenth of the span apart)
/// differ.
fn tick(v: f64, log: bool, span: f64) -> String {
    if !log {
        return num(v);
    }
    if (v - v.round()).abs() < 1e-6 {
        return num(10f64.powi(v.round() as i32));
    }
    if span >= 1.5 {
        return String::new();
    }
    let x = 10f64.powf(v);
    // Relative step between neighbouring ticks ≈ ln 10 · span / 10.
    let step = (std::f64::consts::LN_10 * span / 10.0).max(1e-12);
    let sig = ((-step.log10()).ceil() as i32 + 1).clamp(2, 12);
    if !(1e-3..1e5).contains(&x) {
        return format!("{x:.*e}", (sig - 1) as usize);
    }
    let decimals = (sig - 1 - x.log10().floor() as i32).max(0) as usize;
    let s = format!("{x:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

fn num(v: f64) -> String {
    let a = v.abs();
    if a < 1e-12 {
        "0".into()
    } else if !(1e-3..1e5).contains(&a) {
        format!("{v:.0e}")
    } else {
        let s = format!("{v:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

/// Axis ranges (transformed) that fit everything, or the panel's fixed ranges.
fn ranges(p: &Panel, pixels: (f64, f64)) -> ((f64, f64), (f64, f64)) {
    let mut xs: Vec<f64> = Vec::new();
    let mut ys: Vec<f64> = Vec::new();
    for s in &p.series {
        for (i, &(x, y)) in s.points.iter().enumerate() {
            xs.extend(tf(x, p.log_x));
            ys.extend(tf(y, p.log_y));
            if let Some((lo, hi)) = s.errors.as_ref().and_then(|e| e.get(i)) {
                ys.extend(tf(*lo, p.log_y).into_iter().chain(tf(*hi, p.log_y)));
            }
        }
    }
    let grids = p
        .heat
        .iter()
        .map(|h| (&h.xs, &h.ys))
        .chain(p.contours.iter().map(|c| (&c.xs, &c.ys)));
    for (gx, gy) in grids {
        xs.extend(gx.iter().filter_map(|&v| tf(v, p.log_x)));
        ys.extend(gy.iter().filter_map(|&v| tf(v, p.log_y)));
    }
    let fit = |v: &[f64], fixed: Option<(f64, f64)>, log: bool| {
        if let Some((lo, hi)) = fixed.and_then(|(a, b)| Some((tf(a, log)?, tf(b, log)?))) {
            return (lo, hi);
        }
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if !lo.is_finite() {
            return (0.0, 1.0);
        }
        let pad = if hi > lo {
            0.05 * (hi - lo)
        } else {
            0.5 * lo.abs().max(1.0)
        };
        (lo - pad, hi + pad)
    };
    let (mut x, mut y) = (fit(&xs, p.x_range, p.log_x), fit(&ys, p.y_range, p.log_y));
    if p.equal_axes {
        let (ux, uy) = ((x.1 - x.0) / pixels.0, (y.1 - y.0) / pixels.1);
        let widen = |r: (f64, f64), span: f64| {
            let c = 0.5 * (r.0 + r.1);
            (c - 0.5 * span, c + 0.5 * span)
        };
        if ux > uy {
            y = widen(y, ux * pixels.1);
        } else {
            x = widen(x, uy * pixels.0);
        }
    }
    (x, y)
}

fn draw_panel<DB: DrawingBackend>(p: &Panel, cell: &DrawingArea<DB, Shift>) -> Result<()> {
    let (w, h) = cell.dim_in_pixel();
    let pixels = (
        (w - Y_AREA - 2 * MARGIN) as f64,
        (h - X_AREA - 2 * MARGIN - CAPTION) as f64,
    );
    let ((x0, x1), (y0, y1)) = ranges(p, pixels);
    let mut chart = ChartBuilder::on(cell)
        .caption(&p.title, (FONT, 20))
        .margin(MARGIN)
        .x_label_area_size(X_AREA)
        .y_label_area_size(Y_AREA)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(err)?;
    let (lx, ly) = (p.log_x, p.log_y);
    let fx = move |v: &f64| tick(*v, lx, x1 - x0);
    let fy = move |v: &f64| tick(*v, ly, y1 - y0);
    chart
        .configure_mesh()
        .x_desc(&p.x_label)
        .y_desc(&p.y_label)
        .label_style((FONT, 15))
        .axis_desc_style((FONT, 16))
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .bold_line_style(RGBColor(215, 215, 215))
        .light_line_style(RGBColor(240, 240, 240))
        .draw()
        .map_err(err)?;
    let t = |(x, y): (f64, f64)| Some((tf(x, lx)?, tf(y, ly)?));
    if let Some(hm) = &p.heat {
        let flat = hm.z.iter().flatten().copied().filter(|v| v.is_finite());
        let (lo, hi) = hm.range.unwrap_or_else(|| {
            flat.fold((f64::INFINITY, f64::NEG_INFINITY), |a, v| {
                (a.0.min(v), a.1.max(v))
            })
        });
        let edges = |g: &[f64], i: usize| {
            let a = if i == 0 {
                g[0]
            } else {
                0.5 * (g[i - 1] + g[i])
            };
            let b = if i + 1 == g.len() {
                g[i]
            } else {
                0.5 * (g[i] + g[i + 1])
            };
            (a, b)
        };
        let mut cells = Vec::new();
        for (iy, row) in hm.z.iter().enumerate().take(hm.ys.len()) {
            for (ix, &v) in row.iter().enumerate().take(hm.xs.len()) {
                let ((xa, xb), (ya, yb)) = (edges(&hm.xs, ix), edges(&hm.ys, iy));
                if let (Some(a), Some(b), true) = (t((xa, ya)), t((xb, yb)), v.is_finite()) {
                    let c = rgb(viridis((v - lo) / (hi - lo)));
                    cells.push(Rectangle::new([a, b], c.filled()));
                }
            }
        }
        chart.draw_series(cells).map_err(err)?;
    }
    for c in &p.contours {
        let mut labelled = c.label.is_none();
        for &level in &c.levels {
            for line in contour_lines(&c.xs, &c.ys, &c.z, level) {
                let pts: Vec<(f64, f64)> = line.into_iter().filter_map(t).collect();
                let s = Series {
                    label: None,
                    points: pts,
                    errors: None,
                    color: Some(c.color),
                    style: if c.dashed { Style::Dashed } else { Style::Line },
                    width: 1,
                };
                let label = if labelled { None } else { c.label.as_deref() };
                labelled = true;
                draw_lines(&mut chart, &s, &s.points, rgb(c.color), label)?;
            }
        }
    }
    for (i, s) in p.series.iter().enumerate() {
        let color = rgb(s.color.unwrap_or(PALETTE[i % PALETTE.len()]));
        draw_series(&mut chart, s, color, t)?;
    }
    let pos = match p.legend {
        Legend::None => return Ok(()),
        Legend::UpperRight => SeriesLabelPosition::UpperRight,
        Legend::UpperLeft => SeriesLabelPosition::UpperLeft,
        Legend::LowerRight => SeriesLabelPosition::LowerRight,
        Legend::LowerLeft => SeriesLabelPosition::LowerLeft,
    };
    let any_label =
        p.series.iter().any(|s| s.label.is_some()) || p.contours.iter().any(|c| c.label.is_some());
    if any_label {
        chart
            .configure_series_labels()
            .position(pos)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.4))
            .label_font((FONT, 14))
            .draw()
            .map_err(err)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::tick;

    #[test]
    fn log_ticks_label_decades_and_short_axes_label_every_tick() {
        // A wide log axis: decades only.
        assert_eq!(tick(-1.0, true, 3.0), "0.1");
        assert_eq!(tick(2.0, true, 3.0), "100");
        assert_eq!(tick(0.05f64.log10(), true, 3.0), "");
        // Less than 1.5 decades: every tick, two significant digits (trailing zeros dropped).
        assert_eq!(tick(0.05f64.log10(), true, 0.6), "0.05");
        assert_eq!(tick(0.063f64.log10(), true, 0.6), "0.063");
        assert_eq!(tick(1.4f64.log10(), true, 0.6), "1.4");
        assert_eq!(tick(25f64.log10(), true, 0.6), "25");
        assert_eq!(tick(2e-5f64.log10(), true, 0.6), "2.0e-5");
        // A very short axis (0.991–1.0): enough digits that neighbouring ticks differ.
        let span = 1.0f64.log10() - 0.991f64.log10();
        assert_eq!(tick(0.992f64.log10(), true, span), "0.992");
        assert_eq!(tick(0.9925f64.log10(), true, span), "0.9925");
        assert_ne!(
            tick(0.993f64.log10(), true, span),
            tick(0.994f64.log10(), true, span)
        );
        // Linear axes are unchanged.
        assert_eq!(tick(0.25, false, 0.6), "0.25");
    }
}
