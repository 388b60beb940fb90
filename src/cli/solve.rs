//! `vrep-maze solve`: the solution of a layout as data (cells and floor waypoints), for a
//! robot or a program to follow.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result, anyhow};
use clap::{Args, ValueEnum};

use super::output::write_output;
use super::progress::Progress;
use super::say::{self, note};
use super::validate::read_checking;
use crate::layout::geometry::round_um;
use crate::layout::passages;
use crate::layout::solution::{SOLVE_FORMAT, Solution, SolveReport, solve};
use crate::maze::{Cell, Grid};

/// Options of `solve`.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  vrep-maze solve maze.json\n  vrep-maze solve maze.json --format csv --speed 0.3 -o path.csv\n  vrep-maze solve maze.json --from 4,4"
)]
pub struct SolveArgs {
    /// The layout file (`-` reads standard input).
    pub file: PathBuf,
    /// json (the cells, the waypoints, length and turns) or csv (rows t,x,y,yaw: a robot
    /// moving at --speed along the waypoints).
    #[arg(long, value_enum, default_value_t = SolveFormat::Json)]
    pub format: SolveFormat,
    /// Start from this cell 'x,y' instead of the layout's start.
    #[arg(long, value_parser = parse_cell)]
    pub from: Option<Cell>,
    /// CSV only: constant speed along the path, metres per second; a turn takes no time
    /// (two rows with the same t).
    #[arg(long, default_value_t = 0.2, value_parser = super::values::parse_metres)]
    pub speed: f64,
    /// Write here instead of standard output.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// The same as --format json (schema/solve-v1.schema.json), as every command's --json.
    #[arg(long, conflicts_with = "format")]
    pub json: bool,
}

/// What `solve` writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum SolveFormat {
    /// One JSON document (schema/solve-v1.schema.json).
    Json,
    /// A header `t,x,y,yaw` and one row per waypoint.
    Csv,
}

/// A cell `x,y` of whole numbers.
fn parse_cell(s: &str) -> Result<Cell, String> {
    let bad = || format!("'{s}' is not a cell x,y (e.g. 0,0)");
    let (x, y) = s.split_once(',').ok_or_else(bad)?;
    let whole = |v: &str| v.trim().parse::<u32>().map_err(|_| bad());
    Ok(Cell::new(whole(x)?, whole(y)?))
}

/// Runs `solve`.
pub fn run(args: SolveArgs, progress: Progress) -> Result<ExitCode> {
    say::set_json(args.json);
    let name = args.file.display().to_string();
    let (layout, validator) = read_checking(&args.file, progress)?;
    validator
        .finish()
        .finish()
        .into_result()
        .with_context(|| format!("{name}: nothing was solved"))?;
    let grid = Grid::new(layout.grid.columns.into(), layout.grid.rows.into())?;
    let maze = passages::decode(grid, &layout.passages).map_err(|e| anyhow!("{name}: {e}"))?;
    let solution = solve(&layout, &maze, args.from)
        .map_err(|e| super::usage::usage(format!("{name}: {e}")))?;
    let summary = format!(
        "solution from {:?} to {:?}: {} cells, {} m, {} turns",
        solution.from,
        solution.to,
        solution.cells.len(),
        solution.length,
        solution.turns
    );
    let report = SolveReport {
        format: SOLVE_FORMAT.into(),
        version: 1,
        layout: name,
        solution,
    };
    let speed = args.speed;
    write_output(args.output.as_deref(), |w| match args.format {
        SolveFormat::Json => {
            serde_json::to_writer(&mut *w, &report)?;
            writeln!(w)
        }
        SolveFormat::Csv => write_csv(&report.solution, speed, w),
    })?;
    if let Some(path) = args.output.as_deref().filter(|p| p.as_os_str() != "-") {
        note(format!("wrote {}: {summary}", path.display()));
    }
    Ok(ExitCode::SUCCESS)
}

/// The waypoints as CSV rows `t,x,y,yaw`: `t` the seconds a robot moving at `speed` m/s
/// takes to reach the waypoint.
fn write_csv(solution: &Solution, speed: f64, w: &mut dyn Write) -> std::io::Result<()> {
    writeln!(w, "t,x,y,yaw")?;
    for p in &solution.waypoints {
        writeln!(
            w,
            "{},{},{},{}",
            round_um(p.distance / speed),
            p.x,
            p.y,
            p.yaw
        )?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_are_two_whole_numbers() {
        assert_eq!(parse_cell("3,4").unwrap(), Cell::new(3, 4));
        assert_eq!(parse_cell(" 0 , 7").unwrap(), Cell::new(0, 7));
        for bad in ["3", "3,x", "-1,2", "1.5,2", ""] {
            assert!(parse_cell(bad).unwrap_err().contains("not a cell"), "{bad}");
        }
    }
}
