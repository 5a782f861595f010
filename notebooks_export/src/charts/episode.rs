//! One episode: joint angles and gripper opening over time, and the TCP and cube paths in top
//! (x–y) and side (x–z) views of `base_link`.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::axis::Axis;
use super::{
    Chart, PALETTE, draw_axes, draw_legend, equal_aspect, finite_points, line_mark, min_max, padded,
};
use crate::error::ReportError;
use crate::raster::{FONT, de, render_png};
use crate::trajectory::Trajectory;

/// Pixel size of the episode chart.
pub const SIZE: (u32, u32) = (1400, 860);

const TCP_COLOR: RGBColor = RGBColor(78, 121, 167);
const CUBE_COLOR: RGBColor = RGBColor(225, 87, 89);

/// Draws the episode chart of `t` titled `title`; refuses an episode without steps.
pub fn episode_chart(t: &Trajectory, title: &str, path: &Path) -> Result<(), ReportError> {
    if t.rows.is_empty() {
        return Err(ReportError::chart(
            path,
            "the episode has no recorded steps",
        ));
    }
    let time: Vec<f64> = t.rows.iter().map(|r| r.time_s).collect();
    let time_axis = time_axis(&time);
    render_png(path, SIZE, |root| {
        let (head, body) = root.split_vertically(44);
        head.draw(&Text::new(title.to_string(), (14, 10), (FONT, 22)))
            .map_err(de)?;
        let (left, right) = body.split_horizontally(760);
        let (joints_area, grip_area) = left.split_vertically(body.dim_in_pixel().1 / 2 + 40);
        let (top_area, side_area) = right.split_vertically(body.dim_in_pixel().1 / 2 + 40);
        draw_joint_angles(&joints_area, t, &time, time_axis)?;
        draw_gripper_and_lift(&grip_area, t, &time, time_axis)?;
        draw_paths(&top_area, t, 1, "TCP and cube paths, top view")?;
        draw_paths(&side_area, t, 2, "TCP and cube paths, side view")
    })
}

/// The time axis \[s\] of the two time panels: from 0 (or the first time, if negative) to the
/// last time, 1 ms long at least; 0–1 s when no time is finite.
fn time_axis(time: &[f64]) -> Axis {
    let (t_first, t_last) = min_max(time.iter().copied());
    if t_first <= t_last {
        Axis::new(t_first.min(0.0), t_last.max(1e-3))
    } else {
        Axis::new(0.0, 1.0)
    }
}

/// The six joint angles \[deg\] against `time` \[s\], one colour per joint.
fn draw_joint_angles(
    area: &DrawingArea<BitMapBackend, Shift>,
    t: &Trajectory,
    time: &[f64],
    time_axis: Axis,
) -> Result<(), String> {
    let deg: Vec<[f64; 6]> = t
        .rows
        .iter()
        .map(|r| r.joints.map(f64::to_degrees))
        .collect();
    let mut chart = ChartBuilder::on(area)
        .caption("Joint angles", (FONT, 17))
        .margin(8)
        .x_label_area_size(34)
        .y_label_area_size(52)
        .build_cartesian_2d(
            time_axis,
            Axis::fit(deg.iter().flatten().copied(), 0.05, 10.0),
        )
        .map_err(de)?;
    draw_axes(&mut chart, "time [s]", "angle [deg]", None)?;
    for j in 0..6 {
        let color = PALETTE[j];
        chart
            .draw_series(LineSeries::new(
                finite_points(time.iter().zip(&deg).map(|(s, q)| (*s, q[j]))),
                color.stroke_width(2),
            ))
            .map_err(de)?
            .label(format!("j{}", j + 1))
            .legend(line_mark(color));
    }
    draw_legend(&mut chart, SeriesLabelPosition::UpperRight, 12)
}

/// The gripper opening between the pads and the cube's bottom above the table top, both \[mm\],
/// against `time` \[s\].
fn draw_gripper_and_lift(
    area: &DrawingArea<BitMapBackend, Shift>,
    t: &Trajectory,
    time: &[f64],
    time_axis: Axis,
) -> Result<(), String> {
    let table = t.scene.table_top_z;
    let half = 0.5 * t.scene.cube_size;
    let opening = finite_points(
        time.iter()
            .zip(&t.rows)
            .map(|(s, r)| (*s, 1e3 * r.gripper_opening_m)),
    );
    let lift = finite_points(
        time.iter()
            .zip(&t.rows)
            .map(|(s, r)| (*s, 1e3 * (r.object_xyz[2] - half - table))),
    );
    let (lo, hi) = min_max(opening.iter().chain(&lift).map(|p| p.1).chain([0.0]));
    let mut chart = ChartBuilder::on(area)
        .caption("Gripper opening and cube lift", (FONT, 17))
        .margin(8)
        .x_label_area_size(34)
        .y_label_area_size(52)
        .build_cartesian_2d(time_axis, Axis::new(lo - 5.0, hi + 8.0))
        .map_err(de)?;
    draw_axes(&mut chart, "time [s]", "[mm]", None)?;
    for (points, color, label) in [
        (opening, TCP_COLOR, "opening between the pads"),
        (lift, CUBE_COLOR, "cube bottom above the table"),
    ] {
        chart
            .draw_series(LineSeries::new(points, color.stroke_width(2)))
            .map_err(de)?
            .label(label)
            .legend(line_mark(color));
    }
    draw_legend(&mut chart, SeriesLabelPosition::UpperLeft, 12)
}

/// The TCP and cube-centre paths in `base_link` against x, with `axis` (1: y, the top view;
/// 2: z, the side view, which also shows the table) upward, at equal scale \[m\]; the cube's
/// start is a shaded square, the TCP's start and end are dots.
fn draw_paths(
    area: &DrawingArea<BitMapBackend, Shift>,
    t: &Trajectory,
    axis: usize,
    caption: &str,
) -> Result<(), String> {
    let table = t.scene.table_top_z;
    let tcp = finite_points(t.rows.iter().map(|r| (r.tcp_xyz[0], r.tcp_xyz[axis])));
    let cube = finite_points(t.rows.iter().map(|r| (r.object_xyz[0], r.object_xyz[axis])));
    let (xr, yr) = path_axes(area, &tcp, &cube, (axis == 2).then_some(table));
    let mut chart = ChartBuilder::on(area)
        .caption(caption, (FONT, 17))
        .margin(8)
        .x_label_area_size(34)
        .y_label_area_size(56)
        .build_cartesian_2d(xr, yr)
        .map_err(de)?;
    let (xr, yr) = (xr.ends(), yr.ends());
    draw_axes(
        &mut chart,
        "x [m]",
        if axis == 1 { "y [m]" } else { "z [m]" },
        Some(5),
    )?;
    if axis == 2 {
        chart
            .draw_series([Rectangle::new(
                [(xr.0, yr.0), (xr.1, table)],
                RGBColor(215, 200, 175).filled(),
            )])
            .map_err(de)?;
    }
    draw_cube_start(&mut chart, &cube, 0.5 * t.scene.cube_size)?;
    draw_path_lines(&mut chart, &tcp, &cube)?;
    draw_legend(&mut chart, SeriesLabelPosition::UpperLeft, 12)
}

/// Equal-aspect axes \[m\] for a path view in `area`: they hold every TCP and cube point, and the
/// table top's height `table_z` when given (the side view).
fn path_axes(
    area: &DrawingArea<BitMapBackend, Shift>,
    tcp: &[(f64, f64)],
    cube: &[(f64, f64)],
    table_z: Option<f64>,
) -> (Axis, Axis) {
    let all = tcp.iter().chain(cube);
    let xr = min_max(all.clone().map(|p| p.0));
    let yr = min_max(all.map(|p| p.1).chain(table_z));
    let (w, h) = area.dim_in_pixel();
    equal_aspect(
        padded(xr.0, xr.1, 0.15, 0.06),
        padded(yr.0, yr.1, 0.15, 0.06),
        (f64::from(w) - 80.0, f64::from(h) - 80.0),
    )
}

/// The cube's start: a shaded square `2 * half` \[m\] wide centred on the first cube point.
fn draw_cube_start(
    chart: &mut Chart<'_, '_>,
    cube: &[(f64, f64)],
    half: f64,
) -> Result<(), String> {
    if let Some(first) = cube.first() {
        chart
            .draw_series([Rectangle::new(
                [
                    (first.0 - half, first.1 - half),
                    (first.0 + half, first.1 + half),
                ],
                CUBE_COLOR.mix(0.25).filled(),
            )])
            .map_err(de)?;
    }
    Ok(())
}

/// The TCP and cube paths as labelled lines, then the TCP's start (blue) and end (black) dots.
fn draw_path_lines(
    chart: &mut Chart<'_, '_>,
    tcp: &[(f64, f64)],
    cube: &[(f64, f64)],
) -> Result<(), String> {
    chart
        .draw_series(LineSeries::new(tcp.to_vec(), TCP_COLOR.stroke_width(2)))
        .map_err(de)?
        .label("TCP")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], TCP_COLOR.stroke_width(3)));
    chart
        .draw_series(LineSeries::new(cube.to_vec(), CUBE_COLOR.stroke_width(2)))
        .map_err(de)?
        .label("cube centre (start: shaded square)")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], CUBE_COLOR.stroke_width(3)));
    if let (Some(start), Some(end)) = (tcp.first(), tcp.last()) {
        chart
            .draw_series([
                Circle::new(*start, 5, TCP_COLOR.filled()),
                Circle::new(*end, 5, BLACK.filled()),
            ])
            .map_err(de)?;
    }
    Ok(())
}
