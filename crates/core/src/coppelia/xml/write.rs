//! The writer: a [`Document`] as the text a real CoppeliaSim 4.5.1 writes (four-space
//! indentation, numbers as C's `%.4e`, booleans as `true`/`false`). Mesh vertices and normals
//! are written exactly (the shortest text that reads back as the same `f32`) rather than with
//! five digits, so a maze's rectangles keep their ends to the micrometre.

use std::fmt::Write as _;

use super::{Body, Document, Dummy, FileKind, IDENTITY, Mesh, Primitive, Shape, XmlObject};
use crate::coppelia::{
    SPECIAL_COLLIDABLE, SPECIAL_DETECTABLE, SPECIAL_MEASURABLE, SPECIAL_RENDERABLE,
};

/// The material of a shape made by `sim.createMeshShape` (from the reference mesh model).
const MATERIAL: &str = include_str!("material.xml");
/// A scene's settings after its objects: ghosts, settings, environment, dynamics, simulation,
/// views (from the reference course scene).
const SCENE_SETTINGS: &str = include_str!("scene_settings.xml");

/// The special-property bits of the five detection kinds (ultrasonic, infrared, laser,
/// inductive, capacitive), in the order of their tags.
const DETECTION_KINDS: [(&str, i32); 5] = [
    ("ultrasonicDetectable", 16),
    ("infraredDetectable", 32),
    ("laserDetectable", 64),
    ("inductiveDetectable", 128),
    ("capacitiveDetectable", 256),
];

/// `doc` as CoppeliaSim XML text; the same document always gives the same bytes.
pub fn write(doc: &Document) -> String {
    let mut w = Writer::default();
    w.open("CoppeliaSim");
    w.leaf("filetype", doc.kind.tag());
    w.leaf("xmlSerializationNb", "2");
    w.leaf("prgFlavor", "-1");
    w.leaf("prgVer", "40501");
    w.leaf("prgRev", "4");
    if doc.kind == FileKind::Model {
        thumbnail_info(&mut w, doc);
    }
    w.line("<modelThumbnail/>");
    for o in &doc.objects {
        w.open("sceneObject");
        object(&mut w, o);
        w.close("sceneObject");
    }
    if doc.kind == FileKind::Scene {
        w.fragment(SCENE_SETTINGS);
    }
    w.close("CoppeliaSim");
    w.out
}

/// Indented XML text.
#[derive(Default)]
struct Writer {
    out: String,
    depth: usize,
}

impl Writer {
    fn indent(&mut self) {
        for _ in 0..self.depth {
            self.out.push_str("    ");
        }
    }

    fn line(&mut self, text: &str) {
        self.indent();
        self.out.push_str(text);
        self.out.push('\n');
    }

    fn open(&mut self, tag: &str) {
        self.line(&format!("<{tag}>"));
        self.depth += 1;
    }

    fn close(&mut self, tag: &str) {
        self.depth -= 1;
        self.line(&format!("</{tag}>"));
    }

    /// `<tag>text</tag>`, the text escaped.
    fn leaf(&mut self, tag: &str, text: &str) {
        self.indent();
        let _ = writeln!(
            self.out,
            "<{tag}>{}</{tag}>",
            quick_xml::escape::escape(text)
        );
    }

    fn flag(&mut self, tag: &str, on: bool) {
        self.leaf(tag, if on { "true" } else { "false" });
    }

    fn floats(&mut self, tag: &str, values: &[f64]) {
        let text: Vec<String> = values.iter().map(|v| sci(*v)).collect();
        self.leaf(tag, &text.join(" "));
    }

    fn comment(&mut self, text: &str) {
        self.line(&format!("<!--{text}-->"));
    }

    /// A block of lines written at the current depth (the fragments are kept unindented).
    fn fragment(&mut self, text: &str) {
        for line in text.lines() {
            self.line(line);
        }
    }

    fn frame(&mut self, tag: &str, position: [f64; 3], quaternion: [f64; 4]) {
        self.open(tag);
        self.floats("position", &position);
        self.floats("quaternion", &quaternion);
        self.close(tag);
    }
}

/// C's `%.4e`: `1.0000e+00`, `-5.0000e-02`, `3.3952e-313`.
fn sci(v: f64) -> String {
    let rust = format!("{v:.4e}");
    match rust.split_once('e') {
        Some((mantissa, exp)) => {
            let exp: i32 = exp.parse().unwrap_or(0);
            let sign = if exp < 0 { '-' } else { '+' };
            format!("{mantissa}e{sign}{:02}", exp.unsigned_abs())
        }
        None => rust, // inf, NaN: never in a document we build
    }
}

/// The model's pose and size for its thumbnail: the box around every shape, in the frame of
/// the model base's parent (what the reference models show: the Line plane's own box, the
/// mesh's box).
fn thumbnail_info(w: &mut Writer, doc: &Document) {
    let (lo, hi) = model_bounds(doc).unwrap_or(([0.0; 3], [0.0; 3]));
    let centre: [f64; 3] = std::array::from_fn(|k| (lo[k] + hi[k]) / 2.0);
    let size: [f64; 3] = std::array::from_fn(|k| hi[k] - lo[k]);
    w.open("modelThumbnailInfo");
    w.frame("pose", centre, IDENTITY);
    w.floats("modelBoundingBoxSize", &size);
    w.floats("modelNonDefaultTranslationStepSize", &[0.0]);
    w.close("modelThumbnailInfo");
}

/// The axis-aligned box around every shape's vertices placed by the object tree.
fn model_bounds(doc: &Document) -> Option<([f64; 3], [f64; 3])> {
    use crate::coppelia::frame::Frame;
    use nalgebra::{Point3, Quaternion, Translation3, UnitQuaternion};
    use std::collections::HashMap;
    let mut frames: HashMap<i32, Frame> = HashMap::new();
    let mut bounds: Option<([f64; 3], [f64; 3])> = None;
    for o in &doc.objects {
        let [qw, qx, qy, qz] = o.quaternion;
        let local = Frame::from_parts(
            Translation3::new(o.position[0], o.position[1], o.position[2]),
            UnitQuaternion::from_quaternion(Quaternion::new(qw, qx, qy, qz)),
        );
        let world = o
            .parent
            .and_then(|p| frames.get(&p))
            .map_or(local, |p| p * local);
        frames.insert(o.handle, world);
        let Body::Shape(s) = &o.body else { continue };
        for v in &s.mesh.vertices {
            let p = world * Point3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2]));
            let p = [p.x, p.y, p.z];
            bounds = Some(match bounds {
                None => (p, p),
                Some((lo, hi)) => (
                    std::array::from_fn(|k| lo[k].min(p[k])),
                    std::array::from_fn(|k| hi[k].max(p[k])),
                ),
            });
        }
    }
    bounds
}

fn object(w: &mut Writer, o: &XmlObject) {
    let (tag, layer) = match o.body {
        Body::Dummy(_) => ("dummy", 4),
        Body::Shape(_) => ("shape", 1),
    };
    w.open(tag);
    common(w, o, layer);
    match &o.body {
        Body::Dummy(d) => dummy(w, d),
        Body::Shape(s) => shape(w, s),
    }
    w.close(tag);
}

/// The `<common>` block every scene object has.
fn common(w: &mut Writer, o: &XmlObject, layer: i32) {
    w.open("common");
    w.leaf("alias", &o.alias);
    w.leaf("name", &o.alias);
    w.leaf(
        "altName",
        match o.body {
            Body::Dummy(_) => "Dummy",
            Body::Shape(_) => "Shape",
        },
    );
    w.leaf("handle", &o.handle.to_string());
    w.leaf("parentHandle", &o.parent.unwrap_or(-1).to_string());
    w.frame("localFrame", o.position, o.quaternion);
    w.open("assembling");
    w.frame("localFrame", [0.0; 3], IDENTITY);
    w.open("matchValues");
    w.leaf("child", "default");
    w.leaf("parent", "default");
    w.close("matchValues");
    w.flag("localFrameIsUsed", false);
    w.close("assembling");
    w.leaf("hierarchyColorIndex", "-1");
    w.leaf("collectionSelfCollisionIndicator", "0");
    object_properties(w, o);
    w.leaf("layer", &layer.to_string());
    w.leaf("childOrder", "-1");
    w.open("switches");
    w.flag("modelBase", o.model_base);
    w.close("switches");
    manipulation(w);
    w.floats("sizeFactor", &[1.0]);
    w.leaf("scriptExecPriority", "1");
    w.floats("sizeValues", &[1.0, 1.0, 1.0]);
    w.floats("transparentObjectDistanceOffset", &[0.0]);
    w.leaf("authorizedViewableObjects", "-1");
    w.leaf("extensionString", "");
    w.leaf("modelAcknowledgement", "");
    w.close("common");
}

/// The object, special and model property blocks of `<common>`: selectable, and
/// collidable, measurable, detectable and renderable as `o.special` says.
fn object_properties(w: &mut Writer, o: &XmlObject) {
    w.open("localObjectProperty");
    w.flag("hierarchyCollapsed", false);
    w.flag("selectable", true);
    for tag in [
        "selectModelBaseInstead",
        "dontShowAsInsideModel",
        "selectInvisible",
        "depthInvisible",
        "cannotDelete",
        "cannotDeleteDuringSimulation",
        "ignoreViewFitting",
    ] {
        w.flag(tag, false);
    }
    w.close("localObjectProperty");
    let has = |bits: i32| o.special & bits == bits;
    w.open("localObjectSpecialProperty");
    w.flag("collidable", has(SPECIAL_COLLIDABLE));
    w.flag("measurable", has(SPECIAL_MEASURABLE));
    w.flag("detectable", has(SPECIAL_DETECTABLE));
    w.flag("renderable", has(SPECIAL_RENDERABLE));
    for (tag, bit) in DETECTION_KINDS {
        w.flag(tag, has(bit));
    }
    w.close("localObjectSpecialProperty");
    w.open("localModelProperty");
    for tag in [
        "notCollidable",
        "notMeasurable",
        "notDetectable",
        "notDynamic",
        "notRespondable",
        "notReset",
        "notVisible",
        "scriptsInactive",
        "notShowAsInsideModel",
        "notRenderable",
    ] {
        w.flag(tag, false);
    }
    w.close("localModelProperty");
}

/// The `<manipulation>` block of `<common>`: CoppeliaSim's defaults.
fn manipulation(w: &mut Writer) {
    w.open("manipulation");
    w.leaf("permissions", "35");
    for (tag, relative_to) in [("translation", "0"), ("rotation", "2")] {
        w.open(tag);
        w.flag("disabledDuringSimulation", false);
        w.flag("disabledDuringNonSimulation", false);
        w.flag("settingsLocked", false);
        w.leaf("relativeTo", relative_to);
        w.floats("nonDefaultStepSize", &[0.0]);
        w.close(tag);
    }
    w.close("manipulation");
}

/// A `<color>` block with this ambient-diffuse colour and CoppeliaSim's defaults otherwise.
fn colour(w: &mut Writer, tag: &str, rgb: [f32; 3]) {
    w.open(tag);
    w.leaf("name", "");
    w.leaf("extensionString", "povray { pattern {default}}");
    w.floats("ambient", &rgb.map(f64::from));
    w.floats("diffuse", &[0.0; 3]);
    w.floats("specular", &[0.25; 3]);
    w.floats("emission", &[0.0; 3]);
    w.floats("temperature", &[0.5, 0.0, 0.0]);
    w.leaf("shininess", "48");
    w.floats("transparency", &[0.5]);
    w.open("switches");
    w.flag("transparent", false);
    w.close("switches");
    w.open("flashing");
    w.flag("enabled", false);
    w.flag("inSimulationTime", false);
    w.floats("frequency", &[2.0]);
    w.floats("ratio", &[0.5]);
    w.floats("phase", &[0.0]);
    w.close("flashing");
    w.close(tag);
}

fn dummy(w: &mut Writer, d: &Dummy) {
    w.floats("size", &[d.size]);
    w.leaf("linkedDummyHandle", "-1");
    w.leaf("linkType", "dynamics_loopClosure");
    w.open("switches");
    w.flag("assignedToParentPath", false);
    w.flag("freeOnPathTrajectory", false);
    w.flag("assignedToParentPathOrientation", false);
    w.close("switches");
    w.floats("virtualDistanceOffsetOnPath", &[0.0]);
    w.floats("virtualDistanceOffsetOnPath_whenCopy", &[0.0]);
    colour(w, "color", d.colour);
    w.open("dynamics");
    w.open("engines");
    w.open("mujoco");
    w.floats("range", &[0.0, 0.0]);
    w.floats("solreflimit", &[0.02, 1.0]);
    w.floats("solimplimit", &[0.9, 0.95, 0.001, 0.05, 2.0]);
    w.floats("margin", &[0.0]);
    w.floats("springlength", &[-1.0]);
    w.floats("stiffness", &[0.0]);
    w.floats("damping", &[0.0]);
    w.flag("limited", false);
    w.close("mujoco");
    w.close("engines");
    w.close("dynamics");
}

fn shape(w: &mut Writer, s: &Shape) {
    // CoppeliaSim keeps a mesh's vertices relative to the centre of their box (`bbFrame`).
    let (lo, hi) = s.mesh.bounds().unwrap_or(([0.0; 3], [0.0; 3]));
    let centre: [f64; 3] = std::array::from_fn(|k| (lo[k] + hi[k]) / 2.0);
    let size: [f64; 3] = std::array::from_fn(|k| hi[k] - lo[k]);
    w.open("meshProxy");
    w.open("mesh");
    w.open("common");
    w.leaf("name", "sub__0");
    w.comment(" 'transformationSinceGrouping' tag: deprecated, for backward compatibility ");
    w.frame("transformationSinceGrouping", [0.0; 3], IDENTITY);
    w.open("dynamics");
    w.floats("mass", &[1.0]);
    w.comment(" 'localInertiaFrame' tag: deprecated, for backward compatibility ");
    w.open("localInertiaFrame");
    w.floats("position", &[0.0; 3]);
    w.floats("quaternion", &IDENTITY);
    w.floats("principalMomentsOfInertia", &[0.01; 3]);
    w.close("localInertiaFrame");
    w.frame("inertiaFrame", [0.0; 3], IDENTITY);
    w.floats("centerOfMass", &[0.0; 3]);
    w.floats("inertia", &[0.01, 0.0, 0.0, 0.0, 0.01, 0.0, 0.0, 0.0, 0.01]);
    w.frame("bbFrame", centre, IDENTITY);
    w.floats("bbSize", &size);
    w.close("dynamics");
    w.close("common");
    w.floats("shadingAngle", &[0.0]);
    w.floats("edgeThresholdAngle", &[0.0]);
    colour(w, "color", s.colour);
    let (kind, sizes) = match s.primitive {
        Primitive::None => ("none", [0.0; 3]),
        Primitive::Plane(sizes) => ("plane", sizes),
        Primitive::Cuboid(sizes) => ("cuboid", sizes),
    };
    w.open("primitive");
    w.leaf("type", kind);
    w.floats("insideScaling", &[0.0]);
    w.floats("sizes", &sizes);
    w.close("primitive");
    w.comment(" 'verticesLocalFrame' tag: deprecated, for backward compatibility ");
    w.frame("verticesLocalFrame", centre, IDENTITY);
    w.open("switches");
    w.flag("edgesVisible", false);
    w.flag("culling", false);
    w.flag("wireframe", false);
    w.comment(" 'hideEdgeBorders' tag: deprecated, for backward compatibility ");
    w.flag("hideEdgeBorders", false);
    w.close("switches");
    w.open("heightfield");
    w.leaf("sizes", "0 0");
    w.leaf("data", "");
    w.close("heightfield");
    mesh_data(w, &s.mesh, centre);
    w.close("mesh");
    w.close("meshProxy");
    w.open("dynamics");
    w.leaf("respondableMask", "65535");
    w.floats("initialLinearVelocity", &[0.0; 3]);
    w.floats("initialAngularVelocity", &[0.0; 3]);
    w.open("switches");
    w.flag("static", s.is_static);
    w.flag("kinematic", true);
    w.flag("respondable", s.respondable);
    w.flag("startSleeping", false);
    w.flag("setToDynamicIfGetsParent", false);
    w.close("switches");
    w.fragment(MATERIAL);
    w.close("dynamics");
}

/// Vertices (relative to `centre`), indices, one flat normal per triangle corner, and every
/// edge marked visible (three bits per triangle, as the reference mesh has them).
fn mesh_data(w: &mut Writer, mesh: &Mesh, centre: [f64; 3]) {
    w.open("meshData");
    let mut text = String::with_capacity(mesh.vertices.len() * 30);
    for v in &mesh.vertices {
        for k in 0..3 {
            let relative = (f64::from(v[k]) - centre[k]) as f32;
            push_value(&mut text, relative);
        }
    }
    w.leaf("vertices", &text);
    text.clear();
    for i in &mesh.indices {
        push_value(&mut text, i);
    }
    w.leaf("indices", &text);
    text.clear();
    for t in mesh.indices.chunks_exact(3) {
        let normal = triangle_normal(mesh, t);
        for _ in 0..3 {
            for c in normal {
                push_value(&mut text, c);
            }
        }
    }
    w.leaf("normals", &text);
    let bits = mesh.triangles() * 3;
    let edges: Vec<String> = (0..bits.div_ceil(8))
        .map(|byte| {
            let in_byte = (bits - byte * 8).min(8);
            ((1u16 << in_byte) - 1).to_string()
        })
        .collect();
    w.leaf("edges", &edges.join(" "));
    w.close("meshData");
}

/// Appends `value` to a space-separated list.
fn push_value(text: &mut String, value: impl std::fmt::Display) {
    if !text.is_empty() {
        text.push(' ');
    }
    let _ = write!(text, "{value}");
}

/// The unit normal of triangle `t` (counter-clockwise seen from its front), `[0, 0, 1]` for a
/// degenerate one or an index out of range.
fn triangle_normal(mesh: &Mesh, t: &[u32]) -> [f32; 3] {
    let vertex = |k: usize| {
        mesh.vertices
            .get(t[k] as usize)
            .map(|v| nalgebra::Vector3::new(v[0], v[1], v[2]))
    };
    let (Some(a), Some(b), Some(c)) = (vertex(0), vertex(1), vertex(2)) else {
        return [0.0, 0.0, 1.0];
    };
    let n = (b - a).cross(&(c - a));
    match n.try_normalize(f32::EPSILON) {
        Some(u) => [u.x, u.y, u.z],
        None => [0.0, 0.0, 1.0],
    }
}

/// [`sci`] for the module's tests.
#[cfg(test)]
pub(super) fn sci_for_tests(v: f64) -> String {
    sci(v)
}
