//! `vrep-maze clear`: remove a drawn maze from CoppeliaSim (templates stay).

use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use super::apply::ConnectArgs;
use super::connect::Connected;
use super::interrupt::{INTERRUPTED_EXIT_CODE, Interrupt};
use super::reports::{ClearJson, REPORT_VERSION};
use super::say::{self, say};
use crate::draw::{self, ClearOptions, DrawError};

/// Remove every maze line (children of the maze dummy other than the templates, and stray
/// parentless copies of the line template). Idempotent.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Example:\n  vrep-maze clear\n  vrep-maze clear --port 19997 --parent MyMaze --dry-run"
)]
pub struct ClearArgs {
    /// Connection and object names.
    #[command(flatten)]
    pub scene: ConnectArgs,
    /// Stop a running simulation first (CoppeliaSim undoes removals made while it runs).
    #[arg(long)]
    pub stop_simulation: bool,
    /// Only list what would be removed.
    #[arg(long)]
    pub dry_run: bool,
    /// Print one JSON document on standard output (schema/clear-v1.schema.json).
    #[arg(long)]
    pub json: bool,
}

impl ClearArgs {
    /// The library's options for this command line, stopped by `interrupt` when it is set.
    pub fn options(&self, interrupt: Option<Arc<AtomicBool>>) -> ClearOptions {
        ClearOptions {
            names: self.scene.names(),
            stop_simulation: self.stop_simulation,
            dry_run: self.dry_run,
            interrupt,
        }
    }
}

/// Runs `clear`.
pub fn run(args: ClearArgs) -> anyhow::Result<std::process::ExitCode> {
    say::set_json(args.json);
    args.scene.check_roles()?;
    let interrupt = Interrupt::install()?;
    let Connected {
        mut backend,
        description: connection,
    } = args.scene.connect_until(Some(interrupt.flag()))?;
    let opts = args.options(Some(interrupt.shared()));
    let result = draw::clear(backend.as_mut(), &opts);
    if let Err(DrawError::Interrupted { placed, total }) = &result {
        let _ = backend.close();
        eprintln!("{}", super::summary::clear_interrupted(*placed, *total));
        eprintln!("  hint: run the same clear again to finish");
        return Ok(std::process::ExitCode::from(INTERRUPTED_EXIT_CODE));
    }
    let report = result?;
    let _ = backend.close();
    for warning in &report.warnings {
        eprintln!("warning: {warning}");
    }
    if report.stopped_simulation {
        say("stopped the simulation first")?;
    }
    let lines = super::summary::clear_lines(
        &report,
        &opts.names.parent,
        args.dry_run,
        super::wording::worded,
    );
    for line in lines {
        say(line)?;
    }
    if args.json {
        say::document(&ClearJson {
            format: "vrep-maze/clear".into(),
            version: REPORT_VERSION,
            connection,
            removed: report.removed,
            removed_meshes: report.removed_meshes,
            round_trips: report.round_trips,
            restored_idle_fps: report.restored_idle_fps,
            stopped_simulation: report.stopped_simulation,
            dry_run: args.dry_run,
        })?;
    }
    Ok(std::process::ExitCode::SUCCESS)
}
