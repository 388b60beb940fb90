//! CoppeliaSim's XML scene and model format (`.simscene.xml`, `.simmodel.xml`), as far as
//! this project writes and reads it: dummies and mesh shapes with their pose, parent, alias,
//! model base flag, special properties, colour and dynamics switches.
//!
//! [`fn@write`] emits the element structure a real CoppeliaSim 4.5.1 writes (the reference
//! files in `../shared/spec/coppeliasim-xml/`: the course scene, the `Line` plane as a model,
//! a mesh of two rectangles as a model), the same bytes for the same [`Document`]. It leaves out
//! only what must not repeat between files or may be left out (spec, "One object instead of
//! thousands": a model without `<normals>` and `<edges>` loaded correctly): the objects'
//! random `dnaString` and `uniquePersistentString` and the scene's persistent id, which a
//! real CoppeliaSim makes new when they are missing (coppeliaSimLib 4.5.1
//! `sceneObject.cpp:3303-3307`). [`read`] takes what [`fn@write`] emits and what the reference
//! files hold; anything else (other object types, compound shapes, meshes in side files, a
//! broken tree) is a one-line [`XmlError`], never a panic.
//!
//! Both our clients (the legacy mesh drawing, `export`) and our emulator (`simxLoadModel`,
//! `sim.loadModel`, `sim.saveModel`) use this module, so it sits in the CoppeliaSim
//! vocabulary layer.

mod read;
mod write;

pub use read::read;
pub use write::write;

/// The most bytes of an XML model or scene file the emulator loads (`simxLoadModel`,
/// `sim.loadModel`): far above a mesh model of the largest maze, so a path to an endless
/// or huge file (`/dev/zero`, a disk image) fails after a bounded read.
pub const MAX_FILE_BYTES: u64 = 4 << 30;

/// The text of the XML file at `path`, read within [`MAX_FILE_BYTES`]; the error says why not.
pub fn read_file(path: &std::path::Path) -> std::io::Result<String> {
    use std::io::Read;
    let mut text = String::new();
    std::fs::File::open(path)?
        .take(MAX_FILE_BYTES + 1)
        .read_to_string(&mut text)?;
    if text.len() as u64 > MAX_FILE_BYTES {
        return Err(std::io::Error::other(format!(
            "more than {} GiB: not a model",
            MAX_FILE_BYTES >> 30
        )));
    }
    Ok(text)
}

/// Whether a file is a model (dragged into a scene) or a whole scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileKind {
    /// `exhaustiveModel`: a tree of objects under one model base (`.simmodel.xml`).
    Model,
    /// `exhaustiveScene`: every object of a scene plus the scene's settings (`.simscene.xml`).
    Scene,
}

impl FileKind {
    /// The `<filetype>` text.
    pub const fn tag(self) -> &'static str {
        match self {
            FileKind::Model => "exhaustiveModel",
            FileKind::Scene => "exhaustiveScene",
        }
    }

    /// The file name ending CoppeliaSim chooses the XML reader by.
    pub const fn extension(self) -> &'static str {
        match self {
            FileKind::Model => ".simmodel.xml",
            FileKind::Scene => ".simscene.xml",
        }
    }
}

/// The objects of one XML file, parents before their children.
#[derive(Debug, Clone, PartialEq)]
pub struct Document {
    /// Model or scene.
    pub kind: FileKind,
    /// The objects; a model's first object is its base.
    pub objects: Vec<XmlObject>,
}

/// One scene object of a file.
#[derive(Debug, Clone, PartialEq)]
pub struct XmlObject {
    /// Its handle inside the file (what `parent` refers to; a loading simulator gives new ones).
    pub handle: i32,
    /// The parent's handle inside the file, `None` at the root.
    pub parent: Option<i32>,
    /// Alias (and old-style name).
    pub alias: String,
    /// Position relative to the parent, metres.
    pub position: [f64; 3],
    /// Orientation relative to the parent as a unit quaternion `[w, x, y, z]` (the file's order).
    pub quaternion: [f64; 4],
    /// Whether the object is a model base (`sim.setModelProperty(h, 0)`).
    pub model_base: bool,
    /// Special properties as `sim.objectspecialproperty_*` bits
    /// ([`crate::coppelia::SPECIAL_COLLIDABLE`], ...).
    pub special: i32,
    /// What kind of object it is.
    pub body: Body,
}

/// The object types this module reads and writes.
#[derive(Debug, Clone, PartialEq)]
pub enum Body {
    /// A dummy.
    Dummy(Dummy),
    /// A shape with one mesh.
    Shape(Shape),
}

/// A dummy's own data.
#[derive(Debug, Clone, PartialEq)]
pub struct Dummy {
    /// Its drawn size, metres.
    pub size: f64,
    /// Ambient-diffuse colour, RGB in 0..=1.
    pub colour: [f32; 3],
}

/// A shape with one mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct Shape {
    /// The triangles, in the shape's frame.
    pub mesh: Mesh,
    /// Ambient-diffuse colour, RGB in 0..=1.
    pub colour: [f32; 3],
    /// The primitive the mesh is (a plane or cuboid made by CoppeliaSim), or none.
    pub primitive: Primitive,
    /// Static: not moved by the physics engine.
    pub is_static: bool,
    /// Respondable: collides in the physics engine.
    pub respondable: bool,
}

/// A pure primitive shape's kind and sizes (x, y, z in metres).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Primitive {
    /// A general mesh.
    None,
    /// `plane` (z is CoppeliaSim's 0.0001).
    Plane([f64; 3]),
    /// `cuboid`.
    Cuboid([f64; 3]),
}

/// Triangles: vertex positions and three vertex indices per triangle.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Mesh {
    /// Vertex positions (x, y, z), metres.
    pub vertices: Vec<[f32; 3]>,
    /// Vertex indices, three per triangle.
    pub indices: Vec<u32>,
}

impl Mesh {
    /// Number of triangles.
    pub fn triangles(&self) -> usize {
        self.indices.len() / 3
    }

    /// The axis-aligned bounding box `(min, max)` of the vertices, `None` without any.
    pub fn bounds(&self) -> Option<([f64; 3], [f64; 3])> {
        let first = self.vertices.first()?;
        let widen = |v: &[f32; 3]| v.map(f64::from);
        Some(
            self.vertices
                .iter()
                .fold((widen(first), widen(first)), |(lo, hi), v| {
                    let v = widen(v);
                    (
                        std::array::from_fn(|k| lo[k].min(v[k])),
                        std::array::from_fn(|k| hi[k].max(v[k])),
                    )
                }),
        )
    }
}

impl Mesh {
    /// A mesh from flat `x, y, z` floats and three indices per triangle (as the drawing
    /// code keeps them); `None` when the counts do not make triples or an index names no
    /// vertex.
    pub fn from_flat(vertices: &[f32], indices: &[i32]) -> Option<Mesh> {
        let count = vertices.len() / 3;
        if !vertices.len().is_multiple_of(3) || !indices.len().is_multiple_of(3) {
            return None;
        }
        let indices = indices
            .iter()
            .map(|&i| u32::try_from(i).ok().filter(|&i| (i as usize) < count))
            .collect::<Option<Vec<u32>>>()?;
        Some(Mesh {
            vertices: vertices
                .chunks_exact(3)
                .map(|v| [v[0], v[1], v[2]])
                .collect(),
            indices,
        })
    }
}

/// The identity rotation as a file quaternion `[w, x, y, z]`.
pub const IDENTITY: [f64; 4] = [1.0, 0.0, 0.0, 0.0];

/// The rotation by `yaw` radians about z as a file quaternion `[w, x, y, z]`.
pub fn yaw_quaternion(yaw: f64) -> [f64; 4] {
    [(yaw / 2.0).cos(), 0.0, 0.0, (yaw / 2.0).sin()]
}

impl XmlObject {
    /// A dummy of `size` and `colour` on its parent's frame, no special properties (as
    /// CoppeliaSim makes them), not a model base.
    pub fn dummy(
        handle: i32,
        parent: Option<i32>,
        alias: &str,
        size: f64,
        colour: [f32; 3],
    ) -> XmlObject {
        XmlObject {
            handle,
            parent,
            alias: alias.to_string(),
            position: [0.0; 3],
            quaternion: IDENTITY,
            model_base: false,
            special: 0,
            body: Body::Dummy(Dummy { size, colour }),
        }
    }

    /// A static mesh shape on its parent's frame (its vertices are in that frame), with
    /// `special` properties, respondable or not.
    pub fn static_mesh(
        handle: i32,
        parent: Option<i32>,
        alias: &str,
        mesh: Mesh,
        look: ([f32; 3], i32),
        respondable: bool,
    ) -> XmlObject {
        XmlObject {
            handle,
            parent,
            alias: alias.to_string(),
            position: [0.0; 3],
            quaternion: IDENTITY,
            model_base: false,
            special: look.1,
            body: Body::Shape(Shape {
                mesh,
                colour: look.0,
                primitive: Primitive::None,
                is_static: true,
                respondable,
            }),
        }
    }
}

/// Why a file could not be read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum XmlError {
    /// The text is not well-formed XML.
    #[error("not well-formed XML: {0}")]
    Syntax(String),
    /// Well-formed, but not something this reader knows.
    #[error("{0}")]
    Unsupported(String),
    /// A node's content is wrong (names the node).
    #[error("<{node}>: {problem}")]
    Bad {
        /// The node's path, `sceneObject[2]/shape/common/handle`.
        node: String,
        /// What is wrong with it.
        problem: String,
    },
}

#[cfg(test)]
pub(crate) mod tests;
