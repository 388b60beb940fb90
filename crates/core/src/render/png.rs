//! PNG pictures: the SVG's picture ([`super::figure`]) rasterized here, in horizontal
//! strips streamed through the PNG encoder, so memory holds one strip (about 8 MiB) and
//! the runs, never the image.
//!
//! Every shape is filled by the pixel-centre rule (a pixel takes the shape's colour when
//! its centre lies inside), without anti-aliasing: the colours stay pure where the
//! robot's camera (and a test) looks, and a pixel's colour depends only on its own
//! position, so strips join without seams. Lines, walls, markers, grid lines and the scale
//! bar's strokes are drawn at least one pixel wide, so a huge maze drawn at a few pixels per
//! metre stays visible (a 0.1 m line at 4 px/m is 0.4 px: it is drawn 1 px wide).

use std::io::{self, Write};
use std::ops::Range;

use super::Result;
use crate::progress::Progress;

use super::figure::{
    Colour, END, FLOOR, GOAL, GRID, INK, LINE, MetreGrid, PAPER, SOLUTION, SOLUTION_OPACITY, START,
    ScaleBar, WALL,
};
use super::{MazeView, RenderOptions, Renderer, trajectory};
use crate::layout::Layout;
use crate::layout::runs::{Run, WallRun, for_each_run, for_each_wall_run, post_rect};
use crate::maze::Cell;
use crate::score::Sample;
use crate::wording::{Message, Opt};

/// Pixels per metre when the floor is small enough: the course's 10 m floor is 800 x 800.
const PX_PER_METRE: f64 = 80.0;
/// The longest side of a PNG, pixels: a larger floor is drawn at a smaller scale (the
/// 4100 m floor of a 4096 x 4096 maze at 4 px/m, 4 px a cell). 16384 is the largest side
/// common viewers and GPUs still open.
const MAX_SIDE: f64 = 16384.0;
/// Pixel bytes in one strip: the image is drawn and encoded this much at a time.
const STRIP_BYTES: usize = 8 << 20;
/// Bytes of compressed data per PNG chunk (`IDAT`).
const IDAT_BYTES: usize = 1 << 20;
/// Corners closer than this (pixels) to an axis-aligned rectangle's are filled as that
/// rectangle: the microradian a layout stores a quarter turn to moves a 4 km maze's far
/// end by 1.3 mm, a hundredth of a pixel.
const ALIGNED: f64 = 1e-3;

/// The PNG renderer.
#[derive(Debug, Clone, Copy, Default)]
pub struct Png;

impl Renderer for Png {
    /// Sets `progress` to the image's pixel rows and advances it a strip at a time.
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

impl Png {
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
        let picture = Picture::of(layout, options, trajectory)?;
        let strip_rows = (STRIP_BYTES / (picture.width as usize * 3)).max(1);
        picture.encode(out, progress, strip_rows)
    }
}

/// A point in pixels: x right, y down, (0, 0) the image's top-left corner.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Px {
    x: f64,
    y: f64,
}

/// A convex quadrilateral in pixels, corners in order around it.
type Quad = [Px; 4];

/// A shape to fill.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Shape {
    /// A convex quadrilateral.
    Quad(Quad),
    /// A disc: centre and radius, pixels.
    Disc(Px, f64),
}

impl Shape {
    /// The pixel rows whose centres it can cover.
    fn rows(&self) -> Range<i64> {
        let (top, bottom) = match self {
            Shape::Quad(q) => q
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(t, b), p| {
                    (t.min(p.y), b.max(p.y))
                }),
            Shape::Disc(c, r) => (c.y - r, c.y + r),
        };
        centre_index(top)..centre_index(bottom)
    }

    /// Calls `span(row, columns)` for every row of `rows` it covers, with the columns
    /// (within `0..width`) whose pixel centres lie inside it.
    fn spans(&self, rows: Range<u32>, width: u32, mut span: impl FnMut(u32, Range<usize>)) {
        let own = self.rows();
        let first = own.start.max(i64::from(rows.start));
        let end = own.end.min(i64::from(rows.end));
        if first >= end {
            return;
        }
        let columns = |left: f64, right: f64| {
            let clamp = |x: f64| centre_index(x).clamp(0, i64::from(width)) as usize;
            clamp(left)..clamp(right)
        };
        match self {
            Shape::Quad(q) if aligned(q) => {
                let (left, right) = q
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, r), p| {
                        (l.min(p.x), r.max(p.x))
                    });
                let cols = columns(left, right);
                for row in first..end {
                    span(row as u32, cols.clone());
                }
            }
            Shape::Quad(q) => {
                for row in first..end {
                    let y = row as f64 + 0.5;
                    let (mut left, mut right) = (f64::INFINITY, f64::NEG_INFINITY);
                    for (a, b) in q.iter().zip(q.iter().cycle().skip(1)) {
                        if (a.y <= y) != (b.y <= y) {
                            let x = a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y);
                            left = left.min(x);
                            right = right.max(x);
                        }
                    }
                    if left < right {
                        span(row as u32, columns(left, right));
                    }
                }
            }
            Shape::Disc(c, r) => {
                for row in first..end {
                    let dy = row as f64 + 0.5 - c.y;
                    let half = (r * r - dy * dy).max(0.0).sqrt();
                    span(row as u32, columns(c.x - half, c.x + half));
                }
            }
        }
    }
}

/// The index of the first pixel whose centre is at or after `at` (pixels): pixel `k`'s
/// centre is `k + 0.5`, so `[a, b)` covers the centres of pixels
/// `centre_index(a)..centre_index(b)`.
fn centre_index(at: f64) -> i64 {
    (at - 0.5).ceil().clamp(-1e15, 1e15) as i64
}

/// `true` if the quad is an axis-aligned rectangle (within [`ALIGNED`]).
fn aligned(q: &Quad) -> bool {
    let near = |a: f64, b: f64| (a - b).abs() < ALIGNED;
    let upright = near(q[0].x, q[3].x) && near(q[1].x, q[2].x);
    let level = near(q[0].y, q[1].y) && near(q[3].y, q[2].y);
    let upright_turned = near(q[0].x, q[1].x) && near(q[3].x, q[2].x);
    let level_turned = near(q[0].y, q[3].y) && near(q[1].y, q[2].y);
    (upright && level) || (upright_turned && level_turned)
}

/// An affine map from metres (in some frame) to pixels.
#[derive(Debug, Clone, Copy)]
struct Affine {
    /// Pixel x = `xx` * x + `xy` * y + `x0`.
    xx: f64,
    xy: f64,
    x0: f64,
    /// Pixel y = `yx` * x + `yy` * y + `y0`.
    yx: f64,
    yy: f64,
    y0: f64,
}

impl Affine {
    fn apply(&self, x: f64, y: f64) -> Px {
        Px {
            x: self.xx * x + self.xy * y + self.x0,
            y: self.yx * x + self.yy * y + self.y0,
        }
    }

    /// The rectangle `[x0, y0, x1, y1]` as a quad.
    fn rect(&self, [x0, y0, x1, y1]: [f64; 4]) -> Shape {
        Shape::Quad([
            self.apply(x0, y0),
            self.apply(x1, y0),
            self.apply(x1, y1),
            self.apply(x0, y1),
        ])
    }

    /// The rectangle `width` wide around the segment `[ax, ay, bx, by]`, butt ends.
    fn bar(&self, [ax, ay, bx, by]: [f64; 4], width: f64) -> Shape {
        let length = (bx - ax).hypot(by - ay).max(f64::MIN_POSITIVE);
        let (nx, ny) = (
            -(by - ay) / length * width / 2.0,
            (bx - ax) / length * width / 2.0,
        );
        Shape::Quad([
            self.apply(ax + nx, ay + ny),
            self.apply(bx + nx, by + ny),
            self.apply(bx - nx, by - ny),
            self.apply(ax - nx, ay - ny),
        ])
    }
}

/// Everything the PNG shows, in pixels, with the green runs (or the walls) left in the
/// maze to be placed strip by strip.
struct Picture {
    width: u32,
    height: u32,
    /// Maze-frame metres to pixels.
    maze_frame: Affine,
    view: MazeView,
    cell_size: f64,
    /// Line width, or a wall maze's wall thickness, as drawn: at least a pixel.
    bar_width: f64,
    /// A wall maze's post side, metres (at least a pixel), if it has posts.
    post_width: Option<f64>,
    /// The metre grid, the start and end markers: drawn in every strip they touch.
    grid: Vec<Shape>,
    markers: [(Shape, Colour); 2],
    /// A wall maze's tinted goal cells.
    goal: Vec<Shape>,
    /// The solution path (bars and round joins), drawn at [`SOLUTION_OPACITY`].
    solution: Vec<Shape>,
    /// A robot's run (bars and round joins), coloured by time, drawn over everything but
    /// the scale bar.
    run: Vec<(Shape, Colour)>,
    /// The scale bar: shapes in painting order.
    scale_bar: Vec<(Shape, Colour)>,
}

/// Pixels per metre for a window `wx` by `wy` metres: as `options` ask, or
/// [`PX_PER_METRE`] at most so the longest side is at most [`MAX_SIDE`] pixels; refused
/// when the asked scale makes a side longer.
fn picture_scale(options: &RenderOptions, wx: f64, wy: f64) -> Result<f64> {
    let scale = options
        .scale
        .px_per_metre(wx, PX_PER_METRE.min(MAX_SIDE / wx.max(wy)));
    let too_big = wx.max(wy) * scale - 1e-6;
    let fits = too_big <= MAX_SIDE; // a NaN size is refused too
    if !fits {
        return Err(Message::text(format!(
            "the picture would be {} px on its longest side; a PNG is at most {MAX_SIDE} px (use a smaller ",
            too_big.ceil()
        ))
        .and_opt(Opt::PxPerM)
        .and(" or ")
        .and_opt(Opt::Width)
        .and(")")
        .into());
    }
    Ok(scale)
}

/// The metre grid over a floor of `[fx, fy]` metres, as bars in pixels (`floor` maps the
/// Floor frame to them), each at least `pixel` metres wide.
fn grid_shapes(floor: &Affine, [fx, fy]: [f64; 2], pixel: f64) -> Vec<Shape> {
    let visible = |metres: f64| metres.max(pixel);
    let grid_lines = MetreGrid::for_floor([fx, fy]);
    let mut grid = Vec::new();
    for (at, w) in grid_lines.lines(fx) {
        grid.push(floor.bar([at, -fy / 2.0, at, fy / 2.0], visible(w)));
    }
    for (at, w) in grid_lines.lines(fy) {
        grid.push(floor.bar([-fx / 2.0, at, fx / 2.0, at], visible(w)));
    }
    grid
}

/// A robot's run in pixels (`floor` maps the Floor frame to them, `scale` pixels a
/// metre): bars `run_width` metres wide with round joins, coloured by time.
fn run_shapes(
    floor: &Affine,
    trajectory: &[Sample],
    run_width: f64,
    scale: f64,
) -> Vec<(Shape, Colour)> {
    let mut run = Vec::new();
    for (points, colour) in trajectory::bands(trajectory) {
        for pair in points.windows(2) {
            let [[ax, ay], [bx, by]] = [pair[0], pair[1]];
            run.push((floor.bar([ax, ay, bx, by], run_width), colour));
        }
        for &[x, y] in &points {
            let disc = Shape::Disc(floor.apply(x, y), run_width / 2.0 * scale);
            run.push((disc, colour));
        }
    }
    run
}

/// The scale bar of `window` in pixels (`floor` maps the Floor frame to them, `scale`
/// pixels a metre): its outlined box and its label's strokes, in painting order.
fn scale_bar_shapes(floor: &Affine, window: [f64; 4], scale: f64) -> Vec<(Shape, Colour)> {
    let visible = |metres: f64| metres.max(1.0 / scale);
    let bar = ScaleBar::for_window(window);
    let outline = visible(bar.outline_width()) / 2.0;
    let (x1, y1) = (bar.x + bar.length, bar.y + bar.unit);
    let mut scale_bar = vec![
        (
            floor.rect([bar.x - outline, bar.y - outline, x1 + outline, y1 + outline]),
            INK,
        ),
        (
            floor.rect([bar.x + outline, bar.y + outline, x1 - outline, y1 - outline]),
            PAPER,
        ),
    ];
    let ink = visible(bar.label_width());
    for stroke in bar.label_strokes() {
        scale_bar.push((floor.bar(stroke, ink), INK));
        for end in [[stroke[0], stroke[1]], [stroke[2], stroke[3]]] {
            let centre = floor.apply(end[0], end[1]);
            scale_bar.push((Shape::Disc(centre, ink / 2.0 * scale), INK));
        }
    }
    scale_bar
}

impl Picture {
    /// The picture of `layout`: [`PX_PER_METRE`], or less so the longest side is at most
    /// [`MAX_SIDE`] pixels.
    fn of(layout: &Layout, options: &RenderOptions, trajectory: &[Sample]) -> Result<Self> {
        let view = MazeView::of(layout, options)?;
        let window = super::window(layout, options);
        let [wx0, wy0, wx1, wy1] = window;
        let (wx, wy) = (wx1 - wx0, wy1 - wy0);
        let scale = picture_scale(options, wx, wy)?;
        // The epsilon keeps an exact fit (16384.000000001) from adding a pixel.
        let side = |metres: f64| ((metres * scale - 1e-6).ceil().clamp(1.0, MAX_SIDE)) as u32;
        let (width, height) = (side(wx), side(wy));
        let floor = Affine {
            xx: scale,
            xy: 0.0,
            x0: -wx0 * scale,
            yx: 0.0,
            yy: -scale,
            y0: wy1 * scale,
        };
        let (sin, cos) = layout.grid.rotation.sin_cos();
        let origin = floor.apply(layout.grid.origin[0], layout.grid.origin[1]);
        let maze_frame = Affine {
            xx: scale * cos,
            xy: -scale * sin,
            x0: origin.x,
            yx: -scale * sin,
            yy: -scale * cos,
            y0: origin.y,
        };
        let pixel = 1.0 / scale;
        let visible = |metres: f64| metres.max(pixel);
        let grid = grid_shapes(&floor, layout.floor.size, pixel);
        let c = layout.grid.cell_size;
        let marker = |cell: Cell| {
            let half = visible(c) / 2.0;
            let (x, y) = (f64::from(cell.x) * c, f64::from(cell.y) * c);
            maze_frame.rect([x - half, y - half, x + half, y + half])
        };
        let markers = [(marker(view.start), START), (marker(view.end), END)];
        let goal = view
            .walls
            .iter()
            .flat_map(|walls| walls.goal.iter().map(|&cell| marker(cell)))
            .collect();
        let bar_width = visible(match &view.walls {
            Some(walls) => walls.thickness,
            None => layout.line.width,
        });
        let post_width = view.walls.as_ref().and_then(|w| w.post).map(visible);
        let solution = solution_shapes(&view.solution, c, visible(layout.line.width / 2.0))
            .into_iter()
            .map(|shape| match shape {
                Shape::Quad(q) => Shape::Quad(q.map(|p| maze_frame.apply(p.x, p.y))),
                Shape::Disc(p, r) => Shape::Disc(maze_frame.apply(p.x, p.y), r * scale),
            })
            .collect();
        let run = run_shapes(
            &floor,
            trajectory,
            visible(layout.line.width * trajectory::WIDTH_SHARE),
            scale,
        );
        let scale_bar = scale_bar_shapes(&floor, window, scale);
        Ok(Self {
            width,
            height,
            maze_frame,
            view,
            cell_size: c,
            bar_width,
            post_width,
            grid,
            markers,
            goal,
            solution,
            run,
            scale_bar,
        })
    }

    /// The picture of a line run.
    fn run_shape(&self, run: &Run) -> Shape {
        self.maze_frame
            .rect(run.rect(self.cell_size, self.bar_width))
    }

    /// The picture of a wall run.
    fn wall_shape(&self, run: &WallRun) -> Shape {
        self.maze_frame
            .rect(run.rect(self.cell_size, self.bar_width))
    }

    /// The picture of the post at lattice corner `corner`, `size` wide.
    fn post_shape(&self, corner: [u32; 2], size: f64) -> Shape {
        self.maze_frame
            .rect(post_rect(corner, self.cell_size, size))
    }

    /// The maze's own shapes (line runs, or wall runs, posts and goal cells), bucketed by
    /// strip.
    fn bars(&self, strips: usize, strip_rows: u32) -> Bars {
        match &self.view.walls {
            None => Bars::Lines(Buckets::new(
                strips,
                strip_rows,
                self.height,
                |emit| {
                    let Ok(()) = for_each_run::<std::convert::Infallible>(
                        &self.view.maze,
                        |run| {
                            emit(run);
                            Ok(())
                        },
                        |_| {},
                    );
                },
                |run| self.run_shape(run).rows(),
            )),
            Some(walls) => Bars::Walls {
                runs: Buckets::new(
                    strips,
                    strip_rows,
                    self.height,
                    |emit| {
                        let Ok(()) = for_each_wall_run::<std::convert::Infallible>(
                            &self.view.maze,
                            &walls.open,
                            |run| {
                                emit(run);
                                Ok(())
                            },
                            |_| {},
                        );
                    },
                    |run| self.wall_shape(run).rows(),
                ),
                posts: self.post_width.map(|size| {
                    let (columns, rows) = (
                        self.view.maze.grid().width(),
                        self.view.maze.grid().height(),
                    );
                    Buckets::new(
                        strips,
                        strip_rows,
                        self.height,
                        |emit| {
                            for j in 0..=rows {
                                for i in 0..=columns {
                                    emit([i, j]);
                                }
                            }
                        },
                        |&corner| self.post_shape(corner, size).rows(),
                    )
                }),
                goal: Buckets::new(
                    strips,
                    strip_rows,
                    self.height,
                    |emit| self.goal.iter().copied().for_each(&mut *emit),
                    Shape::rows,
                ),
            },
        }
    }

    /// Paints the maze itself into `strip` (strip `k`): the green runs then the markers
    /// over them, or the goal tint, the markers (whole cells) and the walls over them.
    fn paint_maze(&self, strip: &mut Strip, k: usize, bars: &mut Bars) {
        let top = strip.rows.start;
        let markers = |strip: &mut Strip| {
            for (shape, colour) in &self.markers {
                strip.paint(shape, *colour);
            }
        };
        match bars {
            Bars::Lines(runs) => {
                runs.visit(
                    k,
                    top,
                    |run| self.run_shape(run).rows(),
                    |run| {
                        strip.paint(&self.run_shape(run), LINE);
                    },
                );
                markers(strip);
            }
            Bars::Walls { runs, posts, goal } => {
                goal.visit(k, top, Shape::rows, |shape| strip.paint(shape, GOAL));
                markers(strip);
                runs.visit(
                    k,
                    top,
                    |run| self.wall_shape(run).rows(),
                    |run| {
                        strip.paint(&self.wall_shape(run), WALL);
                    },
                );
                if let (Some(posts), Some(size)) = (posts, self.post_width) {
                    posts.visit(
                        k,
                        top,
                        |&corner| self.post_shape(corner, size).rows(),
                        |&corner| {
                            strip.paint(&self.post_shape(corner, size), WALL);
                        },
                    );
                }
            }
        }
    }

    /// Draws the picture `strip_rows` pixel rows at a time and streams it into `out` as a
    /// PNG.
    fn encode(
        &self,
        out: &mut dyn Write,
        progress: &dyn Progress,
        strip_rows: usize,
    ) -> Result<()> {
        progress.set_length(u64::from(self.height));
        let strip_rows = strip_rows.clamp(1, self.height as usize) as u32;
        let strips = self.height.div_ceil(strip_rows) as usize;
        let mut bars = self.bars(strips, strip_rows);
        let mut solution = Buckets::new(
            strips,
            strip_rows,
            self.height,
            |emit| self.solution.iter().copied().for_each(&mut *emit),
            Shape::rows,
        );

        let mut encoder = png::Encoder::new(out, self.width, self.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::Fast);
        let mut header = encoder.write_header().map_err(io::Error::from)?;
        let mut writer = header
            .stream_writer_with_size(IDAT_BYTES)
            .map_err(io::Error::from)?;

        let width = self.width as usize;
        let mut pixels = vec![0u8; width * 3 * strip_rows as usize];
        let mut mask = Vec::new();
        for k in 0..strips {
            let top = k as u32 * strip_rows;
            let bottom = (top + strip_rows).min(self.height);
            let mut strip = Strip {
                pixels: &mut pixels[..(bottom - top) as usize * width * 3],
                rows: top..bottom,
                width: self.width,
            };
            // The floor, then everything on it in the SVG's order.
            strip.pixels.fill(FLOOR.0[0]);
            debug_assert!(FLOOR.0.iter().all(|&b| b == FLOOR.0[0]));
            for shape in &self.grid {
                strip.paint(shape, GRID);
            }
            self.paint_maze(&mut strip, k, &mut bars);
            mask.clear();
            mask.resize(strip.pixels.len() / 3, false);
            let mut any = false;
            solution.visit(k, top, Shape::rows, |shape| {
                any = true;
                strip.mark(shape, &mut mask);
            });
            if any {
                strip.blend(&mask, SOLUTION, SOLUTION_OPACITY);
            }
            for (shape, colour) in &self.run {
                strip.paint(shape, *colour);
            }
            for (shape, colour) in &self.scale_bar {
                strip.paint(shape, *colour);
            }
            writer.write_all(strip.pixels)?;
            progress.advance(u64::from(bottom - top));
        }
        writer.finish().map_err(io::Error::from)?;
        header.finish().map_err(io::Error::from)?;
        Ok(())
    }
}

/// The maze's own shapes, bucketed by the strip they start in.
enum Bars {
    /// A line maze's green runs.
    Lines(Buckets<Run>),
    /// A wall maze's walls, its posts (if any) and its tinted goal cells.
    Walls {
        runs: Buckets<WallRun>,
        posts: Option<Buckets<[u32; 2]>>,
        goal: Buckets<Shape>,
    },
}

/// Some pixel rows of the image, RGB.
struct Strip<'a> {
    pixels: &'a mut [u8],
    /// The image rows these are.
    rows: Range<u32>,
    /// Pixels in a row.
    width: u32,
}

impl Strip<'_> {
    /// Calls `pixels(span)` with the indices (pixels from the strip's start) of every
    /// horizontal span of `shape` in this strip.
    fn spans(rows: &Range<u32>, width: u32, shape: &Shape, mut pixels: impl FnMut(Range<usize>)) {
        let top = rows.start;
        shape.spans(rows.clone(), width, |row, columns| {
            let at = (row - top) as usize * width as usize;
            pixels(at + columns.start..at + columns.end);
        });
    }

    /// Fills `shape` with `colour`.
    fn paint(&mut self, shape: &Shape, colour: Colour) {
        let pixels = &mut *self.pixels;
        Self::spans(&self.rows, self.width, shape, |span| {
            for pixel in pixels[span.start * 3..span.end * 3].chunks_exact_mut(3) {
                pixel.copy_from_slice(&colour.0);
            }
        });
    }

    /// Sets `mask` (one flag per pixel of the strip) where `shape` lies.
    fn mark(&self, shape: &Shape, mask: &mut [bool]) {
        Self::spans(&self.rows, self.width, shape, |span| mask[span].fill(true));
    }

    /// Paints `colour` at `opacity` over the pixels `mask` marks, each once.
    fn blend(&mut self, mask: &[bool], colour: Colour, opacity: f64) {
        let marked = self
            .pixels
            .chunks_exact_mut(3)
            .zip(mask)
            .filter(|(_, m)| **m);
        for (pixel, _) in marked {
            for (channel, over) in pixel.iter_mut().zip(colour.0) {
                let mixed = opacity * f64::from(over) + (1.0 - opacity) * f64::from(*channel);
                *channel = mixed.round() as u8;
            }
        }
    }
}

/// The solution path through the cell centres `path` (cells `cell` metres apart), in the
/// maze frame, `width` wide: one bar per straight stretch, butt ends, a disc at every turn
/// (the SVG's round joins).
fn solution_shapes(path: &[Cell], cell: f64, width: f64) -> Vec<Shape> {
    let centre = |c: &Cell| Px {
        x: f64::from(c.x) * cell,
        y: f64::from(c.y) * cell,
    };
    let identity = Affine {
        xx: 1.0,
        xy: 0.0,
        x0: 0.0,
        yx: 0.0,
        yy: 1.0,
        y0: 0.0,
    };
    let mut shapes = Vec::new();
    let mut from = 0;
    for k in 1..path.len() {
        let turns = path.get(k + 1).is_some_and(|next| {
            let (a, b) = (&path[k - 1], &path[k]);
            (b.x != a.x) != (next.x != b.x)
        });
        if turns || k + 1 == path.len() {
            let (a, b) = (centre(&path[from]), centre(&path[k]));
            shapes.push(identity.bar([a.x, a.y, b.x, b.y], width));
            if turns {
                shapes.push(Shape::Disc(b, width / 2.0));
            }
            from = k;
        }
    }
    shapes
}

/// Items sorted by the strip their first pixel row falls in, and those still being
/// drawn: each item is looked at once per strip it touches, so drawing costs
/// O(items + pixels), not O(strips x items).
struct Buckets<T> {
    /// Strip `k`'s items are `items[starts[k]..starts[k + 1]]`.
    items: Vec<T>,
    starts: Vec<usize>,
    /// Items from earlier strips, with the pixel row they end before.
    active: Vec<(T, i64)>,
}

impl<T: Copy> Buckets<T> {
    /// Buckets the items `produce` emits (it is called twice: to count, then to place)
    /// whose `rows` meet the image's `0..height`, in strips of `strip_rows`.
    fn new(
        strips: usize,
        strip_rows: u32,
        height: u32,
        produce: impl Fn(&mut dyn FnMut(T)),
        rows: impl Fn(&T) -> Range<i64>,
    ) -> Self {
        let strip_of = |item: &T| {
            let r = rows(item);
            let first = r.start.max(0);
            (first < r.end && first < i64::from(height))
                .then(|| (first / i64::from(strip_rows)) as usize)
        };
        let mut starts = vec![0usize; strips + 1];
        let mut filler = None;
        produce(&mut |item| {
            if let Some(k) = strip_of(&item) {
                starts[k + 1] += 1;
                filler.get_or_insert(item);
            }
        });
        for k in 0..strips {
            starts[k + 1] += starts[k];
        }
        let mut items = filler.map_or_else(Vec::new, |f| vec![f; starts[strips]]);
        let mut next = starts.clone();
        produce(&mut |item| {
            if let Some(k) = strip_of(&item) {
                items[next[k]] = item;
                next[k] += 1;
            }
        });
        Self {
            items,
            starts,
            active: Vec::new(),
        }
    }

    /// Calls `draw` for every item that may touch strip `k` (starting at pixel row `top`).
    /// Strips must be visited in order.
    fn visit(
        &mut self,
        k: usize,
        top: u32,
        rows: impl Fn(&T) -> Range<i64>,
        mut draw: impl FnMut(&T),
    ) {
        self.active.retain(|(_, end)| *end > i64::from(top));
        for item in &self.items[self.starts[k]..self.starts[k + 1]] {
            self.active.push((*item, rows(item).end));
        }
        for (item, _) in &self.active {
            draw(item);
        }
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use nalgebra::{Isometry2, Point2, Vector2};

    use super::*;
    use crate::generate::Algorithm;
    use crate::layout::runs::tests::wall_layout;
    use crate::layout::walls::{WallAxis, WallOptions, into_walls, is_closed, lattice};
    use crate::layout::{GenerateSpec, build_layout};
    use crate::maze::{Direction, Grid};

    /// A decoded PNG: width, height and RGB pixels.
    struct Image {
        width: u32,
        height: u32,
        rgb: Vec<u8>,
    }

    impl Image {
        fn pixel(&self, x: u32, y: u32) -> (u8, u8, u8) {
            let at = (y * self.width + x) as usize * 3;
            (self.rgb[at], self.rgb[at + 1], self.rgb[at + 2])
        }
    }

    fn encode(layout: &Layout, options: &RenderOptions, strip_rows: usize) -> Vec<u8> {
        let mut bytes = Vec::new();
        Picture::of(layout, options, &[])
            .unwrap()
            .encode(&mut bytes, &crate::progress::Silent, strip_rows)
            .unwrap();
        bytes
    }

    fn decode(bytes: &[u8]) -> Image {
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
        let mut reader = png::Decoder::new(io::Cursor::new(bytes))
            .read_info()
            .unwrap();
        let mut rgb = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut rgb).unwrap();
        assert_eq!(info.color_type, png::ColorType::Rgb);
        Image {
            width: info.width,
            height: info.height,
            rgb,
        }
    }

    #[test]
    fn a_run_is_painted_over_the_maze_in_its_time_colours() {
        // the 3 x 1 course corridor, driven from Start (floor x = -1) to End (x = 1)
        let layout = build_layout(&GenerateSpec::course(
            Grid::new(3, 1).unwrap(),
            Algorithm::Dfs,
            1,
        ))
        .unwrap();
        let run: Vec<Sample> = (0..=20)
            .map(|k| Sample {
                t: f64::from(k),
                x: -1.0 + f64::from(k) * 0.1,
                y: 0.0,
                yaw: 0.0,
            })
            .collect();
        let mut bytes = Vec::new();
        Png.render_run(
            &layout,
            &RenderOptions::default(),
            &run,
            &mut bytes,
            &crate::progress::Silent,
        )
        .unwrap();
        let image = decode(&bytes);
        let bands = trajectory::bands(&run);
        let (first, last) = (bands[0].1.0, bands.last().unwrap().1.0);
        let rgb = |c: [u8; 3]| (c[0], c[1], c[2]);
        // over the blue Start, the start of the run; over the red End, its end
        assert_eq!(at(&image, &layout, -0.99, 0.0), rgb(first));
        assert_eq!(at(&image, &layout, 0.99, 0.0), rgb(last));
        // beside the path, the markers are as they were
        assert_eq!(at(&image, &layout, 1.0, 0.3), rgb(END.0));
    }

    fn render(layout: &Layout, options: &RenderOptions) -> Image {
        let mut bytes = Vec::new();
        Png.render(layout, options, &mut bytes, &crate::progress::Silent)
            .unwrap();
        decode(&bytes)
    }

    /// The colour at floor point (x, y), at 80 px/m.
    fn at(image: &Image, layout: &Layout, x: f64, y: f64) -> (u8, u8, u8) {
        let [fx, fy] = layout.floor.size;
        let px = ((x + fx / 2.0) * 80.0) as u32;
        let py = ((fy / 2.0 - y) * 80.0) as u32;
        image.pixel(px, py)
    }

    fn course(size: u32, algorithm: Algorithm, rotation_degrees: f64) -> Layout {
        let mut spec =
            GenerateSpec::course(Grid::new(size.into(), size.into()).unwrap(), algorithm, 42);
        spec.geometry.rotation = rotation_degrees.to_radians();
        build_layout(&spec).unwrap()
    }

    /// With `--crop`, the scale bar (black outline, white bar, black label) has a strip of
    /// its own below the maze: no pixel over the maze's bounding box is the bar's, and the
    /// strip holds it. Checked on the micromouse walls (whose Start is the south-west cell
    /// the bar used to cover) and the course's lines.
    #[test]
    fn a_cropped_picture_s_scale_bar_covers_nothing_of_the_maze() {
        let micromouse = crate::layout::json::parse_layout(
            include_str!("../../../../mazes/dfs-micromouse-seed42.json"),
            "dfs-micromouse-seed42.json",
        )
        .unwrap();
        // the mazes' heights: 16 cells of 0.18 m and 0.012 m walls; 9 of 1 m and 0.1 m lines
        for (layout, height) in [(micromouse, 2.892), (course(9, Algorithm::Dfs, 0.0), 9.1)] {
            let options = RenderOptions {
                crop: true,
                solution: true,
                ..Default::default()
            };
            let image = render(&layout, &options);
            // the maze's rows at the top (80 px a metre), the strip's below
            let maze_rows = (height * 80.0_f64).floor() as u32;
            let is_bar = |p: (u8, u8, u8)| p == (0, 0, 0) || p == (255, 255, 255);
            let covered = (0..maze_rows)
                .flat_map(|y| (0..image.width).map(move |x| (x, y)))
                .filter(|&(x, y)| is_bar(image.pixel(x, y)))
                .count();
            assert_eq!(covered, 0, "{}", layout.generator.algorithm);
            let in_strip = (maze_rows..image.height)
                .flat_map(|y| (0..image.width).map(move |x| (x, y)))
                .filter(|&(x, y)| is_bar(image.pixel(x, y)))
                .count();
            assert!(in_strip > 100, "the bar is drawn in its strip: {in_strip}");
        }
    }

    #[test]
    fn the_png_shows_the_pure_colours_and_the_solution() {
        let layout = course(9, Algorithm::Dfs, 0.0);
        let image = render(
            &layout,
            &RenderOptions {
                solution: true,
                ..Default::default()
            },
        );
        assert_eq!((image.width, image.height), (800, 800));
        let pixel = |x: f64, y: f64| at(&image, &layout, x, y);
        let start = &layout.start.pose;
        assert_eq!(pixel(start.x + 0.3, start.y + 0.3), (0, 0, 255));
        let end = &layout.end.pose;
        assert_eq!(pixel(end.x + 0.3, end.y - 0.3), (255, 0, 0));
        // Cell corners lie off every line and metre line.
        assert_eq!(pixel(0.5, 0.5), (180, 180, 180));
        let view = MazeView::of(
            &layout,
            &RenderOptions {
                solution: true,
                ..Default::default()
            },
        )
        .unwrap();
        let [ox, oy] = layout.grid.origin;
        let off_path = view
            .maze
            .passages()
            .find(|&(cell, dir)| {
                let far = |c: Cell| c.x.abs_diff(cell.x) > 1 || c.y.abs_diff(cell.y) > 1;
                dir == Direction::East
                    && !view.solution.contains(&cell)
                    && far(view.start)
                    && far(view.end)
            })
            .unwrap()
            .0;
        let (x, y) = (ox + f64::from(off_path.x) + 0.5, oy + f64::from(off_path.y));
        assert_eq!(pixel(x, y), (0, 255, 0));
        // Opaque orange over green: its red exceeds its green by half the range, where a
        // line's green exceeds its red by all of it (orange at 0.8 was olive, 204, 183, 0)
        let on_path = view.solution[view.solution.len() / 2];
        let (x, y) = (ox + f64::from(on_path.x), oy + f64::from(on_path.y));
        let (r, g, b) = pixel(x, y);
        assert_eq!((r, g, b), (255, 128, 0));
        assert!(i32::from(r) - i32::from(g) >= 100, "{:?}", (r, g, b));
    }

    #[test]
    fn a_rotated_maze_is_drawn_where_the_geometry_says() {
        for degrees in [30.0, 90.0] {
            let layout = course(9, Algorithm::Prim, degrees);
            let image = render(&layout, &RenderOptions::default());
            let view = MazeView::of(&layout, &RenderOptions::default()).unwrap();
            let grid = view.maze.grid();
            let [ox, oy] = layout.grid.origin;
            let to_floor = Isometry2::new(Vector2::new(ox, oy), layout.grid.rotation);
            let bar = ScaleBar::for_floor(layout.floor.size);
            let (mut lines, mut walls) = (0, 0);
            for index in 0..grid.cell_count() {
                let cell = grid.cell(index);
                if cell == view.start || cell == view.end {
                    continue;
                }
                for (dir, step) in [
                    (Direction::East, (0.5, 0.0)),
                    (Direction::North, (0.0, 0.5)),
                ] {
                    let Some(next) = grid.step(cell, dir) else {
                        continue;
                    };
                    if next == view.start || next == view.end {
                        continue;
                    }
                    let middle = to_floor
                        * Point2::new(f64::from(cell.x) + step.0, f64::from(cell.y) + step.1);
                    if middle.y < bar.y + 3.0 * bar.unit {
                        continue; // under the scale bar's label
                    }
                    let colour = at(&image, &layout, middle.x, middle.y);
                    if view.maze.is_open(index, dir) {
                        assert_eq!(colour, (0, 255, 0), "{degrees} deg: {cell} {dir:?}");
                        lines += 1;
                    } else {
                        assert_ne!(colour, (0, 255, 0), "{degrees} deg: wall {cell} {dir:?}");
                        walls += 1;
                    }
                }
            }
            assert!(lines > 40 && walls > 40, "{lines} lines, {walls} walls");
        }
        assert!((90.0f64.to_radians() - PI / 2.0).abs() < 1e-12);
    }

    /// The floor point a quarter of the way along side `k` of lattice line `line`.
    fn on_side(layout: &Layout, axis: WallAxis, line: u32, k: u32) -> Point2<f64> {
        let [ox, oy] = layout.grid.origin;
        let to_floor = Isometry2::new(Vector2::new(ox, oy), layout.grid.rotation);
        let c = layout.grid.cell_size;
        let (across, along) = ((f64::from(line) - 0.5) * c, (f64::from(k) - 0.25) * c);
        to_floor
            * match axis {
                WallAxis::AlongX => Point2::new(along, across),
                WallAxis::AlongY => Point2::new(across, along),
            }
    }

    const DARK: (u8, u8, u8) = (0x20, 0x20, 0x20);
    const LIGHT: (u8, u8, u8) = (180, 180, 180);

    #[test]
    fn a_wall_maze_shows_dark_walls_on_the_light_floor_its_opening_and_goal() {
        let mut layout = wall_layout(7, 5, 4, 0.0, "start");
        let end = layout.end.cell;
        // the cell north of the end, or south on the top row
        let beside = [end[0], end[1] + 1 - 2 * u32::from(end[1] + 1 == 5)];
        layout.end.region = vec![end, beside];
        let image = render(
            &layout,
            &RenderOptions {
                solution: true,
                ..Default::default()
            },
        );
        let pixel = |p: Point2<f64>| at(&image, &layout, p.x, p.y);
        let start = &layout.start.pose;
        assert_eq!(
            pixel(Point2::new(start.x + 0.3, start.y + 0.3)),
            (0, 0, 255)
        );
        let end = &layout.end.pose;
        assert_eq!(pixel(Point2::new(end.x + 0.3, end.y - 0.3)), (255, 0, 0));
        let [ox, oy] = layout.grid.origin;
        let goal = Point2::new(
            ox + f64::from(beside[0]) + 0.3,
            oy + f64::from(beside[1]) + 0.3,
        );
        assert_eq!(pixel(goal), (0xe6, 0xa0, 0xa0));
        // inside a cell, off the walls and the metre grid
        assert_eq!(pixel(Point2::new(ox + 2.3, oy + 1.3)), LIGHT);
        let view = MazeView::of(
            &layout,
            &RenderOptions {
                solution: true,
                ..Default::default()
            },
        )
        .unwrap();
        let opening = layout.wall.as_ref().unwrap().openings[0];
        let mut closed = 0;
        for axis in [WallAxis::AlongX, WallAxis::AlongY] {
            let (lines, sides) = lattice(view.maze.grid(), axis);
            for line in 0..lines {
                for k in 0..sides {
                    let colour = pixel(on_side(&layout, axis, line, k));
                    if is_closed(&view.maze, &[opening], axis, line, k) {
                        assert_eq!(colour, DARK, "{axis:?} {line} {k}");
                        closed += 1;
                    } else {
                        assert_ne!(colour, DARK, "{axis:?} {line} {k} is open");
                    }
                }
            }
        }
        assert_eq!(closed, layout.walls.len());
        // the start's south side is the opening: floor there, a wall without it
        let gap = on_side(&layout, WallAxis::AlongX, 0, 0);
        assert_eq!(pixel(gap), LIGHT);
        let shut = wall_layout(7, 5, 4, 0.0, "none");
        assert_eq!(shut.passages, layout.passages);
        let shut_image = render(&shut, &RenderOptions::default());
        assert_eq!(at(&shut_image, &shut, gap.x, gap.y), DARK);
        // the solution crosses the floor in orange
        let on_path = view.solution[view.solution.len() / 2];
        let (x, y) = (ox + f64::from(on_path.x), oy + f64::from(on_path.y));
        let (r, _, b) = pixel(Point2::new(x, y));
        assert!(r >= 230 && b <= 40, "{:?}", pixel(Point2::new(x, y)));
    }

    #[test]
    fn posts_stand_dark_at_every_lattice_corner() {
        let grid = Grid::new(6, 4).unwrap();
        let mut with_posts = build_layout(&GenerateSpec::course(grid, Algorithm::Prim, 3)).unwrap();
        let mut without = with_posts.clone();
        let maze = crate::layout::passages::decode(grid, &with_posts.passages).unwrap();
        let options = |posts| WallOptions {
            length: 0.8,
            posts,
            ..WallOptions::default()
        };
        into_walls(&mut with_posts, &maze, &options(Some(0.2)), true).unwrap();
        into_walls(&mut without, &maze, &options(None), true).unwrap();
        let posts = render(&with_posts, &RenderOptions::default());
        let bare = render(&without, &RenderOptions::default());
        let [ox, oy] = with_posts.grid.origin;
        let markers = [with_posts.start.cell, with_posts.end.cell];
        for j in 0..=4u32 {
            for i in 0..=6u32 {
                // 0.08 m north-east of the corner: inside its 0.2 m post, off the 0.05 m walls
                let (x, y) = (ox + f64::from(i) - 0.42, oy + f64::from(j) - 0.42);
                assert_eq!(
                    at(&posts, &with_posts, x, y),
                    DARK,
                    "post at corner ({i},{j})"
                );
                if !markers.contains(&[i, j]) {
                    assert_ne!(at(&bare, &without, x, y), DARK, "no post at ({i},{j})");
                }
            }
        }
    }

    #[test]
    fn a_rotated_wall_maze_is_drawn_where_the_geometry_says() {
        for degrees in [30.0, 90.0, -135.0] {
            let layout = wall_layout(9, 9, 6, degrees, "start");
            let image = render(&layout, &RenderOptions::default());
            let view = MazeView::of(&layout, &RenderOptions::default()).unwrap();
            let openings = &layout.wall.as_ref().unwrap().openings;
            let bar = ScaleBar::for_floor(layout.floor.size);
            let (mut open, mut closed) = (0, 0);
            for axis in [WallAxis::AlongX, WallAxis::AlongY] {
                let (lines, sides) = lattice(view.maze.grid(), axis);
                for line in 0..lines {
                    for k in 0..sides {
                        let p = on_side(&layout, axis, line, k);
                        if p.y < bar.y + 3.0 * bar.unit {
                            continue; // under the scale bar's label
                        }
                        let colour = at(&image, &layout, p.x, p.y);
                        if is_closed(&view.maze, openings, axis, line, k) {
                            assert_eq!(colour, DARK, "{degrees} deg: {axis:?} {line} {k}");
                            closed += 1;
                        } else {
                            assert_ne!(colour, DARK, "{degrees} deg: {axis:?} {line} {k}");
                            open += 1;
                        }
                    }
                }
            }
            assert!(open > 40 && closed > 40, "{open} open, {closed} closed");
        }
    }

    #[test]
    fn a_huge_floor_is_capped_and_its_lines_stay_visible() {
        let layout = build_layout(&GenerateSpec::course(
            Grid::new(4096, 16).unwrap(),
            Algorithm::Dfs,
            1,
        ))
        .unwrap();
        let [fx, fy] = layout.floor.size;
        let image = render(&layout, &RenderOptions::default());
        assert_eq!(image.width, MAX_SIDE as u32);
        let scale = MAX_SIDE / fx;
        assert_eq!(image.height, (fy * scale).ceil() as u32);
        // The pixel row through the centres of cell row 8: a 0.1 m line is 0.4 px here,
        // drawn 1 px wide.
        let y = ((fy / 2.0 - (layout.grid.origin[1] + 8.0)) * scale) as u32;
        let green = (0..image.width)
            .filter(|&x| image.pixel(x, y) == (0, 255, 0))
            .count();
        assert!(green > 4000, "{green} green pixels");
        // 0.05 m walls are 0.2 px here, drawn 1 px wide
        let grid = Grid::new(4096, 16).unwrap();
        let mut walls = layout;
        let maze = crate::layout::passages::decode(grid, &walls.passages).unwrap();
        into_walls(&mut walls, &maze, &WallOptions::default(), true).unwrap();
        let image = render(&walls, &RenderOptions::default());
        let [fx, fy] = walls.floor.size;
        let scale = MAX_SIDE / fx;
        assert_eq!(image.width, MAX_SIDE as u32);
        let y = ((fy / 2.0 - (walls.grid.origin[1] + 8.0)) * scale) as u32;
        let dark = (0..image.width)
            .filter(|&x| image.pixel(x, y) == DARK)
            .count();
        let closed = (0..=4096)
            .filter(|&x| is_closed(&maze, &[], WallAxis::AlongY, x, 8))
            .count();
        assert!(
            dark >= closed && closed > 1000,
            "{dark} dark pixels, {closed} walls"
        );
    }

    #[test]
    fn strips_join_without_seams() {
        let lines =
            [(9, 0.0), (5, 30.0)].map(|(size, degrees)| course(size, Algorithm::Dfs, degrees));
        let mut walls = wall_layout(6, 5, 2, 30.0, "start");
        walls.end.region = vec![walls.end.cell, [3, 2], [3, 3]];
        for layout in lines.into_iter().chain([walls]) {
            let degrees = layout.grid.rotation.to_degrees();
            let options = RenderOptions {
                solution: true,
                ..Default::default()
            };
            let whole = decode(&encode(&layout, &options, usize::MAX));
            for strip_rows in [1, 7] {
                let strips = decode(&encode(&layout, &options, strip_rows));
                assert_eq!((strips.width, strips.height), (whole.width, whole.height));
                assert!(
                    strips.rgb == whole.rgb,
                    "{degrees} deg, strips of {strip_rows} rows"
                );
            }
        }
    }

    #[test]
    fn spans_follow_the_pixel_centre_rule() {
        let quad = |x0: f64, y0: f64, x1: f64, y1: f64| {
            Shape::Quad([
                Px { x: x0, y: y0 },
                Px { x: x1, y: y0 },
                Px { x: x1, y: y1 },
                Px { x: x0, y: y1 },
            ])
        };
        let spans = |shape: Shape| {
            let mut all = Vec::new();
            shape.spans(0..10, 10, |row, columns| all.push((row, columns)));
            all
        };
        // Centres 1.5 and 2.5 lie in [1.2, 2.7); 1 px wide covers exactly one pixel.
        assert_eq!(spans(quad(1.2, 0.0, 2.7, 1.0)), vec![(0, 1..3)]);
        assert_eq!(spans(quad(3.9, 4.6, 4.9, 5.6)), vec![(5, 4..5)]);
        // Clipped to the image.
        assert_eq!(spans(quad(-5.0, 9.2, 20.0, 30.0)), vec![(9, 0..10)]);
        assert_eq!(spans(Shape::Disc(Px { x: 5.0, y: 5.0 }, 1.0)).len(), 2);
    }
}
