//! Importing a maze drawn as text: the drawings the micromouse community shares (posts
//! `o` or `+`, walls `---` and `|`, one text row per row of cells, optional `S` start and
//! `G` goal marks) and our own ASCII render (`+---+`, `S`, `E`, `G`, `.`).
//!
//! Every cell is four characters wide (a post or wall character, then three inside), every
//! row of cells two text lines (a line of posts and walls, then the cells), north at the
//! top; the last line is the south wall. Missing characters at the end of a line count as
//! spaces. The result is a wall layout (or a line layout, on request) whose passages are
//! the drawing's; gaps in the outer wall become openings.

use std::collections::BTreeMap;

use super::build::{GenerateSpec, plan_maze};
use super::endpoints::EndpointSpec;
use super::geometry::{Geometry, round_um};
use super::walls::{Openings, WallOptions, into_walls_with};
use super::{FloorSize, Layout, Opening, Side, Style};
use crate::generate::Algorithm;
use crate::maze::analysis::{UNREACHED, distances_from, farthest_from};
use crate::maze::{Cell, Direction, Grid, Maze};

/// The `generator.algorithm` of an imported layout.
pub const ALGORITHM: &str = "import";
/// The `generator.options` key naming the file a layout was imported from.
pub const SOURCE: &str = "source";

/// How an imported maze is laid out.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImportOptions {
    /// Side of a cell, metres; walls are one cell long, cell / 15 thick and 5/18 of a
    /// cell high (the micromouse proportions: 0.012 m and 0.05 m for 0.18 m cells); the
    /// line template is 0.6 x 0.1 cells.
    pub cell_size: f64,
    /// Walls (the default) or lines.
    pub style: Style,
}

impl Default for ImportOptions {
    fn default() -> Self {
        Self {
            cell_size: 0.18,
            style: Style::Walls,
        }
    }
}

/// What the drawing says, before it is laid out.
#[derive(Debug, Clone, PartialEq)]
pub struct TextMaze {
    /// The passages.
    pub maze: Maze,
    /// The `S` cell, if marked.
    pub start: Option<Cell>,
    /// The `E` cell, if marked.
    pub end: Option<Cell>,
    /// The `G` cells, in reading order.
    pub goal: Vec<Cell>,
    /// Gaps in the outer wall.
    pub openings: Vec<Opening>,
}

/// `FILE:LINE:COL: message`.
fn at(name: &str, line: usize, column: usize, message: impl std::fmt::Display) -> String {
    format!("{name}:{}:{}: {message}", line + 1, column + 1)
}

/// Reads the drawing in `text`; `name` (the file) starts every error, which names the line
/// and column. In phases: the drawing's size (`drawn_size`), then each line, a wall line
/// (`Reader::wall_line`) or a cell line (`Reader::cell_line`), then the maze of the
/// passages read.
pub fn parse(text: &str, name: &str) -> Result<TextMaze, String> {
    let mut lines: Vec<Vec<char>> = text
        .lines()
        .map(|l| l.trim_end().chars().collect())
        .collect();
    while lines.last().is_some_and(Vec::is_empty) {
        lines.pop();
    }
    let (width, height) = drawn_size(&lines, name)?;
    let grid = Grid::new(width as u64, height as u64).map_err(|e| format!("{name}: {e}"))?;
    let mut reader = Reader {
        name,
        grid,
        width,
        height,
        masks: vec![0u8; grid.cell_count()],
        drawing: TextMaze {
            maze: Maze::closed(grid),
            start: None,
            end: None,
            goal: Vec::new(),
            openings: Vec::new(),
        },
        marks: BTreeMap::new(),
    };
    for (l, line) in lines.iter().enumerate() {
        if line.len() > 4 * width + 1 {
            return Err(at(
                name,
                l,
                4 * width + 1,
                format!(
                    "the line is longer than the top wall ({} characters)",
                    4 * width + 1
                ),
            ));
        }
        // text line l: even = posts and walls south of cell row (height - l/2), odd = cells
        if l % 2 == 0 {
            reader.wall_line(l, line)?;
        } else {
            reader.cell_line(l, line)?;
        }
    }
    let Reader {
        mut drawing, masks, ..
    } = reader;
    drawing.maze = Maze::from_masks(grid, masks).map_err(|e| format!("{name}: {e}"))?;
    Ok(drawing)
}

/// The cells across and the rows of the drawing `lines` (trailing empty lines dropped), or
/// why they are no drawing: the top wall is 4 characters a cell plus 1, and a wall line
/// follows each row's cell line.
fn drawn_size(lines: &[Vec<char>], name: &str) -> Result<(usize, usize), String> {
    let first = lines
        .first()
        .ok_or_else(|| format!("{name}: empty file: no maze drawn"))?;
    if first.len() < 5 || (first.len() - 1) % 4 != 0 {
        return Err(at(
            name,
            0,
            first.len().saturating_sub(1),
            format!(
                "the top wall is {} characters long; a drawing is 4 characters a cell plus 1 (o---o is one cell)",
                first.len()
            ),
        ));
    }
    let width = (first.len() - 1) / 4;
    if lines.len() < 3 || lines.len().is_multiple_of(2) {
        return Err(at(
            name,
            lines.len() - 1,
            0,
            format!(
                "the drawing has {} lines; it needs a wall line, then a cell line and a wall line per row (an odd number)",
                lines.len()
            ),
        ));
    }
    Ok((width, (lines.len() - 1) / 2))
}

/// The character at `col` of `line`, a space past its end.
fn char_at(line: &[char], col: usize) -> char {
    line.get(col).copied().unwrap_or(' ')
}

/// What [`parse`] has read so far: the passages as masks, the openings and the marks.
struct Reader<'a> {
    /// The file, for errors.
    name: &'a str,
    grid: Grid,
    width: usize,
    height: usize,
    /// Open-passage bits per cell.
    masks: Vec<u8>,
    drawing: TextMaze,
    /// Where each `S` and `E` was found (line, column), to name the first of two.
    marks: BTreeMap<char, (usize, usize)>,
}

impl Reader<'_> {
    /// Wall line `l`: posts and, between them, walls or gaps south of a cell row (an
    /// opening where the outer wall has a gap).
    fn wall_line(&mut self, l: usize, line: &[char]) -> Result<(), String> {
        let (name, width, height) = (self.name, self.width, self.height);
        let north_of = height - l / 2; // the wall between rows north_of - 1 and north_of
        for x in 0..=width {
            let post = char_at(line, 4 * x);
            if post != 'o' && post != '+' {
                return Err(at(
                    name,
                    l,
                    4 * x,
                    format!("expected a post 'o' or '+', found '{post}'"),
                ));
            }
            if x == width {
                break;
            }
            let wall: String = (1..4).map(|k| char_at(line, 4 * x + k)).collect();
            let open = match wall.as_str() {
                "---" => false,
                "   " => true,
                _ => {
                    let k = (1..4)
                        .find(|&k| char_at(line, 4 * x + k) != '-')
                        .unwrap_or(1);
                    return Err(at(
                        name,
                        l,
                        4 * x + k,
                        format!(
                            "expected a wall '---' or a gap '   ' between posts, found '{wall}'"
                        ),
                    ));
                }
            };
            if !open {
                continue;
            }
            let x = x as u32;
            if north_of == 0 {
                self.drawing.openings.push(Opening {
                    cell: [x, 0],
                    side: Side::South,
                });
            } else if north_of == height {
                self.drawing.openings.push(Opening {
                    cell: [x, height as u32 - 1],
                    side: Side::North,
                });
            } else {
                let south = self.grid.index(Cell::new(x, north_of as u32 - 1));
                let north = self.grid.index(Cell::new(x, north_of as u32));
                self.masks[south] |= Direction::North.bit();
                self.masks[north] |= Direction::South.bit();
            }
        }
        Ok(())
    }

    /// Cell line `l`: walls or gaps between the cells of a row (an opening where the outer
    /// wall has a gap), and each cell's marks.
    fn cell_line(&mut self, l: usize, line: &[char]) -> Result<(), String> {
        let (name, width) = (self.name, self.width);
        let y = (self.height - 1 - l / 2) as u32;
        for x in 0..=width {
            let side = char_at(line, 4 * x);
            let open = match side {
                '|' => false,
                ' ' => true,
                _ => {
                    return Err(at(
                        name,
                        l,
                        4 * x,
                        format!("expected a wall '|' or a gap ' ', found '{side}'"),
                    ));
                }
            };
            if open {
                if x == 0 {
                    self.drawing.openings.push(Opening {
                        cell: [0, y],
                        side: Side::West,
                    });
                } else if x == width {
                    self.drawing.openings.push(Opening {
                        cell: [width as u32 - 1, y],
                        side: Side::East,
                    });
                } else {
                    let west = self.grid.index(Cell::new(x as u32 - 1, y));
                    self.masks[west] |= Direction::East.bit();
                    self.masks[west + 1] |= Direction::West.bit();
                }
            }
            if x == width {
                break;
            }
            let cell = Cell::new(x as u32, y);
            for k in 1..4 {
                self.mark(l, 4 * x + k, cell, char_at(line, 4 * x + k))?;
            }
        }
        Ok(())
    }

    /// The mark `mark` at line `l`, column `col`, inside `cell`: `S`, `E` (once each), `G`,
    /// or nothing (a space, or `.` of a drawn solution).
    fn mark(&mut self, l: usize, col: usize, cell: Cell, mark: char) -> Result<(), String> {
        match mark {
            ' ' | '.' => {}
            'S' | 'E' => {
                if let Some(&(pl, pc)) = self.marks.get(&mark) {
                    return Err(at(
                        self.name,
                        l,
                        col,
                        format!(
                            "a second '{mark}': the first is at line {}, column {}",
                            pl + 1,
                            pc + 1
                        ),
                    ));
                }
                self.marks.insert(mark, (l, col));
                if mark == 'S' {
                    self.drawing.start = Some(cell);
                } else {
                    self.drawing.end = Some(cell);
                }
            }
            'G' => {
                if !self.drawing.goal.contains(&cell) {
                    self.drawing.goal.push(cell);
                }
            }
            _ => {
                return Err(at(
                    self.name,
                    l,
                    col,
                    format!(
                        "'{mark}' is not a mark: a cell holds spaces, S (start), G (goal), E (end) or . (solution)"
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// The layout of the drawing in `text` (from the file `name`), laid out as `options`
/// says: start at `S` (else the south-west cell), end at `E` or the goal cell nearest the
/// start (else the cell farthest from the start), the `G` cells (and `E`) as the goal
/// region. Refused, naming the file, when the maze falls apart or cannot be laid out.
pub fn import(text: &str, name: &str, options: &ImportOptions) -> Result<Layout, String> {
    let drawing = parse(text, name)?;
    let maze = &drawing.maze;
    let grid = maze.grid();
    let start = drawing.start.unwrap_or(Cell::new(0, 0));
    let dist = distances_from(maze, grid.index(start));
    let mut region = drawing.goal.clone();
    if let Some(end) = drawing.end
        && !region.is_empty()
        && !region.contains(&end)
    {
        region.push(end);
    }
    let end = if !region.is_empty() {
        *region
            .iter()
            .min_by_key(|c| (dist[grid.index(**c)], grid.index(**c)))
            .expect("a region")
    } else {
        drawing
            .end
            .unwrap_or_else(|| grid.cell(farthest_from(maze, grid.index(start)).0))
    };
    let unreached = dist.iter().filter(|&&d| d == UNREACHED).count();
    if unreached > 0 {
        return Err(format!(
            "{name}: {unreached} of {} cells cannot be reached from the start {start}: a maze must hang together",
            grid.cell_count()
        ));
    }
    if options.style == Style::Lines && !drawing.openings.is_empty() {
        return Err(format!(
            "{name}: the outer wall has {} gap(s); a line maze has no outer wall: import it with walls",
            drawing.openings.len()
        ));
    }
    let cell = options.cell_size;
    let spec = GenerateSpec {
        start: EndpointSpec::Cell(start),
        end: EndpointSpec::Cell(end),
        geometry: Geometry {
            cell_size: cell,
            origin: Geometry::centred_origin(grid, cell),
            line_length: round_um(0.6 * cell),
            line_width: round_um(0.1 * cell),
            ..Geometry::course(grid)
        },
        floor: FloorSize::Auto,
        ..GenerateSpec::course(grid, Algorithm::Dfs, 0)
    };
    let mut planned = plan_maze(maze.clone(), &spec).map_err(|e| format!("{name}: {e}"))?;
    let head = &mut planned.head;
    head.generator.algorithm = ALGORITHM.to_string();
    head.generator.options = BTreeMap::from([(SOURCE.to_string(), name.to_string())]);
    if region.len() > 1 {
        head.end.region = region.iter().map(|c| [c.x, c.y]).collect();
    }
    if options.style == Style::Walls {
        let walls = WallOptions {
            length: cell,
            thickness: cell / 15.0,
            height: cell * 5.0 / 18.0,
            openings: Openings::default(),
            posts: None,
        };
        let openings = drawing.openings;
        planned = planned
            .with_walls(|head, maze| into_walls_with(head, maze, &walls, openings, true))
            .map_err(|e| format!("{name}: {e}"))?;
    }
    Ok(planned.into_layout())
}

#[cfg(test)]
mod tests {
    use super::*;

    const MOUSE: &str = "\
o---o---o---o
|       | G |
o   o   o   o
| S |     G |
o---o---o---o
";

    #[test]
    fn reads_a_micromouse_drawing() {
        let d = parse(MOUSE, "m.txt").unwrap();
        let grid = d.maze.grid();
        assert_eq!((grid.width(), grid.height()), (3, 2));
        assert_eq!(d.start, Some(Cell::new(0, 0)));
        assert_eq!(d.goal, vec![Cell::new(2, 1), Cell::new(2, 0)]);
        assert!(
            d.maze
                .is_open(grid.index(Cell::new(0, 0)), Direction::North)
        );
        assert!(!d.maze.is_open(grid.index(Cell::new(0, 0)), Direction::East));
        assert!(d.openings.is_empty());
        let layout = import(MOUSE, "m.txt", &ImportOptions::default()).unwrap();
        assert_eq!(layout.generator.algorithm, "import");
        assert_eq!(layout.end.region.len(), 2);
        let report = crate::validate::validate(&layout);
        assert!(report.is_ok(), "{:?}", report.problems);
    }

    #[test]
    fn errors_name_file_line_and_column() {
        let bad_post = MOUSE.replacen("o   o   o   o", "o   o   x   o", 1);
        assert_eq!(
            parse(&bad_post, "m.txt").unwrap_err(),
            "m.txt:3:9: expected a post 'o' or '+', found 'x'"
        );
        let bad_wall = MOUSE.replacen("o---o---o---o\n|", "o---o-=-o---o\n|", 1);
        assert_eq!(
            parse(&bad_wall, "m.txt").unwrap_err(),
            "m.txt:1:7: expected a wall '---' or a gap '   ' between posts, found '-=-'"
        );
        let two_starts = MOUSE.replacen("|       |", "| S     |", 1);
        assert_eq!(
            parse(&two_starts, "m.txt").unwrap_err(),
            "m.txt:4:3: a second 'S': the first is at line 2, column 3"
        );
        assert!(
            parse("o---o\n|   |\n", "m.txt")
                .unwrap_err()
                .starts_with("m.txt:2:1: the drawing has 2 lines")
        );
        assert!(
            parse("o--o\n", "m.txt")
                .unwrap_err()
                .starts_with("m.txt:1:4: the top wall is 4")
        );
        let mark = MOUSE.replacen(" S ", " X ", 1);
        assert!(
            parse(&mark, "m.txt")
                .unwrap_err()
                .starts_with("m.txt:4:3: 'X' is not a mark")
        );
    }
}
