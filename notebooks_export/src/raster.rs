//! Rendering targets: an RGB buffer drawn by plotters, encoded to PNG or to GIF frames, with
//! the DejaVu font registered so text renders on a machine without any system font.

use std::path::Path;
use std::sync::Once;

use plotters::prelude::*;
use plotters::style::FontStyle;

use crate::error::{ReportError, write_file};

/// The font family every chart uses (DejaVu Sans, embedded).
pub const FONT: &str = "sans-serif";

/// Registers the embedded DejaVu Sans (regular and bold) with plotters' `ab_glyph` backend.
pub fn register_fonts() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The bytes are a valid TTF shipped by the `dejavu` crate: registration cannot fail.
        plotters::style::register_font(FONT, FontStyle::Normal, dejavu::sans::regular())
            .unwrap_or_else(|_| unreachable!("DejaVu Sans is a valid font"));
        plotters::style::register_font(FONT, FontStyle::Bold, dejavu::sans::bold())
            .unwrap_or_else(|_| unreachable!("DejaVu Sans Bold is a valid font"));
    });
}

/// Draws with `draw` into a `width × height` RGB canvas and writes it to `path` as PNG
/// (atomically).
pub fn render_png(
    path: &Path,
    (width, height): (u32, u32),
    draw: impl FnOnce(&DrawingArea<BitMapBackend, plotters::coord::Shift>) -> Result<(), String>,
) -> Result<(), ReportError> {
    register_fonts();
    let mut rgb = vec![255u8; (width * height * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| ReportError::chart(path, e))?;
        draw(&root).map_err(|e| ReportError::chart(path, e))?;
        root.present().map_err(|e| ReportError::chart(path, e))?;
    }
    write_file(
        path,
        &encode_png(&rgb, width, height).map_err(|e| ReportError::chart(path, e))?,
    )
}

/// Draws into an in-memory RGB buffer (`width × height × 3`, white background).
pub fn render_rgb(
    (width, height): (u32, u32),
    draw: impl FnOnce(&DrawingArea<BitMapBackend, plotters::coord::Shift>) -> Result<(), String>,
) -> Result<Vec<u8>, String> {
    register_fonts();
    let mut rgb = vec![255u8; (width * height * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        draw(&root)?;
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(rgb)
}

/// PNG bytes of an RGB buffer.
pub fn encode_png(rgb: &[u8], width: u32, height: u32) -> Result<Vec<u8>, png::EncodingError> {
    let mut out = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut out, width, height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::Best);
        // The mark that lets a later command replace this file (fairgrasp_types::output).
        encoder.add_text_chunk("Software".into(), fairgrasp_types::output::GENERATOR.into())?;
        let mut writer = encoder.write_header()?;
        writer.write_image_data(rgb)?;
    }
    Ok(out)
}

/// A GIF palette: 16 greys, and each of `colors` pure and blended 1/3 and 2/3 towards white
/// (anti-aliased edges). At most 256 entries.
pub fn gif_palette(colors: &[RGBColor]) -> Vec<[u8; 3]> {
    let mut palette: Vec<[u8; 3]> = (0..16u8).map(|i| [i * 17; 3]).collect();
    for c in colors {
        for k in 0..3u16 {
            let mix = |v: u8| ((u16::from(v) * (3 - k) + 255 * k) / 3) as u8;
            palette.push([mix(c.0), mix(c.1), mix(c.2)]);
        }
    }
    // The last entry is kept free: `render_gif` uses it as "unchanged since the last frame".
    palette.truncate(255);
    palette
}

/// Nearest palette entry of every 15-bit colour (5 bits per channel).
fn palette_lookup(palette: &[[u8; 3]]) -> Vec<u8> {
    (0..32768u32)
        .map(|key| {
            let c = [(key >> 10) & 31, (key >> 5) & 31, key & 31].map(|v| (v * 255 / 31) as i32);
            let distance =
                |p: &[u8; 3]| (0..3).map(|i| (c[i] - i32::from(p[i])).pow(2)).sum::<i32>();
            (0..palette.len())
                .min_by_key(|&i| distance(&palette[i]))
                .unwrap_or(0) as u8
        })
        .collect()
}

/// Renders one frame per entry of `delays_cs` (hundredths of a second each) with
/// `draw(frame_index, area)` and writes them as a looping GIF (atomically). Pixels are mapped
/// to the nearest colour of `palette` (see [`gif_palette`]): flat colours compress well.
pub fn render_gif(
    path: &Path,
    (width, height): (u32, u32),
    delays_cs: &[u16],
    palette: &[[u8; 3]],
    mut draw: impl FnMut(
        usize,
        &DrawingArea<BitMapBackend, plotters::coord::Shift>,
    ) -> Result<(), String>,
) -> Result<(), ReportError> {
    register_fonts();
    let err = |e: &dyn std::fmt::Display| ReportError::chart(path, e);
    let (w, h) = (
        u16::try_from(width).map_err(|e| err(&e))?,
        u16::try_from(height).map_err(|e| err(&e))?,
    );
    let mut bytes = Vec::new();
    {
        let flat: Vec<u8> = palette
            .iter()
            .flatten()
            .chain(&[255, 0, 255])
            .copied()
            .collect();
        let lookup = palette_lookup(palette);
        let mut indices = vec![0u8; (width * height) as usize];
        let mut previous = vec![u8::MAX; indices.len()];
        let mut delta = vec![0u8; indices.len()];
        // Pixels equal to the previous frame's are written as this transparent index: long
        // runs of it compress to almost nothing.
        let unchanged = u8::try_from(palette.len()).map_err(|e| err(&e))?;
        let mut encoder = gif::Encoder::new(&mut bytes, w, h, &flat).map_err(|e| err(&e))?;
        encoder
            .set_repeat(gif::Repeat::Infinite)
            .map_err(|e| err(&e))?;
        // The mark that lets a later command replace this file (fairgrasp_types::output).
        encoder
            .write_raw_extension(
                gif::Extension::Comment.into(),
                &[fairgrasp_types::output::GENERATOR.as_bytes()],
            )
            .map_err(|e| err(&e))?;
        let mut rgb = vec![255u8; (width * height * 3) as usize];
        for (i, delay) in delays_cs.iter().enumerate() {
            rgb.fill(255);
            {
                let root =
                    BitMapBackend::with_buffer(&mut rgb, (width, height)).into_drawing_area();
                draw(i, &root).map_err(|e| err(&e))?;
                root.present().map_err(|e| err(&e))?;
            }
            for (index, px) in indices.iter_mut().zip(rgb.chunks_exact(3)) {
                let key = (usize::from(px[0] >> 3) << 10)
                    | (usize::from(px[1] >> 3) << 5)
                    | usize::from(px[2] >> 3);
                *index = lookup[key];
            }
            for ((d, now), before) in delta.iter_mut().zip(&indices).zip(&previous) {
                *d = if now == before { unchanged } else { *now };
            }
            previous.copy_from_slice(&indices);
            let mut frame = gif::Frame {
                width: w,
                height: h,
                buffer: std::borrow::Cow::Borrowed(&delta),
                transparent: Some(unchanged),
                dispose: gif::DisposalMethod::Keep,
                ..gif::Frame::default()
            };
            frame.delay = *delay;
            encoder.write_frame(&frame).map_err(|e| err(&e))?;
        }
    }
    write_file(path, &bytes)
}

/// Turns any displayable drawing error into the `String` the render closures return.
pub fn de<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}
