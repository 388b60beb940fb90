//! `vrep-maze validate`: check layout files and print what each maze is like.

use std::fs::File;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Result;
use clap::Args;

use super::escape::escaped;
use super::progress::{Progress, Unit};
use super::stdout::outln;
use crate::layout::json::{Background, ReadError, read_from};
use crate::layout::{Layout, Style};
use crate::maze::Metrics;
use crate::validate::Validator;

/// Options of `validate`.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  vrep-maze validate maze.json\n  vrep-maze validate mazes/*.json\n  vrep-maze generate --seed 3 | vrep-maze validate -"
)]
pub struct ValidateArgs {
    /// Layout files to check (`-` reads standard input).
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
}

/// Runs `validate`: exit 0 only if every file is valid. Each file is read once, its
/// segments checked as they stream in.
pub fn run(args: ValidateArgs, progress: Progress) -> Result<ExitCode> {
    let mut all_ok = true;
    for path in &args.files {
        let name = path.display().to_string();
        let name = escaped(&name);
        let (layout, validator) = match read_checking(path, progress) {
            Ok(read) => read,
            Err(e) => {
                eprintln!("error: {}", escaped(&e.to_string()));
                all_ok = false;
                continue;
            }
        };
        let validator = validator.finish();
        let segments = validator.segments();
        match validator.finish().into_result() {
            Ok(metrics) => {
                outln!("OK {name}: {}", describe(&layout, segments))?;
                if let Some(metrics) = &metrics {
                    print_metrics(metrics)?;
                }
            }
            Err(invalid) => {
                all_ok = false;
                for line in invalid.shown() {
                    eprintln!("error: {name}: {}", escaped(&line));
                }
                eprintln!("INVALID {name}: {} problem(s)", invalid.count());
            }
        }
    }
    Ok(if all_ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

/// Reads the layout at `path` (`-`: standard input), validating its segments as they
/// stream past (on a second thread), with a bar over the file's bytes.
pub fn read_checking(
    path: &Path,
    progress: Progress,
) -> Result<(Layout, Background<Validator>), ReadError> {
    let start = |head: &Layout| Background::new(Validator::new(head));
    let name = path.display().to_string();
    let io = |source| ReadError::Io {
        path: name.clone(),
        source,
    };
    if name == "-" {
        return read_from(std::io::stdin().lock(), &name, start);
    }
    let file = File::open(path).map_err(io)?;
    let size = file.metadata().map_err(io)?.len();
    let bar = progress.bar(format!("reading {name}"), size, Unit::Bytes);
    let read = read_from(bar.wrap_read(file), &name, start);
    bar.finish_and_clear();
    read
}

/// One line naming the maze and what it draws: its number of segments (counted as they
/// streamed past) or of walls (and posts).
pub fn describe(layout: &Layout, segments: usize) -> String {
    format!(
        "{}x{} {} seed {}, {}",
        layout.grid.columns,
        layout.grid.rows,
        escaped(&layout.generator.algorithm),
        layout.generator.seed,
        match layout.style {
            Style::Lines => format!("{segments} segments"),
            Style::Walls if layout.posts.is_empty() => format!("{} walls", layout.walls.len()),
            Style::Walls => format!(
                "{} walls and {} posts",
                layout.walls.len(),
                layout.posts.len()
            ),
        }
    )
}

/// The metrics, a few to a line.
pub fn print_metrics(m: &Metrics) -> Result<()> {
    outln!(
        "  cells {}, passages {}, loops {}",
        m.cells,
        m.passages,
        m.loops
    )?;
    outln!(
        "  solution {} cells, {} turns, {} decision points",
        m.solution_cells,
        m.solution_turns,
        m.decision_points
    )?;
    outln!(
        "  dead ends {} ({:.1}%), junctions {}, straights {}",
        m.dead_ends,
        m.dead_end_percent(),
        m.junctions,
        m.straights
    )?;
    outln!("  diameter {} cells", m.diameter_cells)
}
