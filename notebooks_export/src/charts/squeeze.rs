//! What a squeezing residual learned: each episode's grip force as the lift began against the
//! squeeze its cube needed (weight over twice the pad–cube friction), coloured by outcome, with
//! the line where the two are equal: above it the grip holds the cube, below it the cube slides.

use std::path::Path;

use plotters::prelude::*;

use super::axis::Axis;
use super::{draw_axes, draw_legend, finite_points, outcome_color};
use crate::error::ReportError;
use crate::raster::{FONT, de, render_png};
use fairgrasp_types::Outcome;

/// Pixel size of the chart.
pub const SIZE: (u32, u32) = (1000, 760);

/// One episode on the chart: the squeeze needed \[N\], the grip force at lift \[N\], its outcome.
pub type SqueezePoint = (f64, f64, Outcome);

/// Draws `points` (episodes that never lifted are left out by the caller) under `title`.
pub fn squeeze_chart(points: &[SqueezePoint], title: &str, path: &Path) -> Result<(), ReportError> {
    let xy = finite_points(points.iter().map(|p| (p.0, p.1)));
    let all = xy.iter().flat_map(|p| [p.0, p.1]).chain([0.0]);
    let axis = Axis::fit(all, 0.06, 1.0);
    let (lo, hi) = axis.ends();
    render_png(path, SIZE, |root| {
        let (head, body) = root.split_vertically(64);
        head.draw(&Text::new(title.to_string(), (14, 8), (FONT, 20)))
            .map_err(de)?;
        head.draw(&Text::new(
            "grip force as the lift began against the squeeze each cube needed; one dot per episode that lifted · dashed: grip = need",
            (14, 38),
            (FONT, 14).into_font().color(&RGBColor(90, 90, 90)),
        ))
        .map_err(de)?;
        let mut chart = ChartBuilder::on(&body)
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(56)
            .build_cartesian_2d(axis, axis)
            .map_err(de)?;
        draw_axes(
            &mut chart,
            "squeeze the cube needs per finger, m·g / (2·μ) [N]",
            "grip force per finger as the lift began [N]",
            Some(8),
        )?;
        chart
            .draw_series(DashedLineSeries::new(
                vec![(lo, lo), (hi, hi)],
                8,
                5,
                BLACK.mix(0.6).stroke_width(1),
            ))
            .map_err(de)?;
        for outcome in Outcome::ALL.iter().copied() {
            let mine: Vec<(f64, f64)> = points
                .iter()
                .filter(|p| p.2 == outcome && p.0.is_finite() && p.1.is_finite())
                .map(|p| (p.0, p.1))
                .collect();
            if mine.is_empty() {
                continue;
            }
            let color = outcome_color(outcome);
            chart
                .draw_series(mine.iter().map(|p| Circle::new(*p, 4, color.filled())))
                .map_err(de)?
                .label(format!("{outcome} ({})", mine.len()))
                .legend(move |(x, y)| Circle::new((x + 8, y), 4, color.filled()));
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperLeft, 13)
    })
}
