//! `vrep-maze export`: a layout as a file another program loads: CoppeliaSim XML, MuJoCo
//! MJCF, Gazebo SDF, URDF, a Webots world or
//! Gymnasium-Robotics' PointMaze arguments.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::Args;

use super::output::write_output;
use super::usage;
use crate::export::{Format, export};

/// Options of `export`.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  vrep-maze export maze.json -o maze.simmodel.xml   # a model to drag into any scene\n  vrep-maze export maze.json -o maze.simscene.xml   # a complete scene: Floor, Maze, Start, End\n  vrep-maze export maze.json -o maze.mjcf           # MuJoCo\n  vrep-maze export maze.json -o maze.world          # Gazebo (SDF)\n  vrep-maze export maze.json -o maze.urdf           # URDF\n  vrep-maze export maze.json -o maze.wbt            # Webots\n  vrep-maze export maze.json -o maze.pointmaze.json # Gymnasium-Robotics PointMaze/AntMaze maze_map\n  vrep-maze export maze.json -o maze.xml --format mjcf   # any name, the format named"
)]
pub struct ExportArgs {
    /// The layout file (`-` reads standard input).
    pub file: PathBuf,
    /// The file to write; its ending chooses the format: .simmodel.xml (CoppeliaSim model),
    /// .simscene.xml (CoppeliaSim scene), .mjcf or .mujoco.xml (MuJoCo), .sdf or .world
    /// (Gazebo), .urdf, .wbt (Webots), .pointmaze.json (Gymnasium-Robotics PointMaze/AntMaze).
    #[arg(short, long)]
    pub output: PathBuf,
    /// The format, whatever the output's ending (for a bare `.xml`, say).
    #[arg(long, value_name = "NAME")]
    pub format: Option<Format>,
}

/// Runs `export`: the layout is read and validated completely before anything is written,
/// and the file is replaced atomically.
pub fn run(args: ExportArgs) -> Result<ExitCode> {
    let format = match args.format {
        Some(format) => format,
        None => {
            Format::from_path(&args.output).ok_or_else(|| usage(Format::refusal(&args.output)))?
        }
    };
    let layout = crate::layout::read_layout(&args.file)?;
    let mut text = Vec::new();
    export(format, &layout, &mut text)
        .with_context(|| format!("{}: nothing was exported", args.file.display()))?;
    write_output(Some(&args.output), |w| w.write_all(&text))?;
    // said as `render` says what it wrote
    super::say::note(format!(
        "wrote {}: {} of {}",
        args.output.display(),
        format.label(),
        super::validate::describe(&layout, layout.segments.len())
    ));
    Ok(ExitCode::SUCCESS)
}
