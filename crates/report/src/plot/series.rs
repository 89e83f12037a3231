//! Drawing one data series (lines, dashes, markers, error bars) and its legend entry.

use super::render::err;
use super::{Series, Style};
use crate::error::Result;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

/// The chart type every panel uses (transformed f64 axes).
pub(super) type Chart<'a, DB> =
    ChartContext<'a, DB, Cartesian2d<RangedCoordf64, plotters::coord::types::RangedCoordf64>>;

/// Draws one series (points mapped by `t`, which drops unshowable points) with its legend entry.
pub(super) fn draw_series<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    s: &Series,
    color: RGBColor,
    t: impl Fn((f64, f64)) -> Option<(f64, f64)>,
) -> Result<()> {
    let w = s.width.max(1);
    if let Some(errs) = &s.errors {
        let bars = s
            .points
            .iter()
            .zip(errs)
            .filter_map(|(&(x, y), &(lo, hi))| {
                let ((xt, yt), (_, lt), (_, ht)) = (t((x, y))?, t((x, lo))?, t((x, hi))?);
                Some(ErrorBar::new_vertical(
                    xt,
                    lt,
                    yt,
                    ht,
                    color.stroke_width(w),
                    8,
                ))
            });
        chart.draw_series(bars).map_err(err)?;
    }
    let mut label = s.label.as_deref();
    if matches!(s.style, Style::Line | Style::Dashed | Style::LineMarkers) {
        // Split the polyline at points that cannot be shown.
        let mut run = Vec::new();
        for p in s.points.iter().map(|&p| t(p)).chain(std::iter::once(None)) {
            match p {
                Some(q) => run.push(q),
                None if !run.is_empty() => {
                    draw_lines(chart, s, &run, color, label.take())?;
                    run.clear();
                }
                None => {}
            }
        }
    }
    if matches!(s.style, Style::Markers | Style::LineMarkers) {
        let r = if s.style == Style::Markers { w } else { w + 2 };
        let dots = s
            .points
            .iter()
            .filter_map(|&p| t(p))
            .map(|q| Circle::new(q, r, color.filled()));
        let anno = chart.draw_series(dots).map_err(err)?;
        if let Some(l) = label {
            anno.label(l)
                .legend(move |(x, y)| Circle::new((x + 10, y), r, color.filled()));
        }
    }
    Ok(())
}

/// Draws one polyline in the style of `s`, with a legend entry if `label` is given.
pub(super) fn draw_lines<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    s: &Series,
    pts: &[(f64, f64)],
    color: RGBColor,
    label: Option<&str>,
) -> Result<()> {
    let style = color.stroke_width(s.width.max(1));
    let anno = if s.style == Style::Dashed {
        let dash = 4 + 2 * s.width;
        chart
            .draw_series(DashedLineSeries::new(
                pts.to_vec(),
                dash,
                dash * 2 / 3,
                style,
            ))
            .map_err(err)?
    } else {
        chart
            .draw_series(LineSeries::new(pts.to_vec(), style))
            .map_err(err)?
    };
    if let Some(l) = label {
        let dashed = s.style == Style::Dashed;
        // Very light lines (e.g. white contours over a heat map) get a grey legend glyph.
        let light = color.0 as u32 + color.1 as u32 + color.2 as u32 > 600;
        let glyph = if light {
            RGBColor(150, 150, 150).stroke_width(s.width.max(1))
        } else {
            style
        };
        anno.label(l).legend(move |(x, y)| {
            let dash = |a: i32, b: i32| PathElement::new(vec![(a, 0), (b, 0)], glyph);
            if dashed {
                EmptyElement::at((x, y)) + dash(0, 6) + dash(10, 16) + dash(20, 24)
            } else {
                EmptyElement::at((x, y)) + dash(0, 8) + dash(8, 16) + dash(16, 24)
            }
        });
    }
    Ok(())
}
