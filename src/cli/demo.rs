//! `vrep-maze demo`: the whole job on the course default, with nothing to set up.

use std::process::ExitCode;

use anyhow::{Result, anyhow, bail};
use clap::Args;

use super::validate::{describe, print_metrics};
use crate::generate::Algorithm;
use crate::layout::geometry::course;
use crate::layout::{GenerateSpec, build_layout};
use crate::maze::Grid;
use crate::render::{Format, RenderOptions};
use crate::validate::validate;

/// Options of `demo`.
#[derive(Debug, Args)]
#[command(after_help = "Example:\n  vrep-maze demo --seed 7 --algo kruskal")]
pub struct DemoArgs {
    /// Seed of the course maze.
    #[arg(long, default_value_t = 42)]
    pub seed: u64,
    /// Algorithm.
    #[arg(long, default_value = "dfs", value_parser = clap::value_parser!(Algorithm))]
    pub algo: Algorithm,
}

/// Runs `demo`: generate the 9x9 course maze, validate it, draw it with its solution.
pub fn run(args: DemoArgs) -> Result<ExitCode> {
    let grid = Grid::new(course::SIZE.into(), course::SIZE.into())?;
    let layout =
        build_layout(&GenerateSpec::course(grid, args.algo, args.seed)).map_err(|e| anyhow!(e))?;
    let report = validate(&layout);
    if !report.is_ok() {
        bail!(
            "the generated maze failed validation: {}",
            report.problems[0]
        );
    }
    let picture = Format::Ascii
        .renderer()
        .render(&layout, &RenderOptions { solution: true })?;
    println!("{}", String::from_utf8_lossy(&picture).trim_end());
    println!("OK {}", describe(&layout));
    if let Some(metrics) = &report.metrics {
        print_metrics(metrics);
    }
    println!(
        "(S start, E end, . solution; `vrep-maze generate --seed {} --algo {} -o maze.json` writes this layout)",
        args.seed, args.algo
    );
    Ok(ExitCode::SUCCESS)
}
