//! `vrep-maze export`: a layout as a file another program loads: CoppeliaSim XML, MuJoCo
//! MJCF, Gazebo SDF, URDF, a Webots world, Gymnasium-Robotics' PointMaze arguments or a ROS
//! map_server occupancy map.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::Args;

use super::output::write_output;
use super::usage::{ensure_usage, usage};
use crate::export::{Format, export, ros_map};

/// Options of `export`.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  vrep-maze export maze.json -o maze.simmodel.xml   # a model to drag into any scene\n  vrep-maze export maze.json -o maze.simscene.xml   # a complete scene: Floor, Maze, Start, End\n  vrep-maze export maze.json -o maze.mjcf           # MuJoCo\n  vrep-maze export maze.json -o maze.world          # Gazebo (SDF)\n  vrep-maze export maze.json -o maze.urdf           # URDF\n  vrep-maze export maze.json -o maze.wbt            # Webots\n  vrep-maze export maze.json -o maze.pointmaze.json # Gymnasium-Robotics PointMaze/AntMaze maze_map\n  vrep-maze export maze.json -o maze.yaml           # ROS map_server: maze.yaml + maze.pgm\n  vrep-maze export maze.json -o maze.xml --format mjcf   # any name, the format named"
)]
pub struct ExportArgs {
    /// The layout file (`-` reads standard input).
    pub file: PathBuf,
    /// The file to write; its ending chooses the format: .simmodel.xml (CoppeliaSim model),
    /// .simscene.xml (CoppeliaSim scene), .mjcf or .mujoco.xml (MuJoCo), .sdf or .world
    /// (Gazebo), .urdf, .wbt (Webots), .pointmaze.json (Gymnasium-Robotics PointMaze/AntMaze),
    /// .yaml or .yml (a ROS map_server occupancy map: the YAML and beside it the PGM image of
    /// the same name).
    #[arg(short, long)]
    pub output: PathBuf,
    /// The format, whatever the output's ending (for a bare `.xml`, say).
    #[arg(long, value_name = "NAME")]
    pub format: Option<Format>,
    /// ROS map: pixels a metre [default: the thinnest line, wall or post two pixels across,
    /// at least 20 (5 cm a pixel)].
    #[arg(long, value_name = "PX")]
    pub px_per_m: Option<f64>,
    /// ROS map of a line maze: the lines occupied on free ground, instead of free lines on
    /// occupied ground (the robot may drive on the lines only).
    #[arg(long)]
    pub occupied_lines: bool,
}

/// Runs `export`: the layout is read and validated completely before anything is written,
/// and the file is replaced atomically.
pub fn run(args: ExportArgs) -> Result<ExitCode> {
    let ros = args.format.is_none() && is_ros_map(&args.output);
    if ros {
        return ros_map(&args);
    }
    ensure_usage!(
        args.px_per_m.is_none() && !args.occupied_lines,
        "--px-per-m and --occupied-lines shape a ROS map (-o FILE.yaml), not {}",
        args.output.display()
    );
    let format = match args.format {
        Some(format) => format,
        None => Format::from_path(&args.output)
            .ok_or_else(|| usage(Format::refusal(&args.output, true)))?,
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

/// Whether `path` ends as a ROS map's YAML does ([`ros_map::FILE_ENDINGS`]).
fn is_ros_map(path: &Path) -> bool {
    let name = path.to_string_lossy().to_ascii_lowercase();
    ros_map::FILE_ENDINGS.iter().any(|e| name.ends_with(e))
}

/// `export -o maze.yaml`: the PGM beside the YAML (same name, `.pgm`), then the YAML
/// naming it, each replaced atomically.
fn ros_map(args: &ExportArgs) -> Result<ExitCode> {
    let layout = crate::layout::read_layout(&args.file)?;
    ensure_usage!(
        !args.occupied_lines || layout.style == crate::layout::Style::Lines,
        "--occupied-lines is for a line maze; {} is a wall maze, whose walls are occupied",
        args.file.display()
    );
    let pgm = args.output.with_extension("pgm");
    let image = pgm
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let options = ros_map::Options {
        px_per_metre: args.px_per_m,
        lines: if args.occupied_lines {
            ros_map::Lines::Occupied
        } else {
            ros_map::Lines::Free
        },
    };
    let map = ros_map::map(&layout, &options, &image)
        .with_context(|| format!("{}: nothing was exported", args.file.display()))?;
    write_output(Some(&pgm), |w| w.write_all(&map.pgm))?;
    write_output(Some(&args.output), |w| w.write_all(map.yaml.as_bytes()))?;
    super::say::note(format!(
        "wrote {} and {}: a ROS map_server occupancy map of {}, {} x {} px at {} m a pixel",
        args.output.display(),
        pgm.display(),
        super::validate::describe(&layout, layout.segments.len()),
        map.size[0],
        map.size[1],
        map.resolution
    ));
    Ok(ExitCode::SUCCESS)
}
