//! PNG charts and the GIF replay, drawn with plotters and the embedded DejaVu font.
//!
//! Every chart finishes on any numbers its input holds. Axes are [`axis::Axis`] (bounded tick
//! computation, overflow-free pixel mapping): finite values of any size are drawn, pinned just
//! past the axis end when they lie far outside it. Points with a non-finite coordinate (NaN,
//! ±infinity: an empty `metrics.csv` cell, a value beyond `f64`) are skipped, as if not
//! recorded; a line joins the points on either side. A request the data cannot meet (a replay
//! still past the last step, an episode without steps) is refused with an error that names the
//! allowed range.

pub mod axis;
pub mod curves;
pub(crate) mod draw_all;
pub mod episode;
pub mod heatmap;
pub mod replay;
pub mod squeeze;
pub mod success;
pub mod takt;
pub mod workspace;

pub(crate) use axis::{min_max, padded};

use plotters::prelude::*;

use crate::raster::{FONT, de};
use axis::Axis;
use fairgrasp_types::Outcome;

/// Every chart here: [`Axis`] × [`Axis`] Cartesian coordinates on the bitmap backend.
pub(crate) type Chart<'a, 'b> = ChartContext<'a, BitMapBackend<'b>, Cartesian2d<Axis, Axis>>;

/// Draws the chart's legend at `position` in the house style (white box, black border).
pub(crate) fn draw_legend<'a, 'b: 'a>(
    chart: &mut Chart<'a, 'b>,
    position: SeriesLabelPosition,
    font_size: u32,
) -> Result<(), String> {
    chart
        .configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .label_font((FONT, font_size))
        .draw()
        .map_err(de)
}

/// Draws axes, tick labels and the major grid in the house style (no minor grid); `labels` sets
/// the number of ticks on both axes (plotters' default when `None`).
pub(crate) fn draw_axes<'a, 'b: 'a>(
    chart: &mut Chart<'a, 'b>,
    x_desc: &str,
    y_desc: &str,
    labels: Option<usize>,
) -> Result<(), String> {
    let mut mesh = chart.configure_mesh();
    if let Some(n) = labels {
        mesh.x_labels(n).y_labels(n);
    }
    mesh.x_desc(x_desc)
        .y_desc(y_desc)
        .label_style((FONT, 12))
        .axis_desc_style((FONT, 13))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(de)
}

/// A legend entry for a line series: a short thick stroke.
pub(crate) fn line_mark(color: RGBColor) -> impl Fn((i32, i32)) -> PathElement<(i32, i32)> {
    move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(3))
}

/// Tableau 10 and two darker colours: readable on white, distinguishable in greyscale print by
/// lightness; the twelve methods of the default comparison (the four scripts and eight shipped
/// policies) get twelve colours before any repeats.
pub const PALETTE: [RGBColor; 12] = [
    RGBColor(78, 121, 167),
    RGBColor(242, 142, 43),
    RGBColor(89, 161, 79),
    RGBColor(225, 87, 89),
    RGBColor(176, 122, 161),
    RGBColor(118, 183, 178),
    RGBColor(156, 117, 95),
    RGBColor(237, 201, 72),
    RGBColor(255, 157, 167),
    RGBColor(186, 176, 172),
    RGBColor(64, 64, 64),
    RGBColor(106, 61, 154),
];

/// The colour of the `i`-th method or run (the same in every chart).
pub fn series_color(i: usize) -> RGBColor {
    PALETTE[i % PALETTE.len()]
}

/// The colour of an episode outcome in workspace maps.
pub fn outcome_color(outcome: Outcome) -> RGBColor {
    match outcome {
        Outcome::Success => RGBColor(89, 161, 79),
        Outcome::MissedGrasp => RGBColor(242, 142, 43),
        Outcome::SlipOrDrop => RGBColor(176, 122, 161),
        Outcome::Collision => RGBColor(225, 87, 89),
        Outcome::IkFailure => RGBColor(156, 117, 95),
        Outcome::ObjectOffTable => RGBColor(118, 183, 178),
        Outcome::ProtectiveStop => RGBColor(78, 121, 167),
        Outcome::Timeout => RGBColor(120, 120, 120),
        Outcome::PhysicsFault => RGBColor(0, 0, 0),
    }
}

/// Axes for an equal-aspect plot of `(x, y)` bounds (from [`padded`]) in a `w × h` pixel area.
pub(crate) fn equal_aspect(
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
    (w, h): (f64, f64),
) -> (Axis, Axis) {
    let (w, h) = (w.max(1.0), h.max(1.0));
    let scale = ((0.5 * x1 - 0.5 * x0) / w).max((0.5 * y1 - 0.5 * y0) / h);
    let (cx, cy) = (0.5 * x0 + 0.5 * x1, 0.5 * y0 + 0.5 * y1);
    (
        Axis::new(cx - scale * w, cx + scale * w),
        Axis::new(cy - scale * h, cy + scale * h),
    )
}

/// The points whose both coordinates are finite (see the module documentation).
pub(crate) fn finite_points(points: impl IntoIterator<Item = (f64, f64)>) -> Vec<(f64, f64)> {
    points
        .into_iter()
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .collect()
}
