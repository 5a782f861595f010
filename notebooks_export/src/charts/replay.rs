//! An episode replay as an animated GIF: the arm's and gripper's capsules, the cube, the table
//! and, on the place task, the fixture's walls, in two orthographic views of `base_link` (top:
//! x–y; side: x–z, seen from −y).

use std::path::Path;

use plotters::prelude::*;

use super::{equal_aspect, finite_points, min_max, padded};
use crate::error::ReportError;
use crate::raster::{FONT, de, gif_palette, render_gif, render_png};
use crate::trajectory::{Trajectory, TrajectoryRow};

/// Pixel size of a replay frame.
pub const SIZE: (u32, u32) = (960, 500);
/// At most this many frames (long episodes are subsampled; playback stays real time): 40 keeps
/// a 200-step episode's GIF near 300 kB, so a report's seven of them fit its notebook's 5 MB
/// (the 3D replay is the smooth one).
pub const MAX_FRAMES: usize = 40;

const TABLE: RGBColor = RGBColor(222, 208, 184);
/// Alternating link colours, so neighbouring housings stay apart.
const LINK_SHADES: [RGBColor; 2] = [RGBColor(150, 172, 196), RGBColor(110, 136, 166)];
const SKELETON: RGBColor = RGBColor(40, 55, 75);
const GRIPPER: RGBColor = RGBColor(80, 80, 80);
const CUBE: RGBColor = RGBColor(225, 87, 89);
const CUBE_EDGE: RGBColor = RGBColor(140, 30, 30);
const FIXTURE: RGBColor = RGBColor(120, 150, 110);
const FIXTURE_EDGE: RGBColor = RGBColor(60, 80, 55);
/// Shapes whose names start with this are the fixture's (`fixture_wall_0` …).
const FIXTURE_PREFIX: &str = "fixture";

/// Writes the replay GIF of `t` with `title` above both views; refuses an episode without
/// steps.
pub fn replay_gif(t: &Trajectory, title: &str, path: &Path) -> Result<(), ReportError> {
    let n = t.rows.len();
    if n == 0 {
        return Err(ReportError::chart(
            path,
            "the episode has no recorded steps",
        ));
    }
    let stride = n.div_ceil(MAX_FRAMES).max(1);
    let frames: Vec<usize> = (0..n).step_by(stride).chain([n - 1]).collect();
    let dt = if n > 1 {
        (t.rows[n - 1].time_s - t.rows[0].time_s) / (n - 1) as f64
    } else {
        0.05
    };
    // Saturating conversion: a NaN or absurd time gives the shortest or longest delay.
    let step_cs = ((100.0 * dt * stride as f64).round() as u16).max(2);
    let mut delays: Vec<u16> = vec![step_cs; frames.len()];
    if let Some(last) = delays.last_mut() {
        *last = 200;
    }
    let bounds = view_bounds(t);
    let palette = gif_palette(&[
        TABLE,
        LINK_SHADES[0],
        LINK_SHADES[1],
        SKELETON,
        GRIPPER,
        CUBE,
        CUBE_EDGE,
    ]);
    render_gif(path, SIZE, &delays, &palette, |i, root| {
        draw_frame(t, &t.rows[frames[i]], title, &bounds, root)
    })
}

/// Writes one frame of the replay (row `step` of the episode) as a PNG: a still for documents
/// that cannot show GIFs. A step past the last row is refused with the allowed range, and
/// nothing is written.
pub fn replay_still(
    t: &Trajectory,
    title: &str,
    step: usize,
    path: &Path,
) -> Result<(), ReportError> {
    let Some(row) = t.rows.get(step) else {
        return Err(ReportError::chart(
            path,
            match t.rows.len() {
                0 => "the episode has no recorded steps".to_string(),
                n => format!(
                    "step {step} is past the end of the episode: it has {n} recorded steps, \
                     numbered 0–{}",
                    n - 1
                ),
            },
        ));
    };
    let bounds = view_bounds(t);
    render_png(path, SIZE, |root| draw_frame(t, row, title, &bounds, root))
}

/// One frame of the replay (row `step`) as RGB bytes, `SIZE.0 × SIZE.1 × 3`, row-major: what
/// gymnasium's `render_mode = "rgb_array"` returns from Python. A step past the last row is
/// refused with the allowed range.
pub fn replay_frame_rgb(t: &Trajectory, title: &str, step: usize) -> Result<Vec<u8>, ReportError> {
    let here = Path::new("<render>");
    let Some(row) = t.rows.get(step) else {
        return Err(ReportError::chart(
            here,
            format!(
                "step {step}: the episode has {} recorded steps",
                t.rows.len()
            ),
        ));
    };
    let bounds = view_bounds(t);
    crate::raster::render_rgb(SIZE, |root| draw_frame(t, row, title, &bounds, root))
        .map_err(|e| ReportError::chart(here, e))
}

/// The fixed view bounds of a replay \[m\]: everything that moves, over the whole episode.
struct ViewBounds {
    x: (f64, f64),
    y: (f64, f64),
    z: (f64, f64),
}

fn view_bounds(t: &Trajectory) -> ViewBounds {
    let points = t.rows.iter().flat_map(|r| {
        r.capsules
            .iter()
            .flat_map(|c| [[c[0], c[1], c[2]], [c[3], c[4], c[5]]])
            .chain(r.cube_corners(t.scene.cube_size))
            .chain(fixture_boxes(t, r).into_iter().flatten())
    });
    let bounds = |k: usize| min_max(points.clone().map(|p| p[k]));
    let z = bounds(2);
    ViewBounds {
        x: bounds(0),
        y: bounds(1),
        z: (z.0.min(t.scene.table_top_z), z.1),
    }
}

/// The corners of each of the fixture's boxes at `row` (`base_link`, m; none on the lift task):
/// every box shape named [`FIXTURE_PREFIX`]… on its recorded body's pose.
fn fixture_boxes(t: &Trajectory, row: &TrajectoryRow) -> Vec<[[f64; 3]; 8]> {
    use fairgrasp_types::body::{Geometry, rotate};
    let mut out = Vec::new();
    for shape in &t.scene.shapes {
        let (
            Geometry::Box {
                centre,
                half_extents: h,
            },
            Some(pose),
        ) = (&shape.geometry, row.bodies.get(shape.body))
        else {
            continue;
        };
        if !shape.name.starts_with(FIXTURE_PREFIX) {
            continue;
        }
        let q = [pose[3], pose[4], pose[5], pose[6]];
        out.push(std::array::from_fn(|i| {
            let sign = |bit: usize| if i & bit == 0 { -1.0 } else { 1.0 };
            let local = [
                centre[0] + sign(1) * h[0],
                centre[1] + sign(2) * h[1],
                centre[2] + sign(4) * h[2],
            ];
            let r = rotate(q, local);
            [pose[0] + r[0], pose[1] + r[1], pose[2] + r[2]]
        }));
    }
    out
}

/// One frame: the title with the time, the top view and the side view.
fn draw_frame(
    t: &Trajectory,
    row: &TrajectoryRow,
    title: &str,
    b: &ViewBounds,
    root: &DrawingArea<BitMapBackend, plotters::coord::Shift>,
) -> Result<(), String> {
    root.fill(&WHITE).map_err(de)?;
    let (head, body) = root.split_vertically(40);
    head.draw(&Text::new(
        format!("{title} — t = {:.2} s", row.time_s),
        (12, 10),
        (FONT, 18),
    ))
    .map_err(de)?;
    let (left, right) = body.split_horizontally(SIZE.0 / 2);
    draw_view(t, row, &left, [0, 1], (b.x, b.y), "top view (x–y)")?;
    draw_view(t, row, &right, [0, 2], (b.x, b.z), "side view (x–z)")
}

/// One orthographic view onto axes `axes` of `base_link`.
fn draw_view(
    t: &Trajectory,
    row: &TrajectoryRow,
    area: &DrawingArea<BitMapBackend, plotters::coord::Shift>,
    axes: [usize; 2],
    (ur, vr): ((f64, f64), (f64, f64)),
    caption: &str,
) -> Result<(), String> {
    let (w, h) = area.dim_in_pixel();
    let (ur, vr) = equal_aspect(
        padded(ur.0, ur.1, 0.08, 0.1),
        padded(vr.0, vr.1, 0.08, 0.1),
        (f64::from(w) - 70.0, f64::from(h) - 70.0),
    );
    let mut chart = ChartBuilder::on(area)
        .caption(caption, (FONT, 15))
        .margin(6)
        .x_label_area_size(30)
        .y_label_area_size(44)
        .build_cartesian_2d(ur, vr)
        .map_err(de)?;
    let (ur, vr) = (ur.ends(), vr.ends());
    chart
        .configure_mesh()
        .x_labels(5)
        .y_labels(5)
        .x_desc(["x [m]", "y [m]", "z [m]"][axes[0]])
        .y_desc(["x [m]", "y [m]", "z [m]"][axes[1]])
        .label_style((FONT, 11))
        .axis_desc_style((FONT, 12))
        .light_line_style(WHITE.mix(0.0))
        .bold_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(de)?;
    // Pixels per metre from the axis ends (points far off the axis are pinned near it).
    let px_per_m = {
        let a = chart.backend_coord(&(ur.0, vr.0));
        let b = chart.backend_coord(&(ur.1, vr.0));
        f64::from(b.0 - a.0).abs() / (ur.1 - ur.0)
    };
    draw_table(&mut chart, &t.scene, axes, (ur, vr))?;
    // The fixture's walls lie on the table, below everything that moves: drawn first.
    for corners in fixture_boxes(t, row) {
        draw_solid(&mut chart, &corners, axes, FIXTURE, FIXTURE_EDGE)?;
    }
    // Depth order: lowest first in the top view, largest y first in the side view; the cube
    // takes part so that the gripper hides it from above and it hides what is behind it.
    let depth = |c: &[f64; 7]| {
        if axes[1] == 1 {
            c[2].max(c[5])
        } else {
            -c[1].min(c[4])
        }
    };
    let corners = row.cube_corners(t.scene.cube_size);
    let cube_depth = if axes[1] == 1 {
        corners.iter().map(|p| p[2]).fold(f64::MIN, f64::max)
    } else {
        -corners.iter().map(|p| p[1]).fold(f64::MAX, f64::min)
    };
    let mut order: Vec<(f64, Option<usize>)> = row
        .capsules
        .iter()
        .enumerate()
        .map(|(i, c)| (depth(c), Some(i)))
        .chain([(cube_depth, None)])
        .collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0));
    for (_, item) in order {
        match item {
            None => draw_solid(&mut chart, &corners, axes, CUBE, CUBE_EDGE)?,
            Some(i) => {
                let name = t.scene.capsule_names.get(i).map_or("", String::as_str);
                let fill = if name == "palm" || name.starts_with("finger") {
                    GRIPPER
                } else {
                    LINK_SHADES[i % LINK_SHADES.len()]
                };
                draw_capsule(&mut chart, &row.capsules[i], axes, fill, px_per_m)?;
            }
        }
    }
    Ok(())
}

/// The chart of one view: metres on both axes.
type ViewChart<'a, 'b> =
    ChartContext<'a, BitMapBackend<'b>, Cartesian2d<super::axis::Axis, super::axis::Axis>>;

/// The table: its top's outline seen from above, its top's height seen from the side (filling
/// the view's ranges `ur`, `vr` below it).
fn draw_table(
    chart: &mut ViewChart,
    scene: &crate::trajectory::TrajectoryScene,
    axes: [usize; 2],
    (ur, vr): ((f64, f64), (f64, f64)),
) -> Result<(), String> {
    if axes[1] == 1 {
        let corners: Vec<(f64, f64)> = scene
            .table_corners_xy
            .iter()
            .map(|c| (c[0], c[1]))
            .collect();
        chart
            .draw_series([Polygon::new(corners, TABLE.filled())])
            .map_err(de)?;
    } else {
        let top = [(ur.0, vr.0), (ur.1, scene.table_top_z)];
        chart
            .draw_series([Rectangle::new(top, TABLE.filled())])
            .map_err(de)?;
    }
    Ok(())
}

/// A box given by its 8 corners [m, `base_link`] (the cube, a fixture wall): the convex hull of
/// its projection, filled and outlined; left out if a corner is not finite.
fn draw_solid(
    chart: &mut ViewChart,
    corners: &[[f64; 3]; 8],
    axes: [usize; 2],
    fill: RGBColor,
    edge: RGBColor,
) -> Result<(), String> {
    let projected: Vec<(f64, f64)> = corners.iter().map(|p| (p[axes[0]], p[axes[1]])).collect();
    if projected.len() != finite_points(projected.iter().copied()).len() {
        return Ok(());
    }
    let hull = convex_hull(projected);
    let mut outline = hull.clone();
    outline.extend(hull.first());
    chart
        .draw_series([Polygon::new(hull, fill.filled())])
        .map_err(de)?;
    chart
        .draw_series([PathElement::new(outline, edge.stroke_width(1))])
        .map_err(de)?;
    Ok(())
}

/// A capsule `[a, b, radius]` [m] as a housing of colour `fill` with a dark rim and its axis
/// (the kinematic skeleton shows through); left out if not finite.
fn draw_capsule(
    chart: &mut ViewChart,
    c: &[f64; 7],
    axes: [usize; 2],
    fill: RGBColor,
    px_per_m: f64,
) -> Result<(), String> {
    let a = (c[axes[0]], c[axes[1]]);
    let b = (c[3 + axes[0]], c[3 + axes[1]]);
    if ![a.0, a.1, b.0, b.1, c[6]].iter().all(|v| v.is_finite()) {
        return Ok(());
    }
    // At most the frame's width: a wider capsule would cover the whole view anyway, and the
    // rasteriser's work grows with the radius.
    let r_px = (c[6] * px_per_m).clamp(1.0, f64::from(SIZE.0));
    for (color, extra) in [(BLACK.mix(0.8), 2.0), (fill.mix(1.0), 0.0)] {
        let width = (2.0 * r_px + extra).round() as u32;
        let radius = (r_px + 0.5 * extra).round() as i32;
        chart
            .draw_series([PathElement::new(vec![a, b], color.stroke_width(width))])
            .map_err(de)?;
        chart
            .draw_series([a, b].map(|p| Circle::new(p, radius, color.filled())))
            .map_err(de)?;
    }
    chart
        .draw_series([PathElement::new(vec![a, b], SKELETON.stroke_width(2))])
        .map_err(de)?;
    Ok(())
}

/// The convex hull of 2-D points, counter-clockwise (Andrew's monotone chain).
fn convex_hull(mut p: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    p.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    if p.len() < 3 {
        return p;
    }
    let cross = |o: (f64, f64), a: (f64, f64), b: (f64, f64)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    let mut hull: Vec<(f64, f64)> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let points: Box<dyn Iterator<Item = &(f64, f64)>> = if pass == 0 {
            Box::new(p.iter())
        } else {
            Box::new(p.iter().rev())
        };
        for &q in points {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
            {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    hull
}
