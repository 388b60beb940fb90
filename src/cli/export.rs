//! `vrep-maze export`: a layout as a file another program loads: CoppeliaSim XML, MuJoCo
//! MJCF, Gazebo SDF, URDF, a Webots world, Gymnasium-Robotics' PointMaze arguments or a ROS
//! map_server occupancy map.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::Args;

use super::output::write_output;
use super::usage::{ensure_usage, export_error, usage};
use crate::atomic_file::write_all_or_none;
use crate::export::{Format, Target, export, ros_map};

/// Options of `export`.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  vrep-maze export maze.json -o maze.simmodel.xml   # a model to drag into any scene\n  vrep-maze export maze.json -o maze.simscene.xml   # a complete scene: Floor, Maze, Start, End\n  vrep-maze export maze.json -o maze.mjcf           # MuJoCo\n  vrep-maze export maze.json -o maze.world          # Gazebo (SDF)\n  vrep-maze export maze.json -o maze.urdf           # URDF\n  vrep-maze export maze.json -o maze.wbt            # Webots\n  vrep-maze export maze.json -o maze.pointmaze.json # Gymnasium-Robotics PointMaze/AntMaze maze_map\n  vrep-maze export maze.json -o maze.yaml           # ROS map_server: maze.yaml + maze.pgm\n  vrep-maze export maze.json -o maze.xml --format mjcf   # any name, the format named"
)]
pub struct ExportArgs {
    /// The layout file (`-` reads standard input).
    pub file: PathBuf,
    /// The file to write; its ending chooses the format ([`output_help`] lists them).
    #[arg(short, long, help = output_help())]
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

/// `--output`'s help: every ending and what it writes, from [`Format::ALL`] and the ROS
/// map's [`ros_map::FILE_ENDINGS`], so no ending is listed by hand.
fn output_help() -> String {
    let formats = Format::ALL
        .iter()
        .map(|f| format!("{} ({})", f.file_endings().join(" or "), f.label()));
    let ros = format!(
        "{} (a ROS map_server occupancy map: the YAML and beside it the PGM image of the same name)",
        ros_map::FILE_ENDINGS.join(" or ")
    );
    let endings: Vec<String> = formats.chain([ros]).collect();
    format!(
        "The file to write; its ending chooses the format: {}",
        endings.join(", ")
    )
}

/// Runs `export`: the layout is read and validated completely before anything is written,
/// and the file is replaced atomically.
pub fn run(args: ExportArgs) -> Result<ExitCode> {
    let target = Target::from_path(&args.output);
    if args.format.is_none() && target == Some(Target::RosMap) {
        return ros_map(&args);
    }
    ensure_usage!(
        args.px_per_m.is_none() && !args.occupied_lines,
        "--px-per-m and --occupied-lines shape a ROS map (-o FILE.yaml), not {}",
        args.output.display()
    );
    let format = match args.format {
        Some(format) => format,
        None => match target {
            Some(Target::Format(format)) => format,
            _ => return Err(usage(Format::refusal(&args.output, true))),
        },
    };
    let layout = crate::layout::read_layout(&args.file)?;
    let mut text = Vec::new();
    export(format, &layout, &mut text)
        .map_err(export_error)
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

/// `export -o maze.yaml`: the PGM beside the YAML (same name, `.pgm`) and the YAML naming
/// it, both replaced atomically or neither written.
fn ros_map(args: &ExportArgs) -> Result<ExitCode> {
    let layout = crate::layout::read_layout(&args.file)?;
    ensure_usage!(
        !args.occupied_lines || layout.style == crate::layout::Style::Lines,
        "--occupied-lines is for a line maze; {} is a wall maze, whose walls are occupied",
        args.file.display()
    );
    let pgm = args.output.with_extension("pgm");
    // the YAML names the image in UTF-8: a name that is not would name another file
    let image = pgm.file_name().and_then(|n| n.to_str());
    ensure_usage!(
        image.is_some(),
        "{}: a ROS map's YAML names its image in UTF-8, and this file name is not UTF-8",
        pgm.display()
    );
    let image = image.unwrap_or_default().to_string();
    let options = ros_map::Options {
        px_per_metre: args.px_per_m,
        lines: if args.occupied_lines {
            ros_map::Lines::Occupied
        } else {
            ros_map::Lines::Free
        },
    };
    let map = ros_map::map(&layout, &options, &image)
        .map_err(export_error)
        .with_context(|| format!("{}: nothing was exported", args.file.display()))?;
    // both files or neither: a YAML that cannot be written leaves no PGM behind
    write_all_or_none(&[(&pgm, &map.pgm), (&args.output, map.yaml.as_bytes())]).map_err(|e| {
        anyhow::Error::new(e.error).context(format!(
            "{}: cannot write, so neither file was written",
            e.path.display()
        ))
    })?;
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
