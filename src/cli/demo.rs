//! `vrep-maze demo`: the whole job on the course default, with nothing to set up: generate
//! the course maze, validate it, draw it into an emulated CoppeliaSim over the legacy remote
//! API, and show the result.

use std::process::ExitCode;
use std::str::FromStr;

use std::net::SocketAddr;
use std::time::Duration;

use anyhow::{Context, Result, anyhow, bail};
use clap::Args;

use super::listed::listed;
use super::stdout::outln;
use super::validate::{describe, print_metrics};
use crate::coppelia::DEFAULT_IDLE_FPS;
use crate::draw::{self, ApplyOptions, Drawing, ObjectNames};
use crate::generate::Algorithm;
use crate::layout::geometry::course;
use crate::layout::{GenerateSpec, build_layout};
use crate::legacy::LegacyBackend;
use crate::legacy::{ServerConfig, spawn};
use crate::maze::Grid;
use crate::render::{Format, RenderOptions};
use crate::sim::{Scene as SimScene, Simulator, Timing};
use crate::validate::validate;

/// Options of `demo`.
#[derive(Debug, Args)]
#[command(after_help = "Example:\n  vrep-maze demo --seed 7 --algo kruskal")]
pub struct DemoArgs {
    /// Seed of the course maze.
    #[arg(long, default_value_t = 42, allow_negative_numbers = true)]
    pub seed: u64,
    /// Algorithm of the course maze (any of `generate --algo`).
    #[arg(
        long,
        default_value = "dfs",
        value_parser = listed(Algorithm::from_str, Algorithm::ALL.map(Algorithm::name)),
        hide_possible_values = true
    )]
    pub algo: Algorithm,
}

/// Runs `demo`: generate the 9x9 course maze, validate it, show it with its solution, then
/// draw it into the course scene of an in-process `serve` over the legacy remote API (at
/// CoppeliaSim's default idle rate) and verify it there.
pub fn run(args: DemoArgs) -> Result<ExitCode> {
    let grid = Grid::new(course::SIZE.into(), course::SIZE.into())?;
    let layout =
        build_layout(&GenerateSpec::course(grid, args.algo, args.seed)).map_err(|e| anyhow!(e))?;
    let report = validate(&layout);
    if !report.is_ok() {
        bail!(
            "the generated maze failed validation: {}",
            report.problems[0].worded(&super::wording::Flags)
        );
    }
    let picture = Format::Ascii.render_to_vec(
        &layout,
        &RenderOptions {
            solution: true,
            ..Default::default()
        },
    )?;
    outln!("{}", String::from_utf8_lossy(&picture).trim_end())?;
    outln!("OK {}", describe(&layout, layout.segments.len()))?;
    if let Some(metrics) = &report.metrics {
        print_metrics(metrics)?;
    }
    outln!(
        "(S start, E end, . solution; `vrep-maze generate --seed {} --algo {} -o maze.json` writes this layout)",
        args.seed,
        args.algo
    )?;
    draw_into_emulator(&layout)?;
    Ok(ExitCode::SUCCESS)
}

/// Starts the legacy emulator on a free loopback port, applies `layout` through our client,
/// verifies it, and reports what the emulated scene holds.
fn draw_into_emulator(layout: &crate::layout::Layout) -> Result<()> {
    // the time a real CoppeliaSim 4.5.1 takes, so the figure printed is what to expect
    let config = ServerConfig {
        listen: SocketAddr::from(([127, 0, 0, 1], 0)),
        timing: Timing::realistic(),
        ..ServerConfig::default()
    };
    let server = spawn(config, Simulator::new(SimScene::course(), DEFAULT_IDLE_FPS))
        .context("starting the emulated simulator")?;
    let port = server.local_addr().port();
    let drawing = Drawing::try_from(layout)?;
    let result = (|| -> Result<String> {
        let mut scene = LegacyBackend::connect("127.0.0.1", port, Duration::from_secs(10))?;
        let report = draw::apply(&mut scene, &drawing, &ApplyOptions::default(), &mut |_| {})?;
        draw::verify(&mut scene, &drawing, &ObjectNames::default())?;
        Ok(super::summary::apply_line(&report))
    })();
    let lines = server.with_sim(|sim| sim.scene.objects().filter(|o| o.alias == "Line").count());
    server.shutdown();
    let report = result?;
    outln!(
        "\nDrawn into an emulated CoppeliaSim (`vrep-maze serve`, legacy remote API, idle fps {DEFAULT_IDLE_FPS}):"
    )?;
    outln!("  {report}")?;
    outln!("  verified: the scene holds {lines} green lines, Start and End where the layout says")?;
    outln!("(with CoppeliaSim running: `vrep-maze apply maze.json`, see the README)")?;
    Ok(())
}
