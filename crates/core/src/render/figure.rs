//! What the SVG and PNG pictures show, in metres: the colours, the green line runs, the
//! floor's metre grid and the scale bar (a wall maze's walls are in [`super::walls`]). Both
//! formats draw exactly this, each its own way.

use std::fmt;

/// An opaque sRGB colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Colour(pub [u8; 3]);

impl fmt::Display for Colour {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [r, g, b] = self.0;
        write!(f, "#{r:02x}{g:02x}{b:02x}")
    }
}

/// The floor.
pub(crate) const FLOOR: Colour = Colour([0xb4, 0xb4, 0xb4]);
/// The metre grid on the floor.
pub(super) const GRID: Colour = Colour([0x8c, 0x8c, 0x8c]);
/// The lines the robot follows: pure green, as the camera must see them.
pub(crate) const LINE: Colour = Colour([0x00, 0xff, 0x00]);
/// A wall maze's walls: near-black bars on the light floor.
pub(crate) const WALL: Colour = Colour([0x20, 0x20, 0x20]);
/// A wall maze's goal region (but its end cell): a light red tint.
pub(super) const GOAL: Colour = Colour([0xe6, 0xa0, 0xa0]);
/// The start marker: pure blue.
pub(crate) const START: Colour = Colour([0x00, 0x00, 0xff]);
/// The end marker: pure red.
pub const END: Colour = Colour([0xff, 0x00, 0x00]);
/// The solution path, drawn at [`SOLUTION_OPACITY`]: a deep orange, as far in hue from the
/// green lines as from the red End.
pub(super) const SOLUTION: Colour = Colour([0xff, 0x80, 0x00]);
/// Opacity of the solution path: opaque, since orange (#ffa500) at 0.8 over the green
/// lines came out #ccb700, an olive that read as a darker line at the default scale.
pub(super) const SOLUTION_OPACITY: f64 = 1.0;
/// The scale bar.
pub(super) const PAPER: Colour = Colour([0xff, 0xff, 0xff]);
/// The scale bar's outline and label.
pub(super) const INK: Colour = Colour([0x00, 0x00, 0x00]);

/// Most lines of the metre grid along one axis: beyond, they are thinned out.
const MAX_GRID_LINES: f64 = 200.0;

/// The floor's metre grid: lines through the floor origin every `step` metres, every
/// fifth one thick (the 5 m floor panels when `step` is 1 m).
///
/// `step` is 1 m unless that would draw more than [`MAX_GRID_LINES`] lines along the
/// floor's longer side; then it is the smallest of 2, 5, 10, 20, 50, 100 ... m that draws
/// no more, so a 4 km floor gets a line every 50 m (a thick one every 250 m) and the
/// picture is not dominated by grid lines. Line widths grow with the step (1 % and 3 % of
/// it), so the grid looks the same at every size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct MetreGrid {
    /// Metres between two lines.
    pub step: f64,
}

impl MetreGrid {
    /// The grid for a floor of `size` (x, y) metres.
    pub fn for_floor(size: [f64; 2]) -> Self {
        let extent = size[0].max(size[1]);
        let mut step = 1.0;
        for next in [2.0, 2.5, 2.0].into_iter().cycle() {
            if extent / step <= MAX_GRID_LINES {
                break;
            }
            step *= next;
        }
        Self { step }
    }

    /// The lines across an axis `extent` metres long, centred on 0: (position, width).
    pub fn lines(&self, extent: f64) -> impl Iterator<Item = (f64, f64)> + use<> {
        let step = self.step;
        let n = (extent / 2.0 / step).floor() as i64;
        (-n..=n).map(move |k| {
            let width = if k % 5 == 0 { 0.03 } else { 0.01 } * step;
            (k as f64 * step, width)
        })
    }
}

/// A scale bar in the south-west corner of the floor: a white bar of a round number of
/// metres (about a fifth of the floor), outlined in black, labelled with stroked
/// seven-segment digits so the label needs no font.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct ScaleBar {
    /// Floor x of the bar's west end.
    pub x: f64,
    /// Floor y of the bar's south edge.
    pub y: f64,
    /// Length, metres.
    pub length: f64,
    /// Height of the bar (a tenth of its length), metres.
    pub unit: f64,
}

impl ScaleBar {
    /// The bar for a floor of `size` (x, y) metres.
    #[cfg(test)]
    pub fn for_floor(size: [f64; 2]) -> Self {
        let [fx, fy] = size;
        Self::for_window([-fx / 2.0, -fy / 2.0, fx / 2.0, fy / 2.0])
    }

    /// The bar in the south-west corner of a picture of the floor's `[x0, y0, x1, y1]`.
    pub fn for_window([x0, y0, x1, _]: [f64; 4]) -> Self {
        let width = x1 - x0;
        // At least a metre (the label writes whole metres), even on a picture under 5 m.
        let length = [
            1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0, 2000.0,
        ]
        .into_iter()
        .take_while(|&l| l <= width / 5.0)
        .last()
        .unwrap_or(1.0);
        let unit = length / 10.0;
        Self {
            x: x0 + unit,
            y: y0 + unit,
            length,
            unit,
        }
    }

    /// The height of the strip the bar and its label fill, a unit's margin on both sides:
    /// below the maze in a cropped picture, the bar covers none of it.
    pub fn strip(&self) -> f64 {
        // the label's glyphs are two units high, above the bar's margin
        4.0 * self.unit
    }

    /// Width of the bar's outline.
    pub fn outline_width(&self) -> f64 {
        self.unit / 5.0
    }

    /// Width of the label's strokes (round caps).
    pub fn label_width(&self) -> f64 {
        self.unit / 3.0
    }

    /// The label's strokes, `[x0, y0, x1, y1]` on the floor: "2m" after the bar.
    pub fn label_strokes(&self) -> Vec<[f64; 4]> {
        let label = format!("{}m", self.length as u64);
        let glyph_height = self.unit * 2.0;
        let mut x = self.x + self.length + self.unit;
        let mut strokes = Vec::new();
        for ch in label.chars() {
            for (ax, ay, bx, by) in glyph_strokes(ch) {
                strokes.push([
                    x + ax * glyph_height / 2.0,
                    self.y + ay * glyph_height,
                    x + bx * glyph_height / 2.0,
                    self.y + by * glyph_height,
                ]);
            }
            x += glyph_height * 0.75;
        }
        strokes
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_metre_grid_thins_out_on_huge_floors() {
        assert_eq!(MetreGrid::for_floor([10.0, 10.0]).step, 1.0);
        assert_eq!(MetreGrid::for_floor([200.0, 15.0]).step, 1.0);
        assert_eq!(MetreGrid::for_floor([15.0, 201.0]).step, 2.0);
        let huge = MetreGrid::for_floor([4100.0, 4100.0]);
        assert_eq!(huge.step, 50.0);
        let lines: Vec<_> = huge.lines(4100.0).collect();
        assert_eq!(lines.len(), 83);
        assert_eq!(lines[41], (0.0, 1.5));
        assert_eq!(lines[42], (50.0, 0.5));
        assert_eq!(MetreGrid::for_floor([10_000.0, 1.0]).step, 50.0);
        assert_eq!(Colour([0, 0xff, 0x0a]).to_string(), "#00ff0a");
    }

    #[test]
    fn the_scale_bar_is_labelled() {
        let bar = ScaleBar::for_floor([10.0, 10.0]);
        assert_eq!((bar.length, bar.x, bar.y), (2.0, -4.8, -4.8));
        // "2" has five segments, "m" four strokes.
        assert_eq!(bar.label_strokes().len(), 9);
        assert_eq!(glyph_strokes('1').len(), 2);
        assert_eq!(glyph_strokes('0').len(), 6);
    }
}
