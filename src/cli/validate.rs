//! `vrep-maze validate`: check layout files and print what each maze is like.

use std::fs::File;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Result;
use clap::Args;

use super::escape::escaped;
use super::progress::{Progress, Unit};
use super::reports::{MazeSummary, REPORT_VERSION, ValidateReport, ValidatedFile};
use super::say::{self, say};
use crate::layout::json::{Background, ReadError, read_from};
use crate::layout::{Layout, Style};
use crate::maze::Metrics;
use crate::validate::Validator;

/// Options of `validate`.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  vrep-maze validate maze.json\n  vrep-maze validate mazes/*.json\n  vrep-maze generate --seed 3 | vrep-maze validate -\n  vrep-maze validate mouse.json --robot-width 0.2   # a warning: 0.168 m between the posts"
)]
pub struct ValidateArgs {
    /// Layout files to check (`-` reads standard input).
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// Print one JSON document on standard output (schema/validate-v1.schema.json).
    #[arg(long)]
    pub json: bool,
    /// Warn (exit 0 all the same) when a robot this many metres wide does not fit the
    /// passages of a valid maze: between its walls or posts, or, for lines, the cell.
    #[arg(long, value_name = "M", value_parser = super::values::parse_metres, allow_negative_numbers = true)]
    pub robot_width: Option<f64>,
}

/// Runs `validate`: exit 0 only if every file is valid. Each file is read once, its
/// segments checked as they stream in.
pub fn run(args: ValidateArgs, progress: Progress) -> Result<ExitCode> {
    say::set_json(args.json);
    let mut files = Vec::with_capacity(args.files.len());
    for path in &args.files {
        let name = path.display().to_string();
        let name = escaped(&name);
        let mut entry = ValidatedFile {
            file: path.display().to_string(),
            valid: false,
            error: None,
            maze: None,
            metrics: None,
            problems: Vec::new(),
            problem_count: 0,
            warnings: Vec::new(),
        };
        let (layout, validator) = match read_checking(path, progress) {
            Ok(read) => read,
            Err(e) => {
                eprintln!("error: {}", escaped(&e.to_string()));
                entry.error = Some(e.to_string());
                files.push(entry);
                continue;
            }
        };
        let validator = validator.finish();
        let segments = validator.segments();
        entry.maze = Some(MazeSummary::of(&layout, segments));
        match validator.finish().into_result() {
            Ok(metrics) => {
                say(format!("OK {name}: {}", describe(&layout, segments)))?;
                if let Some(metrics) = &metrics {
                    print_metrics(metrics)?;
                }
                entry.valid = true;
                entry.metrics = metrics;
                let fit = args
                    .robot_width
                    .and_then(|width| crate::validate::robot_fit(&layout, width));
                if let Some(warning) = fit {
                    eprintln!("warning: {name}: {}", escaped(&warning));
                    entry.warnings.push(warning);
                }
            }
            Err(invalid) => {
                for line in invalid.shown(&super::wording::Flags) {
                    eprintln!("error: {name}: {}", escaped(&line));
                }
                eprintln!("INVALID {name}: {} problem(s)", invalid.count());
                if let Some(hint) = metrics_hint(&invalid) {
                    eprintln!("  hint: {hint}");
                }
                entry.problems = invalid
                    .problems
                    .iter()
                    .map(|p| p.worded(&super::wording::Flags))
                    .collect();
                entry.problem_count = invalid.count();
            }
        }
        files.push(entry);
    }
    let all_ok = files.iter().all(|f| f.valid);
    if args.json {
        say::document(&ValidateReport {
            format: "vrep-maze/validate".into(),
            version: REPORT_VERSION,
            valid: all_ok,
            files,
        })?;
    }
    Ok(if all_ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

/// What to do about metrics that disagree with the maze (a layout edited by hand: its
/// passages, start or end changed, its `metrics` not): `None` when none do.
pub fn metrics_hint(invalid: &crate::validate::Invalid) -> Option<String> {
    invalid
        .problems
        .iter()
        .any(|p| p.location.starts_with("metrics."))
        .then(|| {
            "the layout's metrics describe another maze (an edit of its passages, start or end?): write the maze's values the lines above give into those `metrics` fields, or make the layout anew with `vrep-maze generate` (the seed and options of its `generator` field)".to_string()
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
    say(format!(
        "  cells {}, passages {}, loops {}",
        m.cells, m.passages, m.loops
    ))?;
    say(format!(
        "  solution {} cells, {} turns, {} decision points",
        m.solution_cells, m.solution_turns, m.decision_points
    ))?;
    say(format!(
        "  dead ends {} ({:.1}%), junctions {}, straights {}",
        m.dead_ends,
        m.dead_end_percent(),
        m.junctions,
        m.straights
    ))?;
    say(format!("  diameter {} cells", m.diameter_cells))
}
