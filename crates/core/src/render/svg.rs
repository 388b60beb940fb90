//! The floor as a top-down camera sees it: grey floor with a metre grid, pure green
//! lines (a wall maze: near-black walls over a light red goal region), pure blue start,
//! pure red end, and optionally the solution path.
//!
//! Written while it is drawn, through a buffer, never held whole: the lines are one
//! `<rect>` per run ([`Run`]), the walls one per wall run ([`WallRun`]), in a group placed
//! in the maze frame (`translate(origin) rotate(rotation)`), so each is an axis-aligned
//! rectangle with four short numbers, at any rotation.

use std::fmt;
use std::io::{self, BufWriter, Write};

use super::Result;
use crate::progress::Progress;

use super::figure::{
    END, FLOOR, GOAL, GRID, INK, LINE, MetreGrid, PAPER, SOLUTION, SOLUTION_OPACITY, START,
    ScaleBar, WALL,
};
use super::walls::Walls;
use super::{MazeView, RenderOptions, Renderer, trajectory};
use crate::layout::Layout;
use crate::layout::runs::{Run, WallRun, for_each_run, for_each_wall_run, post_rect};
use crate::maze::Cell;
use crate::score::Sample;

/// Pixels per metre of the picture's nominal size.
const SCALE: f64 = 40.0;

/// The SVG renderer.
#[derive(Debug, Clone, Copy, Default)]
pub struct Svg;

/// A number as SVG text: at most 4 decimals (a tenth of a millimetre), no trailing zeros,
/// never `-0`. It is written digit by digit without allocating: a 4096 x 4096 maze writes
/// tens of millions of them.
struct Num(f64);

/// `value` as SVG text (see [`Num`]).
fn num(value: f64) -> Num {
    Num(value)
}

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let scaled = (self.0 * 1e4).round();
        if !scaled.is_finite() || scaled.abs() >= 1e18 {
            // Not finite, or beyond i64: no checked layout has such a number.
            return write!(f, "{}", self.0);
        }
        let scaled = scaled as i64;
        let mut buf = [0u8; 24];
        let mut at = buf.len();
        let mut push = |digit: u8| {
            at -= 1;
            buf[at] = digit;
        };
        let mut whole = scaled.unsigned_abs();
        let mut fraction = whole % 10_000;
        whole /= 10_000;
        let mut decimals = 4;
        while decimals > 0 && fraction.is_multiple_of(10) {
            fraction /= 10;
            decimals -= 1;
        }
        if decimals > 0 {
            for _ in 0..decimals {
                push(b'0' + (fraction % 10) as u8);
                fraction /= 10;
            }
            push(b'.');
        }
        loop {
            push(b'0' + (whole % 10) as u8);
            whole /= 10;
            if whole == 0 {
                break;
            }
        }
        if scaled < 0 {
            push(b'-');
        }
        f.write_str(std::str::from_utf8(&buf[at..]).map_err(|_| fmt::Error)?)
    }
}

impl Renderer for Svg {
    /// Sets `progress` to the maze's rows and advances it a row at a time.
    fn render(
        &self,
        layout: &Layout,
        options: &RenderOptions,
        out: &mut dyn Write,
        progress: &dyn Progress,
    ) -> Result<()> {
        self.render_run(layout, options, &[], out, progress)
    }
}

impl Svg {
    /// [`Renderer::render`] with a robot's run (`trajectory`, floor frame) drawn over the
    /// maze, coloured by time; nothing more when it is empty.
    pub(super) fn render_run(
        &self,
        layout: &Layout,
        options: &RenderOptions,
        trajectory: &[Sample],
        out: &mut dyn Write,
        progress: &dyn Progress,
    ) -> Result<()> {
        let view = MazeView::of(layout, options)?;
        progress.set_length(u64::from(layout.grid.rows));
        let mut out = BufWriter::with_capacity(1 << 16, out);
        write_svg(&mut out, layout, &view, options, trajectory, progress)?;
        out.flush()?;
        Ok(())
    }
}

fn write_svg(
    out: &mut impl Write,
    layout: &Layout,
    view: &MazeView,
    options: &RenderOptions,
    trajectory: &[Sample],
    progress: &dyn Progress,
) -> io::Result<()> {
    let window = super::window(layout, options);
    let [fx, fy] = layout.floor.size;
    let [x0, y0, x1, y1] = window;
    let (wx, wy) = (x1 - x0, y1 - y0);
    let scale = options.scale.px_per_metre(wx, SCALE);
    writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" viewBox="{} {} {} {}">"#,
        num(wx * scale),
        num(wy * scale),
        num(x0),
        num(-y1),
        num(wx),
        num(wy)
    )?;
    writeln!(
        out,
        "<title>vrep-maze {}x{} {} seed {}</title>",
        layout.grid.columns, layout.grid.rows, layout.generator.algorithm, layout.generator.seed
    )?;
    // Floor y grows up, SVG y grows down: flip once for everything inside.
    out.write_all(b"<g transform=\"scale(1,-1)\">\n")?;
    writeln!(
        out,
        r#"<rect x="{}" y="{}" width="{}" height="{}" fill="{FLOOR}"/>"#,
        num(-fx / 2.0),
        num(-fy / 2.0),
        num(fx),
        num(fy)
    )?;
    metre_grid(out, layout.floor.size)?;
    let (c, w) = (layout.grid.cell_size, layout.line.width);
    let [ox, oy] = layout.grid.origin;
    // The maze frame: cell (i, j) is centred at (i c, j c).
    writeln!(
        out,
        r#"<g transform="translate({},{}) rotate({})">"#,
        num(ox),
        num(oy),
        num(layout.grid.rotation.to_degrees())
    )?;
    match &view.walls {
        None => {
            line_runs(out, view, c, w, progress)?;
            markers(out, view, c)?;
        }
        Some(walls) => {
            goal(out, &walls.goal, c)?;
            markers(out, view, c)?;
            wall_runs(out, view, walls, c, progress)?;
        }
    }
    solution(out, &view.solution, c, w)?;
    out.write_all(b"</g>\n")?;
    run_path(out, trajectory, layout.line.width * trajectory::WIDTH_SHARE)?;
    scale_bar(out, &ScaleBar::for_window(window))?;
    out.write_all(b"</g>\n</svg>\n")
}

/// A robot's run in the floor frame, one `<polyline>` per colour band; nothing when empty.
fn run_path(out: &mut impl Write, samples: &[Sample], width: f64) -> io::Result<()> {
    if samples.is_empty() {
        return Ok(());
    }
    writeln!(
        out,
        r#"<g fill="none" stroke-width="{}" stroke-linecap="round" stroke-linejoin="round">"#,
        num(width)
    )?;
    for (points, colour) in trajectory::bands(samples) {
        out.write_all(b"<polyline points=\"")?;
        for (k, [x, y]) in points.iter().enumerate() {
            let separator = if k == 0 { "" } else { " " };
            write!(out, "{separator}{},{}", num(*x), num(*y))?;
        }
        writeln!(out, r#"" stroke="{colour}"/>"#)?;
    }
    out.write_all(b"</g>\n")
}

/// The solution's cells as one polyline, `w / 2` wide (nothing when none is drawn).
fn solution(out: &mut impl Write, cells: &[Cell], c: f64, w: f64) -> io::Result<()> {
    if cells.is_empty() {
        return Ok(());
    }
    out.write_all(b"<polyline points=\"")?;
    for (k, cell) in cells.iter().enumerate() {
        let separator = if k == 0 { "" } else { " " };
        write!(
            out,
            "{separator}{},{}",
            num(f64::from(cell.x) * c),
            num(f64::from(cell.y) * c)
        )?;
    }
    writeln!(
        out,
        r#"" fill="none" stroke="{SOLUTION}" stroke-width="{}" stroke-linejoin="round" stroke-opacity="{}"/>"#,
        num(w / 2.0),
        num(SOLUTION_OPACITY)
    )
}

/// The green line runs, one `<rect>` each, advancing `progress` a maze row at a time.
fn line_runs(
    out: &mut impl Write,
    view: &MazeView,
    c: f64,
    w: f64,
    progress: &dyn Progress,
) -> io::Result<()> {
    writeln!(out, r#"<g fill="{LINE}">"#)?;
    for_each_run(
        &view.maze,
        |run: Run| rect(out, run.rect(c, w)),
        |_| progress.advance(1),
    )?;
    out.write_all(b"</g>\n")
}

/// The wall runs, one `<rect>` each, advancing `progress` a maze row at a time.
fn wall_runs(
    out: &mut impl Write,
    view: &MazeView,
    walls: &Walls,
    c: f64,
    progress: &dyn Progress,
) -> io::Result<()> {
    writeln!(out, r#"<g fill="{WALL}">"#)?;
    for_each_wall_run(
        &view.maze,
        &walls.open,
        |run: WallRun| rect(out, run.rect(c, walls.thickness)),
        |_| progress.advance(1),
    )?;
    if let Some(size) = walls.post {
        posts(out, view, c, size)?;
    }
    out.write_all(b"</g>\n")
}

/// The post at every lattice corner: one square tiled by a pattern of the cell's period
/// over the lattice, not one element per post (a 4096x4096 maze has 16.8 million).
fn posts(out: &mut impl Write, view: &MazeView, c: f64, size: f64) -> io::Result<()> {
    let grid = view.maze.grid();
    let [x0, y0, ..] = post_rect([0, 0], c, size);
    let [.., x1, y1] = post_rect([grid.width(), grid.height()], c, size);
    writeln!(
        out,
        r#"<pattern id="posts" patternUnits="userSpaceOnUse" x="{}" y="{}" width="{}" height="{}"><rect width="{}" height="{}"/></pattern>"#,
        num(x0),
        num(y0),
        num(c),
        num(c),
        num(size),
        num(size)
    )?;
    writeln!(
        out,
        r#"<rect fill="url(#posts)" x="{}" y="{}" width="{}" height="{}"/>"#,
        num(x0),
        num(y0),
        num(x1 - x0),
        num(y1 - y0)
    )
}

/// The goal region's tinted cells, if any.
fn goal(out: &mut impl Write, cells: &[Cell], c: f64) -> io::Result<()> {
    if cells.is_empty() {
        return Ok(());
    }
    writeln!(out, r#"<g fill="{GOAL}">"#)?;
    for cell in cells {
        rect(out, cell_rect(*cell, c))?;
    }
    out.write_all(b"</g>\n")
}

/// The start and end markers: whole cells in pure blue and pure red.
fn markers(out: &mut impl Write, view: &MazeView, c: f64) -> io::Result<()> {
    for (cell, colour) in [(view.start, START), (view.end, END)] {
        let [x0, y0, ..] = cell_rect(cell, c);
        writeln!(
            out,
            r#"<rect x="{}" y="{}" width="{}" height="{}" fill="{colour}"/>"#,
            num(x0),
            num(y0),
            num(c),
            num(c)
        )?;
    }
    Ok(())
}

/// The square of `cell` in the maze frame, `[x0, y0, x1, y1]`, for cells of side `c`.
fn cell_rect(cell: Cell, c: f64) -> [f64; 4] {
    let (x, y) = (f64::from(cell.x) * c, f64::from(cell.y) * c);
    [x - c / 2.0, y - c / 2.0, x + c / 2.0, y + c / 2.0]
}

/// A `<rect>` filled as its group says.
fn rect(out: &mut impl Write, [x0, y0, x1, y1]: [f64; 4]) -> io::Result<()> {
    writeln!(
        out,
        r#"<rect x="{}" y="{}" width="{}" height="{}"/>"#,
        num(x0),
        num(y0),
        num(x1 - x0),
        num(y1 - y0)
    )
}

/// The scale bar: a rectangle and one path of round-capped label strokes.
fn scale_bar(out: &mut impl Write, bar: &ScaleBar) -> io::Result<()> {
    writeln!(
        out,
        r#"<rect x="{}" y="{}" width="{}" height="{}" fill="{PAPER}" stroke="{INK}" stroke-width="{}"/>"#,
        num(bar.x),
        num(bar.y),
        num(bar.length),
        num(bar.unit),
        num(bar.outline_width())
    )?;
    out.write_all(b"<path d=\"")?;
    for [ax, ay, bx, by] in bar.label_strokes() {
        write!(out, "M{},{}L{},{}", num(ax), num(ay), num(bx), num(by))?;
    }
    writeln!(
        out,
        r#"" fill="none" stroke="{INK}" stroke-width="{}" stroke-linecap="round"/>"#,
        num(bar.label_width())
    )
}

/// The metre grid ([`MetreGrid`]) as `<line>`s across the whole floor.
fn metre_grid(out: &mut impl Write, size: [f64; 2]) -> io::Result<()> {
    writeln!(out, r#"<g stroke="{GRID}">"#)?;
    let grid = MetreGrid::for_floor(size);
    let [fx, fy] = size;
    for (vertical, extent, other) in [(true, fx, fy), (false, fy, fx)] {
        for (at, width) in grid.lines(extent) {
            let (x1, y1, x2, y2) = if vertical {
                (at, -other / 2.0, at, other / 2.0)
            } else {
                (-other / 2.0, at, other / 2.0, at)
            };
            writeln!(
                out,
                r#"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke-width="{}"/>"#,
                num(x1),
                num(y1),
                num(x2),
                num(y2),
                num(width)
            )?;
        }
    }
    out.write_all(b"</g>\n")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::Algorithm;
    use crate::layout::Side;
    use crate::layout::runs::tests::count_runs;
    use crate::layout::runs::tests::{count_wall_runs, wall_layout};
    use crate::layout::{GenerateSpec, build_layout};
    use crate::maze::Direction;
    use crate::maze::Grid;
    use crate::render::figure::Colour;

    fn svg_of(layout: &Layout, options: &RenderOptions) -> String {
        let mut bytes = Vec::new();
        Svg.render(layout, options, &mut bytes, &crate::progress::Silent)
            .unwrap();
        String::from_utf8(bytes).unwrap()
    }

    /// The elements of the green group.
    fn line_elements(svg: &str) -> &str {
        svg.split(&format!("<g fill=\"{LINE}\">"))
            .nth(1)
            .unwrap()
            .split("</g>")
            .next()
            .unwrap()
    }

    #[test]
    fn posts_are_one_pattern_over_the_lattice_in_the_wall_group() {
        let mut layout = wall_layout(6, 4, 3, 30.0, "none");
        let maze =
            crate::layout::passages::decode(Grid::new(6, 4).unwrap(), &layout.passages).unwrap();
        let bare = svg_of(&layout, &RenderOptions::default());
        assert!(!bare.contains("<pattern"));
        let options = crate::layout::walls::WallOptions {
            length: 0.8,
            posts: Some(0.2),
            ..Default::default()
        };
        crate::layout::walls::into_walls(&mut layout, &maze, &options, true).unwrap();
        let svg = svg_of(&layout, &RenderOptions::default());
        let walls = svg
            .split(&format!("<g fill=\"{WALL}\">"))
            .nth(1)
            .unwrap()
            .split("</g>")
            .next()
            .unwrap();
        // a 0.2 m square repeated every cell from the south-west corner's post...
        assert!(walls.contains(
            r#"<pattern id="posts" patternUnits="userSpaceOnUse" x="-0.6" y="-0.6" width="1" height="1"><rect width="0.2" height="0.2"/></pattern>"#
        ), "{walls}");
        // ...over the lattice, the north-east corner's post included: 7 x 5 posts
        assert!(
            walls.contains(
                r#"<rect fill="url(#posts)" x="-0.6" y="-0.6" width="6.2" height="4.2"/>"#
            ),
            "{walls}"
        );
        assert_eq!(layout.posts.len(), 7 * 5);
    }

    #[test]
    fn draws_one_rect_per_run_both_markers_and_the_solution() {
        let layout = build_layout(&GenerateSpec::course(
            Grid::new(9, 9).unwrap(),
            Algorithm::Prim,
            42,
        ))
        .unwrap();
        let svg = svg_of(
            &layout,
            &RenderOptions {
                solution: true,
                ..Default::default()
            },
        );
        assert!(svg.starts_with("<svg "));
        assert!(svg.ends_with("</svg>\n"));
        let view = MazeView::of(&layout, &RenderOptions::default()).unwrap();
        let lines = line_elements(&svg);
        assert_eq!(lines.matches("<rect").count(), count_runs(&view.maze));
        assert!(
            lines.contains(r#"<rect x="-0.05" y="-0.05" width="#),
            "{lines}"
        );
        assert!(svg.contains(r#"<g transform="translate(-4,-4) rotate(0)">"#));
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
        assert!(path.starts_with("0,0 "), "the solution starts at the start");
        assert!(svg.contains("fill=\"#ffffff\""), "a scale bar");
        // 11 metre lines each way on the 10 m floor.
        assert_eq!(svg.matches("<line ").count(), 22);
        assert!(!svg_of(&layout, &RenderOptions::default()).contains("<polyline"));
    }

    /// The `<rect>`s of the group filled with `colour`, as `[x0, y0, x1, y1]`.
    fn rects(svg: &str, colour: Colour) -> Vec<[f64; 4]> {
        let group = svg
            .split(&format!("<g fill=\"{colour}\">"))
            .nth(1)
            .unwrap()
            .split("</g>")
            .next()
            .unwrap();
        group
            .lines()
            .filter(|l| l.starts_with("<rect"))
            .map(|l| {
                let value = |name: &str| -> f64 {
                    l.split(&format!(" {name}=\""))
                        .nth(1)
                        .unwrap()
                        .split('"')
                        .next()
                        .unwrap()
                        .parse()
                        .unwrap()
                };
                let (x, y) = (value("x"), value("y"));
                [x, y, x + value("width"), y + value("height")]
            })
            .collect()
    }

    #[test]
    fn a_wall_maze_draws_one_rect_per_wall_run_and_none_across_a_passage() {
        let mut layout = wall_layout(8, 6, 5, 30.0, "start");
        layout.end.region = vec![layout.end.cell, [4, 3], [4, 4]];
        let svg = svg_of(
            &layout,
            &RenderOptions {
                solution: true,
                ..Default::default()
            },
        );
        assert!(svg.contains(r#" rotate(30)">"#), "the maze frame turns");
        assert!(
            !svg.contains(&format!("<g fill=\"{LINE}\">")),
            "no green lines"
        );
        let view = MazeView::of(&layout, &RenderOptions::default()).unwrap();
        let openings = &layout.wall.as_ref().unwrap().openings;
        let walls = rects(&svg, WALL);
        assert_eq!(walls.len(), count_wall_runs(&view.maze, openings));
        // every wall is 5 cm thick and whole cells long, on a lattice line
        for [x0, y0, x1, y1] in &walls {
            let (w, h) = (x1 - x0, y1 - y0);
            let (thin, long, at) = if w < h { (w, h, x0) } else { (h, w, y0) };
            assert!((thin - 0.05).abs() < 1e-9, "{w} x {h}");
            assert!(
                (long - long.round()).abs() < 1e-9 && long >= 1.0,
                "{w} x {h}"
            );
            assert!((at + 0.525 - (at + 0.525).round()).abs() < 1e-9, "{at}");
        }
        // no wall covers the middle of an open side: a passage or the opening
        let grid = view.maze.grid();
        let mut gaps: Vec<(f64, f64)> = view
            .maze
            .passages()
            .map(|(cell, dir)| {
                let (x, y) = (f64::from(cell.x), f64::from(cell.y));
                match dir {
                    Direction::East => (x + 0.5, y),
                    _ => (x, y + 0.5),
                }
            })
            .collect();
        assert_eq!(gaps.len(), view.maze.passage_count());
        assert_eq!(openings[0].side, Side::South);
        gaps.push((0.0, -0.5));
        for (x, y) in gaps {
            let across = walls
                .iter()
                .filter(|[x0, y0, x1, y1]| *x0 < x && x < *x1 && *y0 < y && y < *y1)
                .count();
            assert_eq!(across, 0, "a wall across the open side at ({x}, {y})");
        }
        // and every closed side's middle is under a wall
        let mut covered = 0;
        for index in 0..grid.cell_count() {
            let cell = grid.cell(index);
            for (dir, (dx, dy)) in [
                (Direction::East, (0.5, 0.0)),
                (Direction::North, (0.0, 0.5)),
            ] {
                if grid.step(cell, dir).is_none() || view.maze.is_open(index, dir) {
                    continue;
                }
                let (x, y) = (f64::from(cell.x) + dx, f64::from(cell.y) + dy);
                assert!(
                    walls
                        .iter()
                        .any(|[x0, y0, x1, y1]| *x0 < x && x < *x1 && *y0 < y && y < *y1),
                    "no wall at ({x}, {y})"
                );
                covered += 1;
            }
        }
        assert!(covered > 10, "{covered}");
        // the goal tint: the region but the end, under the markers and the walls
        assert_eq!(
            rects(&svg, GOAL),
            [[3.5, 2.5, 4.5, 3.5], [3.5, 3.5, 4.5, 4.5]]
        );
        let order: Vec<usize> = [GOAL.to_string(), START.to_string(), WALL.to_string()]
            .iter()
            .map(|colour| svg.find(&format!("fill=\"{colour}\"")).unwrap())
            .collect();
        assert!(order.is_sorted(), "{order:?}");
        assert_eq!(svg.matches("<polyline").count(), 1);
    }

    #[test]
    fn a_one_cell_maze_draws_no_line() {
        let layout = build_layout(&GenerateSpec::course(
            Grid::new(1, 1).unwrap(),
            Algorithm::Dfs,
            1,
        ))
        .unwrap();
        let svg = svg_of(
            &layout,
            &RenderOptions {
                solution: true,
                ..Default::default()
            },
        );
        assert_eq!(line_elements(&svg).matches('<').count(), 0);
    }

    #[test]
    fn numbers_have_at_most_four_decimals() {
        let text = |v: f64| num(v).to_string();
        assert_eq!(text(0.30000000000000004), "0.3");
        assert_eq!(text(-0.00001), "0");
        assert_eq!(text(-0.05), "-0.05");
        assert_eq!(text(4095.95), "4095.95");
        assert_eq!(text(12.0), "12");
        assert_eq!(text(0.00005), "0.0001");
        assert_eq!(text(-1234.56789), "-1234.5679");
        assert_eq!(text(90.00000250447816), "90");
        assert_eq!(text(f64::NAN), "NaN");
    }
}
