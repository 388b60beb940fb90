//! Top view of a scene: every shape as its (rotated) footprint in its colour, lowest first,
//! so a drawn maze can be looked at without CoppeliaSim (`vrep-maze render DUMP.json`), as
//! SVG, PNG (filled by the pixel-centre rule, as layouts' PNGs are) or text for a terminal.

use std::fmt::Write;

use nalgebra::Point3;

use super::object::ObjectType;
use super::scene::Scene;

/// A shape's footprint: world z (drawing order), colour, corners in the xy plane.
type Footprint = (f64, [u8; 3], [(f64, f64); 4]);

/// The shapes seen from above, lowest first, and the box around them.
struct View {
    /// Footprints, lowest first.
    shapes: Vec<Footprint>,
    /// min x, min y, max x, max y, metres (a 2 m square at the origin when there is nothing).
    bounds: [f64; 4],
}

impl View {
    /// The footprints of `scene`'s shapes with an area.
    fn of(scene: &Scene) -> View {
        let mut shapes: Vec<Footprint> = Vec::new();
        for o in scene
            .objects()
            .filter(|o| o.kind == ObjectType::Shape && o.size[0] > 0.0 && o.size[1] > 0.0)
        {
            let Ok(world) = scene.world(o.handle) else {
                continue;
            };
            let (hx, hy) = (o.size[0] / 2.0, o.size[1] / 2.0);
            let corners = [(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy)].map(|(x, y)| {
                let p = world * Point3::new(x, y, 0.0);
                (p.x, p.y)
            });
            shapes.push((world.translation.vector.z, o.colour, corners));
        }
        shapes.sort_by(|a, b| a.0.total_cmp(&b.0));
        let bounds = if shapes.is_empty() {
            [-1.0, -1.0, 1.0, 1.0]
        } else {
            shapes.iter().flat_map(|s| s.2).fold(
                [f64::MAX, f64::MAX, f64::MIN, f64::MIN],
                |[x0, y0, x1, y1], (x, y)| [x0.min(x), y0.min(y), x1.max(x), y1.max(y)],
            )
        };
        View { shapes, bounds }
    }

    /// Width and height of the box, metres (never 0).
    fn span(&self) -> (f64, f64) {
        let [x0, y0, x1, y1] = self.bounds;
        ((x1 - x0).max(1e-6), (y1 - y0).max(1e-6))
    }
}

/// `true` when (x, y) lies in the convex quadrilateral `q` (either winding), edges included.
fn inside(q: &[(f64, f64); 4], x: f64, y: f64) -> bool {
    let side = |k: usize| {
        let (ax, ay) = q[k];
        let (bx, by) = q[(k + 1) % 4];
        (bx - ax) * (y - ay) - (by - ay) * (x - ax)
    };
    let sides = [side(0), side(1), side(2), side(3)];
    sides.iter().all(|&s| s >= 0.0) || sides.iter().all(|&s| s <= 0.0)
}

/// SVG of the scene seen from above (+x right, +y up), `width` pixels wide.
pub fn scene_svg(scene: &Scene, width: f64) -> String {
    let view = View::of(scene);
    let [min_x, _, _, max_y] = view.bounds;
    let (span_x, span_y) = view.span();
    let scale = width / span_x;
    let height = span_y * scale;
    let mut out = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width:.0}\" height=\"{height:.0}\" viewBox=\"0 0 {width:.2} {height:.2}\">\n"
    );
    for (_, c, corners) in &view.shapes {
        let points: Vec<String> = corners
            .iter()
            .map(|(x, y)| format!("{:.2},{:.2}", (x - min_x) * scale, (max_y - y) * scale))
            .collect();
        let _ = writeln!(
            out,
            "  <polygon points=\"{}\" fill=\"rgb({},{},{})\"/>",
            points.join(" "),
            c[0],
            c[1],
            c[2]
        );
    }
    out.push_str("</svg>\n");
    out
}

/// PNG of the scene seen from above, `width` pixels wide (the height follows, at least 1):
/// a pixel takes the colour of the highest shape holding its centre, white where none does.
pub fn scene_png(scene: &Scene, width: u32) -> Result<Vec<u8>, png::EncodingError> {
    let view = View::of(scene);
    let [min_x, _, _, max_y] = view.bounds;
    let (span_x, span_y) = view.span();
    let width = width.max(1);
    let scale = f64::from(width) / span_x;
    let height = ((span_y * scale).round() as u32).max(1);
    let mut pixels = vec![255u8; width as usize * height as usize * 3];
    // each shape, lowest first, over the pixels of its box whose centre it holds
    for (_, colour, q) in &view.shapes {
        let xs = q.map(|(x, _)| (x - min_x) * scale);
        let ys = q.map(|(_, y)| (max_y - y) * scale);
        let range = |v: [f64; 4], n: u32| {
            let lo = v.iter().copied().fold(f64::MAX, f64::min).floor().max(0.0) as u32;
            let hi = (v.iter().copied().fold(f64::MIN, f64::max).ceil().max(0.0) as u32).min(n);
            lo..hi
        };
        for row in range(ys, height) {
            let y = max_y - (f64::from(row) + 0.5) / scale;
            for col in range(xs, width) {
                let x = min_x + (f64::from(col) + 0.5) / scale;
                if inside(q, x, y) {
                    let k = (row as usize * width as usize + col as usize) * 3;
                    pixels[k..k + 3].copy_from_slice(colour);
                }
            }
        }
    }
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(&pixels)?;
    writer.finish()?;
    Ok(out)
}

/// The scene seen from above as text, `columns` characters wide (a character twice as tall
/// as wide): `#` a line (pure green) or a wall or post (any other colour but the floor's),
/// `S` the start (pure blue), `E` the end (pure red), `.` the floor (grey), a space where
/// there is no shape. Each shape marks every character it reaches (sampled at half a
/// character, so a line narrower than a character shows); markers win over lines and walls,
/// and those over the floor.
pub fn scene_ascii(scene: &Scene, columns: u32) -> String {
    let view = View::of(scene);
    let [min_x, _, _, max_y] = view.bounds;
    let (span_x, span_y) = view.span();
    let columns = columns.max(1) as usize;
    let char_w = span_x / columns as f64;
    let rows = ((span_y / (2.0 * char_w)).round() as usize).max(1);
    let char_h = span_y / rows as f64;
    let mut grid: Vec<Option<(u8, char)>> = vec![None; rows * columns];
    let step = char_w.min(char_h) / 2.0;
    for (_, colour, q) in &view.shapes {
        let here = symbol(*colour);
        let (o, a, b) = (q[0], q[1], q[3]);
        let len = |p: (f64, f64)| ((p.0 - o.0).powi(2) + (p.1 - o.1).powi(2)).sqrt();
        let (nu, nv) = (
            (len(a) / step).ceil().max(1.0) as usize,
            (len(b) / step).ceil().max(1.0) as usize,
        );
        for i in 0..nu {
            let u = (i as f64 + 0.5) / nu as f64;
            for j in 0..nv {
                let v = (j as f64 + 0.5) / nv as f64;
                let x = o.0 + u * (a.0 - o.0) + v * (b.0 - o.0);
                let y = o.1 + u * (a.1 - o.1) + v * (b.1 - o.1);
                let col = (((x - min_x) / char_w) as usize).min(columns - 1);
                let row = (((max_y - y) / char_h) as usize).min(rows - 1);
                let cell = &mut grid[row * columns + col];
                if cell.is_none_or(|c| here.0 >= c.0) {
                    *cell = Some(here);
                }
            }
        }
    }
    let mut out = String::new();
    for row in grid.chunks(columns) {
        let line: String = row.iter().map(|c| c.map_or(' ', |c| c.1)).collect();
        out.push_str(line.trim_end());
        out.push('\n');
    }
    out
}

/// A colour's character and its precedence in a character cell (higher wins).
fn symbol(c: [u8; 3]) -> (u8, char) {
    match c {
        [0, 0, 255] => (3, 'S'),
        [255, 0, 0] => (3, 'E'),
        [128, 128, 128] => (0, '.'),
        _ => (2, '#'),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn course_scene_svg_has_every_shape_in_its_colour() {
        let svg = scene_svg(&Scene::course(), 400.0);
        assert_eq!(svg.matches("<polygon").count(), 4);
        assert!(
            svg.contains("rgb(0,255,0)")
                && svg.contains("rgb(0,0,255)")
                && svg.contains("rgb(255,0,0)")
        );
        // the floor (lowest) is drawn first
        assert!(svg.find("rgb(128,128,128)") < svg.find("rgb(0,255,0)"));
    }

    #[test]
    fn course_scene_png_shows_the_markers_and_the_line_over_the_floor() {
        let bytes = scene_png(&Scene::course(), 1000).unwrap();
        let mut reader = png::Decoder::new(std::io::Cursor::new(bytes))
            .read_info()
            .unwrap();
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buf).unwrap();
        // the 10 m floor, the markers and the line on it, 100 px a metre
        assert_eq!((info.width, info.height), (1000, 1000));
        let at = |x: f64, y: f64| {
            let (col, row) = ((x + 5.0) * 100.0, (5.0 - y) * 100.0);
            let k = (row as usize * 1000 + col as usize) * 3;
            [buf[k], buf[k + 1], buf[k + 2]]
        };
        assert_eq!(at(-4.0, -4.0), [0, 0, 255], "Start");
        assert_eq!(at(4.0, 4.0), [255, 0, 0], "End");
        assert_eq!(at(0.0, 0.0), [0, 255, 0], "Line");
        assert_eq!(at(0.0, 3.0), [128, 128, 128], "Floor");
    }

    #[test]
    fn course_scene_ascii_marks_start_end_and_floor() {
        let text = scene_ascii(&Scene::course(), 40);
        // the 10 m floor holds everything: 40 columns, half as many rows (a cell is 1:2)
        assert_eq!(text.lines().count(), 20, "{text}");
        assert!(text.lines().all(|l| l.chars().count() <= 40));
        assert!(
            text.contains('S') && text.contains('E') && text.contains('#'),
            "{text}"
        );
        assert!(text.contains("...."), "{text}");
        let at = |c: char| {
            let row = text.lines().position(|l| l.contains(c)).unwrap();
            (row, text.lines().nth(row).unwrap().find(c).unwrap())
        };
        let (s, e) = (at('S'), at('E'));
        assert!(e.0 < s.0 && s.1 < e.1, "end north-east of start:\n{text}");
    }
}
