//! A maze as a ROS `map_server` occupancy map (ROS 1 `map_server`, ROS 2 nav2's
//! `nav2_map_server`): a YAML file naming a binary PGM image, its resolution (metres a
//! pixel) and the pose of its lower-left pixel's corner (`origin`) in the map frame, which is
//! the floor frame (the floor centred on 0, 0).
//!
//! With `negate: 0` a pixel's occupancy is `(255 - value) / 255`; `mode: trinary` makes it
//! occupied above `occupied_thresh`, free below `free_thresh`, unknown between. The image
//! holds only [`OCCUPIED`] (0) and [`FREE`] (254, what `map_saver` writes), so every pixel
//! is one or the other. The image's first row is the map's north edge.
//!
//! A wall maze's walls and posts are occupied on free floor: a pixel is occupied when the
//! wall overlaps it at all, so a wall thinner than a pixel leaves no gap. A line maze's lines
//! are free on occupied ground (the robot may drive on them only): a pixel is free when its
//! centre is on a line; or, with [`Lines::Occupied`], the lines are the obstacles (a pixel
//! they overlap) on free floor. The markers are not drawn; the YAML's comments say where
//! Start and End are.

use crate::layout::{Layout, Style};
use crate::mesh::MeshMaze;
use crate::wording::{Message, Opt};

use super::solids::{Part, Slab, Solids, num};

/// The value of an occupied pixel: black.
pub const OCCUPIED: u8 = 0;
/// The value of a free pixel: 254, as `map_saver` writes free space.
pub const FREE: u8 = 254;
/// `occupied_thresh` of the YAML: [`OCCUPIED`] is above it.
pub const OCCUPIED_THRESH: f64 = 0.65;
/// `free_thresh` of the YAML: [`FREE`] is below it.
pub const FREE_THRESH: f64 = 0.25;
/// The file endings that choose a ROS map (the YAML; the PGM is written beside it).
pub const FILE_ENDINGS: [&str; 2] = [".yaml", ".yml"];
/// The most pixels of the image along either side.
pub const MAX_SIDE: u32 = 16384;
/// The coarsest default resolution, metres a pixel (nav2's usual 5 cm).
const COARSEST: f64 = 0.05;

/// What a line maze's lines are on the map.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Lines {
    /// Free lines on occupied ground: the robot may drive on the lines only.
    #[default]
    Free,
    /// Occupied lines on free ground.
    Occupied,
}

/// How the map is made.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Options {
    /// Pixels a metre [default: [`default_px_per_metre`]].
    pub px_per_metre: Option<f64>,
    /// What a line maze's lines are.
    pub lines: Lines,
}

/// The two files: the YAML (naming the image as it was given) and the PGM.
#[derive(Debug, Clone, PartialEq)]
pub struct RosMap {
    /// The YAML document.
    pub yaml: String,
    /// The binary PGM (P5) image.
    pub pgm: Vec<u8>,
    /// Its width and height, pixels.
    pub size: [u32; 2],
    /// Metres a pixel.
    pub resolution: f64,
}

/// The default scale: the thinnest thing drawn (a line's width, a wall's thickness, a
/// post's side) two pixels across, and at least 20 px a metre (5 cm a pixel).
pub fn default_px_per_metre(layout: &Layout) -> f64 {
    let thinnest = match layout.style {
        Style::Lines => layout.line.width,
        Style::Walls => [
            layout.wall.as_ref().map(|w| w.thickness),
            layout.post.as_ref().map(|p| p.size),
        ]
        .into_iter()
        .flatten()
        .fold(f64::INFINITY, f64::min),
    };
    1.0 / (thinnest / 2.0).min(COARSEST)
}

/// The map of a layout that passed [`crate::validate::checked`] (checked here), its image
/// named `image` in the YAML (the PGM's file name, beside the YAML).
pub fn map(layout: &Layout, options: &Options, image: &str) -> Result<RosMap, super::ExportError> {
    let maze = MeshMaze::try_from(layout)?;
    let px = options
        .px_per_metre
        .unwrap_or_else(|| default_px_per_metre(layout));
    if !(px.is_finite() && px > 0.0) {
        return Err(Message::opt(Opt::PxPerM)
            .and(format!(" must be a positive number, got {px}"))
            .into());
    }
    let resolution = 1.0 / px;
    let [fx, fy] = layout.floor.size;
    let side = |metres: f64| (metres * px - 1e-9).ceil().max(1.0);
    let (w, h) = (side(fx), side(fy));
    let fits = w <= f64::from(MAX_SIDE) && h <= f64::from(MAX_SIDE);
    if !fits {
        return Err(Message::text(format!(
            "a {fx} m x {fy} m floor at {px} px a metre is {w} x {h} px, more than {MAX_SIDE} a side: pass a smaller "
        ))
        .and_opt(Opt::PxPerM)
        .into());
    }
    let solids = Solids::new(layout, &maze);
    let raster = Raster {
        size: [w as u32, h as u32],
        origin: [-fx / 2.0, -fy / 2.0],
        resolution,
    };
    let ground = match (layout.style, options.lines) {
        (Style::Lines, Lines::Free) => OCCUPIED,
        _ => FREE,
    };
    let mut pixels = vec![ground; raster.size[0] as usize * raster.size[1] as usize];
    for slab in &solids.maze {
        let (value, grow) = match (slab.part, options.lines) {
            (Part::Line, Lines::Free) => (FREE, 0.0),
            _ => (OCCUPIED, resolution / 2.0),
        };
        raster.paint(&mut pixels, slab, grow, value);
    }
    let mut pgm = format!("P5\n{w} {h}\n255\n").into_bytes();
    pgm.extend_from_slice(&pixels);
    Ok(RosMap {
        yaml: yaml(&solids, &raster, image),
        pgm,
        size: raster.size,
        resolution,
    })
}

/// The image's grid on the floor.
struct Raster {
    /// Width and height, pixels.
    size: [u32; 2],
    /// The floor point of the lower-left pixel's lower-left corner.
    origin: [f64; 2],
    /// Metres a pixel.
    resolution: f64,
}

impl Raster {
    /// Sets to `value` every pixel whose centre lies in `slab`'s footprint grown by `grow`
    /// on every side (half a pixel: every pixel an axis-aligned box overlaps).
    fn paint(&self, pixels: &mut [u8], slab: &Slab, grow: f64, value: u8) {
        let [w, h] = self.size;
        let (sin, cos) = slab.yaw.sin_cos();
        let [hx, hy] = [slab.size[0] / 2.0 + grow, slab.size[1] / 2.0 + grow];
        let reach = [
            cos.abs() * hx + sin.abs() * hy,
            sin.abs() * hx + cos.abs() * hy,
        ];
        let [cx, cy] = [slab.centre[0], slab.centre[1]];
        // the columns and rows (from the south) whose centres may lie inside
        let span = |centre: f64, reach: f64, origin: f64, n: u32| {
            let first = ((centre - reach - origin) / self.resolution - 0.5)
                .floor()
                .max(0.0);
            let end = ((centre + reach - origin) / self.resolution - 0.5)
                .ceil()
                .min(f64::from(n) - 1.0)
                + 1.0;
            first as u32..end.max(first) as u32
        };
        for row in span(cy, reach[1], self.origin[1], h) {
            let y = self.origin[1] + (f64::from(row) + 0.5) * self.resolution - cy;
            for col in span(cx, reach[0], self.origin[0], w) {
                let x = self.origin[0] + (f64::from(col) + 0.5) * self.resolution - cx;
                let (along, across) = (x * cos + y * sin, -x * sin + y * cos);
                if along.abs() <= hx + 1e-12 && across.abs() <= hy + 1e-12 {
                    // the image's first row is the north edge
                    let at = (h - 1 - row) as usize * w as usize + col as usize;
                    pixels[at] = value;
                }
            }
        }
    }
}

/// `text` as a YAML double-quoted scalar, which every YAML parser reads back as `text`
/// whatever it holds (`: `, `#`, `[`, `{`, `*`, `&`, `!`, `%`, `@`, `|`, `>`, quotes, a
/// leading space, a line break): `"` and `\` escaped, and every character that is not
/// printable, or breaks a line, in YAML (C0 and C1 controls, DEL, U+2028 and U+2029, the
/// byte order mark, U+FFFE and U+FFFF) as an escape (`\n`, `\t`, `\x1B`, `\u2028`): YAML
/// 1.1 (PyYAML, yaml-cpp, which map_server uses) and 1.2 read them alike.
pub fn yaml_quoted(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 2);
    out.push('"');
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            '\0' => out.push_str("\\0"),
            c if c.is_control() => out.push_str(&format!("\\x{:02X}", u32::from(c))),
            '\u{2028}' | '\u{2029}' | '\u{feff}' | '\u{fffe}' | '\u{ffff}' => {
                out.push_str(&format!("\\u{:04X}", u32::from(c)))
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// The YAML document `map_server` loads; the image's file name is quoted
/// ([`yaml_quoted`]), so any name reads back as itself.
fn yaml(s: &Solids, raster: &Raster, image: &str) -> String {
    let image = yaml_quoted(image);
    let [ox, oy] = raster.origin;
    let at = |slab: &Slab| format!("({}, {})", num(slab.centre[0]), num(slab.centre[1]));
    format!(
        "# {}: a ROS map_server occupancy map; the map frame is the floor frame\n\
         # start {}, end {} (metres)\n\
         image: {image}\n\
         resolution: {}\n\
         origin: [{}, {}, 0]\n\
         negate: 0\n\
         occupied_thresh: {OCCUPIED_THRESH}\n\
         free_thresh: {FREE_THRESH}\n\
         mode: trinary\n",
        s.title,
        at(&s.start),
        at(&s.end),
        num(raster.resolution),
        num(ox),
        num(oy),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::Algorithm;
    use crate::layout::{GenerateSpec, build_layout};
    use crate::maze::Grid;

    /// A pixel of the PGM: column `col`, row `row` from the top.
    fn pixel(m: &RosMap, col: u32, row: u32) -> u8 {
        let header = format!("P5\n{} {}\n255\n", m.size[0], m.size[1]).len();
        m.pgm[header + (row * m.size[0] + col) as usize]
    }

    /// The pixel whose square holds floor point (x, y).
    fn at(m: &RosMap, layout: &Layout, x: f64, y: f64) -> u8 {
        let [fx, fy] = layout.floor.size;
        let col = ((x + fx / 2.0) / m.resolution).floor() as u32;
        let row_from_south = ((y + fy / 2.0) / m.resolution).floor() as u32;
        pixel(m, col, m.size[1] - 1 - row_from_south)
    }

    fn course_lines() -> Layout {
        build_layout(&GenerateSpec::course(
            Grid::new(9, 9).unwrap(),
            Algorithm::Dfs,
            42,
        ))
        .unwrap()
    }

    #[test]
    fn a_file_name_is_quoted_with_escapes_for_what_yaml_reads_otherwise() {
        assert_eq!(yaml_quoted("maze.pgm"), "\"maze.pgm\"");
        assert_eq!(
            yaml_quoted("a #b: [c] {d} *e &f !g %h @i |j >k"),
            "\"a #b: [c] {d} *e &f !g %h @i |j >k\""
        );
        assert_eq!(yaml_quoted(" 'q\"\\"), "\" 'q\\\"\\\\\"");
        assert_eq!(
            yaml_quoted("a\nb\r\t\0\u{1b}[31m\u{7f}\u{85}\u{2028}\u{feff}é"),
            "\"a\\nb\\r\\t\\0\\x1B[31m\\x7F\\x85\\u2028\\uFEFFé\""
        );
    }

    #[test]
    fn a_line_maze_is_free_lines_on_occupied_ground_south_row_last() {
        let layout = course_lines();
        let m = map(&layout, &Options::default(), "maze.pgm").unwrap();
        // 0.1 m lines two pixels across: 20 px a metre, 200 x 200 on the 10 m floor
        assert_eq!((m.size, m.resolution), ([200, 200], 0.05));
        assert!(m.pgm.starts_with(b"P5\n200 200\n255\n"));
        assert!(m.yaml.contains("\nimage: \"maze.pgm\"\nresolution: 0.05\norigin: [-5, -5, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.25\nmode: trinary\n"));
        // Start's cell centre lies on a line (the maze's first), a cell corner never does
        let start = &layout.start.pose;
        assert_eq!(at(&m, &layout, start.x + 0.01, start.y + 0.01), FREE);
        assert_eq!(at(&m, &layout, start.x + 0.5, start.y + 0.5), OCCUPIED);
        // the floor's south-west corner is the last row's first pixel, occupied ground
        assert_eq!(pixel(&m, 0, 199), OCCUPIED);
        let reverse = Options {
            lines: Lines::Occupied,
            ..Options::default()
        };
        let r = map(&layout, &reverse, "maze.pgm").unwrap();
        assert_eq!(at(&r, &layout, start.x + 0.01, start.y + 0.01), OCCUPIED);
        assert_eq!(at(&r, &layout, start.x + 0.5, start.y + 0.5), FREE);
    }

    #[test]
    fn a_wall_thinner_than_a_pixel_leaves_no_gap() {
        let layout = crate::layout::json::parse_layout(
            include_str!("../../../../mazes/dfs-micromouse-seed42.json"),
            "dfs-micromouse-seed42.json",
        )
        .unwrap();
        // at 20 px a metre the 12 mm walls are a fifth of a pixel: still occupied
        let coarse = Options {
            px_per_metre: Some(20.0),
            ..Options::default()
        };
        let m = map(&layout, &coarse, "m.pgm").unwrap();
        assert_eq!(m.size, [200, 200]);
        // the outer west wall at x = origin - half a cell, all along the maze
        let [ox, oy] = layout.grid.origin;
        let c = layout.grid.cell_size;
        let west = ox - c / 2.0;
        for k in 0..16 {
            let y = oy + f64::from(k) * c;
            assert_eq!(at(&m, &layout, west, y), OCCUPIED, "row {k}");
        }
        // a cell's centre is free floor
        assert_eq!(at(&m, &layout, ox, oy), FREE);
        // every value is occupied or free, so trinary leaves nothing unknown
        let header = "P5\n200 200\n255\n".len();
        assert!(m.pgm[header..].iter().all(|&v| v == FREE || v == OCCUPIED));
        // by default the walls are two pixels thick: 6 mm a pixel
        assert_eq!(default_px_per_metre(&layout).round(), 167.0);
    }

    #[test]
    fn the_values_read_as_the_thresholds_say() {
        // negate 0: occupancy = (255 - value) / 255
        let p = |v: u8| (255.0 - f64::from(v)) / 255.0;
        assert!(p(OCCUPIED) > OCCUPIED_THRESH);
        assert!(p(FREE) < FREE_THRESH);
    }

    #[test]
    fn a_map_too_large_names_the_option() {
        use crate::wording::Part;
        let layout = course_lines();
        let huge = Options {
            px_per_metre: Some(5000.0),
            ..Options::default()
        };
        let err = map(&layout, &huge, "m.pgm").unwrap_err();
        let crate::export::ExportError::Refused(message) = &err else {
            panic!("a worded message: {err}");
        };
        assert!(
            message.parts().ends_with(&[Part::Opt(Opt::PxPerM)]),
            "{err}"
        );
    }
}
