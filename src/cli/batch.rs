//! `vrep-maze batch`: a dataset of mazes, one per seed, with a manifest.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{Result, anyhow};
use clap::Args;

use super::generate::MazeArgs;
use super::interrupt::{INTERRUPTED_EXIT_CODE, Interrupt};
use super::progress::{Progress, Unit};
use crate::batch::{self, Filter, parse_seeds};

/// Options of `batch`.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  vrep-maze batch --algo prim --size 15x15 --seeds 0..1000 --out-dir dataset\n  vrep-maze batch --algo kruskal --braid 0.3 --size 15x15 --seeds 0..=99 --min-solution 40 --out-dir hard"
)]
pub struct BatchArgs {
    /// Seeds: N, A..B (B excluded), A..=B (B included), or a comma-separated list of these.
    #[arg(long, value_parser = |s: &str| parse_seeds(s).map(SeedList))]
    pub seeds: SeedList,
    /// What mazes to make (as for `generate`).
    #[command(flatten)]
    pub maze: MazeArgs,
    /// Directory for the layouts and manifest.jsonl (created if missing).
    #[arg(long)]
    pub out_dir: PathBuf,
    /// Keep only mazes whose solution has at least this many cells.
    #[arg(long, allow_negative_numbers = true)]
    pub min_solution: Option<u64>,
    /// Keep only mazes with at most this percentage of dead ends.
    #[arg(long, value_parser = super::values::parse_percent, allow_negative_numbers = true)]
    pub max_dead_ends: Option<f64>,
}

/// The seeds of a batch (one option value, many seeds).
#[derive(Debug, Clone)]
pub struct SeedList(pub Vec<u64>);

/// Runs `batch`. Ctrl-C (or SIGTERM, SIGHUP) finishes the mazes in flight, writes the
/// manifest of every maze made, says how to resume and exits 130.
pub fn run(args: BatchArgs, bars: Progress) -> Result<ExitCode> {
    let template = args.maze.spec(0)?;
    let seeds = args.seeds.0;
    let interrupt = Interrupt::install()?;
    let progress = bars.bar("generating", seeds.len() as u64, Unit::Items("mazes"));
    let filter = Filter {
        min_solution: args.min_solution,
        max_dead_end_percent: args.max_dead_ends,
    };
    let started = Instant::now();
    let outcome = batch::run(
        &template,
        &seeds,
        filter,
        &args.out_dir,
        &|| progress.inc(1),
        interrupt.flag(),
    )
    .map_err(|e| anyhow!(e))?;
    progress.finish_and_clear();
    if outcome.stale_removed > 0 {
        eprintln!(
            "removed {} temporary file(s) left by an earlier, killed run",
            outcome.stale_removed
        );
    }
    eprintln!(
        "{} mazes: {} written, {} unchanged, {} refused by the filter, in {:.2} s; manifest {}",
        seeds.len() - outcome.skipped,
        outcome.written,
        outcome.unchanged,
        outcome.filtered,
        started.elapsed().as_secs_f64(),
        outcome.manifest.display()
    );
    if interrupt.requested() {
        eprintln!(
            "interrupted: {} of {} seeds not made; run the same command again to finish (mazes already written are kept)",
            outcome.skipped,
            seeds.len()
        );
        return Ok(ExitCode::from(INTERRUPTED_EXIT_CODE));
    }
    anyhow::ensure!(
        outcome.filtered < seeds.len(),
        "the filter refused all {} mazes: loosen --min-solution or --max-dead-ends, or use a larger --size",
        seeds.len()
    );
    Ok(ExitCode::SUCCESS)
}
