//! `vrep-maze batch`: a dataset of mazes, one per seed, with a manifest.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{Result, anyhow};
use clap::Args;

use super::generate::LayoutArgs;
use super::interrupt::{INTERRUPTED_EXIT_CODE, Interrupt};
use super::progress::{Progress, Unit};
use super::reports::{BatchReport, REPORT_VERSION};
use super::say::{self, note};
use crate::batch::{self, Filter, parse_seeds};
use crate::condition::Condition;
use crate::layout::build::Planned;

/// Options of `batch`.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  vrep-maze batch --algo prim --size 15x15 --seeds 0..1000 --out-dir dataset\n  vrep-maze batch --style walls --posts --seeds 0..100 --out-dir walls\n  vrep-maze batch --preset micromouse --seeds 0..100 --out-dir mice\n  vrep-maze batch --algo kruskal --braid 0.3 --size 15x15 --seeds 0..=99 --min-solution 40 --out-dir hard\n  vrep-maze batch --size 9x9 --seeds 0..100 --where \"solution_cells >= 40 and dead_ends <= 12\" --out-dir curriculum\n  vrep-maze batch --size 15x15 --seeds 0..1000 --where \"solution_cells >= p90\" --out-dir hardest"
)]
pub struct BatchArgs {
    /// Seeds: N, A..B (B excluded), A..=B (B included), or a comma-separated list of these.
    #[arg(long, value_parser = |s: &str| parse_seeds(s).map(SeedList))]
    pub seeds: SeedList,
    /// What mazes to make and how they are drawn: every option of `generate` but the seed
    /// and the output.
    #[command(flatten)]
    pub layout: LayoutArgs,
    /// Directory for the layouts and manifest.jsonl (created if missing).
    #[arg(long)]
    pub out_dir: PathBuf,
    /// Keep only mazes whose solution has at least this many cells.
    #[arg(long, allow_negative_numbers = true)]
    pub min_solution: Option<u64>,
    /// Keep only mazes with at most this percentage of dead ends.
    #[arg(long, value_parser = super::values::parse_percent, allow_negative_numbers = true)]
    pub max_dead_ends: Option<f64>,
    /// Keep only mazes whose metrics meet a condition: comparisons of a metric with a
    /// number joined by `and`, e.g. "solution_cells >= 40 and dead_ends <= 12" (metrics:
    /// those of the manifest, and dead_end_percent).
    #[arg(long = "where", value_name = "CONDITION", value_parser = |s: &str| s.parse::<Condition>())]
    pub condition: Option<Condition>,
    /// Print one JSON document on standard output (schema/batch-v1.schema.json).
    #[arg(long)]
    pub json: bool,
}

/// The seeds of a batch (one option value, many seeds).
#[derive(Debug, Clone)]
pub struct SeedList(pub Vec<u64>);

/// Runs `batch`. Ctrl-C (or SIGTERM, SIGHUP) finishes the mazes in flight, writes the
/// manifest of every maze made, says how to resume and exits 130.
pub fn run(args: BatchArgs, bars: Progress) -> Result<ExitCode> {
    say::set_json(args.json);
    // Every option is checked once, before any maze is made.
    args.layout.check()?;
    let seeds = args.seeds.0;
    let interrupt = Interrupt::install()?;
    let progress = bars.bar("generating", seeds.len() as u64, Unit::Items("mazes"));
    let filter = Filter {
        min_solution: args.min_solution,
        max_dead_end_percent: args.max_dead_ends,
        condition: args.condition,
    };
    let started = Instant::now();
    let make = |seed| {
        let layout = args.layout.plan(seed).map(Planned::into_layout);
        let file = args.layout.file_name(seed);
        layout
            .and_then(|l| Ok((l, file?)))
            .map_err(|e| format!("seed {seed}: {}", super::usage::one_line(&e)).into())
    };
    let outcome = batch::run_with(
        &make,
        &seeds,
        filter,
        &args.out_dir,
        &|| progress.inc(1),
        interrupt.flag(),
    )
    .map_err(|e| anyhow!(e))?;
    progress.finish_and_clear();
    if outcome.stale_removed > 0 {
        note(format!(
            "removed {} temporary file(s) left by an earlier, killed run",
            outcome.stale_removed
        ));
    }
    if args.json {
        say::document(&BatchReport {
            format: "vrep-maze/batch".into(),
            version: REPORT_VERSION,
            seeds: seeds.len(),
            written: outcome.written,
            unchanged: outcome.unchanged,
            filtered: outcome.filtered,
            skipped: outcome.skipped,
            stale_removed: outcome.stale_removed,
            manifest: outcome.manifest.display().to_string(),
            interrupted: interrupt.requested(),
        })?;
    }
    note(format!(
        "{} mazes: {} written, {} unchanged, {} refused by the filter, in {:.2} s; manifest {}",
        seeds.len() - outcome.skipped,
        outcome.written,
        outcome.unchanged,
        outcome.filtered,
        started.elapsed().as_secs_f64(),
        outcome.manifest.display()
    ));
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
        "the filter refused all {} mazes: loosen --min-solution, --max-dead-ends or --where, or use a larger --size",
        seeds.len()
    );
    Ok(ExitCode::SUCCESS)
}

#[cfg(test)]
mod tests {
    use clap::CommandFactory;

    use crate::cli::Cli;

    /// The long names of a subcommand's options.
    fn options(command: &str) -> Vec<String> {
        let cli = Cli::command();
        let sub = cli.find_subcommand(command).expect("a subcommand");
        sub.get_arguments()
            .filter_map(|a| a.get_long().map(str::to_string))
            .collect()
    }

    #[test]
    fn batch_accepts_every_option_of_generate_but_the_seed_and_the_output() {
        let generate = options("generate");
        let batch = options("batch");
        assert!(generate.len() > 20, "{generate:?}");
        for name in &generate {
            if !["seed", "output", "help"].contains(&name.as_str()) {
                assert!(batch.contains(name), "batch lacks --{name}");
            }
        }
        for style in ["style", "preset", "posts", "post-size", "openings"] {
            assert!(batch.iter().any(|b| b == style), "--{style}");
        }
    }
}
