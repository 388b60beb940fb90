//! Pictures of a layout: one file per output format, all behind [`Renderer`].
//!
//! Renderers stream: they write the picture into an [`io::Write`] as they draw it, so a
//! 4096 x 4096 maze never exists as one string or one image in memory. They draw the
//! green lines ([`crate::layout::runs::Run`]) and the walls ([`crate::layout::runs::WallRun`]) from the layout's
//! passages, never from its `segments` or `walls`.

mod ascii;
pub(crate) mod figure;
mod png;
mod svg;
mod trajectory;
mod walls;

use std::fmt;
use std::io;
use std::str::FromStr;

use crate::progress::Progress;

use crate::layout::solution::path_cells;
use crate::layout::{Layout, passages};
use crate::maze::{Cell, Grid, Maze};
use crate::wording::{Message, Opt, Value};

pub use ascii::Ascii;
pub use png::Png;
pub use svg::Svg;

/// Why a picture was not drawn.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// Writing the picture failed.
    #[error(transparent)]
    Io(#[from] io::Error),
    /// The layout cannot be drawn as asked: its grid, a cell off it, no solution to draw,
    /// no wall template.
    #[error("{0}")]
    Layout(String),
    /// A picture the format does not draw (a run as ASCII), the options it names as data.
    #[error(transparent)]
    Refused(#[from] Message),
}

/// A renderer's result.
type Result<T, E = RenderError> = std::result::Result<T, E>;

/// What to draw besides the maze, and which part of the floor at what scale (SVG and PNG).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct RenderOptions {
    /// Overlay the shortest path from start to end.
    pub solution: bool,
    /// Show only the maze's bounding box (what is drawn, grid and walls) and below it the
    /// scale bar's strip, not the whole floor.
    pub crop: bool,
    /// The picture's scale [default: the format's own].
    pub scale: Scale,
}

/// How large an SVG or PNG picture is.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub enum Scale {
    /// The format's own: SVG 40 px a metre, PNG 80 (less on a floor over 204.8 m).
    #[default]
    Default,
    /// This many pixels a metre.
    PxPerMetre(f64),
    /// The picture this many pixels wide.
    Width(u32),
}

impl Scale {
    /// Pixels a metre for a picture of a window `width` metres wide; `default` for
    /// [`Scale::Default`].
    pub fn px_per_metre(self, width: f64, default: f64) -> f64 {
        match self {
            Scale::Default => default,
            Scale::PxPerMetre(px) => px,
            Scale::Width(px) => f64::from(px) / width,
        }
    }
}

/// The part of the floor a picture shows, `[x0, y0, x1, y1]` in floor metres: the whole
/// floor, or with [`RenderOptions::crop`] the maze's bounding box and below it a strip for
/// the scale bar ([`figure::ScaleBar::strip`]), which would otherwise cover Start or walls.
fn window(layout: &Layout, options: &RenderOptions) -> [f64; 4] {
    let [fx, fy] = layout.floor.size;
    if !options.crop {
        return [-fx / 2.0, -fy / 2.0, fx / 2.0, fy / 2.0];
    }
    let c = layout.grid.cell_size;
    let (w, h) = (f64::from(layout.grid.columns), f64::from(layout.grid.rows));
    // What is drawn beyond the cells' outer edges: half a line, wall or post.
    let reach = [
        Some(layout.line.width),
        layout.wall.as_ref().map(|w| w.thickness),
        layout.post.as_ref().map(|p| p.size),
    ]
    .into_iter()
    .flatten()
    .fold(0.0, f64::max)
        / 2.0;
    let (sin, cos) = layout.grid.rotation.sin_cos();
    let [ox, oy] = layout.grid.origin;
    let mut bounds = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for (x, y) in [
        (-c / 2.0 - reach, -c / 2.0 - reach),
        ((w - 0.5) * c + reach, -c / 2.0 - reach),
        ((w - 0.5) * c + reach, (h - 0.5) * c + reach),
        (-c / 2.0 - reach, (h - 0.5) * c + reach),
    ] {
        let (px, py) = (ox + x * cos - y * sin, oy + x * sin + y * cos);
        bounds = [
            bounds[0].min(px),
            bounds[1].min(py),
            bounds[2].max(px),
            bounds[3].max(py),
        ];
    }
    bounds[1] -= figure::ScaleBar::for_window(bounds).strip();
    bounds
}

/// Turns a layout into one picture format.
pub trait Renderer {
    /// Writes the picture of `layout` into `out`, advancing `progress` (whose length it
    /// sets) as it goes; pass [`Silent`](crate::progress::Silent) to show nothing.
    ///
    /// `layout` must have passed [`crate::validate::checked`]; its `segments` are not read
    /// (they may be empty). A failed write is returned as the [`io::Error`] itself.
    fn render(
        &self,
        layout: &Layout,
        options: &RenderOptions,
        out: &mut dyn io::Write,
        progress: &dyn Progress,
    ) -> Result<()>;
}

/// The formats `render --format` accepts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Walls drawn with `+`, `-` and `|`, for a terminal.
    Ascii,
    /// The floor as the robot's camera sees it: green lines (or dark walls), blue start,
    /// red end.
    Svg,
    /// The same picture as pixels.
    Png,
}

impl Format {
    /// Every format.
    pub const ALL: [Format; 3] = [Format::Ascii, Format::Svg, Format::Png];

    /// Its name on the command line.
    pub const fn name(self) -> &'static str {
        match self {
            Format::Ascii => "ascii",
            Format::Svg => "svg",
            Format::Png => "png",
        }
    }

    /// The format a file name's extension implies, if any.
    pub fn from_extension(path: &std::path::Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "svg" => Some(Format::Svg),
            "png" => Some(Format::Png),
            "txt" => Some(Format::Ascii),
            _ => None,
        }
    }

    /// The renderer for this format.
    pub fn renderer(self) -> Box<dyn Renderer> {
        match self {
            Format::Ascii => Box::new(Ascii),
            Format::Svg => Box::new(Svg),
            Format::Png => Box::new(Png),
        }
    }

    /// The picture in memory, without a progress bar: for small mazes (the demo, the
    /// Python package); files of any size stream through [`Renderer::render`] instead.
    pub fn render_to_vec(self, layout: &Layout, options: &RenderOptions) -> Result<Vec<u8>> {
        let mut bytes = Vec::new();
        self.renderer()
            .render(layout, options, &mut bytes, &crate::progress::Silent)?;
        Ok(bytes)
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Format {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|f| f.name().eq_ignore_ascii_case(s))
            .ok_or_else(|| format!("unknown format '{s}' (known: ascii, svg, png)"))
    }
}

/// Writes the picture of `layout` in `format` with a robot's run (`trajectory`, floor
/// frame, by time) drawn over it, coloured by time; pass `options.solution` to compare it
/// with the solution. SVG and PNG only: ASCII has no room for a path.
pub fn render_run(
    format: Format,
    layout: &Layout,
    options: &RenderOptions,
    trajectory: &[crate::score::Sample],
    out: &mut dyn io::Write,
    progress: &dyn Progress,
) -> Result<()> {
    match format {
        Format::Svg => Svg.render_run(layout, options, trajectory, out, progress),
        Format::Png => Png.render_run(layout, options, trajectory, out, progress),
        Format::Ascii => Err(Message::text("a run is drawn as SVG or PNG only (use ")
            .and_setting(Opt::Format, Value::word(Format::Svg))
            .and(" or png, or ")
            .and_setting(Opt::Output, Value::Placeholder("FILE.svg"))
            .and(")")
            .into()),
    }
}

/// The maze of a layout, with its start, end and (if asked) solution cells, and its walls
/// if it is a wall maze.
struct MazeView {
    maze: Maze,
    start: Cell,
    end: Cell,
    solution: Vec<Cell>,
    walls: Option<walls::Walls>,
}

impl MazeView {
    fn of(layout: &Layout, options: &RenderOptions) -> Result<Self> {
        let grid = Grid::new(layout.grid.columns.into(), layout.grid.rows.into())
            .map_err(|e| RenderError::Layout(e.to_string()))?;
        let maze = passages::decode(grid, &layout.passages).map_err(RenderError::Layout)?;
        let start = Cell::new(layout.start.cell[0], layout.start.cell[1]);
        let end = Cell::new(layout.end.cell[0], layout.end.cell[1]);
        for (which, cell) in [("start", start), ("end", end)] {
            if !grid.contains(cell) {
                return Err(RenderError::Layout(format!(
                    "{which}.cell {cell} is off the {grid} grid"
                )));
            }
        }
        let solution = if options.solution {
            path_cells(&maze, start, end).ok_or_else(|| {
                RenderError::Layout(format!(
                    "end {end} cannot be reached from start {start}: no solution to draw"
                ))
            })?
        } else {
            Vec::new()
        };
        let walls = walls::Walls::of(layout, &maze, start, end)?;
        Ok(Self {
            maze,
            start,
            end,
            solution,
            walls,
        })
    }
}

#[cfg(test)]
mod tests {
    use std::time::Instant;

    use super::*;
    use crate::generate::Algorithm;
    use crate::layout::{GenerateSpec, build_layout};

    fn render(format: Format, layout: &Layout, options: &RenderOptions) -> Vec<u8> {
        format.render_to_vec(layout, options).unwrap()
    }

    #[test]
    fn renderers_never_read_the_segments() {
        let mut spec = GenerateSpec::course(Grid::new(6, 5).unwrap(), Algorithm::Kruskal, 7);
        spec.geometry.rotation = 0.3;
        let layout = build_layout(&spec).unwrap();
        let mut bare = layout.clone();
        bare.segments.clear();
        let options = RenderOptions {
            solution: true,
            ..Default::default()
        };
        for format in Format::ALL {
            let picture = render(format, &layout, &options);
            assert!(!picture.is_empty());
            assert!(picture == render(format, &bare, &options), "{format}");
        }
    }

    #[test]
    fn renderers_never_read_the_walls() {
        let layout = crate::layout::runs::tests::wall_layout(6, 5, 7, 0.3, "start");
        let mut bare = layout.clone();
        bare.walls.clear();
        let options = RenderOptions {
            solution: true,
            ..Default::default()
        };
        for format in Format::ALL {
            let picture = render(format, &layout, &options);
            assert!(!picture.is_empty());
            assert!(picture == render(format, &bare, &options), "{format}");
        }
    }

    #[test]
    fn a_run_is_drawn_over_the_maze_and_nothing_changes_without_one() {
        let layout = build_layout(&GenerateSpec::course(
            Grid::new(3, 1).unwrap(),
            Algorithm::Dfs,
            1,
        ))
        .unwrap();
        let options = RenderOptions {
            solution: true,
            ..Default::default()
        };
        let draw = |format, run: &[crate::score::Sample]| {
            let mut bytes = Vec::new();
            render_run(
                format,
                &layout,
                &options,
                run,
                &mut bytes,
                &crate::progress::Silent,
            )
            .unwrap();
            bytes
        };
        for format in [Format::Svg, Format::Png] {
            assert!(
                draw(format, &[]) == render(format, &layout, &options),
                "{format}"
            );
        }
        // from Start (floor x = -1) to End (x = 1) along the corridor
        let run: Vec<crate::score::Sample> = (0..=20)
            .map(|k| crate::score::Sample {
                t: f64::from(k),
                x: -1.0 + f64::from(k) * 0.1,
                y: 0.0,
                yaw: 0.0,
            })
            .collect();
        let svg = String::from_utf8(draw(Format::Svg, &run)).unwrap();
        let bands = trajectory::bands(&run);
        assert!(bands.len() > 2);
        for (_, colour) in &bands {
            assert!(svg.contains(&format!(r#"stroke="{colour}""#)), "{colour}");
        }
        // one polyline per band, and the solution's
        assert_eq!(svg.matches("<polyline").count(), bands.len() + 1);
        let ascii = render_run(
            Format::Ascii,
            &layout,
            &options,
            &run,
            &mut Vec::new(),
            &crate::progress::Silent,
        );
        assert!(ascii.unwrap_err().to_string().contains("SVG or PNG only"));
    }

    /// Render-only time and memory at scale (release build):
    /// `VREP_MAZE_RENDER_SIZE=4096 cargo test --release --lib render::tests::timing -- --ignored --nocapture`.
    /// The layout is built in memory and its segments dropped (as the CLI will hand it
    /// over); the peak resident memory is reset before each render (Linux).
    #[test]
    #[ignore = "a measurement, minutes in release at 4096"]
    fn timing() {
        let size: u64 = std::env::var("VREP_MAZE_RENDER_SIZE")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(1000);
        let started = Instant::now();
        let spec = GenerateSpec::course(Grid::new(size, size).unwrap(), Algorithm::Dfs, 1);
        let mut layout = build_layout(&spec).unwrap();
        layout.segments = Vec::new();
        println!("{size}x{size}: layout built in {:.1?}", started.elapsed());
        let peak = || {
            std::fs::read_to_string("/proc/self/status")
                .unwrap_or_default()
                .lines()
                .find(|l| l.starts_with("VmHWM"))
                .map(|l| l.split_whitespace().nth(1).unwrap_or("?").to_string())
                .unwrap_or_default()
        };
        for format in [Format::Svg, Format::Png] {
            let _ = std::fs::write("/proc/self/clear_refs", "5");
            let before = peak();
            let path = std::env::temp_dir().join(format!("vrep-maze-timing.{format}"));
            let mut file = io::BufWriter::new(std::fs::File::create(&path).unwrap());
            let started = Instant::now();
            format
                .renderer()
                .render(
                    &layout,
                    &RenderOptions::default(),
                    &mut file,
                    &crate::progress::Silent,
                )
                .unwrap();
            io::Write::flush(&mut file).unwrap();
            let bytes = std::fs::metadata(&path).unwrap().len();
            println!(
                "{format}: {:.2?}, {} MB, peak RSS {} kB (was {before} kB before rendering)",
                started.elapsed(),
                bytes / 1_000_000,
                peak()
            );
        }
    }
}
