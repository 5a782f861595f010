//! Success rate per method and preset: grouped bars with 95 % Wilson-interval whiskers.

use std::path::Path;

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::axis::Axis;
use super::series_color;
use crate::comparison_table::Comparison;
use crate::error::ReportError;
use crate::raster::{FONT, de, render_png};

/// Pixel size of the success-rate chart.
pub const SIZE: (u32, u32) = (1000, 560);

/// The narrowest bar \[px\] that carries its value on top ("100.0" at 14 px is ~34 px wide).
const VALUE_LABEL_MIN_PIXELS: f64 = 34.0;

/// Draws `success_rate.png`: one group per preset, one bar per method, value on top where it
/// fits, the legend wrapped into as many rows as the methods need.
pub fn success_chart(c: &Comparison, path: &Path) -> Result<(), ReportError> {
    let presets = &c.presets;
    let methods = &c.methods;
    let n = presets.len().max(1) as f64;
    let bar_width = 0.8 / methods.len().max(1) as f64;
    // Plot area ≈ the image width less the axis label area and margins.
    let bar_pixels = (SIZE.0 as f64 - 92.0) / n * bar_width;
    let episodes = c.results.first().map_or(0, |r| r.report.episodes);
    render_png(path, SIZE, |root| {
        // The legend in rows under the title, wrapped at the chart's width, clear of the bars.
        let style = TextStyle::from((FONT, 15).into_font());
        let mut entries = Vec::new();
        let (mut x, mut row) = (80, 0);
        for (m, method) in methods.iter().enumerate() {
            let (w, _) = root.estimate_text_size(method, &style).map_err(de)?;
            let width = 22 + w as i32;
            if x > 80 && x + width > SIZE.0 as i32 - 20 {
                x = 80;
                row += 1;
            }
            entries.push((m, method, x, 52 + 24 * row));
            x += width + 30;
        }
        let (head, body) = root.split_vertically(80 + 24 * row as u32);
        head.draw(&Text::new(
            format!("Grasp success rate ({episodes} seeded episodes per preset, 95 % CI)"),
            ((SIZE.0 / 2) as i32, 12),
            TextStyle::from((FONT, 24).into_font()).pos(Pos::new(HPos::Center, VPos::Top)),
        ))
        .map_err(de)?;
        for (m, method, x, y) in entries {
            head.draw(&Rectangle::new(
                [(x, y), (x + 16, y + 16)],
                series_color(m).filled(),
            ))
            .map_err(de)?;
            head.draw(&Text::new(method.clone(), (x + 22, y), (FONT, 15)))
                .map_err(de)?;
        }
        let mut chart = ChartBuilder::on(&body)
            .margin(16)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(Axis::new(-0.5, n - 0.5), Axis::new(0.0, 108.0))
            .map_err(de)?;
        let names = presets.clone();
        chart
            .configure_mesh()
            .disable_x_mesh()
            .x_labels(2 * presets.len() + 1)
            .x_label_formatter(&|x| {
                let i = x.round();
                if (x - i).abs() < 1e-6 && i >= 0.0 {
                    names.get(i as usize).cloned().unwrap_or_default()
                } else {
                    String::new()
                }
            })
            .y_labels(6)
            .y_label_formatter(&|y| {
                if *y <= 100.0 {
                    format!("{y:.0}")
                } else {
                    String::new()
                }
            })
            .y_desc("success rate [%]")
            .x_desc("preset")
            .label_style((FONT, 16))
            .axis_desc_style((FONT, 16))
            .draw()
            .map_err(de)?;
        for (m, method) in methods.iter().enumerate() {
            let color = series_color(m);
            let bars: Vec<_> = presets
                .iter()
                .enumerate()
                .filter_map(|(p, preset)| c.get(method, preset).map(|r| (p, r)))
                // A rate whose percentage is not finite has no bar (see `charts`).
                .filter(|(_, r)| (100.0 * r.report.success_rate).is_finite())
                .collect();
            let left = |p: usize| p as f64 - 0.4 + m as f64 * bar_width;
            chart
                .draw_series(bars.iter().map(|(p, r)| {
                    Rectangle::new(
                        [
                            (left(*p) + 0.1 * bar_width, 0.0),
                            (left(*p) + 0.9 * bar_width, 100.0 * r.report.success_rate),
                        ],
                        color.filled(),
                    )
                }))
                .map_err(de)?;
            for (p, r) in &bars {
                let x = left(*p) + 0.5 * bar_width;
                let cap = 0.15 * bar_width;
                let (lo, hi) = (100.0 * r.report.ci_low, 100.0 * r.report.ci_high);
                let whisker = BLACK.stroke_width(2);
                let rate = 100.0 * r.report.success_rate;
                let top = if lo.is_finite() && hi.is_finite() {
                    chart
                        .draw_series([
                            PathElement::new(vec![(x, lo), (x, hi)], whisker),
                            PathElement::new(vec![(x - cap, lo), (x + cap, lo)], whisker),
                            PathElement::new(vec![(x - cap, hi), (x + cap, hi)], whisker),
                        ])
                        .map_err(de)?;
                    hi.max(rate)
                } else {
                    rate
                };
                // A value on top only where the bar is wide enough to carry it (the table has
                // every value).
                if bar_pixels < VALUE_LABEL_MIN_PIXELS {
                    continue;
                }
                chart
                    .draw_series([Text::new(
                        format!("{rate:.1}"),
                        (x, top + 1.5),
                        TextStyle::from((FONT, 14).into_font())
                            .pos(Pos::new(HPos::Center, VPos::Bottom)),
                    )])
                    .map_err(de)?;
            }
        }
        Ok(())
    })
}
