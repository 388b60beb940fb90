//! The floor as a top-down camera sees it: grey floor with a metre grid, pure green
//! lines, pure blue start, pure red end, and optionally the solution path.

use std::fmt::Write;

use anyhow::Result;

use super::{MazeView, RenderOptions, Renderer};
use crate::layout::Layout;

/// Pixels per metre.
const SCALE: f64 = 40.0;

/// The SVG renderer.
#[derive(Debug, Clone, Copy, Default)]
pub struct Svg;

/// A number as SVG text: at most 4 decimals, no trailing zeros.
fn num(value: f64) -> String {
    let text = format!("{value:.4}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" {
        "0".to_string()
    } else {
        text.to_string()
    }
}

impl Renderer for Svg {
    fn render(&self, layout: &Layout, options: &RenderOptions) -> Result<Vec<u8>> {
        let view = MazeView::of(layout, options)?;
        let [fx, fy] = layout.floor.size;
        let (width, height) = (fx * SCALE, fy * SCALE);
        let mut out = String::new();
        let _ = writeln!(
            out,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" viewBox="{} {} {} {}">"#,
            num(width),
            num(height),
            num(-fx / 2.0),
            num(-fy / 2.0),
            num(fx),
            num(fy)
        );
        let _ = writeln!(
            out,
            "<title>vrep-maze {}x{} {} seed {}</title>",
            layout.grid.columns,
            layout.grid.rows,
            layout.generator.algorithm,
            layout.generator.seed
        );
        // Floor y grows up, SVG y grows down: flip once for everything inside.
        out.push_str("<g transform=\"scale(1,-1)\">\n");
        let _ = writeln!(
            out,
            r##"<rect x="{}" y="{}" width="{}" height="{}" fill="#b4b4b4"/>"##,
            num(-fx / 2.0),
            num(-fy / 2.0),
            num(fx),
            num(fy)
        );
        floor_grid(&mut out, fx, fy);
        let (l, w) = (layout.line.length, layout.line.width);
        out.push_str("<g fill=\"#00ff00\">\n");
        for s in &layout.segments {
            let _ = writeln!(
                out,
                r#"<rect x="{}" y="{}" width="{}" height="{}" transform="translate({},{}) rotate({})"/>"#,
                num(-l / 2.0),
                num(-w / 2.0),
                num(l),
                num(w),
                num(s.x),
                num(s.y),
                num(s.yaw.to_degrees())
            );
        }
        out.push_str("</g>\n");
        let c = layout.grid.cell_size;
        for (pose, colour) in [
            (&layout.start.pose, "#0000ff"),
            (&layout.end.pose, "#ff0000"),
        ] {
            let _ = writeln!(
                out,
                r#"<rect x="{}" y="{}" width="{}" height="{}" fill="{colour}" transform="translate({},{}) rotate({})"/>"#,
                num(-c / 2.0),
                num(-c / 2.0),
                num(c),
                num(c),
                num(pose.x),
                num(pose.y),
                num(pose.yaw.to_degrees())
            );
        }
        if !view.solution.is_empty() {
            let geometry = crate::layout::Geometry {
                cell_size: c,
                origin: layout.grid.origin,
                rotation: layout.grid.rotation,
                line_length: l,
                line_width: w,
                line_z: layout.line.z,
                marker_z: layout.start.pose.z,
            };
            let points: Vec<String> = view
                .solution
                .iter()
                .map(|&cell| {
                    let p = geometry.cell_centre(cell);
                    format!("{},{}", num(p.x), num(p.y))
                })
                .collect();
            let _ = writeln!(
                out,
                r##"<polyline points="{}" fill="none" stroke="#ffa500" stroke-width="{}" stroke-linejoin="round" stroke-opacity="0.8"/>"##,
                points.join(" "),
                num(w / 2.0)
            );
        }
        scale_bar(&mut out, fx, fy);
        out.push_str("</g>\n</svg>\n");
        Ok(out.into_bytes())
    }
}

/// A scale bar in the south-west corner of the floor: a white bar of a round number of
/// metres (about a fifth of the floor), labelled with stroked seven-segment digits so the
/// label survives rasterizing without fonts.
fn scale_bar(out: &mut String, fx: f64, fy: f64) {
    let length = [
        1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0, 2000.0,
    ]
    .into_iter()
    .take_while(|&l| l <= fx / 5.0)
    .last()
    .unwrap_or(1.0);
    let unit = length / 10.0;
    let (x0, y0) = (-fx / 2.0 + unit, -fy / 2.0 + unit);
    let _ = writeln!(
        out,
        r##"<rect x="{}" y="{}" width="{}" height="{}" fill="#ffffff" stroke="#000000" stroke-width="{}"/>"##,
        num(x0),
        num(y0),
        num(length),
        num(unit),
        num(unit / 5.0)
    );
    let label = format!("{}m", length as u64);
    let glyph_height = unit * 2.0;
    let mut x = x0 + length + unit;
    let mut path = String::new();
    for ch in label.chars() {
        for (ax, ay, bx, by) in glyph_strokes(ch) {
            let _ = write!(
                path,
                "M{},{}L{},{}",
                num(x + ax * glyph_height / 2.0),
                num(y0 + ay * glyph_height),
                num(x + bx * glyph_height / 2.0),
                num(y0 + by * glyph_height)
            );
        }
        x += glyph_height * 0.75;
    }
    let _ = writeln!(
        out,
        r##"<path d="{path}" fill="none" stroke="#000000" stroke-width="{}" stroke-linecap="round"/>"##,
        num(unit / 3.0)
    );
}

/// The strokes of a seven-segment glyph in a 1 x 1 box (y up): digits and `m`.
fn glyph_strokes(ch: char) -> Vec<(f64, f64, f64, f64)> {
    // Segments a (top), b, c (right, top to bottom), d (bottom), e, f (left), g (middle).
    const SEGMENTS: [(f64, f64, f64, f64); 7] = [
        (0.0, 1.0, 1.0, 1.0),
        (1.0, 1.0, 1.0, 0.5),
        (1.0, 0.5, 1.0, 0.0),
        (0.0, 0.0, 1.0, 0.0),
        (0.0, 0.0, 0.0, 0.5),
        (0.0, 0.5, 0.0, 1.0),
        (0.0, 0.5, 1.0, 0.5),
    ];
    let mask: u8 = match ch {
        '0' => 0b011_1111,
        '1' => 0b000_0110,
        '2' => 0b101_1011,
        '5' => 0b110_1101,
        'm' => {
            return vec![
                (0.0, 0.0, 0.0, 0.5),
                (0.0, 0.5, 1.0, 0.5),
                (0.5, 0.0, 0.5, 0.5),
                (1.0, 0.0, 1.0, 0.5),
            ];
        }
        _ => 0,
    };
    SEGMENTS
        .iter()
        .enumerate()
        .filter(|(i, _)| mask & (1 << i) != 0)
        .map(|(_, &s)| s)
        .collect()
}

/// Thin lines every metre, thicker ones every 5 m floor panel.
fn floor_grid(out: &mut String, fx: f64, fy: f64) {
    out.push_str("<g stroke=\"#8c8c8c\">\n");
    let lines = |out: &mut String, extent: f64, other: f64, vertical: bool| {
        let n = (extent / 2.0).floor() as i64;
        for k in -n..=n {
            let at = k as f64;
            let stroke = if k % 5 == 0 { 0.03 } else { 0.01 };
            let (x1, y1, x2, y2) = if vertical {
                (at, -other / 2.0, at, other / 2.0)
            } else {
                (-other / 2.0, at, other / 2.0, at)
            };
            let _ = writeln!(
                out,
                r#"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke-width="{}"/>"#,
                num(x1),
                num(y1),
                num(x2),
                num(y2),
                num(stroke)
            );
        }
    };
    lines(out, fx, fy, true);
    lines(out, fy, fx, false);
    out.push_str("</g>\n");
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::Algorithm;
    use crate::layout::{GenerateSpec, build_layout};
    use crate::maze::Grid;

    #[test]
    fn draws_every_segment_and_both_markers() {
        let layout = build_layout(&GenerateSpec::course(
            Grid::new(9, 9).unwrap(),
            Algorithm::Prim,
            42,
        ))
        .unwrap();
        let svg = String::from_utf8(
            Svg.render(&layout, &RenderOptions { solution: true })
                .unwrap(),
        )
        .unwrap();
        assert!(svg.starts_with("<svg "));
        assert!(svg.ends_with("</svg>\n"));
        let lines = svg
            .split("<g fill=\"#00ff00\">")
            .nth(1)
            .unwrap()
            .split("</g>")
            .next()
            .unwrap();
        assert_eq!(lines.matches("<rect").count(), layout.segments.len());
        assert_eq!(svg.matches("fill=\"#0000ff\"").count(), 1);
        assert_eq!(svg.matches("fill=\"#ff0000\"").count(), 1);
        let path = svg
            .split("points=\"")
            .nth(1)
            .unwrap()
            .split('"')
            .next()
            .unwrap();
        assert_eq!(
            path.split(' ').count() as u64,
            layout.metrics.solution_cells
        );
        assert_eq!(num(0.30000000000000004), "0.3");
        assert!(svg.contains("fill=\"#ffffff\""), "a scale bar");
        assert_eq!(glyph_strokes('1').len(), 2);
        assert_eq!(glyph_strokes('0').len(), 6);
        assert_eq!(num(-0.00001), "0");
    }
}
