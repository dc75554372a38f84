//! A labelled matrix as a heat map: named rows × named columns, each cell coloured on a
//! diverging scale (blue below 0, red above, white at 0, full colour at ±`scale`) and
//! printed with its value — for tables of standardised values such as the mechanism
//! fingerprints (models × features), readable at 1366 px without looking numbers up.

use super::FigureError;
use super::draw::{atomic, err, figure_paths};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::{Path, PathBuf};

/// A matrix with named rows and columns.
#[derive(Debug, Clone, PartialEq)]
pub struct LabelledMatrix {
    /// Title above the matrix.
    pub title: String,
    /// Row names, top to bottom.
    pub rows: Vec<String>,
    /// Column names, left to right.
    pub columns: Vec<String>,
    /// Values `[rows][columns]`; NaN = missing (a grey cell marked "–").
    pub values: Vec<Vec<f64>>,
    /// Absolute value drawn in full colour (larger values are clamped to it).
    pub scale: f64,
}

/// Fill of a value on the diverging scale.
fn fill(v: f64, scale: f64) -> RGBColor {
    if !v.is_finite() {
        return RGBColor(225, 225, 225);
    }
    let t = (v / scale.max(1e-12)).clamp(-1.0, 1.0);
    let mix = |a: u8, b: u8, f: f64| (a as f64 + (b as f64 - a as f64) * f).round() as u8;
    if t >= 0.0 {
        RGBColor(mix(255, 202, t), mix(255, 0, t), mix(255, 32, t))
    } else {
        RGBColor(mix(255, 5, -t), mix(255, 113, -t), mix(255, 176, -t))
    }
}

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    m: &LabelledMatrix,
    path: &Path,
) -> Result<(), FigureError>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(err(path))?;
    let (w, h) = root.dim_in_pixel();
    // Margins fit the longest row name and column name at the fonts below.
    let longest_row = m.rows.iter().map(|r| r.chars().count()).max().unwrap_or(0) as i32;
    let longest_col = m
        .columns
        .iter()
        .map(|c| c.chars().count())
        .max()
        .unwrap_or(0) as i32;
    let (left, top, right) = ((longest_row * 9 + 24).max(120), 52i32, 16i32);
    let bottom = (longest_col * 9 + 24).max(60);
    let ncol = m.columns.len().max(1) as i32;
    let nrow = m.rows.len().max(1) as i32;
    let cw = ((w as i32 - left - right) / ncol).max(1);
    let ch = ((h as i32 - top - bottom) / nrow).max(1);
    let text = |size: i32| ("sans-serif", size).into_font().color(&BLACK);
    root.draw(&Text::new(
        m.title.clone(),
        (left, 14),
        text(20).pos(Pos::new(HPos::Left, VPos::Top)),
    ))
    .map_err(err(path))?;
    for (i, row) in m.rows.iter().enumerate() {
        let y = top + i as i32 * ch;
        root.draw(&Text::new(
            row.clone(),
            (left - 8, y + ch / 2),
            text(16).pos(Pos::new(HPos::Right, VPos::Center)),
        ))
        .map_err(err(path))?;
        for (j, _) in m.columns.iter().enumerate() {
            let x = left + j as i32 * cw;
            let v = m
                .values
                .get(i)
                .and_then(|r| r.get(j))
                .copied()
                .unwrap_or(f64::NAN);
            root.draw(&Rectangle::new(
                [(x, y), (x + cw - 1, y + ch - 1)],
                fill(v, m.scale).filled(),
            ))
            .map_err(err(path))?;
            let label = if v.is_finite() {
                // No "-0.0" for a value that rounds to zero.
                format!("{v:.1}").replace("-0.0", "0.0")
            } else {
                "–".into()
            };
            root.draw(&Text::new(
                label,
                (x + cw / 2, y + ch / 2),
                text(15).pos(Pos::new(HPos::Center, VPos::Center)),
            ))
            .map_err(err(path))?;
        }
    }
    let below = top + nrow * ch + 8;
    for (j, col) in m.columns.iter().enumerate() {
        let x = left + j as i32 * cw + cw / 2;
        root.draw(&Text::new(
            col.clone(),
            (x, below),
            ("sans-serif", 16)
                .into_font()
                .transform(FontTransform::Rotate90)
                .color(&BLACK)
                .pos(Pos::new(HPos::Left, VPos::Center)),
        ))
        .map_err(err(path))?;
    }
    root.present().map_err(err(path))?;
    Ok(())
}

/// Writes `m` as a heat map at `stem` (`.svg` and `.png`, `size` in pixels).
pub fn write_matrix(
    stem: &Path,
    m: &LabelledMatrix,
    size: (u32, u32),
) -> Result<Vec<PathBuf>, FigureError> {
    let (svg, png) = figure_paths(stem)?;
    atomic(&svg, |tmp| {
        draw(SVGBackend::new(tmp, size).into_drawing_area(), m, &svg)
    })?;
    atomic(&png, |tmp| {
        draw(BitMapBackend::new(tmp, size).into_drawing_area(), m, &png)
    })?;
    Ok(vec![svg, png])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scale_is_white_at_zero_and_saturates_at_the_scale() {
        assert_eq!(fill(0.0, 2.0), RGBColor(255, 255, 255));
        assert_eq!(fill(2.0, 2.0), RGBColor(202, 0, 32));
        assert_eq!(fill(5.0, 2.0), RGBColor(202, 0, 32));
        assert_eq!(fill(-2.0, 2.0), RGBColor(5, 113, 176));
        assert_eq!(fill(f64::NAN, 2.0), RGBColor(225, 225, 225));
    }

    #[test]
    fn every_row_and_column_name_is_written() {
        let dir = tempfile::tempdir().unwrap();
        let m = LabelledMatrix {
            title: "t".into(),
            rows: vec!["ddm".into(), "sbf".into()],
            columns: vec!["foc_cv".into(), "wf".into()],
            values: vec![vec![1.0, f64::NAN], vec![-0.5, 3.0]],
            scale: 2.0,
        };
        let files = write_matrix(&dir.path().join("m"), &m, (600, 400)).unwrap();
        let svg = std::fs::read_to_string(&files[0]).unwrap();
        for name in ["ddm", "sbf", "foc_cv", "wf", "1.0", "-0.5", "3.0", "–"] {
            assert!(svg.contains(name), "{name}");
        }
        assert!(files[1].is_file());
    }
}
