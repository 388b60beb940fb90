//! `vrep-maze render`: draw a layout.

use std::io::{self, IsTerminal, Read};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::str::FromStr;

use anyhow::{Context, Result};
use clap::Args;

use super::listed::listed;
use super::output::write_output;
use super::progress::{Progress, Told, Unit};
use super::say::note;
use super::usage::{ensure_usage, usage};
use super::validate::{describe, read_checking};
use super::values::parse_metres;
use crate::render::{Format, RenderError, RenderOptions, Scale};

/// Options of `render`.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  vrep-maze render maze.json --solution\n  vrep-maze render maze.json --format svg -o maze.svg\n  vrep-maze render maze.json --solution -o maze.png"
)]
pub struct RenderArgs {
    /// The layout file (`-` reads standard input).
    pub file: PathBuf,
    /// ascii (terminal), svg or png [default: from the -o extension, else ascii].
    #[arg(
        long,
        value_parser = listed(Format::from_str, Format::ALL.map(Format::name)),
        hide_possible_values = true
    )]
    pub format: Option<Format>,
    /// Overlay the shortest path from start to end.
    #[arg(long)]
    pub solution: bool,
    /// Write the picture here instead of standard output.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// SVG and PNG: show only the maze (its bounding box, walls and lines included) and a
    /// strip below it for the scale bar, not the whole floor.
    #[arg(long)]
    pub crop: bool,
    /// SVG and PNG: pixels a metre [default: 40 for SVG, 80 for PNG (less on a floor over
    /// 204.8 m); a PNG is at most 16384 px a side].
    #[arg(long, value_name = "PX", value_parser = parse_metres)]
    pub px_per_m: Option<f64>,
    /// SVG and PNG: the picture this many pixels wide (the height follows).
    #[arg(long, value_name = "PX", conflicts_with = "px_per_m", value_parser = clap::value_parser!(u32).range(1..=16384))]
    pub width: Option<u32>,
    /// Draw a robot's run over the maze (a `score --trajectory` CSV: t,x,y,yaw), coloured
    /// by time, with the solution for comparison (SVG and PNG).
    #[arg(long, value_name = "run.csv")]
    pub trajectory: Option<PathBuf>,
}

/// Runs `render`.
pub fn run(args: RenderArgs, bars: Progress) -> Result<ExitCode> {
    let output = args.output.as_deref().filter(|p| p.as_os_str() != "-");
    if let Some(scene) = scene_dump(&args)? {
        return render_scene(&args, output, &scene);
    }
    let format = choose_format(args.format, output, Format::Ascii)?;
    ensure_usage!(
        args.trajectory.is_none() || format != Format::Ascii,
        "--trajectory draws the run as SVG or PNG only (use --format svg or png, or -o FILE.svg)"
    );
    ensure_usage!(
        format != Format::Png || output.is_some() || !std::io::stdout().is_terminal(),
        "PNG is binary and standard output is a terminal: give -o FILE.png (or redirect the output)"
    );
    // Read once: the segments are validated as they stream past and then dropped; the
    // picture is drawn from the passages, which validation proved they cover exactly.
    let (layout, validator) = read_checking(&args.file, bars)?;
    let validator = validator.finish();
    let segments = validator.segments();
    validator
        .finish()
        .into_result()
        .with_context(|| format!("{}: nothing was rendered", args.file.display()))?;
    let trajectory = match &args.trajectory {
        None => None,
        Some(path) => Some(read_trajectory(path)?),
    };
    ensure_usage!(
        format != Format::Ascii || (!args.crop && args.px_per_m.is_none() && args.width.is_none()),
        "--crop, --px-per-m and --width shape SVG and PNG pictures, not ASCII (give --format svg|png or -o FILE.svg|.png)"
    );
    let options = RenderOptions {
        solution: args.solution || trajectory.is_some(),
        crop: args.crop,
        scale: match (args.px_per_m, args.width) {
            (Some(px), _) => Scale::PxPerMetre(px),
            (_, Some(width)) => Scale::Width(width),
            _ => Scale::Default,
        },
    };
    // Each renderer sets the length: maze rows, or pixel rows for PNG.
    let progress = bars.bar("rendering", 0, Unit::Items("rows"));
    let told = Told(&progress);
    // The picture streams into the output; a failure that is not the output's own (an
    // I/O error) is kept whole here and reported with the layout's name.
    let mut failure = None;
    let written = write_output(output, |w| {
        match &trajectory {
            None => format.renderer().render(&layout, &options, w, &told),
            Some(run) => crate::render::render_run(format, &layout, &options, run, w, &told),
        }
        .map_err(|e| match e {
            RenderError::Io(e) => e,
            // a refusal's options are worded by the command line: the message itself
            RenderError::Refused(message) => {
                failure = Some(anyhow::Error::new(message));
                io::Error::other("the picture could not be drawn")
            }
            other => {
                failure = Some(anyhow::Error::new(other));
                io::Error::other("the picture could not be drawn")
            }
        })
    });
    progress.finish_and_clear();
    if let Some(e) = failure {
        return Err(e.context(format!("{}", args.file.display())));
    }
    written?;
    if let Some(path) = output {
        note(format!(
            "wrote {}: {format} of {}",
            path.display(),
            describe(&layout, segments)
        ));
    }
    Ok(ExitCode::SUCCESS)
}

/// A `--trajectory` file's samples, read within [`super::input::MAX_TRAJECTORY_BYTES`].
fn read_trajectory(path: &Path) -> Result<Vec<crate::score::Sample>> {
    let text = super::input::read_trajectory_text(path)
        .with_context(|| format!("cannot read the trajectory {}", path.display()))?;
    crate::score::trajectory::parse_csv(&text)
        .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))
}

/// The format to write: `--format` if given, else the one the output's extension names, else
/// `default`. An extension that names no format we write, or another format than `--format`,
/// is refused, so a `.png` never holds SVG text and a `.jpg` never holds ASCII.
fn choose_format(
    explicit: Option<Format>,
    output: Option<&Path>,
    default: Format,
) -> Result<Format> {
    let by_extension = match output.and_then(|p| p.extension().map(|e| (p, e))) {
        None => None,
        Some((path, ext)) => Some(Format::from_extension(path).ok_or_else(|| {
            usage(format!(
                "{}: render writes .svg, .png and .txt (ascii) files, not .{}",
                path.display(),
                ext.to_string_lossy()
            ))
        })?),
    };
    match (explicit, by_extension) {
        (Some(f), Some(e)) if f != e => Err(usage(format!(
            "--format {f} does not match the output file's extension (.{})",
            output
                .and_then(|p| p.extension())
                .map(|e| e.to_string_lossy().into_owned())
                .unwrap_or_default()
        ))),
        (f, e) => Ok(f.or(e).unwrap_or(default)),
    }
}
/// Columns of a scene dump's ASCII picture (a classic terminal's width).
const ASCII_COLUMNS: u32 = 80;

/// Draws a scene dump seen from above ([`crate::sim::top_view`]): ASCII by default
/// ([`ASCII_COLUMNS`] wide), SVG or PNG 800 px wide (or `--width`), the format chosen as a
/// layout's is.
fn render_scene(
    args: &RenderArgs,
    output: Option<&Path>,
    scene: &crate::sim::Scene,
) -> Result<ExitCode> {
    use crate::sim::top_view;
    let format = choose_format(args.format, output, Format::Ascii)?;
    ensure_usage!(
        !args.solution && args.trajectory.is_none() && !args.crop && args.px_per_m.is_none(),
        "{}: a scene dump is drawn as it is (--width sets an SVG's or PNG's size; --solution, --trajectory, --crop and --px-per-m draw layouts)",
        args.file.display()
    );
    ensure_usage!(
        format != Format::Png || output.is_some() || !std::io::stdout().is_terminal(),
        "PNG is binary and standard output is a terminal: give -o FILE.png (or redirect the output)"
    );
    let width = args.width.unwrap_or(800);
    let bytes = match format {
        Format::Svg => top_view::scene_svg(scene, f64::from(width)).into_bytes(),
        Format::Png => top_view::scene_png(scene, width)
            .with_context(|| format!("{}: the PNG could not be encoded", args.file.display()))?,
        Format::Ascii => top_view::scene_ascii(scene, ASCII_COLUMNS).into_bytes(),
    };
    write_output(output, |w| w.write_all(&bytes))?;
    if let Some(path) = output {
        note(format!(
            "wrote {}: {format} of the scene dump {} ({} objects)",
            path.display(),
            args.file.display(),
            scene.len()
        ));
    }
    Ok(ExitCode::SUCCESS)
}

/// A `vrep-maze serve --dump` scene file, else `None`.
/// The most bytes of a scene dump read whole.
const MAX_SCENE_DUMP_BYTES: usize = 1 << 30;
/// Bytes read from the start of a file to tell a scene dump from a layout.
const SNIFF: u64 = 4096;

fn scene_dump(args: &RenderArgs) -> Result<Option<crate::sim::Scene>> {
    if args.file.as_os_str() == "-" {
        return Ok(None);
    }
    // A dump says what it is in its first lines: a layout (of any size) is not read whole.
    let Ok(file) = std::fs::File::open(&args.file) else {
        return Ok(None);
    };
    let mut start = Vec::new();
    if file.take(SNIFF).read_to_end(&mut start).is_err()
        || !String::from_utf8_lossy(&start).contains("\"vrep-maze scene\"")
    {
        return Ok(None);
    }
    let text = super::input::read_text(
        &args.file,
        MAX_SCENE_DUMP_BYTES,
        "a scene dump",
        "a dump is read whole, so its size is bounded",
    )?;
    let scene =
        crate::sim::Scene::from_json(&text).with_context(|| format!("{}", args.file.display()))?;
    Ok(Some(scene))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_extension_decides_and_unknown_or_conflicting_ones_are_refused() {
        let f = |explicit, out: Option<&str>| {
            choose_format(explicit, out.map(Path::new), Format::Ascii)
        };
        assert_eq!(f(None, None).unwrap(), Format::Ascii);
        assert_eq!(f(None, Some("m.png")).unwrap(), Format::Png);
        assert_eq!(f(None, Some("M.SVG")).unwrap(), Format::Svg);
        assert_eq!(f(None, Some("maze")).unwrap(), Format::Ascii);
        assert_eq!(f(Some(Format::Svg), Some("maze")).unwrap(), Format::Svg);
        assert_eq!(f(Some(Format::Png), Some("m.png")).unwrap(), Format::Png);
        let jpg = f(None, Some("m.jpg")).unwrap_err().to_string();
        assert!(jpg.contains("not .jpg"), "{jpg}");
        let clash = f(Some(Format::Svg), Some("m.png")).unwrap_err().to_string();
        assert!(
            clash.contains("--format svg") && clash.contains(".png"),
            "{clash}"
        );
        assert!(f(Some(Format::Ascii), Some("m.jpg")).is_err());
    }
}
