//! A layout as a file another program loads, one file per format, chosen by the output's
//! ending ([`Format::from_path`]). Today CoppeliaSim's own XML: a model to drag into any scene
//! ([`simmodel`]) and a complete scene ([`simscene`]), both loadable without any remote API
//! (CoppeliaSim 4.11 has no legacy API). Both draw the maze as meshes
//! ([`crate::draw::mesh::geometry`]: one rectangle per run of lines, boxes for walls and
//! posts), written by [`crate::coppelia::xml::write`], the writer the legacy mesh drawing uses.
//!
//! A new format (MJCF, SDF, URDF, Webots) is a file here with its `export` function and a
//! [`Format`] variant with its arms in `ALL`, `endings` and [`export`].

mod simmodel;
mod simscene;

use std::io;
use std::path::Path;

use crate::draw::mesh::MeshMaze;
use crate::layout::Layout;

/// The formats `export` writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// CoppeliaSim XML model (`.simmodel.xml`): the `Maze` dummy as model base holding the
    /// meshes.
    CoppeliaModel,
    /// CoppeliaSim XML scene (`.simscene.xml`): Floor, Maze with the meshes, Start, End (and
    /// the Line template of a line maze, so `apply` can draw into it).
    CoppeliaScene,
}

impl Format {
    /// Every format.
    pub const ALL: [Format; 2] = [Format::CoppeliaModel, Format::CoppeliaScene];

    /// The file name ending that chooses it.
    pub const fn ending(self) -> &'static str {
        match self {
            Format::CoppeliaModel => ".simmodel.xml",
            Format::CoppeliaScene => ".simscene.xml",
        }
    }

    /// The format a file name's ending names (case-insensitive), if any.
    pub fn from_path(path: &Path) -> Option<Format> {
        let name = path.file_name()?.to_str()?.to_ascii_lowercase();
        Format::ALL
            .into_iter()
            .find(|f| name.ends_with(f.ending()) && name.len() > f.ending().len())
    }

    /// The endings of every format, for messages: `.simmodel.xml, .simscene.xml`.
    pub fn endings() -> String {
        Format::ALL.map(Format::ending).join(", ")
    }
}

/// Writes `layout` in `format` to `out`. The layout must pass [`crate::validate::checked`]
/// (checked here, before anything is written).
pub fn export(format: Format, layout: &Layout, out: &mut dyn io::Write) -> anyhow::Result<()> {
    let maze = MeshMaze::try_from(layout)?;
    let text = match format {
        Format::CoppeliaModel => simmodel::document(&maze),
        Format::CoppeliaScene => simscene::document(layout, &maze),
    };
    out.write_all(crate::coppelia::xml::write(&text).as_bytes())?;
    Ok(())
}

#[cfg(test)]
mod tests;
