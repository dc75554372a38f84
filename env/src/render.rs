//! Rendering from the codes observation (so a rendering can never show the hidden timer):
//! ASCII for terminals, PNG frames and animated GIFs.

use crate::error::EnvError;
use crate::kitchen::CODE_CHANNELS;
use crate::layout::{Layout, ObjectKind};
use crate::task::TaskFamily;

/// ASCII picture of a codes observation: one 4-character cell per grid cell.
///
/// `.` free, `O` onion dispenser, `D` delivery, `S`/`L` short/long counters,
/// `K` sink, `B` button, `V` oven (`V*` on, `V!` ready, `V<n>` multi-timer cue),
/// `@` agent (`@o` carrying an onion, `@s` carrying soup).
pub fn ascii(layout: &Layout, family: TaskFamily, codes: &[u8]) -> String {
    let cue = family == TaskFamily::MultiTimer;
    let mut out = String::new();
    for r in 0..layout.rows() {
        for c in 0..layout.cols() {
            let cell = layout.index(r, c);
            let px = &codes[cell * CODE_CHANNELS..(cell + 1) * CODE_CHANNELS];
            let text = match layout.object_at(cell) {
                Some(ObjectKind::Oven) => match px[4] {
                    0 => "V".to_string(),
                    v if cue => format!("V{v}"),
                    1 => "V*".to_string(),
                    2 => "V!".to_string(),
                    v => format!("V{v}"),
                },
                Some(kind) => kind.symbol().to_string(),
                None if px[1] == 1 => match (px[2], px[3]) {
                    (1, _) => "@o".to_string(),
                    (_, 1) => "@s".to_string(),
                    _ => "@".to_string(),
                },
                None => ".".to_string(),
            };
            out.push_str(&format!(" {text:<3}"));
        }
        out.push('\n');
    }
    out
}

/// Pixels per grid cell in image renderings.
pub const CELL_PX: usize = 32;

/// The fixed palette (RGB) of image renderings; indices are used directly in frames.
pub const PALETTE: [[u8; 3]; 13] = [
    [235, 235, 228], // 0 floor
    [60, 60, 60],    // 1 grid lines / agent
    [232, 196, 40],  // 2 onion (dispenser, carried onion)
    [60, 160, 80],   // 3 delivery counter
    [120, 40, 40],   // 4 oven off
    [240, 120, 30],  // 5 oven on
    [220, 30, 30],   // 6 oven ready
    [60, 110, 220],  // 7 short counter
    [150, 70, 190],  // 8 long counter
    [40, 190, 200],  // 9 sink
    [220, 60, 160],  // 10 button
    [250, 250, 250], // 11 soup (carried)
    [150, 150, 150], // 12 cue bar
];

/// An indexed-colour frame (`width × height` palette indices).
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Row-major palette indices.
    pub pixels: Vec<u8>,
}

impl Frame {
    fn fill_rect(&mut self, x0: usize, y0: usize, w: usize, h: usize, color: u8) {
        for y in y0..(y0 + h).min(self.height) {
            let row = y * self.width;
            for x in x0..(x0 + w).min(self.width) {
                self.pixels[row + x] = color;
            }
        }
    }

    fn fill_disc(&mut self, cx: usize, cy: usize, radius: usize, color: u8) {
        let r2 = (radius * radius) as isize;
        for y in cy.saturating_sub(radius)..(cy + radius + 1).min(self.height) {
            for x in cx.saturating_sub(radius)..(cx + radius + 1).min(self.width) {
                let (dx, dy) = (x as isize - cx as isize, y as isize - cy as isize);
                if dx * dx + dy * dy <= r2 {
                    self.pixels[y * self.width + x] = color;
                }
            }
        }
    }
}

/// Draws a codes observation as an indexed-colour frame.
pub fn frame(layout: &Layout, family: TaskFamily, codes: &[u8]) -> Frame {
    let cue = family == TaskFamily::MultiTimer;
    let (w, h) = (layout.cols() * CELL_PX, layout.rows() * CELL_PX);
    let mut f = Frame {
        width: w,
        height: h,
        pixels: vec![0; w * h],
    };
    for r in 0..layout.rows() {
        for c in 0..layout.cols() {
            let cell = layout.index(r, c);
            let px = &codes[cell * CODE_CHANNELS..(cell + 1) * CODE_CHANNELS];
            let (x, y) = (c * CELL_PX, r * CELL_PX);
            f.fill_rect(x, y, CELL_PX, 1, 1);
            f.fill_rect(x, y, 1, CELL_PX, 1);
            let body = match layout.object_at(cell) {
                Some(ObjectKind::OnionDispenser) => Some(2),
                Some(ObjectKind::DeliveryCounter) => Some(3),
                Some(ObjectKind::Oven | ObjectKind::Oven2 | ObjectKind::Oven3) => {
                    Some(match px[4] {
                        0 => 4,
                        2 if !cue => 6,
                        _ => 5,
                    })
                }
                Some(ObjectKind::ShortCounter | ObjectKind::Counter3) => Some(7),
                Some(ObjectKind::LongCounter | ObjectKind::Counter4) => Some(8),
                Some(ObjectKind::RewardSink) => Some(9),
                Some(ObjectKind::OvenButton) => Some(10),
                None => None,
            };
            if let Some(color) = body {
                f.fill_rect(x + 3, y + 3, CELL_PX - 6, CELL_PX - 6, color);
                if layout.object_at(cell) == Some(ObjectKind::Oven) && cue && px[4] > 0 {
                    // Multi-timer cue: a bar whose length grows with the cue value.
                    let len = (px[4] as usize).min(CELL_PX - 8);
                    f.fill_rect(x + 4, y + CELL_PX - 8, len, 3, 12);
                }
            }
            if px[1] == 1 {
                let (cx, cy) = (x + CELL_PX / 2, y + CELL_PX / 2);
                f.fill_disc(cx, cy, CELL_PX / 3, 1);
                if px[2] == 1 {
                    f.fill_disc(cx, cy, CELL_PX / 7, 2);
                } else if px[3] != 0 {
                    f.fill_disc(cx, cy, CELL_PX / 7, 11);
                }
            }
        }
    }
    f
}

fn flat_palette() -> Vec<u8> {
    PALETTE.iter().flatten().copied().collect()
}

/// Encodes a frame as an indexed PNG.
pub fn png_bytes(frame: &Frame) -> Result<Vec<u8>, EnvError> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, frame.width as u32, frame.height as u32);
        enc.set_color(png::ColorType::Indexed);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_palette(flat_palette());
        let mut writer = enc
            .write_header()
            .map_err(|e| EnvError::Output(format!("png: {e}")))?;
        writer
            .write_image_data(&frame.pixels)
            .map_err(|e| EnvError::Output(format!("png: {e}")))?;
    }
    Ok(out)
}

/// Encodes frames as an endlessly looping animated GIF (`delay_cs` hundredths of a second per frame).
pub fn gif_bytes(frames: &[Frame], delay_cs: u16) -> Result<Vec<u8>, EnvError> {
    let first = frames
        .first()
        .ok_or_else(|| EnvError::Output("no frames to encode".into()))?;
    let mut out = Vec::new();
    {
        let palette = flat_palette();
        let mut enc =
            gif::Encoder::new(&mut out, first.width as u16, first.height as u16, &palette)
                .map_err(|e| EnvError::Output(format!("gif: {e}")))?;
        enc.set_repeat(gif::Repeat::Infinite)
            .map_err(|e| EnvError::Output(format!("gif: {e}")))?;
        for f in frames {
            let mut g = gif::Frame::from_indexed_pixels(
                f.width as u16,
                f.height as u16,
                f.pixels.clone(),
                None,
            );
            g.delay = delay_cs;
            enc.write_frame(&g)
                .map_err(|e| EnvError::Output(format!("gif: {e}")))?;
        }
    }
    Ok(out)
}
