//! A layout as a file another program loads, one file per format, chosen by the output's
//! ending ([`Format::from_path`]): the robot simulators' own formats, MuJoCo MJCF
//! ([`mjcf`]), Gazebo SDF ([`sdf`]), URDF ([`urdf`]) and Webots ([`webots`]), all written
//! from the same boxes ([`solids`], from the mesh geometry).

mod mjcf;
mod sdf;
mod solids;
mod urdf;
mod webots;

use std::io;
use std::path::Path;

use crate::draw::mesh::MeshMaze;
use crate::layout::Layout;
use solids::Solids;

/// The formats `export` writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// MuJoCo MJCF (`.mjcf`, `.mujoco.xml`): box geoms in a body welded to the world.
    Mjcf,
    /// Gazebo SDFormat world (`.sdf`, `.world`): a ground plane and the maze as one static
    /// model.
    Sdf,
    /// URDF (`.urdf`): one link fixed to the world, a collision and a visual box per wall run.
    Urdf,
    /// Webots world (`.wbt`): the maze as one static solid.
    Webots,
}

impl Format {
    /// Every format.
    pub const ALL: [Format; 4] = [Format::Mjcf, Format::Sdf, Format::Urdf, Format::Webots];

    /// The file name endings that choose it.
    pub const fn endings(self) -> &'static [&'static str] {
        match self {
            Format::Mjcf => &[".mjcf", ".mujoco.xml"],
            Format::Sdf => &[".sdf", ".world"],
            Format::Urdf => &[".urdf"],
            Format::Webots => &[".wbt"],
        }
    }

    /// The format a file name's ending names (case-insensitive), if any.
    pub fn from_path(path: &Path) -> Option<Format> {
        let name = path.file_name()?.to_str()?.to_ascii_lowercase();
        Format::ALL.into_iter().find(|f| {
            f.endings()
                .iter()
                .any(|e| name.ends_with(e) && name.len() > e.len())
        })
    }

    /// The endings of every format, for messages: `.mjcf, .mujoco.xml, .sdf, ...`.
    pub fn all_endings() -> String {
        Format::ALL
            .iter()
            .flat_map(|f| f.endings())
            .copied()
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// Writes `layout` in `format` to `out`. The layout must pass [`crate::validate::checked`]
/// (checked here, before anything is written).
pub fn export(format: Format, layout: &Layout, out: &mut dyn io::Write) -> anyhow::Result<()> {
    let maze = MeshMaze::try_from(layout)?;
    let solids = Solids::new(layout, &maze);
    let text = match format {
        Format::Mjcf => mjcf::document(&solids),
        Format::Sdf => sdf::document(&solids),
        Format::Urdf => urdf::document(&solids),
        Format::Webots => webots::document(&solids),
    };
    out.write_all(text.as_bytes())?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use solids::tests::{line_layout, post_layout};

    #[test]
    fn endings_choose_formats() {
        for (name, format) in [
            ("m.mjcf", Some(Format::Mjcf)),
            ("m.MuJoCo.XML", Some(Format::Mjcf)),
            ("m.sdf", Some(Format::Sdf)),
            ("dir/m.world", Some(Format::Sdf)),
            ("m.urdf", Some(Format::Urdf)),
            ("m.wbt", Some(Format::Webots)),
            ("m.xml", None),
            (".urdf", None),
            ("m.png", None),
        ] {
            assert_eq!(Format::from_path(Path::new(name)), format, "{name}");
        }
        assert_eq!(
            Format::all_endings(),
            ".mjcf, .mujoco.xml, .sdf, .world, .urdf, .wbt"
        );
    }

    #[test]
    fn same_layout_same_bytes_and_invalid_layouts_write_nothing() {
        for layout in [line_layout(17.0), post_layout(-40.0)] {
            for format in Format::ALL {
                let (mut a, mut b) = (Vec::new(), Vec::new());
                export(format, &layout, &mut a).unwrap();
                export(format, &layout.clone(), &mut b).unwrap();
                assert_eq!(a, b);
                assert!(!a.is_empty());
            }
        }
        let mut bad = post_layout(0.0);
        bad.grid.cell_size = -1.0;
        let mut out = Vec::new();
        assert!(export(Format::Sdf, &bad, &mut out).is_err());
        assert!(out.is_empty());
    }
}
