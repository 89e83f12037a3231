//! Figures for every experiment: line plots with several series and a legend, scatter/path
//! plots with equal axes, heat maps with contour lines, multi-panel figures — each written as
//! SVG and PNG. Text uses an embedded DejaVu Sans (`assets/`), so no system fonts are needed
//! for the PNG (the SVG names the family `sans-serif` for the viewer).
//!
//! Build a [`Figure`] of [`Panel`]s, each with [`Series`] (and optionally a [`HeatMap`] and
//! [`Contours`]), then [`save`] it:
//! ```
//! use osrl_report::plot::{self, Figure, Panel, Series, PALETTE};
//! let pts: Vec<(f64, f64)> = (0..50).map(|i| (0.1 * i as f64, (0.1 * i as f64).sin())).collect();
//! let panel = Panel::new("tracking", "time [s]", "error [mm]")
//!     .with(Series::line("learned", pts.clone()).color(PALETTE[0]))
//!     .with(Series::line("analytical", pts).dashed());
//! let dir = std::env::temp_dir().join(format!("osrl-plot-doc-{}", std::process::id()));
//! let files = plot::save(&Figure::grid(vec![panel], 1), &dir, "tracking")?; // .svg + .png
//! assert_eq!(files.len(), 2);
//! # std::fs::remove_dir_all(&dir).unwrap();
//! # Ok::<(), osrl_report::ReportError>(())
//! ```

mod contour;
mod render;
mod series;

pub use contour::{contour_lines, contour_segments, viridis};

use crate::error::{ReportError, Result};
use std::path::{Path, PathBuf};

/// An RGB colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rgb(pub u8, pub u8, pub u8);

/// Colour-blind-safe series colours (Okabe–Ito order): blue, vermillion, green, orange, purple,
/// sky blue, yellow, black.
pub const PALETTE: [Rgb; 8] = [
    Rgb(0, 114, 178),
    Rgb(213, 94, 0),
    Rgb(0, 158, 115),
    Rgb(230, 159, 0),
    Rgb(204, 121, 167),
    Rgb(86, 180, 233),
    Rgb(240, 228, 66),
    Rgb(0, 0, 0),
];

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// Solid polyline.
    Line,
    /// Dashed polyline.
    Dashed,
    /// Filled circles only (scatter).
    Markers,
    /// Solid polyline with filled circles.
    LineMarkers,
}

/// One data series. Points with a non-finite coordinate (or non-positive on a log axis) are
/// skipped.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend text; `None` = not in the legend.
    pub label: Option<String>,
    /// `(x, y)` points in drawing order.
    pub points: Vec<(f64, f64)>,
    /// Optional vertical error bars `(low, high)`, one per point.
    pub errors: Option<Vec<(f64, f64)>>,
    /// Colour; `None` = next palette colour by position in the panel.
    pub color: Option<Rgb>,
    /// Line or marker style.
    pub style: Style,
    /// Line width / marker radius in pixels.
    pub width: u32,
}

impl Series {
    /// A solid line; `label` may be empty for no legend entry.
    pub fn line(label: &str, points: Vec<(f64, f64)>) -> Self {
        let label = (!label.is_empty()).then(|| label.to_string());
        Self {
            label,
            points,
            errors: None,
            color: None,
            style: Style::Line,
            width: 2,
        }
    }
    /// A scatter of markers.
    pub fn markers(label: &str, points: Vec<(f64, f64)>) -> Self {
        Self {
            style: Style::Markers,
            width: 3,
            ..Self::line(label, points)
        }
    }
    /// Sets the colour.
    pub fn color(mut self, c: Rgb) -> Self {
        self.color = Some(c);
        self
    }
    /// Sets the style.
    pub fn style(mut self, s: Style) -> Self {
        self.style = s;
        self
    }
    /// Dashed line.
    pub fn dashed(self) -> Self {
        self.style(Style::Dashed)
    }
    /// Sets the line width / marker radius (pixels).
    pub fn width(mut self, w: u32) -> Self {
        self.width = w;
        self
    }
    /// Adds vertical error bars `(low, high)` (same length as `points`).
    pub fn errors(mut self, e: Vec<(f64, f64)>) -> Self {
        self.errors = Some(e);
        self
    }
}

/// Values `z[iy][ix]` on the grid `xs × ys` (increasing), drawn as coloured cells.
#[derive(Debug, Clone, PartialEq)]
pub struct HeatMap {
    /// Grid x coordinates (increasing).
    pub xs: Vec<f64>,
    /// Grid y coordinates (increasing).
    pub ys: Vec<f64>,
    /// `z[iy][ix]`.
    pub z: Vec<Vec<f64>>,
    /// Colour range `(low, high)`; `None` = data min/max.
    pub range: Option<(f64, f64)>,
}

/// Contour lines of `z[iy][ix]` on `xs × ys` at the given levels (marching squares).
#[derive(Debug, Clone, PartialEq)]
pub struct Contours {
    /// Grid x coordinates (increasing).
    pub xs: Vec<f64>,
    /// Grid y coordinates (increasing).
    pub ys: Vec<f64>,
    /// `z[iy][ix]`.
    pub z: Vec<Vec<f64>>,
    /// Levels to draw.
    pub levels: Vec<f64>,
    /// Line colour.
    pub color: Rgb,
    /// Dashed (`true`) or solid lines.
    pub dashed: bool,
    /// Legend text for the contour set, if any.
    pub label: Option<String>,
}

/// Where the legend goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Legend {
    /// No legend.
    None,
    /// Upper right corner.
    UpperRight,
    /// Upper left corner.
    UpperLeft,
    /// Lower right corner.
    LowerRight,
    /// Lower left corner.
    LowerLeft,
}

/// One set of axes.
#[derive(Debug, Clone, PartialEq)]
pub struct Panel {
    /// Title above the axes.
    pub title: String,
    /// x-axis label.
    pub x_label: String,
    /// y-axis label.
    pub y_label: String,
    /// Data series, drawn in order over the heat map and contours.
    pub series: Vec<Series>,
    /// Optional background heat map.
    pub heat: Option<HeatMap>,
    /// Contour line sets.
    pub contours: Vec<Contours>,
    /// Fixed x range; `None` = fit the data with 5% padding.
    pub x_range: Option<(f64, f64)>,
    /// Fixed y range; `None` = fit the data.
    pub y_range: Option<(f64, f64)>,
    /// Logarithmic x axis (decades labelled).
    pub log_x: bool,
    /// Logarithmic y axis.
    pub log_y: bool,
    /// Same scale on both axes (for paths in space); ranges are widened to achieve it.
    pub equal_axes: bool,
    /// Legend position.
    pub legend: Legend,
}

impl Panel {
    /// An empty panel with a legend in the upper right.
    pub fn new(title: &str, x_label: &str, y_label: &str) -> Self {
        Self {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            series: Vec::new(),
            heat: None,
            contours: Vec::new(),
            x_range: None,
            y_range: None,
            log_x: false,
            log_y: false,
            equal_axes: false,
            legend: Legend::UpperRight,
        }
    }
    /// Adds a series.
    pub fn with(mut self, s: Series) -> Self {
        self.series.push(s);
        self
    }
}

/// Panels on a grid, row by row.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// Optional title over all panels.
    pub title: Option<String>,
    /// Panels, row-major.
    pub panels: Vec<Panel>,
    /// Panels per row (≥ 1).
    pub columns: usize,
    /// Size of one panel in pixels (width, height).
    pub panel_size: (u32, u32),
}

impl Figure {
    /// `panels` on `columns` columns, 640×480 pixels each, no title.
    pub fn grid(panels: Vec<Panel>, columns: usize) -> Self {
        Self {
            title: None,
            panels,
            columns: columns.max(1),
            panel_size: (640, 480),
        }
    }
}

/// Registers the embedded font once (plotters looks fonts up by family name).
fn register_font() -> Result<()> {
    static FONT: &[u8] = include_bytes!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/DejaVuSans.ttf"
    ));
    static DONE: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    let ok = *DONE.get_or_init(|| {
        plotters::style::register_font("sans-serif", plotters::style::FontStyle::Normal, FONT)
            .is_ok()
    });
    ok.then_some(())
        .ok_or_else(|| ReportError::Draw("embedded font could not be loaded".into()))
}

/// Writes `dir/stem.svg` and `dir/stem.png` (creating `dir`), returning both paths. Fails on
/// an empty figure, an I/O error, or a drawing error.
pub fn save(fig: &Figure, dir: &Path, stem: &str) -> Result<Vec<PathBuf>> {
    if fig.panels.is_empty() {
        return Err(ReportError::Draw(format!("figure {stem} has no panels")));
    }
    register_font()?;
    crate::error::create_dir(dir)?;
    let svg = dir.join(format!("{stem}.svg"));
    let png = dir.join(format!("{stem}.png"));
    osrl_files::check_output(&svg)?;
    osrl_files::check_output(&png)?;
    let at = |p: &Path, e: ReportError| ReportError::Draw(format!("drawing {}: {e}", p.display()));
    render::to_svg(fig, &svg).map_err(|e| at(&svg, e))?;
    render::to_png(fig, &png).map_err(|e| at(&png, e))?;
    Ok(vec![svg, png])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_kind_of_panel_is_written_as_svg_and_png() {
        let dir = std::env::temp_dir().join(format!("osrl-plot-test-{}", std::process::id()));
        let g: Vec<f64> = (0..21).map(|i| -1.0 + 0.1 * i as f64).collect();
        let z: Vec<Vec<f64>> = g
            .iter()
            .map(|y| g.iter().map(|x| x * x + 2.0 * y * y).collect())
            .collect();
        let curve: Vec<(f64, f64)> = (1..50).map(|i| (i as f64, 1.0 / i as f64)).collect();
        let mut lines = Panel::new("lines", "x", "y")
            .with(
                Series::line("a", curve.clone())
                    .errors(curve.iter().map(|p| (p.1 * 0.5, p.1 * 2.0)).collect()),
            )
            .with(
                Series::line(
                    "b",
                    vec![(1.0, f64::NAN), (2.0, 0.5), (3.0, -1.0), (4.0, 0.2)],
                )
                .dashed(),
            );
        lines.log_x = true;
        lines.log_y = true; // the NaN and the negative point are skipped
        let mut path = Panel::new("path", "x [m]", "z [m]")
            .with(Series::markers("pts", vec![(0.0, 0.0), (1.0, 0.1)]));
        path.equal_axes = true;
        path.legend = Legend::LowerLeft;
        let mut heat = Panel::new("heat", "x", "y");
        heat.heat = Some(HeatMap {
            xs: g.clone(),
            ys: g.clone(),
            z: z.clone(),
            range: None,
        });
        heat.contours.push(Contours {
            xs: g.clone(),
            ys: g.clone(),
            z,
            levels: vec![0.2, 0.5],
            color: Rgb(255, 255, 255),
            dashed: true,
            label: Some("levels".into()),
        });
        let mut fig = Figure::grid(vec![lines, path, heat], 2);
        fig.title = Some("test figure".into());
        let files = save(&fig, &dir, "all").unwrap();
        let png = std::fs::read(&files[1]).unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
        let svg = std::fs::read_to_string(&files[0]).unwrap();
        assert!(svg.contains("test figure") && svg.contains("levels") && svg.contains("<svg"));
        assert!(save(&Figure::grid(vec![], 1), &dir, "empty").is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
