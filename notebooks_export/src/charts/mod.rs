//! PNG charts and the GIF replay, drawn with plotters and the embedded DejaVu font.

pub mod curves;
pub mod episode;
pub mod replay;
pub mod success;
pub mod workspace;

use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

use crate::raster::{FONT, de};
use fairgrasp_types::Outcome;

/// Every chart here: f64 × f64 Cartesian axes on the bitmap backend.
pub(crate) type Chart<'a, 'b> =
    ChartContext<'a, BitMapBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

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

/// Tableau 10: readable on white, distinguishable in greyscale print by lightness; ten methods
/// (three scripts and seven policies) get ten colours before any repeats.
pub const PALETTE: [RGBColor; 10] = [
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

/// `[lo, hi]` widened by `margin` of its span (and to at least `min_span`).
pub(crate) fn padded(lo: f64, hi: f64, margin: f64, min_span: f64) -> (f64, f64) {
    let (lo, hi) = if lo.is_finite() && hi.is_finite() && lo <= hi {
        (lo, hi)
    } else {
        (0.0, 1.0)
    };
    let mid = 0.5 * (lo + hi);
    let half = (0.5 * (hi - lo)).max(0.5 * min_span) * (1.0 + margin);
    (mid - half, mid + half)
}

/// The smallest and largest finite value.
pub(crate) fn min_max(values: impl IntoIterator<Item = f64>) -> (f64, f64) {
    values
        .into_iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        })
}

/// Ranges for an equal-aspect plot of `(x, y)` bounds in a `w × h` pixel area.
pub(crate) fn equal_aspect(
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
    (w, h): (f64, f64),
) -> ((f64, f64), (f64, f64)) {
    let scale = ((x1 - x0) / w).max((y1 - y0) / h);
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    (
        (cx - 0.5 * scale * w, cx + 0.5 * scale * w),
        (cy - 0.5 * scale * h, cy + 0.5 * scale * h),
    )
}
