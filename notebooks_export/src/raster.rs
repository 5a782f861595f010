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
        encoder.set_compression(png::Compression::Default);
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
/// to the nearest colour of `palette` (see [`gif_palette`]): flat colours compress well. After
/// the first frame, each frame holds only the rectangle that changed (`changed_rect`).
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
        let mut cropped = Vec::with_capacity(indices.len());
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
            let ((left, top), (cw, ch)) = changed_rect(&delta, w, unchanged);
            cropped.clear();
            for row in delta
                .chunks_exact(usize::from(w.max(1)))
                .skip(usize::from(top))
                .take(usize::from(ch))
            {
                cropped.extend_from_slice(&row[usize::from(left)..usize::from(left + cw)]);
            }
            let mut frame = gif::Frame {
                left,
                top,
                width: cw,
                height: ch,
                buffer: std::borrow::Cow::Borrowed(&cropped),
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

/// The smallest rectangle of a `width`-wide frame of palette indices holding every pixel that
/// is not `unchanged`: `((left, top), (width, height))` in pixels. A frame where nothing changed
/// gets its top-left pixel (a GIF frame has at least one), which is `unchanged` and so draws
/// nothing. Encoding only this rectangle gives the same picture (pixels outside it are kept
/// from the previous frame, as transparent ones are) with far less LZW work.
fn changed_rect(frame: &[u8], width: u16, unchanged: u8) -> ((u16, u16), (u16, u16)) {
    let w = usize::from(width.max(1));
    let (mut x0, mut y0, mut x1, mut y1) = (usize::MAX, usize::MAX, 0, 0);
    for (y, row) in frame.chunks_exact(w).enumerate() {
        let Some(first) = row.iter().position(|&p| p != unchanged) else {
            continue;
        };
        let last = row.iter().rposition(|&p| p != unchanged).unwrap_or(first);
        (x0, x1) = (x0.min(first), x1.max(last + 1));
        (y0, y1) = (y0.min(y), y + 1);
    }
    if y0 == usize::MAX {
        return ((0, 0), (1, 1));
    }
    // Every coordinate is below `width` or the frame's height, both u16.
    let c = |v: usize| u16::try_from(v).unwrap_or(u16::MAX);
    ((c(x0), c(y0)), (c(x1 - x0), c(y1 - y0)))
}

/// Turns any displayable drawing error into the `String` the render closures return.
pub fn de<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A red 6 × 6 square (plotters fills the corners' half-open range) moving right over
    /// white, with frames where nothing moves: each picture the decoder rebuilds (frames drawn
    /// over the kept picture at their offsets) is exactly white, and red where the square was
    /// drawn.
    #[test]
    fn cropped_frames_rebuild_every_picture() {
        let (w, h) = (40u32, 30u32);
        let xs = [2i32, 2, 9, 20, 20, 31];
        let path = std::env::temp_dir().join(format!("raster-crop-{}.gif", std::process::id()));
        let palette = gif_palette(&[RED]);
        render_gif(&path, (w, h), &[5; 6], &palette, |i, root| {
            root.fill(&WHITE).map_err(de)?;
            let x = xs[i];
            root.draw(&Rectangle::new([(x, 10), (x + 6, 16)], RED.filled()))
                .map_err(de)
        })
        .unwrap();
        let mut options = gif::DecodeOptions::new();
        options.set_color_output(gif::ColorOutput::RGBA);
        let mut decoder = options
            .read_info(std::fs::File::open(&path).unwrap())
            .unwrap();
        let mut picture = vec![[0u8; 3]; (w * h) as usize];
        let mut sizes = Vec::new();
        for &x in &xs {
            let frame = decoder.read_next_frame().unwrap().unwrap();
            sizes.push(usize::from(frame.width) * usize::from(frame.height));
            for (k, px) in frame.buffer.chunks_exact(4).enumerate() {
                let (fx, fy) = (k % usize::from(frame.width), k / usize::from(frame.width));
                if px[3] == 255 {
                    let at =
                        (usize::from(frame.top) + fy) * w as usize + usize::from(frame.left) + fx;
                    picture[at] = [px[0], px[1], px[2]];
                }
            }
            for (k, px) in picture.iter().enumerate() {
                let (px_x, px_y) = ((k % w as usize) as i32, (k / w as usize) as i32);
                let inside = (x..x + 6).contains(&px_x) && (10..16).contains(&px_y);
                let want = if inside { [255, 0, 0] } else { [255, 255, 255] };
                assert_eq!(
                    *px, want,
                    "frame with the square at x = {x}, pixel ({px_x}, {px_y})"
                );
            }
        }
        assert!(decoder.read_next_frame().unwrap().is_none());
        // The first frame is whole, an unchanged one a single pixel, a move only its band.
        assert_eq!(sizes[0], (w * h) as usize);
        assert_eq!(sizes[1], 1);
        assert_eq!(sizes[2], (9 + 6 - 2) * 6);
        std::fs::remove_file(&path).unwrap();
    }
}
