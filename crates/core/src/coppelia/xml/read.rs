//! The reader: CoppeliaSim XML text (what [`super::write`] emits, what a real 4.5.1 writes
//! for dummies and single-mesh shapes) into a [`Document`]. The text is parsed by quick-xml
//! into a small tree first, then the nodes this module knows are read from it; a missing or
//! wrong node is an [`XmlError`] naming it.

use std::collections::HashMap;

use nalgebra::{Point3, Quaternion, Translation3, UnitQuaternion};
use quick_xml::events::Event;

use super::{Body, Document, Dummy, FileKind, Mesh, Primitive, Shape, XmlError, XmlObject};
use crate::coppelia::frame::Frame;
use crate::coppelia::{
    SPECIAL_COLLIDABLE, SPECIAL_DETECTABLE, SPECIAL_MEASURABLE, SPECIAL_RENDERABLE,
};

/// Deepest element nesting accepted (CoppeliaSim's own files nest about 10 deep).
const MAX_DEPTH: usize = 64;

/// Reads a CoppeliaSim XML scene or model.
pub fn read(text: &str) -> Result<Document, XmlError> {
    let root = parse(text)?;
    if root.name != "CoppeliaSim" {
        return Err(XmlError::Unsupported(format!(
            "the root element is <{}>, not <CoppeliaSim>",
            root.name
        )));
    }
    let at = Path::root(&root.name);
    let kind = match root.child("filetype").map(|n| n.text.trim()) {
        Some("exhaustiveModel") => FileKind::Model,
        Some("exhaustiveScene") => FileKind::Scene,
        Some(other) => {
            return Err(XmlError::Unsupported(format!(
                "file type '{other}' is not read (only exhaustiveModel and exhaustiveScene)"
            )));
        }
        None => return Err(at.child("filetype").missing()),
    };
    let mut objects = Vec::new();
    for (n, node) in root
        .children
        .iter()
        .filter(|c| c.name == "sceneObject")
        .enumerate()
    {
        objects.push(object(node, &at.child(&format!("sceneObject[{}]", n + 1)))?);
    }
    check_tree(&objects)?;
    Ok(Document { kind, objects })
}

/// An element: its name, its text (concatenated) and its child elements.
#[derive(Debug, Default)]
struct Node {
    name: String,
    text: String,
    children: Vec<Node>,
}

impl Node {
    fn child(&self, name: &str) -> Option<&Node> {
        self.children.iter().find(|c| c.name == name)
    }
}

/// Where a node is, for error messages.
#[derive(Clone)]
struct Path(String);

impl Path {
    fn root(name: &str) -> Path {
        Path(name.to_string())
    }

    fn child(&self, name: &str) -> Path {
        Path(format!("{}/{name}", self.0))
    }

    fn bad(&self, problem: impl Into<String>) -> XmlError {
        XmlError::Bad {
            node: self.0.clone(),
            problem: problem.into(),
        }
    }

    fn missing(&self) -> XmlError {
        self.bad("missing")
    }
}

/// The element tree of `text` (built without recursion, nesting bounded by [`MAX_DEPTH`]).
fn parse(text: &str) -> Result<Node, XmlError> {
    let mut reader = quick_xml::Reader::from_str(text);
    let syntax = |e: &dyn std::fmt::Display| XmlError::Syntax(e.to_string());
    let mut stack: Vec<Node> = vec![Node::default()];
    loop {
        let event = reader
            .read_event()
            .map_err(|e| XmlError::Syntax(format!("{e} (at byte {})", reader.buffer_position())))?;
        let top = stack.last_mut().ok_or_else(|| syntax(&"unbalanced tags"))?;
        match event {
            Event::Start(e) => {
                if stack.len() > MAX_DEPTH {
                    return Err(XmlError::Unsupported(format!(
                        "elements nest deeper than {MAX_DEPTH}"
                    )));
                }
                let name = String::from_utf8_lossy(e.name().as_ref()).into_owned();
                stack.push(Node {
                    name,
                    ..Node::default()
                });
            }
            Event::Empty(e) => top.children.push(Node {
                name: String::from_utf8_lossy(e.name().as_ref()).into_owned(),
                ..Node::default()
            }),
            Event::End(_) => {
                let done = stack.pop().ok_or_else(|| syntax(&"unbalanced tags"))?;
                stack
                    .last_mut()
                    .ok_or_else(|| syntax(&"unbalanced tags"))?
                    .children
                    .push(done);
            }
            Event::Text(t) => {
                let raw = t.decode().map_err(|e| syntax(&e))?;
                top.text.push_str(&raw);
            }
            Event::CData(t) => {
                let raw = t.decode().map_err(|e| syntax(&e))?;
                top.text.push_str(&raw);
            }
            Event::GeneralRef(r) => {
                let name = r.decode().map_err(|e| syntax(&e))?;
                let entity = format!("&{name};");
                let resolved = quick_xml::escape::unescape(&entity).map_err(|e| syntax(&e))?;
                top.text.push_str(&resolved);
            }
            Event::Eof => break,
            Event::Comment(_) | Event::Decl(_) | Event::PI(_) | Event::DocType(_) => {}
        }
    }
    let mut document = stack
        .pop()
        .filter(|_| stack.is_empty())
        .ok_or_else(|| XmlError::Syntax("the document ends inside an element".to_string()))?;
    match document.children.len() {
        1 => Ok(document.children.remove(0)),
        0 => Err(XmlError::Syntax("no root element".to_string())),
        _ => Err(XmlError::Syntax("more than one root element".to_string())),
    }
}

fn required<'a>(node: &'a Node, at: &Path, name: &str) -> Result<(&'a Node, Path), XmlError> {
    let path = at.child(name);
    node.child(name)
        .map(|n| (n, path.clone()))
        .ok_or_else(|| path.missing())
}

fn numbers<T: std::str::FromStr>(node: &Node, at: &Path) -> Result<Vec<T>, XmlError> {
    node.text
        .split_ascii_whitespace()
        .map(|w| {
            w.parse::<T>()
                .map_err(|_| at.bad(format!("'{w}' is not a number")))
        })
        .collect()
}

fn fixed<const N: usize>(node: &Node, name: &str, at: &Path) -> Result<[f64; N], XmlError> {
    let (n, path) = required(node, at, name)?;
    let values: Vec<f64> = numbers(n, &path)?;
    if values.iter().any(|v| !v.is_finite()) {
        return Err(path.bad("a value is not finite"));
    }
    values
        .try_into()
        .map_err(|v: Vec<f64>| path.bad(format!("{} values, expected {N}", v.len())))
}

fn int(node: &Node, name: &str, at: &Path) -> Result<i32, XmlError> {
    let (n, path) = required(node, at, name)?;
    n.text
        .trim()
        .parse()
        .map_err(|_| path.bad(format!("'{}' is not an integer", n.text.trim())))
}

/// A boolean child (`true`, anything else false, as CoppeliaSim reads them); `false` if absent.
fn flag(node: &Node, name: &str) -> bool {
    node.child(name).is_some_and(|n| n.text.trim() == "true")
}

/// A `position` + `quaternion` frame.
fn frame(node: &Node, at: &Path) -> Result<([f64; 3], [f64; 4]), XmlError> {
    let position = fixed::<3>(node, "position", at)?;
    let q = fixed::<4>(node, "quaternion", at)?;
    let norm = q.iter().map(|v| v * v).sum::<f64>().sqrt();
    if norm < 1e-6 {
        return Err(at.child("quaternion").bad("not a rotation (zero length)"));
    }
    Ok((position, q.map(|v| v / norm)))
}

fn object(node: &Node, at: &Path) -> Result<XmlObject, XmlError> {
    let (kind, body_node) = node
        .children
        .first()
        .map(|c| (c.name.as_str(), c))
        .ok_or_else(|| at.bad("empty"))?;
    let at = at.child(kind);
    let (common, cat) = required(body_node, &at, "common")?;
    let alias = common
        .child("alias")
        .or_else(|| common.child("name"))
        .map(|n| n.text.trim().to_string())
        .filter(|a| !a.is_empty())
        .ok_or_else(|| cat.child("alias").missing())?;
    let handle = int(common, "handle", &cat)?;
    let parent = int(common, "parentHandle", &cat)?;
    let (local, lat) = required(common, &cat, "localFrame")?;
    let (position, quaternion) = frame(local, &lat)?;
    let model_base = common
        .child("switches")
        .is_some_and(|s| flag(s, "modelBase"));
    let special = common
        .child("localObjectSpecialProperty")
        .map_or(0, special_bits);
    let body = match kind {
        "dummy" => Body::Dummy(Dummy {
            size: fixed::<1>(body_node, "size", &at)?[0],
            colour: colour(body_node, &at)?,
        }),
        "shape" => Body::Shape(shape(body_node, &at)?),
        other => {
            return Err(XmlError::Unsupported(format!(
                "{}: object type <{other}> is not read (only dummies and shapes)",
                at.0
            )));
        }
    };
    Ok(XmlObject {
        handle,
        parent: (parent >= 0).then_some(parent),
        alias,
        position,
        quaternion,
        model_base,
        special,
        body,
    })
}

fn special_bits(node: &Node) -> i32 {
    let mut bits = 0;
    for (tag, bit) in [
        ("collidable", SPECIAL_COLLIDABLE),
        ("measurable", SPECIAL_MEASURABLE),
        ("detectable", SPECIAL_DETECTABLE),
        ("renderable", SPECIAL_RENDERABLE),
        ("ultrasonicDetectable", 16),
        ("infraredDetectable", 32),
        ("laserDetectable", 64),
        ("inductiveDetectable", 128),
        ("capacitiveDetectable", 256),
    ] {
        if flag(node, tag) {
            bits |= bit;
        }
    }
    bits
}

/// The ambient component of a `<color>` child.
fn colour(node: &Node, at: &Path) -> Result<[f32; 3], XmlError> {
    let (c, cat) = required(node, at, "color")?;
    let rgb = fixed::<3>(c, "ambient", &cat)?;
    Ok(rgb.map(|v| v.clamp(0.0, 1.0) as f32))
}

fn shape(node: &Node, at: &Path) -> Result<Shape, XmlError> {
    let (proxy, pat) = required(node, at, "meshProxy")?;
    let Some(mesh) = proxy.child("mesh") else {
        return Err(XmlError::Unsupported(format!(
            "{}: only shapes of one mesh are read (this one is a compound: group it no further \
             or ungroup it)",
            pat.0
        )));
    };
    let mat = pat.child("mesh");
    // Vertices are relative to the mesh's box frame (4.5 rev2 and later), else to the old
    // `verticesLocalFrame`.
    let placement = mesh
        .child("common")
        .and_then(|c| c.child("dynamics"))
        .and_then(|d| d.child("bbFrame"))
        .map(|f| (f, mat.child("common/dynamics/bbFrame")))
        .or_else(|| {
            mesh.child("verticesLocalFrame")
                .map(|f| (f, mat.child("verticesLocalFrame")))
        });
    let placement = match placement {
        Some((f, fat)) => {
            let (p, q) = frame(f, &fat)?;
            Frame::from_parts(
                Translation3::new(p[0], p[1], p[2]),
                UnitQuaternion::from_quaternion(Quaternion::new(q[0], q[1], q[2], q[3])),
            )
        }
        None => Frame::identity(),
    };
    let (data, dat) = required(mesh, &mat, "meshData")?;
    let Some(vertices_node) = data.child("vertices") else {
        return Err(XmlError::Unsupported(format!(
            "{}: meshes kept in a side file are not read",
            dat.0
        )));
    };
    let vat = dat.child("vertices");
    let flat: Vec<f32> = numbers(vertices_node, &vat)?;
    if !flat.len().is_multiple_of(3) || flat.iter().any(|v| !v.is_finite()) {
        return Err(vat.bad("not a list of finite x y z triples"));
    }
    let vertices: Vec<[f32; 3]> = flat
        .chunks_exact(3)
        .map(|v| {
            let p = placement * Point3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2]));
            [p.x as f32, p.y as f32, p.z as f32]
        })
        .collect();
    let (indices_node, iat) = required(data, &dat, "indices")?;
    let indices: Vec<u32> = numbers(indices_node, &iat)?;
    if !indices.len().is_multiple_of(3) {
        return Err(iat.bad("not a multiple of three"));
    }
    if let Some(i) = indices.iter().find(|&&i| i as usize >= vertices.len()) {
        return Err(iat.bad(format!("index {i} but only {} vertices", vertices.len())));
    }
    let primitive = match mesh.child("primitive") {
        None => Primitive::None,
        Some(p) => {
            let ppat = mat.child("primitive");
            match p.child("type").map(|t| t.text.trim()) {
                Some("plane") => Primitive::Plane(fixed::<3>(p, "sizes", &ppat)?),
                Some("cuboid") => Primitive::Cuboid(fixed::<3>(p, "sizes", &ppat)?),
                _ => Primitive::None,
            }
        }
    };
    let switches = node.child("dynamics").and_then(|d| d.child("switches"));
    Ok(Shape {
        mesh: Mesh { vertices, indices },
        colour: colour(mesh, &mat)?,
        primitive,
        is_static: switches.is_some_and(|s| flag(s, "static")),
        respondable: switches.is_some_and(|s| flag(s, "respondable")),
    })
}

/// Handles are unique, every parent is an object of the file, and no object is its own
/// ancestor.
fn check_tree(objects: &[XmlObject]) -> Result<(), XmlError> {
    let mut parents = HashMap::new();
    for o in objects {
        if parents.insert(o.handle, o.parent).is_some() {
            return Err(XmlError::Unsupported(format!(
                "object '{}' repeats handle {}",
                o.alias, o.handle
            )));
        }
    }
    for o in objects {
        let mut at = o.parent;
        for _ in 0..=objects.len() {
            let Some(p) = at else { break };
            at = *parents.get(&p).ok_or_else(|| {
                XmlError::Unsupported(format!(
                    "object '{}' has parent handle {p}, which no object of the file has",
                    o.alias
                ))
            })?;
            if p == o.handle {
                return Err(XmlError::Unsupported(format!(
                    "object '{}' is its own ancestor",
                    o.alias
                )));
            }
        }
    }
    Ok(())
}
