//! CoppeliaSim's XML scene and model format (`.simscene.xml`, `.simmodel.xml`), as far as
//! this project writes and reads it: dummies and mesh shapes with their pose, parent, alias,
//! model base flag, special properties, colour and dynamics switches.
//!
//! [`write`] emits the element structure a real CoppeliaSim 4.5.1 writes (the reference files
//! in `../shared/spec/coppeliasim-xml/`: the course scene, the `Line` plane as a model, a mesh
//! of two rectangles as a model), the same bytes for the same [`Document`]. It leaves out
//! only what must not repeat between files or may be left out (spec, "One object instead of
//! thousands": a model without `<normals>` and `<edges>` loaded correctly): the objects'
//! random `dnaString` and `uniquePersistentString` and the scene's persistent id, which a
//! real CoppeliaSim makes new when they are missing (coppeliaSimLib 4.5.1
//! `sceneObject.cpp:3303-3307`). [`read`] takes what [`write`] emits and what the reference
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
mod tests;
