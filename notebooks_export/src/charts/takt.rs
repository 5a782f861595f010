//! Success within the takt against the mean cycle time, for one preset that runs on a takt: each
//! method a labelled point (held-out scenarios), each tuning trial of a control a faint dot
//! (its training scenarios), the takt as a vertical line. A method up and to the left seats
//! more cubes in time, faster.

use std::path::Path;

use plotters::prelude::*;

use crate::charts::axis::Axis;
use crate::charts::{draw_axes, min_max, padded};
use crate::comparison_table::Comparison;
use crate::error::ReportError;
use crate::raster::{FONT, de, render_png};

/// The chart's size \[px\].
const SIZE: (u32, u32) = (900, 600);

/// The methods' colours, in the comparison's order (repeating).
const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
];

/// Draws the chart of `preset` in `c` into `path`; `takt` \[s\] is the preset's.
pub fn takt_chart(c: &Comparison, preset: &str, takt: f64, path: &Path) -> Result<(), ReportError> {
    // (name, mean cycle time s, within the takt %) of every method with a success.
    let methods: Vec<(&str, f64, f64)> = c
        .results
        .iter()
        .filter(|r| r.preset == preset)
        .filter_map(|r| {
            let e = &r.report;
            Some((
                r.method.as_str(),
                e.mean_cycle_time_s?,
                100.0 * e.within_takt_rate,
            ))
        })
        .collect();
    let trials: Vec<(f64, f64)> = c
        .tuning
        .iter()
        .filter(|t| t.preset == preset)
        .flat_map(|t| t.trials.iter().map(|[x, y]| (*x, 100.0 * y)))
        .collect();
    let xs = methods
        .iter()
        .map(|m| m.1)
        .chain(trials.iter().map(|t| t.0))
        .chain([takt]);
    let (x_lo, x_hi) = min_max(xs);
    let (x_lo, x_hi) = padded(x_lo, x_hi, 0.08, 2.0);
    let episodes = c.results.first().map_or(0, |r| r.report.episodes);
    render_png(path, SIZE, |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(
                format!("`{preset}`: success within the {takt} s takt against cycle time ({episodes} episodes)"),
                (FONT, 17),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(52)
            .build_cartesian_2d(Axis::new(x_lo, x_hi), Axis::new(0.0, 100.0))
            .map_err(de)?;
        draw_axes(
            &mut chart,
            "mean cycle time of the successes [s]",
            "success within the takt [%]",
            Some(8),
        )?;
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(takt, 0.0), (takt, 100.0)],
                BLACK.mix(0.5).stroke_width(1),
            )))
            .map_err(de)?;
        if !trials.is_empty() {
            chart
                .draw_series(trials.iter().map(|&(x, y)| {
                    Circle::new((x, y), 2, RGBColor(120, 120, 120).mix(0.35).filled())
                }))
                .map_err(de)?
                .label("tuning trials (training scenarios)")
                .legend(|(x, y)| {
                    Circle::new((x + 9, y), 3, RGBColor(120, 120, 120).mix(0.5).filled())
                });
        }
        for (i, (name, x, y)) in methods.iter().enumerate() {
            let color = PALETTE[i % PALETTE.len()];
            chart
                .draw_series(std::iter::once(Circle::new((*x, *y), 6, color.filled())))
                .map_err(de)?
                .label(format!("{name}: {y:.1} %, {x:.1} s"))
                .legend(move |(lx, ly)| Circle::new((lx + 9, ly), 5, color.filled()));
        }
        crate::charts::draw_legend(&mut chart, SeriesLabelPosition::LowerLeft, 12)
    })
}
