//! `Layout`: one maze, as `vrep-maze generate` writes it, and the functions that make one
//! (`generate`, `load`, `Layout.from_json`).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use numpy::PyArray2;
use numpy::ndarray::Array2;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyString};
use vrep_maze::atomic_file::{write_all_or_none, write_atomically};
use vrep_maze::cli::Command;
use vrep_maze::cli::usage::export_error;
use vrep_maze::export::{Format as ExportFormat, Target, export, ros_map};
use vrep_maze::layout::block_grid::BlockGrid;
use vrep_maze::layout::json::{parse_layout, to_string};
use vrep_maze::layout::solution::solve;
use vrep_maze::layout::{self as library, Pose, Style, build::Planned, passages, read_layout};

use vrep_maze::maze::analysis::shortest_path;
use vrep_maze::maze::{Cell, Direction, Grid, Maze};
use vrep_maze::render::{Format, RenderOptions};
use vrep_maze::rng::os_seed;
use vrep_maze::score::{GradeOptions, Grader, Sample};
use vrep_maze::validate::validate;

use crate::errors::{self, invalid_error, read_error};
use crate::options;
use crate::wording::Keywords;
use crate::worker::{self, OnSignal};

/// One maze: what `vrep-maze generate` writes and `vrep-maze apply` draws.
///
/// A `Layout` has always passed the checks of `vrep-maze validate` (the gate every
/// consumer passes) and never changes. `to_json()` gives the layout file, byte for byte as
/// the command line writes it.
#[pyclass(frozen, module = "vrep_maze", name = "Layout")]
pub struct Layout {
    /// The layout (shared with drawing threads).
    pub layout: Arc<library::Layout>,
    /// Its passages, decoded.
    maze: Maze,
}

impl Layout {
    /// A layout known to pass the gate, with its passages decoded.
    pub fn new(layout: library::Layout) -> PyResult<Layout> {
        let grid = Grid::new(layout.grid.columns.into(), layout.grid.rows.into())
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        let maze = passages::decode(grid, &layout.passages).map_err(PyValueError::new_err)?;
        Ok(Layout {
            layout: Arc::new(layout),
            maze,
        })
    }

    /// `layout` if it passes the gate, else a `ValidationError` naming `name`.
    fn checked(py: Python<'_>, layout: library::Layout, name: &str) -> PyResult<Layout> {
        if let Err(invalid) = py.detach(|| validate(&layout).into_result()) {
            let headline = format!("invalid layout {name}: {} problem(s)", invalid.count());
            return Err(invalid_error(py, &headline, &invalid));
        }
        Layout::new(layout)
    }

    /// The layout as blocks (see `maze_map`).
    fn block_grid(&self) -> PyResult<BlockGrid> {
        BlockGrid::of(&self.layout).map_err(|e| PyValueError::new_err(e.to_string()))
    }

    fn cell(&self, cell: [u32; 2]) -> (u32, u32) {
        (cell[0], cell[1])
    }
}

#[pymethods]
impl Layout {
    /// The layout as JSON, exactly the bytes `vrep-maze generate` writes (top two levels
    /// indented, one segment a line, a final newline).
    fn to_json(&self, py: Python<'_>) -> String {
        py.detach(|| to_string(&self.layout))
    }

    /// Reads a layout from JSON text and checks it as `vrep-maze validate` does: a
    /// `ValueError` if it is not a layout, a `ValidationError` listing the problems if it
    /// is an invalid one.
    #[staticmethod]
    fn from_json(py: Python<'_>, text: &str) -> PyResult<Layout> {
        let name = "<json>";
        let layout = parse_layout(text, name).map_err(read_error)?;
        Layout::checked(py, layout, name)
    }

    /// Writes the layout file to `path` (atomically: a temporary file, then a rename), as
    /// `vrep-maze generate -o path` does.
    fn save(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let text = self.to_json(py);
        py.detach(|| write_atomically(&path, |w| w.write_all(text.as_bytes())))
            .map_err(|e| std::io::Error::new(e.kind(), format!("{}: {e}", path.display())))?;
        Ok(())
    }

    /// Checks the layout again as `vrep-maze validate` does and returns the metrics it
    /// measured (a dict); raises `ValidationError` listing the problems otherwise.
    fn validate<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let metrics = py
            .detach(|| validate(&self.layout).into_result())
            .map_err(|invalid| {
                let headline = format!("invalid layout: {} problem(s)", invalid.count());
                invalid_error(py, &headline, &invalid)
            })?;
        let metrics = metrics.ok_or_else(|| {
            PyRuntimeError::new_err("a valid layout was not measured (please report this)")
        })?;
        json_value(py, &metrics)
    }

    /// What the maze is like (the layout's `metrics`): `cells`, `passages`, `loops`,
    /// `solution_cells`, `solution_turns`, `decision_points`, `dead_ends`, `junctions`,
    /// `straights`, `diameter_cells`.
    #[getter]
    fn metrics<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json_value(py, &self.layout.metrics)
    }

    /// The start cell, `(x, y)`: column, and row from the south.
    #[getter]
    fn start(&self) -> (u32, u32) {
        self.cell(self.layout.start.cell)
    }

    /// The end cell, `(x, y)`.
    #[getter]
    fn end(&self) -> (u32, u32) {
        self.cell(self.layout.end.cell)
    }

    /// Columns and rows, `(width, height)`.
    #[getter]
    fn size(&self) -> (u32, u32) {
        (self.layout.grid.columns, self.layout.grid.rows)
    }

    /// The seed the maze was made from.
    #[getter]
    fn seed(&self) -> u64 {
        self.layout.generator.seed
    }

    /// The algorithm's name (`dfs`, `prim`, ...).
    #[getter]
    fn algorithm(&self) -> &str {
        &self.layout.generator.algorithm
    }

    /// The open passages as a NumPy `uint8` array of shape `(height, width)`, indexed
    /// `[y, x]` (row 0 is the south row): bit 1 east, 2 north, 4 west, 8 south.
    #[getter]
    fn passages<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<u8>>> {
        let grid = self.maze.grid();
        let shape = (grid.height() as usize, grid.width() as usize);
        let masks = Array2::from_shape_vec(shape, self.maze.masks().to_vec())
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        Ok(PyArray2::from_owned_array(py, masks))
    }

    /// Whether cell `(x, y)` has a passage towards `direction`: `"east"`, `"north"`,
    /// `"west"`, `"south"` (or `"e"`, `"n"`, `"w"`, `"s"`).
    fn open(&self, x: u32, y: u32, direction: &str) -> PyResult<bool> {
        let grid = self.maze.grid();
        let cell = Cell::new(x, y);
        if !grid.contains(cell) {
            return Err(PyValueError::new_err(format!(
                "cell {cell} is off the {grid} grid"
            )));
        }
        Ok(self
            .maze
            .is_open(grid.index(cell), parse_direction(direction)?))
    }

    /// The shortest path from start to end, a list of `(x, y)` cells, both ends included.
    fn solution(&self, py: Python<'_>) -> PyResult<Vec<(u32, u32)>> {
        let grid = self.maze.grid();
        let start = Cell::new(self.layout.start.cell[0], self.layout.start.cell[1]);
        let end = Cell::new(self.layout.end.cell[0], self.layout.end.cell[1]);
        let path = py
            .detach(|| shortest_path(&self.maze, grid.index(start), grid.index(end)))
            .ok_or_else(|| PyValueError::new_err(format!("end {end} cannot be reached")))?;
        Ok(path
            .into_iter()
            .map(|i| grid.cell(i))
            .map(|c| (c.x, c.y))
            .collect())
    }

    /// The block grid of Gymnasium-Robotics' PointMaze/AntMaze (`maze_map=`): `2*height+1`
    /// rows of `2*width+1` blocks, row 0 the north edge; `1` wall, `0` free, `"r"` the start,
    /// `"g"` the end. Cell `(x, y)` is block `[2*(height-1-y)+1][2*x+1]`.
    fn maze_map<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json_value(py, &self.block_grid()?.maze_map)
    }

    /// PointMaze's `maze_size_scaling` for `maze_map()`: a block's side, half the cell size
    /// (a cell and the wall beside it are two blocks), so a cell keeps the layout's size.
    #[getter]
    fn maze_size_scaling(&self) -> PyResult<f64> {
        Ok(self.block_grid()?.maze_size_scaling)
    }

    /// The solution as floor waypoints, as `vrep-maze solve` writes them: a NumPy `float64`
    /// array of shape `(n, 4)`, one row `(x, y, yaw, distance)` per waypoint (metres and
    /// radians in the floor's frame; `distance` along the path from the first). A cell where
    /// the path turns has two rows, the heading on arrival and on leaving. `start=(x, y)`
    /// starts from another cell than the layout's start.
    #[pyo3(signature = (*, start=None))]
    fn waypoints<'py>(
        &self,
        py: Python<'py>,
        start: Option<(u32, u32)>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let from = start.map(|(x, y)| Cell::new(x, y));
        let solved = py
            .detach(|| solve(&self.layout, &self.maze, from))
            .map_err(|e| PyValueError::new_err(e.replace("from cell", "start")))?;
        let flat: Vec<f64> = solved
            .waypoints
            .iter()
            .flat_map(|w| [w.x, w.y, w.yaw, w.distance])
            .collect();
        let array = Array2::from_shape_vec((solved.waypoints.len(), 4), flat)
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        Ok(PyArray2::from_owned_array(py, array))
    }

    /// Whether a robot whose centre is at `(x, y)` (floor frame, metres) is inside `End`'s
    /// footprint (the cell size a side), as `score` decides that a run reached it.
    fn reached_end(&self, x: f64, y: f64) -> PyResult<bool> {
        let grader = Grader::new(&self.layout).map_err(|e| PyValueError::new_err(e.to_string()))?;
        let at = Sample {
            t: 0.0,
            x,
            y,
            yaw: 0.0,
        };
        Ok(grader.in_end_at(&at, &GradeOptions::default()))
    }

    /// Grades a run through this maze as `vrep-maze score` does, from its trajectory: rows
    /// `(t, x, y, yaw)` in the floor's frame (seconds, metres, radians), as `score` returns
    /// them. `robot_radius` (metres) counts wall contacts in a wall maze. Returns the report
    /// as a dict (`report["reached_end"]`, `report["spl"]`, `report["cells"]`, ...).
    #[pyo3(signature = (trajectory, *, robot_radius=0.1))]
    fn grade<'py>(
        &self,
        py: Python<'py>,
        trajectory: Vec<[f64; 4]>,
        robot_radius: f64,
    ) -> PyResult<Bound<'py, PyAny>> {
        if !(robot_radius.is_finite() && robot_radius >= 0.0) {
            return Err(PyValueError::new_err(format!(
                "robot_radius must be a finite length, got {robot_radius}"
            )));
        }
        if let Some(k) = trajectory
            .iter()
            .position(|r| r.iter().any(|v| !v.is_finite()))
        {
            return Err(PyValueError::new_err(format!(
                "trajectory row {k} is not finite: {:?}",
                trajectory[k]
            )));
        }
        let samples: Vec<Sample> = trajectory
            .iter()
            .map(|&[t, x, y, yaw]| Sample { t, x, y, yaw })
            .collect();
        let grader = Grader::new(&self.layout).map_err(|e| PyValueError::new_err(e.to_string()))?;
        let options = GradeOptions {
            robot_radius,
            end_size: None,
        };
        let report = py.detach(|| grader.grade(&samples, &options));
        crate::reports::report_dict(py, &report)
    }

    /// The copies of `Line` to draw, a NumPy `float64` array of shape `(n, 4)`: one row
    /// `(x, y, z, yaw)` per segment in the floor's frame (metres, radians), the template
    /// first. Made in one allocation, not one object per segment.
    #[getter]
    fn segments<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        poses_array(py, &self.layout.segments)
    }

    /// A wall layout's copies of `Wall`, as `segments` holds a line layout's: a `float64`
    /// array of shape `(n, 4)`, one row `(x, y, z, yaw)` per wall (its centre; `z` is half
    /// the wall's height). Empty for a line layout.
    #[getter]
    fn walls<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        poses_array(py, &self.layout.walls)
    }

    /// A wall layout's copies of `Post` (with `posts=True`), one per lattice corner, as a
    /// `float64` array of shape `(n, 4)`; empty without posts.
    #[getter]
    fn posts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        poses_array(py, &self.layout.posts)
    }

    /// How the maze is drawn: `"lines"` or `"walls"`.
    #[getter]
    fn style(&self) -> &'static str {
        self.layout.style.name()
    }

    /// Draws the maze as `vrep-maze render` does: `"ascii"` (walls in text), `"svg"` (the
    /// floor as the robot's camera sees it) or `"png"`. With `path`, writes the file (the
    /// format follows its extension, `.txt`, `.svg` or `.png`, unless `format` is given) and
    /// returns `None`; without, returns the picture (`str`, or `bytes` for PNG; ASCII by
    /// default). `solution=True` overlays the shortest path.
    #[pyo3(signature = (path=None, *, format=None, solution=false))]
    fn render<'py>(
        &self,
        py: Python<'py>,
        path: Option<PathBuf>,
        format: Option<&str>,
        solution: bool,
    ) -> PyResult<Option<Bound<'py, PyAny>>> {
        let format = choose_format(format, path.as_deref())?;
        let options = RenderOptions {
            solution,
            ..Default::default()
        };
        let layout = &self.layout;
        let bytes = py
            .detach(|| format.render_to_vec(layout, &options))
            .map_err(|e| errors::from_anyhow(py, &e.into()))?;
        match path {
            Some(path) => {
                py.detach(|| write_atomically(&path, |w| w.write_all(&bytes)))
                    .map_err(|e| {
                        std::io::Error::new(e.kind(), format!("{}: {e}", path.display()))
                    })?;
                Ok(None)
            }
            None if format == Format::Png => Ok(Some(PyBytes::new(py, &bytes).into_any())),
            None => {
                let text =
                    String::from_utf8(bytes).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
                Ok(Some(PyString::new(py, &text).into_any()))
            }
        }
    }

    /// Writes the maze for a simulator as `vrep-maze export -o path` does (atomically), the
    /// format chosen by the ending: `.simmodel.xml` / `.simscene.xml` (CoppeliaSim), `.mjcf` /
    /// `.mujoco.xml` (MuJoCo), `.sdf` / `.world` (Gazebo), `.urdf`, `.wbt` (Webots),
    /// `.pointmaze.json` (Gymnasium-Robotics PointMaze/AntMaze arguments), `.yaml` / `.yml` (a
    /// ROS map_server occupancy map: the YAML and beside it the PGM image of the same name,
    /// at the command line's default scale). A `ValueError` naming the endings for any other
    /// (a bare `.xml` is ambiguous).
    fn export(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let format = match Target::from_path(&path) {
            Some(Target::Format(format)) => format,
            Some(Target::RosMap) => return self.export_ros_map(py, &path),
            None => {
                return Err(PyValueError::new_err(
                    ExportFormat::refusal(&path, false).worded(&Keywords),
                ));
            }
        };
        let layout = &self.layout;
        let bytes = py
            .detach(|| {
                let mut bytes = Vec::new();
                export(format, layout, &mut bytes).map(|()| bytes)
            })
            .map_err(|e| errors::from_anyhow(py, &export_error(e)))?;
        py.detach(|| write_atomically(&path, |w| w.write_all(&bytes)))
            .map_err(|e| std::io::Error::new(e.kind(), format!("{}: {e}", path.display())))?;
        Ok(())
    }

    /// The SVG picture (without the solution), so Jupyter shows a `Layout` as the maze.
    fn _repr_svg_(&self, py: Python<'_>) -> PyResult<String> {
        let layout = &self.layout;
        let bytes = py
            .detach(|| Format::Svg.render_to_vec(layout, &RenderOptions::default()))
            .map_err(|e| errors::from_anyhow(py, &e.into()))?;
        String::from_utf8(bytes).map_err(|e| PyRuntimeError::new_err(e.to_string()))
    }

    fn __repr__(&self) -> String {
        let l = &self.layout;
        format!(
            "<Layout {}x{} {} seed {}: solution {} cells, {}>",
            l.grid.columns,
            l.grid.rows,
            l.generator.algorithm,
            l.generator.seed,
            l.metrics.solution_cells,
            match l.style {
                Style::Lines => format!("{} segments", l.segments.len()),
                Style::Walls => format!("{} walls", l.walls.len()),
            }
        )
    }

    fn __eq__(&self, other: &Layout) -> bool {
        self.layout == other.layout
    }
}

/// `poses` as a NumPy `(n, 4)` array of `(x, y, z, yaw)` rows, made in one allocation.
fn poses_array<'py>(py: Python<'py>, poses: &[Pose]) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let flat: Vec<f64> = poses.iter().flat_map(|p| [p.x, p.y, p.z, p.yaw]).collect();
    let array = Array2::from_shape_vec((poses.len(), 4), flat)
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    Ok(PyArray2::from_owned_array(py, array))
}

/// The render format: `format` if given, else the one `path`'s extension names, else ASCII;
/// an extension that names no format, or another format than `format`, is refused (as
/// `vrep-maze render -o` refuses it).
fn choose_format(format: Option<&str>, path: Option<&std::path::Path>) -> PyResult<Format> {
    let explicit = format
        .map(|f| f.parse::<Format>().map_err(PyValueError::new_err))
        .transpose()?;
    let by_extension = match path.and_then(|p| p.extension().map(|e| (p, e))) {
        None => None,
        Some((path, ext)) => Some(Format::from_extension(path).ok_or_else(|| {
            PyValueError::new_err(format!(
                "{}: render writes .svg, .png and .txt (ascii) files, not .{}",
                path.display(),
                ext.to_string_lossy()
            ))
        })?),
    };
    match (explicit, by_extension) {
        (Some(f), Some(e)) if f != e => Err(PyValueError::new_err(format!(
            "format {f} does not match the file's extension (.{e})"
        ))),
        (f, e) => Ok(f.or(e).unwrap_or(Format::Ascii)),
    }
}

/// A direction by name or initial.
fn parse_direction(text: &str) -> PyResult<Direction> {
    match text.to_ascii_lowercase().as_str() {
        "e" | "east" => Ok(Direction::East),
        "n" | "north" => Ok(Direction::North),
        "w" | "west" => Ok(Direction::West),
        "s" | "south" => Ok(Direction::South),
        _ => Err(PyValueError::new_err(format!(
            "'{text}' is not a direction: east, north, west or south (or e, n, w, s)"
        ))),
    }
}

/// `value` as Python objects (through its JSON form).
fn json_value<'py>(py: Python<'py>, value: &impl serde::Serialize) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// Makes a maze as `vrep-maze generate` does and returns its layout.
///
/// Every option of `generate` is a keyword, written as in Python: `seed=42`, `algo="prim"`,
/// `size=(20, 15)`, `growing="mix:0.5"`, `bias="sw"`, `braid=0.3`, `start=(0, 3)` or
/// `"nw"` or `"farthest-pair"`, `end="farthest"`, `cell_size=0.5`, `line_length=0.3`,
/// `line_width=0.05`, `line_z=0.001`, `marker_z=0.002`, `origin=(0.0, 0.0)`,
/// `rotation=90` (degrees), `floor_size=(20, 20)`; wall mazes: `style="walls"`,
/// `wall_length=1.0`, `wall_thickness=0.05`, `wall_height=0.2`, `openings="start,end"`,
/// `posts=True`, `post_size=0.05`, or `preset="micromouse"` (or `"micromouse-half"`). An
/// option left out (or `None`) has
/// its command-line default (`algo="dfs"`, `size=(9, 9)`, `start="sw"`,
/// `end="farthest"`, the course geometry); without `seed` one is drawn from the OS and
/// recorded (`layout.seed`). The result is the same maze, byte for byte, as
/// `vrep-maze generate` with the same options. A refused value raises `ValueError` with
/// the command line's message; generation runs without the GIL, and Ctrl-C raises
/// `KeyboardInterrupt` at once.
#[pyfunction]
#[pyo3(signature = (seed=None, algo=None, size=None, **options))]
pub fn generate(
    py: Python<'_>,
    seed: Option<Bound<'_, PyAny>>,
    algo: Option<Bound<'_, PyAny>>,
    size: Option<Bound<'_, PyAny>>,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<Layout> {
    let options = options::with(
        options,
        py,
        &[("seed", seed), ("algo", algo), ("size", size)],
    )?;
    let argv = options::command_line("generate", &[], &options)?;
    let Command::Generate(args) = options::parse(argv)? else {
        return Err(PyRuntimeError::new_err(
            "generate parsed as another command",
        ));
    };
    let seed = args.seed.unwrap_or_else(os_seed);
    let built = worker::run(
        py,
        move || args.plan(seed).map(Planned::into_layout),
        OnSignal::Raise,
    )?;
    Layout::new(built.map_err(|e| errors::from_anyhow(py, &e))?)
}

/// Reads the layout file at `path` and checks it as `vrep-maze validate` does: an
/// `OSError` if it cannot be read, a `ValueError` if it is not a layout, a
/// `ValidationError` listing the problems if it is an invalid one.
#[pyfunction]
pub fn load(py: Python<'_>, path: PathBuf) -> PyResult<Layout> {
    let layout = py.detach(|| read_layout(&path)).map_err(read_error)?;
    Layout::checked(py, layout, &path.display().to_string())
}

impl Layout {
    /// `export` to a ROS map: the PGM beside the YAML (same name, `.pgm`) and the YAML naming
    /// it, both replaced atomically or neither written, as `vrep-maze export -o map.yaml`
    /// writes them.
    fn export_ros_map(&self, py: Python<'_>, yaml: &Path) -> PyResult<()> {
        let pgm = yaml.with_extension("pgm");
        // the YAML names the image in UTF-8: a name that is not would name another file
        let image = pgm
            .file_name()
            .and_then(|n| n.to_str())
            .ok_or_else(|| {
                PyValueError::new_err(format!(
                    "{}: a ROS map's YAML names its image in UTF-8, and this file name is not UTF-8",
                    pgm.display()
                ))
            })?
            .to_string();
        let layout = &self.layout;
        let map = py
            .detach(|| ros_map::map(layout, &ros_map::Options::default(), &image))
            .map_err(|e| errors::from_anyhow(py, &export_error(e)))?;
        // both files or neither: a YAML that cannot be written leaves no PGM behind
        py.detach(|| write_all_or_none(&[(&pgm, &map.pgm[..]), (yaml, map.yaml.as_bytes())]))
            .map_err(|e| {
                std::io::Error::new(e.error.kind(), format!("{e}, so neither file was written"))
            })?;
        Ok(())
    }
}
