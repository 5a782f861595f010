//! Success rate per method and preset: grouped bars with 95 % Wilson-interval whiskers.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::axis::Axis;
use super::{Chart, series_color};
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
    let n = c.presets.len().max(1) as f64;
    let bar_width = 0.8 / c.methods.len().max(1) as f64;
    // Plot area ≈ the image width less the axis label area and margins.
    let bar_pixels = (SIZE.0 as f64 - 92.0) / n * bar_width;
    let episodes = c.results.first().map_or(0, |r| r.report.episodes);
    render_png(path, SIZE, |root| {
        let (entries, rows) = legend_layout(root, &c.methods)?;
        let (head, body) = root.split_vertically(80 + 24 * rows as u32);
        draw_head(&head, episodes, &entries)?;
        let mut chart = ChartBuilder::on(&body)
            .margin(16)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(Axis::new(-0.5, n - 0.5), Axis::new(0.0, 108.0))
            .map_err(de)?;
        draw_mesh(&mut chart, &c.presets)?;
        let bars = Bars {
            width: bar_width,
            labelled: bar_pixels >= VALUE_LABEL_MIN_PIXELS,
        };
        for (m, method) in c.methods.iter().enumerate() {
            draw_method_bars(&mut chart, c, m, method, bars)?;
        }
        Ok(())
    })
}

/// One legend entry: the method's index (its colour), its name and the top-left corner of its
/// swatch in the head area \[px\].
type LegendEntry<'a> = (usize, &'a str, i32, i32);

/// Places the legend in rows under the title, wrapped at the chart's width, clear of the bars:
/// the entries, and the index of the last row (0 for one row).
fn legend_layout<'a>(
    root: &DrawingArea<BitMapBackend, Shift>,
    methods: &'a [String],
) -> Result<(Vec<LegendEntry<'a>>, i32), String> {
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
        entries.push((m, method.as_str(), x, 52 + 24 * row));
        x += width + 30;
    }
    Ok((entries, row))
}

/// The title (with the number of `episodes` per preset) and the legend's swatches and names.
fn draw_head(
    head: &DrawingArea<BitMapBackend, Shift>,
    episodes: usize,
    entries: &[LegendEntry],
) -> Result<(), String> {
    head.draw(&Text::new(
        format!("Grasp success rate ({episodes} seeded episodes per preset, 95 % CI)"),
        ((SIZE.0 / 2) as i32, 12),
        TextStyle::from((FONT, 24).into_font()).pos(Pos::new(HPos::Center, VPos::Top)),
    ))
    .map_err(de)?;
    for &(m, method, x, y) in entries {
        head.draw(&Rectangle::new(
            [(x, y), (x + 16, y + 16)],
            series_color(m).filled(),
        ))
        .map_err(de)?;
        head.draw(&Text::new(method.to_string(), (x + 22, y), (FONT, 15)))
            .map_err(de)?;
    }
    Ok(())
}

/// Axes and horizontal grid: the presets' names under the groups (x = the preset's index), the
/// success rate 0–100 % up the side (the axis runs to 108 to leave room for the values).
fn draw_mesh(chart: &mut Chart<'_, '_>, presets: &[String]) -> Result<(), String> {
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_labels(2 * presets.len() + 1)
        .x_label_formatter(&|x| {
            let i = x.round();
            if (x - i).abs() < 1e-6 && i >= 0.0 {
                presets.get(i as usize).cloned().unwrap_or_default()
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
        .map_err(de)
}

/// The bars' geometry, the same for every method.
#[derive(Clone, Copy)]
struct Bars {
    /// Width of one bar's slot in x units (a preset's group is 0.8 wide).
    width: f64,
    /// Whether a bar is wide enough on screen to carry its value on top.
    labelled: bool,
}

/// Method `m`'s bars, one per preset it has a finite rate on, each with its 95 % interval's
/// whisker and (where `bars.labelled`) its value \[%\].
fn draw_method_bars(
    chart: &mut Chart<'_, '_>,
    c: &Comparison,
    m: usize,
    method: &str,
    bars: Bars,
) -> Result<(), String> {
    let color = series_color(m);
    let bar_width = bars.width;
    let results: Vec<_> = c
        .presets
        .iter()
        .enumerate()
        .filter_map(|(p, preset)| c.get(method, preset).map(|r| (p, r)))
        // A rate whose percentage is not finite has no bar (see `charts`).
        .filter(|(_, r)| (100.0 * r.report.success_rate).is_finite())
        .collect();
    let left = |p: usize| p as f64 - 0.4 + m as f64 * bar_width;
    chart
        .draw_series(results.iter().map(|(p, r)| {
            Rectangle::new(
                [
                    (left(*p) + 0.1 * bar_width, 0.0),
                    (left(*p) + 0.9 * bar_width, 100.0 * r.report.success_rate),
                ],
                color.filled(),
            )
        }))
        .map_err(de)?;
    for (p, r) in &results {
        let x = left(*p) + 0.5 * bar_width;
        let rate = 100.0 * r.report.success_rate;
        let interval = (100.0 * r.report.ci_low, 100.0 * r.report.ci_high);
        let top = draw_whisker(chart, x, 0.15 * bar_width, interval, rate)?;
        // A value on top only where the bar is wide enough to carry it (the table has every
        // value).
        if !bars.labelled {
            continue;
        }
        chart
            .draw_series([Text::new(
                format!("{rate:.1}"),
                (x, top + 1.5),
                TextStyle::from((FONT, 14).into_font()).pos(Pos::new(HPos::Center, VPos::Bottom)),
            )])
            .map_err(de)?;
    }
    Ok(())
}

/// The whisker of the interval `(lo, hi)` \[%\] at `x`, capped `cap` to either side, when both
/// ends are finite; returns the top of bar and whisker (where the value goes), `rate` \[%\] alone
/// when there is no whisker.
fn draw_whisker(
    chart: &mut Chart<'_, '_>,
    x: f64,
    cap: f64,
    (lo, hi): (f64, f64),
    rate: f64,
) -> Result<f64, String> {
    if !(lo.is_finite() && hi.is_finite()) {
        return Ok(rate);
    }
    let whisker = BLACK.stroke_width(2);
    chart
        .draw_series([
            PathElement::new(vec![(x, lo), (x, hi)], whisker),
            PathElement::new(vec![(x - cap, lo), (x + cap, lo)], whisker),
            PathElement::new(vec![(x - cap, hi), (x + cap, hi)], whisker),
        ])
        .map_err(de)?;
    Ok(hi.max(rate))
}
