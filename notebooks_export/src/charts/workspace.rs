//! Top view of the workspace: where each episode's object started (in `base_link`), coloured by
//! outcome, one panel per method, for one preset.

use std::path::Path;

use plotters::prelude::*;

use super::{draw_axes, equal_aspect, min_max, outcome_color, padded};
use crate::comparison_table::{Comparison, Outcome};
use crate::error::ReportError;
use crate::raster::{FONT, de, render_png};

/// Pixel height of a workspace map; the width grows with the number of methods.
pub const HEIGHT: u32 = 560;
/// Pixel width of one method's panel.
pub const PANEL_WIDTH: u32 = 480;

/// Draws the map of `preset` (all methods side by side, same axes).
pub fn workspace_map(c: &Comparison, preset: &str, path: &Path) -> Result<(), ReportError> {
    let results: Vec<_> = c.results.iter().filter(|r| r.preset == preset).collect();
    let points = results
        .iter()
        .flat_map(|r| r.report.results.iter().map(|e| e.object_xy));
    let (x_lo, x_hi) = min_max(points.clone().map(|p| p[0]).chain([0.0]));
    let (y_lo, y_hi) = min_max(points.map(|p| p[1]).chain([0.0]));
    let (xr, yr) = (padded(x_lo, x_hi, 0.08, 0.1), padded(y_lo, y_hi, 0.08, 0.1));
    let width = PANEL_WIDTH * results.len().max(1) as u32;
    let used: Vec<Outcome> = Outcome::ALL
        .iter()
        .copied()
        .filter(|&o| {
            results
                .iter()
                .any(|r| r.report.results.iter().any(|e| e.outcome == o))
        })
        .collect();
    render_png(path, (width, HEIGHT), |root| {
        let (title, body) = root.split_vertically(74);
        title
            .draw(&Text::new(
                format!("Object start positions on preset `{preset}` (top view, base_link; arm base at the cross)"),
                (14, 10),
                (FONT, 20),
            ))
            .map_err(de)?;
        // One legend for all panels, in the header.
        let mut x = 20;
        for &outcome in &used {
            let color = outcome_color(outcome);
            title
                .draw(&Circle::new((x + 6, 54), 6, color.filled()))
                .map_err(de)?;
            title
                .draw(&Text::new(outcome.to_string(), (x + 16, 46), (FONT, 14)))
                .map_err(de)?;
            let style = TextStyle::from((FONT, 14).into_font());
            x += 16
                + title
                    .estimate_text_size(outcome.as_str(), &style)
                    .map_err(de)?
                    .0 as i32
                + 28;
        }
        let panels = body.split_evenly((1, results.len().max(1)));
        for (r, area) in results.iter().zip(&panels) {
            let (w, h) = area.dim_in_pixel();
            let (xr, yr) = equal_aspect(xr, yr, (f64::from(w) - 70.0, f64::from(h) - 90.0));
            let mut chart = ChartBuilder::on(area)
                .caption(
                    format!(
                        "{} — {:.1} % success",
                        r.method,
                        100.0 * r.report.success_rate
                    ),
                    (FONT, 16),
                )
                .margin(8)
                .x_label_area_size(34)
                .y_label_area_size(48)
                .build_cartesian_2d(xr, yr)
                .map_err(de)?;
            draw_axes(&mut chart, "x [m]", "y [m]", Some(5))?;
            let cross = BLACK.stroke_width(2);
            chart
                .draw_series([
                    PathElement::new(vec![(-0.02, 0.0), (0.02, 0.0)], cross),
                    PathElement::new(vec![(0.0, -0.02), (0.0, 0.02)], cross),
                ])
                .map_err(de)?;
            // Successes first, so failures are drawn on top and stay visible.
            for &outcome in &used {
                let color = outcome_color(outcome);
                chart
                    .draw_series(
                        r.report
                            .results
                            .iter()
                            .filter(|e| e.outcome == outcome)
                            .filter(|e| e.object_xy.iter().all(|v| v.is_finite()))
                            .map(|e| {
                                let size = if outcome == Outcome::Success { 3 } else { 5 };
                                Circle::new((e.object_xy[0], e.object_xy[1]), size, color.filled())
                            }),
                    )
                    .map_err(de)?;
            }
        }
        Ok(())
    })
}
