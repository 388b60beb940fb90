//! `vrep-maze apply`: draw a layout into CoppeliaSim over the legacy remote API.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::Duration;

use anyhow::Context;

use crate::draw::{self, ApplyOptions, Drawing, SceneNames, Stage};
use crate::legacy::LegacyScene;

/// Where the simulator is and what its objects are called (shared by `apply` and `clear`).
#[derive(Debug, Clone, clap::Args)]
pub struct SceneArgs {
    /// Host running CoppeliaSim (dotted IPv4 or a name).
    #[arg(long, default_value = "127.0.0.1")]
    pub host: String,
    /// Port of the legacy remote API server (CoppeliaSim's always-on one is 19997).
    #[arg(long, default_value_t = 19997)]
    pub port: u16,
    /// The floor: every layout coordinate is relative to it.
    #[arg(long, default_value = "Floor")]
    pub floor: String,
    /// The dummy every maze line becomes a child of.
    #[arg(long, default_value = "Maze")]
    pub parent: String,
    /// The line template (a 0.6 m x 0.1 m green plane).
    #[arg(long, default_value = "Line")]
    pub line: String,
    /// The start marker (a 1 m x 1 m blue plane).
    #[arg(long, default_value = "Start")]
    pub start: String,
    /// The end marker (a 1 m x 1 m red plane).
    #[arg(long, default_value = "End")]
    pub end: String,
    /// Seconds to keep retrying to connect, and to wait for each reply.
    #[arg(long, default_value_t = 10.0)]
    pub timeout: f64,
}

impl SceneArgs {
    /// The object names.
    pub fn names(&self) -> SceneNames {
        SceneNames {
            floor: self.floor.clone(),
            parent: self.parent.clone(),
            line: self.line.clone(),
            start: self.start.clone(),
            end: self.end.clone(),
        }
    }

    /// Connects to the simulator.
    pub fn connect(&self) -> anyhow::Result<LegacyScene> {
        anyhow::ensure!(
            self.timeout > 0.0 && self.timeout.is_finite(),
            "--timeout must be a positive number of seconds"
        );
        LegacyScene::connect(&self.host, self.port, Duration::from_secs_f64(self.timeout))
            .with_context(|| format!("connecting to CoppeliaSim at {}:{}", self.host, self.port))
    }
}

/// Draw a layout into a running CoppeliaSim (legacy remote API, simulation stopped).
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Example:\n  vrep-maze generate --seed 42 --algo prim -o m.json\n  vrep-maze apply m.json\n  vrep-maze apply m.json --port 19997 --line GreenLine --stop-simulation"
)]
pub struct ApplyArgs {
    /// Layout JSON written by `vrep-maze generate` (`-` reads standard input).
    pub layout: PathBuf,
    /// Connection and object names.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Stop a running simulation first (changes made while it runs would be lost).
    #[arg(long)]
    pub stop_simulation: bool,
    /// Only show what would change.
    #[arg(long)]
    pub dry_run: bool,
}

/// Runs `apply`.
pub fn run(args: ApplyArgs) -> anyhow::Result<std::process::ExitCode> {
    let layout = crate::layout::read_layout(&args.layout)?;
    let drawing = Drawing::from(&layout);
    let opts = ApplyOptions {
        names: args.scene.names(),
        stop_simulation: args.stop_simulation,
        dry_run: args.dry_run,
        ..Default::default()
    };
    let mut scene = args.scene.connect()?;
    let bar = std::io::stderr().is_terminal().then(|| {
        let b = indicatif::ProgressBar::new(drawing.lines.len() as u64);
        b.set_style(
            indicatif::ProgressStyle::with_template("{spinner} {msg} [{bar:30}] {pos}/{len}")
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        b.enable_steady_tick(Duration::from_millis(100));
        b
    });
    let mut progress = |stage: Stage| {
        if let Some(b) = &bar {
            match stage {
                Stage::Surveyed => b.set_message("reading the scene"),
                Stage::Pasting { done, .. } => {
                    b.set_message("pasting lines");
                    b.set_position(done as u64 + 1);
                }
                Stage::Placing => {
                    b.set_message("placing lines");
                    b.set_position(drawing.lines.len() as u64);
                }
                Stage::Verifying => b.set_message("verifying"),
            }
        }
    };
    let result = draw::apply(&mut scene, &drawing, &opts, &mut progress);
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let report = result.with_context(|| format!("drawing {}", args.layout.display()))?;
    scene.close().ok();
    if report.stopped_simulation {
        println!("stopped the simulation first");
    }
    println!("{report}");
    if !report.dry_run {
        println!("verified: every line, start and end in place");
    }
    Ok(std::process::ExitCode::SUCCESS)
}
