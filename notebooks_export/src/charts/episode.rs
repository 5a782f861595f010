//! One episode: joint angles and gripper opening over time, and the TCP and cube paths in top
//! (x–y) and side (x–z) views of `base_link`.

use std::path::Path;

use plotters::prelude::*;

use super::axis::Axis;
use super::{
    PALETTE, draw_axes, draw_legend, equal_aspect, finite_points, line_mark, min_max, padded,
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
    let (t_first, t_last) = min_max(time.iter().copied());
    let time_axis = if t_first <= t_last {
        Axis::new(t_first.min(0.0), t_last.max(1e-3))
    } else {
        Axis::new(0.0, 1.0)
    };
    render_png(path, SIZE, |root| {
        let (head, body) = root.split_vertically(44);
        head.draw(&Text::new(title.to_string(), (14, 10), (FONT, 22)))
            .map_err(de)?;
        let (left, right) = body.split_horizontally(760);
        let (joints_area, grip_area) = left.split_vertically(body.dim_in_pixel().1 / 2 + 40);
        let (top_area, side_area) = right.split_vertically(body.dim_in_pixel().1 / 2 + 40);

        // Joint angles.
        let deg: Vec<[f64; 6]> = t
            .rows
            .iter()
            .map(|r| r.joints.map(f64::to_degrees))
            .collect();
        let mut chart = ChartBuilder::on(&joints_area)
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
        draw_legend(&mut chart, SeriesLabelPosition::UpperRight, 12)?;

        // Gripper opening and cube height above the table.
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
        let mut chart = ChartBuilder::on(&grip_area)
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
        draw_legend(&mut chart, SeriesLabelPosition::UpperLeft, 12)?;

        // Paths: top view (x, y) and side view (x, z).
        for (area, axis, caption) in [
            (&top_area, 1usize, "TCP and cube paths, top view"),
            (&side_area, 2usize, "TCP and cube paths, side view"),
        ] {
            let tcp = finite_points(t.rows.iter().map(|r| (r.tcp_xyz[0], r.tcp_xyz[axis])));
            let cube = finite_points(t.rows.iter().map(|r| (r.object_xyz[0], r.object_xyz[axis])));
            let all = tcp.iter().chain(&cube);
            let xr = min_max(all.clone().map(|p| p.0));
            let yr = min_max(
                all.map(|p| p.1)
                    .chain(if axis == 2 { vec![table] } else { vec![] }),
            );
            let (w, h) = area.dim_in_pixel();
            let (xr, yr) = equal_aspect(
                padded(xr.0, xr.1, 0.15, 0.06),
                padded(yr.0, yr.1, 0.15, 0.06),
                (f64::from(w) - 80.0, f64::from(h) - 80.0),
            );
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
            chart
                .draw_series(LineSeries::new(tcp.clone(), TCP_COLOR.stroke_width(2)))
                .map_err(de)?
                .label("TCP")
                .legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 18, y)], TCP_COLOR.stroke_width(3))
                });
            chart
                .draw_series(LineSeries::new(cube.clone(), CUBE_COLOR.stroke_width(2)))
                .map_err(de)?
                .label("cube centre (start: shaded square)")
                .legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 18, y)], CUBE_COLOR.stroke_width(3))
                });
            if let (Some(start), Some(end)) = (tcp.first(), tcp.last()) {
                chart
                    .draw_series([
                        Circle::new(*start, 5, TCP_COLOR.filled()),
                        Circle::new(*end, 5, BLACK.filled()),
                    ])
                    .map_err(de)?;
            }
            draw_legend(&mut chart, SeriesLabelPosition::UpperLeft, 12)?;
        }
        Ok(())
    })
}
