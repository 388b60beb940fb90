//! `vrep-maze validate`: check layout files and print what each maze is like.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Result;
use clap::Args;

use crate::layout::{Layout, Style, read_layout};
use crate::maze::Metrics;
use crate::validate::{Invalid, validate};

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

/// Runs `validate`: exit 0 only if every file is valid.
pub fn run(args: ValidateArgs) -> Result<ExitCode> {
    let mut all_ok = true;
    for path in &args.files {
        let name = path.display();
        let layout = match read_layout(path) {
            Ok(layout) => layout,
            Err(e) => {
                eprintln!("error: {e}");
                all_ok = false;
                continue;
            }
        };
        let report = validate(&layout);
        if report.is_ok() {
            println!("OK {name}: {}", describe(&layout));
            if let Some(metrics) = &report.metrics {
                print_metrics(metrics);
            }
        } else {
            all_ok = false;
            let count = report.problems.len();
            let invalid = Invalid {
                problems: report.problems,
            };
            for line in invalid.shown() {
                eprintln!("error: {name}: {line}");
            }
            eprintln!("INVALID {name}: {count} problem(s)");
        }
    }
    Ok(if all_ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

/// One line naming the maze.
pub fn describe(layout: &Layout) -> String {
    format!(
        "{}x{} {} seed {}, {}",
        layout.grid.columns,
        layout.grid.rows,
        layout.generator.algorithm,
        layout.generator.seed,
        match layout.style {
            Style::Lines => format!("{} segments", layout.segments.len()),
            Style::Walls => format!("{} walls", layout.walls.len()),
        }
    )
}

/// The metrics, a few to a line.
pub fn print_metrics(m: &Metrics) {
    println!(
        "  cells {}, passages {}, loops {}",
        m.cells, m.passages, m.loops
    );
    println!(
        "  solution {} cells, {} turns, {} decision points",
        m.solution_cells, m.solution_turns, m.decision_points
    );
    println!(
        "  dead ends {} ({:.1}%), junctions {}, straights {}",
        m.dead_ends,
        m.dead_end_percent(),
        m.junctions,
        m.straights
    );
    println!("  diameter {} cells", m.diameter_cells);
}
