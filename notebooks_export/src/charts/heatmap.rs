//! Success rate per method and preset as a heatmap: one row per method, one column per preset,
//! each cell coloured by its rate (red 0 %, amber 50 %, green 100 %) and carrying the rate and its
//! 95 % Wilson interval. Readable with a dozen methods on eight presets, where bars are not.

use std::path::Path;

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::comparison_table::Comparison;
use crate::error::ReportError;
use crate::raster::{FONT, de, render_png};

/// Width of the method-name column \[px\].
const NAME_WIDTH: u32 = 300;
/// Size of one cell \[px\].
const CELL: (u32, u32) = (118, 44);
/// Height of the title and the preset names above the cells \[px\].
const HEAD: u32 = 84;

/// The image size for `methods` rows and `presets` columns \[px\].
pub fn heatmap_size(methods: usize, presets: usize) -> (u32, u32) {
    (
        NAME_WIDTH + CELL.0 * presets.max(1) as u32 + 16,
        HEAD + CELL.1 * methods.max(1) as u32 + 16,
    )
}

/// The cell colour of a success rate in [0, 1] (a non-finite rate is grey).
pub fn rate_color(rate: f64) -> RGBColor {
    if !rate.is_finite() {
        return RGBColor(200, 200, 200);
    }
    let r = rate.clamp(0.0, 1.0);
    let mix = |a: (f64, f64, f64), b: (f64, f64, f64), t: f64| {
        RGBColor(
            (a.0 + (b.0 - a.0) * t) as u8,
            (a.1 + (b.1 - a.1) * t) as u8,
            (a.2 + (b.2 - a.2) * t) as u8,
        )
    };
    let (red, amber, green) = (
        (222.0, 94.0, 86.0),
        (246.0, 204.0, 92.0),
        (92.0, 184.0, 112.0),
    );
    if r < 0.5 {
        mix(red, amber, 2.0 * r)
    } else {
        mix(amber, green, 2.0 * r - 1.0)
    }
}

/// Draws the heatmap of `c` into `path`.
pub fn success_heatmap(c: &Comparison, path: &Path) -> Result<(), ReportError> {
    let size = heatmap_size(c.methods.len(), c.presets.len());
    let episodes = c.results.first().map_or(0, |r| r.report.episodes);
    render_png(path, size, |root| {
        let centred = |px: u32| {
            TextStyle::from((FONT, px).into_font()).pos(Pos::new(HPos::Center, VPos::Center))
        };
        root.draw(&Text::new(
            format!("Success rate [%] and 95 % CI, {episodes} seeded episodes per preset"),
            ((size.0 / 2) as i32, 18),
            centred(20),
        ))
        .map_err(de)?;
        for (p, preset) in c.presets.iter().enumerate() {
            let x = (NAME_WIDTH + CELL.0 * p as u32 + CELL.0 / 2) as i32;
            root.draw(&Text::new(
                preset.clone(),
                (x, HEAD as i32 - 16),
                centred(14),
            ))
            .map_err(de)?;
        }
        for (m, method) in c.methods.iter().enumerate() {
            let y = (HEAD + CELL.1 * m as u32) as i32;
            let name =
                TextStyle::from((FONT, 15).into_font()).pos(Pos::new(HPos::Right, VPos::Center));
            root.draw(&Text::new(
                method.clone(),
                (NAME_WIDTH as i32 - 10, y + CELL.1 as i32 / 2),
                name,
            ))
            .map_err(de)?;
            for (p, preset) in c.presets.iter().enumerate() {
                let x = (NAME_WIDTH + CELL.0 * p as u32) as i32;
                let Some(r) = c.get(method, preset) else {
                    continue;
                };
                let e = &r.report;
                root.draw(&Rectangle::new(
                    [
                        (x + 1, y + 1),
                        (x + CELL.0 as i32 - 1, y + CELL.1 as i32 - 1),
                    ],
                    rate_color(e.success_rate).filled(),
                ))
                .map_err(de)?;
                let cx = x + CELL.0 as i32 / 2;
                root.draw(&Text::new(
                    format!("{:.1}", 100.0 * e.success_rate),
                    (cx, y + 15),
                    centred(16),
                ))
                .map_err(de)?;
                root.draw(&Text::new(
                    format!("{:.0}–{:.0}", 100.0 * e.ci_low, 100.0 * e.ci_high),
                    (cx, y + 33),
                    centred(12),
                ))
                .map_err(de)?;
            }
        }
        Ok(())
    })
}
