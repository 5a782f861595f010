//! Learning curves of one or more training runs: success rate, return, losses, entropy and
//! explained variance against environment steps, with curriculum stage changes marked.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::axis::Axis;
use super::{Chart, draw_legend, finite_points, line_mark, min_max, series_color};
use crate::error::ReportError;
use crate::raster::{FONT, de, render_png};
use crate::runs::RunFolder;

/// Pixel size of the learning-curve chart.
pub const SIZE: (u32, u32) = (1500, 900);

/// The panels: metrics.csv column, panel title, y-axis label.
const PANELS: [(&str, &str, &str); 6] = [
    ("success_rate", "Training success rate", "success rate"),
    ("episode_return", "Episode return", "mean return"),
    ("entropy", "Policy entropy", "entropy [nats]"),
    ("policy_loss", "Policy (clipped surrogate) loss", "loss"),
    ("value_loss", "Value loss", "loss"),
    (
        "explained_variance",
        "Explained variance of the value",
        "1 − Var[R−V]/Var[R]",
    ),
];

/// Draws `path` with one line per run in each panel; the success panel also shows evaluation
/// success (`eval_success_rate`) as dots, and dashed verticals mark curriculum stage changes.
pub fn learning_curves(runs: &[RunFolder], path: &Path) -> Result<(), ReportError> {
    render_png(path, SIZE, |root| {
        let (title, body) = root.split_vertically(70);
        draw_title(&title, runs)?;
        let panels = body.split_evenly((2, 3));
        let x_axis = steps_axis(runs);
        for (panel, area) in PANELS.iter().zip(&panels) {
            draw_panel(area, *panel, runs, x_axis)?;
        }
        Ok(())
    })
}

/// The chart's title (the runs' names) and a line explaining the marks.
fn draw_title(title: &DrawingArea<BitMapBackend, Shift>, runs: &[RunFolder]) -> Result<(), String> {
    let names: Vec<&str> = runs.iter().map(|r| r.name.as_str()).collect();
    title
        .draw(&Text::new(
            format!("Learning curves: {}", names.join(", ")),
            (16, 8),
            (FONT, 26),
        ))
        .map_err(de)?;
    title
        .draw(&Text::new(
            "thin: per PPO update · thick: moving average over 15 updates · dots: evaluation success on the run's \
             fixed scenario set · dashed: curriculum stage change",
            (16, 44),
            (FONT, 14).into_font().color(&RGBColor(90, 90, 90)),
        ))
        .map_err(de)?;
    Ok(())
}

/// The shared x axis \[environment steps\]: from 0 (or the first step, if negative) to the last
/// step of any run; one step wide at least, and 0–1 when no run has a step.
fn steps_axis(runs: &[RunFolder]) -> Axis {
    let (x_lo, x_hi) = min_max(
        runs.iter()
            .flat_map(|r| r.metrics.column("timesteps").unwrap_or_default()),
    );
    if x_lo <= x_hi {
        Axis::new(x_lo.min(0.0), x_hi.max(x_lo.min(0.0) + 1.0))
    } else {
        Axis::new(0.0, 1.0)
    }
}

/// One panel (`(column, caption, y_desc)` of [`PANELS`]): every run's metric against steps; the
/// success panel adds evaluation dots and the legend.
fn draw_panel(
    area: &DrawingArea<BitMapBackend, Shift>,
    (column, caption, y_desc): (&str, &str, &str),
    runs: &[RunFolder],
    x_axis: Axis,
) -> Result<(), String> {
    let is_success = column == "success_rate";
    let series: Vec<Vec<(f64, f64)>> = runs
        .iter()
        .map(|r| finite_points(r.metrics.series(column)))
        .collect();
    let y_axis = if is_success {
        Axis::new(-0.03, 1.03)
    } else {
        Axis::fit(series.iter().flatten().map(|p| p.1), 0.08, 1e-3)
    };
    let y_ends = y_axis.ends();
    let mut chart = ChartBuilder::on(area)
        .caption(caption, (FONT, 18))
        .margin(10)
        .x_label_area_size(36)
        .y_label_area_size(64)
        .build_cartesian_2d(x_axis, y_axis)
        .map_err(de)?;
    chart
        .configure_mesh()
        .x_labels(5)
        .y_labels(6)
        .x_label_formatter(&|x| format_steps(*x))
        .x_desc("environment steps")
        .y_desc(y_desc)
        .label_style((FONT, 13))
        .axis_desc_style((FONT, 14))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(de)?;
    for (i, (run, points)) in runs.iter().zip(&series).enumerate() {
        draw_run(&mut chart, run, series_color(i), points, y_ends, is_success)?;
    }
    if is_success {
        draw_legend(&mut chart, SeriesLabelPosition::LowerRight, 13)?;
    }
    Ok(())
}

/// One run in a panel, in `color`: its stage changes as dashed verticals from `y_lo` to `y_hi`
/// (the panel's y-axis ends), `points` raw (thin) and smoothed (thick); in the success panel
/// (`is_success`) also its evaluation success as dots and its name in the legend.
fn draw_run(
    chart: &mut Chart<'_, '_>,
    run: &RunFolder,
    color: RGBColor,
    points: &[(f64, f64)],
    (y_lo, y_hi): (f64, f64),
    is_success: bool,
) -> Result<(), String> {
    for (x, _) in finite_points(run.metrics.stage_changes()) {
        chart
            .draw_series(DashedLineSeries::new(
                vec![(x, y_lo), (x, y_hi)],
                6,
                4,
                color.mix(0.7).stroke_width(1),
            ))
            .map_err(de)?;
    }
    // Raw values thin and light, a moving average on top: PPO metrics are noisy, and plotters'
    // thick polylines spike at sharp turns.
    chart
        .draw_series(LineSeries::new(
            points.to_vec(),
            color.mix(0.35).stroke_width(1),
        ))
        .map_err(de)?;
    let line = chart
        .draw_series(LineSeries::new(
            moving_average(points, SMOOTHING),
            color.stroke_width(2),
        ))
        .map_err(de)?;
    if is_success {
        line.label(run.name.as_str()).legend(line_mark(color));
    }
    let eval = if is_success {
        finite_points(run.metrics.series("eval_success_rate"))
    } else {
        Vec::new()
    };
    chart
        .draw_series(eval.iter().map(|p| Circle::new(*p, 4, color.filled())))
        .map_err(de)?;
    Ok(())
}

/// Updates averaged by the smoothed line.
pub const SMOOTHING: usize = 15;

/// Centred moving average over `window` points (shorter at the ends). A mean that overflows
/// (values near ±1.8e308) is left out of the result.
pub fn moving_average(points: &[(f64, f64)], window: usize) -> Vec<(f64, f64)> {
    let half = window / 2;
    let averaged = (0..points.len()).map(|i| {
        let part = &points[i.saturating_sub(half)..(i + half + 1).min(points.len())];
        let mean = part.iter().map(|p| p.1).sum::<f64>() / part.len() as f64;
        (points[i].0, mean)
    });
    finite_points(averaged)
}

/// `1.2M`, `350k`, `900`.
pub fn format_steps(x: f64) -> String {
    if x.abs() >= 1e6 {
        format!("{:.1}M", x / 1e6)
    } else if x.abs() >= 1e3 {
        format!("{:.0}k", x / 1e3)
    } else {
        format!("{x:.0}")
    }
}
