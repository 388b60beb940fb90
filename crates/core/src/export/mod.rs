//! A layout as a file another program loads, one file per format, chosen by the output's
//! ending ([`Format::from_path`]). CoppeliaSim's own XML comes as a model to drag into any
//! scene (`simmodel`) and as a complete scene (`simscene`), both loadable without any remote API
//! (CoppeliaSim 4.11 has no legacy API). Both draw the maze as meshes
//! ([`crate::mesh`]: one rectangle per run of lines, boxes for walls and
//! posts), written by [`crate::coppelia::xml::write`], the writer the legacy mesh drawing uses.
//!
//! The robot simulators' own formats, MuJoCo MJCF (`mjcf`), Gazebo SDF (`sdf`), URDF
//! (`urdf`) and Webots (`webots`), are written from one set of boxes (`solids`: a box
//! per wall run, post, run of lines and marker, from the same mesh geometry).
//! Gymnasium-Robotics' PointMaze/AntMaze arguments (`pointmaze`) are the layout's block grid
//! ([`crate::layout::block_grid`]).
//!
//! A ROS `map_server` occupancy map ([`ros_map`]) is two files, a YAML and a PGM beside it,
//! so it is no [`Format`]: `export -o maze.yaml` chooses it by its ending
//! ([`ros_map::FILE_ENDINGS`]).
//!
//! A new format is a file here with its `document` function and a [`Format`] variant with its
//! arms in `ALL`, `label`, `file_endings` and [`export`]; every list a person reads is derived
//! from [`Format::ALL`] or held against it by `tests/it/export_lists.rs`. ARCHITECTURE.md's
//! recipe names every place.

mod mjcf;
mod pointmaze;
pub mod ros_map;
mod sdf;
mod simmodel;
mod simscene;
mod solids;
mod urdf;
mod webots;
mod xml;

use std::io;
use std::path::Path;

use crate::layout::Layout;
use crate::layout::block_grid::BlockGrid;
use crate::mesh::MeshMaze;
use crate::wording::{Message, Opt, Value};
use solids::Solids;

/// The formats `export` writes (`--format` names them in kebab case: `coppelia-model`, ...).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum Format {
    /// CoppeliaSim XML model (`.simmodel.xml`): the `Maze` dummy as model base holding the
    /// meshes.
    CoppeliaModel,
    /// CoppeliaSim XML scene (`.simscene.xml`): Floor, Maze with the meshes, Start, End (and
    /// the Line template of a line maze, so `apply` can draw into it).
    CoppeliaScene,
    /// MuJoCo MJCF (`.mjcf`, `.mujoco.xml`): the floor plane, box geoms in a body welded to
    /// the world, `start` and `end` sites.
    Mjcf,
    /// Gazebo SDFormat world (`.sdf`, `.world`): a ground plane and the maze as one static
    /// model.
    Sdf,
    /// URDF (`.urdf`): one link fixed to the world, a collision and a visual box per wall run
    /// and post.
    Urdf,
    /// Webots world (`.wbt`): the floor and the maze as one static solid.
    Webots,
    /// Gymnasium-Robotics PointMaze/AntMaze arguments (`.pointmaze.json`): `maze_map`, the
    /// block grid of [`crate::layout::block_grid`], and `maze_size_scaling`.
    PointMaze,
}

impl Format {
    /// Every format.
    pub const ALL: [Format; 7] = [
        Format::CoppeliaModel,
        Format::CoppeliaScene,
        Format::Mjcf,
        Format::Sdf,
        Format::Urdf,
        Format::Webots,
        Format::PointMaze,
    ];

    /// What it is, for a person (`CoppeliaSim XML model`, `MuJoCo MJCF`, ...).
    pub const fn label(self) -> &'static str {
        match self {
            Format::CoppeliaModel => "a CoppeliaSim XML model",
            Format::CoppeliaScene => "a CoppeliaSim XML scene",
            Format::Mjcf => "a MuJoCo MJCF model",
            Format::Sdf => "a Gazebo SDFormat world",
            Format::Urdf => "a URDF robot description",
            Format::Webots => "a Webots world",
            Format::PointMaze => "Gymnasium-Robotics PointMaze arguments",
        }
    }

    /// The file name endings that choose it.
    pub const fn file_endings(self) -> &'static [&'static str] {
        match self {
            Format::CoppeliaModel => &[".simmodel.xml"],
            Format::CoppeliaScene => &[".simscene.xml"],
            Format::Mjcf => &[".mjcf", ".mujoco.xml"],
            Format::Sdf => &[".sdf", ".world"],
            Format::Urdf => &[".urdf"],
            Format::Webots => &[".wbt"],
            Format::PointMaze => &[".pointmaze.json"],
        }
    }

    /// The format a file name's ending names (case-insensitive), if any.
    pub fn from_path(path: &Path) -> Option<Format> {
        let name = path.file_name()?.to_str()?.to_ascii_lowercase();
        Format::ALL.into_iter().find(|f| {
            f.file_endings()
                .iter()
                .any(|e| name.ends_with(e) && name.len() > e.len())
        })
    }

    /// Why `path` names no format, in one line: a bare `.xml` is ambiguous (CoppeliaSim or
    /// MuJoCo), anything else unknown; both list every ending, and with `format_option`
    /// (the caller takes a format by name too) say that it may be named.
    pub fn refusal(path: &Path, format_option: bool) -> Message {
        let bare_xml = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("xml"));
        let refusal = Message::text(format!(
            "{}: {}export writes {} files (the ending chooses the format",
            path.display(),
            if bare_xml {
                "a bare .xml is ambiguous; "
            } else {
                ""
            },
            Format::endings()
        ));
        match format_option {
            true => refusal
                .and(", or ")
                .and_setting(Opt::Format, Value::Placeholder("NAME"))
                .and(")"),
            false => refusal.and(")"),
        }
    }

    /// The endings of every format, for messages: `.simmodel.xml, .simscene.xml, .mjcf, ...`,
    /// and last the ROS map's ([`ros_map::FILE_ENDINGS`]).
    pub fn endings() -> String {
        Format::ALL
            .iter()
            .flat_map(|f| f.file_endings())
            .chain(&ros_map::FILE_ENDINGS)
            .copied()
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// What an output file asks `export` to write, by its ending ([`Target::from_path`]): a
/// [`Format`], or the ROS map (a YAML and a PGM beside it, [`ros_map::FILE_ENDINGS`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// One file in this format.
    Format(Format),
    /// A ROS map_server occupancy map.
    RosMap,
}

impl Target {
    /// The target `path`'s ending chooses (case-insensitive), if any: the one place the
    /// command line and Python read an output's ending.
    pub fn from_path(path: &Path) -> Option<Target> {
        let name = path.to_string_lossy().to_ascii_lowercase();
        if ros_map::FILE_ENDINGS.iter().any(|e| name.ends_with(e)) {
            return Some(Target::RosMap);
        }
        Format::from_path(path).map(Target::Format)
    }
}

/// Why a layout was not exported.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// The layout is invalid ([`crate::validate::checked`]).
    #[error(transparent)]
    Invalid(#[from] crate::validate::Invalid),
    /// It has no block grid (PointMaze).
    #[error(transparent)]
    BlockGrid(#[from] crate::layout::block_grid::BlockGridError),
    /// Options it refuses (a ROS map's scale), named as data.
    #[error(transparent)]
    Refused(#[from] Message),
    /// Writing failed.
    #[error(transparent)]
    Io(#[from] io::Error),
}

/// Writes `layout` in `format` to `out`. The layout must pass [`crate::validate::checked`]
/// (checked here, before anything is written).
pub fn export(format: Format, layout: &Layout, out: &mut dyn io::Write) -> Result<(), ExportError> {
    let maze = MeshMaze::try_from(layout)?;
    let text = match format {
        Format::CoppeliaModel => crate::coppelia::xml::write(&simmodel::document(&maze)),
        Format::CoppeliaScene => crate::coppelia::xml::write(&simscene::document(layout, &maze)),
        Format::Mjcf => mjcf::document(&Solids::new(layout, &maze)),
        Format::Sdf => sdf::document(&Solids::new(layout, &maze)),
        Format::Urdf => urdf::document(&Solids::new(layout, &maze)),
        Format::Webots => webots::document(&Solids::new(layout, &maze)),
        Format::PointMaze => pointmaze::document(&BlockGrid::of(layout)?),
    };
    out.write_all(text.as_bytes())?;
    Ok(())
}

#[cfg(test)]
mod tests;
