//! The program that creates a batch of meshes in one request and dresses each as the separate
//! calls would: colour, special properties, static and respondable, alias, the floor's frame,
//! under the holder. It answers `(true, {handles})`, or `(false, message)` having removed
//! what it made, so a failure leaves the scene as it was.
//!
//! Sending the vertices and indices as CBOR arrays is what makes `sim.createShape` slow over
//! the remote API: the add-on decodes every number in Lua. Packed as binary strings in the
//! program's text and unpacked in C (`sim.unpackFloatTable`), the same meshes are made in
//! about half the time on both builds: 1,200 triangles in 10.8 ms against 19.9 ms on the real
//! 4.10.0, 6.9 ms against 11.3 ms on the real 4.5.1 (`docs/measurements.md`, "Meshes created
//! in one request").

use std::borrow::Cow;

use super::{literal, pack_floats, pack_int32s, unpack_floats, unpack_int32s};
use crate::coppelia::{
    COLORCOMPONENT_AMBIENT_DIFFUSE, SHAPEINTPARAM_RESPONDABLE, SHAPEINTPARAM_STATIC,
};

/// Shading angle of the meshes (CoppeliaSim's usual 20 degrees; flat faces show no edge).
pub const SHADING_ANGLE: f64 = 0.349;

/// A batch of meshes to create, and where they go.
#[derive(Debug, Clone, PartialEq)]
pub struct CreateMeshes<'a> {
    /// CoppeliaSim 4.6 or later: `sim.createShape`, and `sim.setObjectPose(h, pose, rel)`;
    /// before, `sim.createMeshShape` and `sim.setObjectPose(h, rel, pose)`.
    pub since_4_6: bool,
    /// The dummy the meshes go under.
    pub holder: i32,
    /// The floor, whose frame the meshes take; `None` when it is the world's (a new mesh is
    /// there already).
    pub floor: Option<i32>,
    /// The meshes, in order: the answer lists their handles in the same order.
    pub meshes: Vec<LuaMesh<'a>>,
}

/// One mesh of a [`CreateMeshes`].
#[derive(Debug, Clone, PartialEq)]
pub struct LuaMesh<'a> {
    /// Its alias.
    pub name: Cow<'a, str>,
    /// x, y, z per vertex.
    pub vertices: Cow<'a, [f32]>,
    /// Three vertex indices per triangle.
    pub indices: Cow<'a, [i32]>,
    /// Ambient-diffuse colour, RGB 0..1.
    pub colour: [f64; 3],
    /// Special-property bits.
    pub special: i32,
    /// Respondable (every mesh is static).
    pub respondable: bool,
}

/// The program creating `batch`.
pub fn create_meshes_code(batch: &CreateMeshes<'_>) -> String {
    let data: usize = batch
        .meshes
        .iter()
        .map(|m| 4 * (m.vertices.len() + m.indices.len()))
        .sum();
    let mut code = String::with_capacity(4 * data + 1024);
    code.push_str(HEAD);
    for m in &batch.meshes {
        code.push('{');
        literal::write(&mut code, m.name.as_bytes());
        let [r, g, b] = m.colour;
        code.push_str(&format!(
            ", {{{r:?}, {g:?}, {b:?}}}, {}, {}, ",
            m.special, m.respondable
        ));
        literal::write(&mut code, &pack_floats(&m.vertices));
        code.push_str(", ");
        literal::write(&mut code, &pack_int32s(&m.indices));
        code.push_str("},\n");
    }
    let floor = batch.floor.map_or("nil".to_string(), |f| f.to_string());
    code.push_str(&format!(
        "}}\nlocal holder, floor = {}, {floor}\n",
        batch.holder
    ));
    code.push_str(&body(batch.since_4_6));
    code
}

/// The batch of a program [`create_meshes_code`] wrote; `None` for any other program.
pub fn parse_create_meshes(code: &str) -> Option<CreateMeshes<'static>> {
    let mut rest = code.strip_prefix(HEAD)?;
    let mut meshes = Vec::new();
    while let Some(entry) = rest.strip_prefix('{') {
        let (mesh, after) = parse_mesh(entry)?;
        meshes.push(mesh);
        rest = after.strip_prefix("},\n")?;
    }
    let rest = rest.strip_prefix("}\nlocal holder, floor = ")?;
    let (holder, rest) = rest.split_once(", ")?;
    let (floor, rest) = rest.split_once('\n')?;
    let holder = holder.parse().ok()?;
    let floor = match floor {
        "nil" => None,
        f => Some(f.parse().ok()?),
    };
    let since_4_6 = [true, false].into_iter().find(|&s| rest == body(s))?;
    Some(CreateMeshes {
        since_4_6,
        holder,
        floor,
        meshes,
    })
}

/// One `{name, {r, g, b}, special, respondable, vertices, indices}` entry, without its `{`.
fn parse_mesh(entry: &str) -> Option<(LuaMesh<'static>, &str)> {
    let (name, rest) = literal::read(entry)?;
    let rest = rest.strip_prefix(", {")?;
    let (colour, rest) = rest.split_once("}, ")?;
    let colour: Vec<f64> = colour
        .split(", ")
        .map(|c| c.parse().ok().filter(|c: &f64| c.is_finite()))
        .collect::<Option<_>>()?;
    let (special, rest) = rest.split_once(", ")?;
    let (respondable, rest) = rest.split_once(", ")?;
    let (vertices, rest) = literal::read(rest)?;
    let (indices, rest) = literal::read(rest.strip_prefix(", ")?)?;
    let mesh = LuaMesh {
        name: Cow::Owned(String::from_utf8(name).ok()?),
        vertices: Cow::Owned(unpack_floats(&vertices)?),
        indices: Cow::Owned(unpack_int32s(&indices)?),
        colour: colour.try_into().ok()?,
        special: special.parse().ok()?,
        respondable: respondable.parse().ok()?,
    };
    Some((mesh, rest))
}

const HEAD: &str = "local M = {\n";

/// What follows the data: create and dress each mesh, undo all on a failure.
fn body(since_4_6: bool) -> String {
    let (create, pose) = if since_4_6 {
        ("sim.createShape", "h, {0, 0, 0, 0, 0, 0, 1}, floor")
    } else {
        ("sim.createMeshShape", "h, floor, {0, 0, 0, 0, 0, 0, 1}")
    };
    format!(
        "local made = {{}}
local ok, err = pcall(function()
for _, m in ipairs(M) do
local h = {create}(0, {SHADING_ANGLE:?}, sim.unpackFloatTable(m[5]), sim.unpackInt32Table(m[6]))
made[#made + 1] = h
sim.setShapeColor(h, '', {COLORCOMPONENT_AMBIENT_DIFFUSE}, m[2])
sim.setObjectSpecialProperty(h, m[3])
sim.setObjectInt32Param(h, {SHAPEINTPARAM_STATIC}, 1)
sim.setObjectInt32Param(h, {SHAPEINTPARAM_RESPONDABLE}, m[4] and 1 or 0)
sim.setObjectAlias(h, m[1])
if floor then sim.setObjectPose({pose}) end
sim.setObjectParent(h, holder, true)
end
end)
if not ok then
if #made > 0 then sim.removeObjects(made) end
error(err, 0)
end
return made"
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn batch() -> CreateMeshes<'static> {
        CreateMeshes {
            since_4_6: true,
            holder: 41,
            floor: Some(7),
            meshes: vec![
                LuaMesh {
                    name: "vrep_maze_lines_0_1f2e".into(),
                    vertices: vec![0.0, 0.0, 0.001, 1.5, -0.25, 0.001, 1.5, 0.0, 0.001].into(),
                    indices: vec![0, 1, 2].into(),
                    colour: [0.0, 0.8, 0.1],
                    special: 176,
                    respondable: false,
                },
                LuaMesh {
                    name: "walls \"quoted\"".into(),
                    vertices: vec![-25.475, 1e-7, 0.2].into(),
                    indices: vec![0, 0, 0].into(),
                    colour: [1.0, 1.0, 1.0],
                    special: 0,
                    respondable: true,
                },
            ],
        }
    }

    #[test]
    fn a_program_reads_back_as_the_batch_it_was_written_from() {
        for since_4_6 in [true, false] {
            for floor in [Some(7), None] {
                let b = CreateMeshes {
                    since_4_6,
                    floor,
                    ..batch()
                };
                let code = create_meshes_code(&b);
                assert!(code.is_ascii());
                assert_eq!(parse_create_meshes(&code), Some(b));
            }
        }
        let empty = CreateMeshes {
            meshes: vec![],
            ..batch()
        };
        assert_eq!(
            parse_create_meshes(&create_meshes_code(&empty)),
            Some(empty)
        );
    }

    #[test]
    fn the_program_calls_what_each_generation_has() {
        let new = create_meshes_code(&batch());
        assert!(new.contains("sim.createShape(0, 0.349,"));
        assert!(new.contains("sim.setObjectPose(h, {0, 0, 0, 0, 0, 0, 1}, floor)"));
        let old = create_meshes_code(&CreateMeshes {
            since_4_6: false,
            ..batch()
        });
        assert!(old.contains("sim.createMeshShape(0, 0.349,"));
        assert!(old.contains("sim.setObjectPose(h, floor, {0, 0, 0, 0, 0, 0, 1})"));
        assert!(new.contains("local holder, floor = 41, 7\n"));
    }

    #[test]
    fn another_program_or_a_changed_one_does_not_parse() {
        let code = create_meshes_code(&batch());
        let changed = [
            code.replace("sim.setObjectAlias(h, m[1])", "sim.setObjectAlias(h, 'x')"),
            code.replace("176", "17x"),
            code.replace("{0.0, 0.8, 0.1}", "{0.0, 0.8}"),
            code.replace("0.8", "NaN"),
            code.replace("false, \"", "maybe, \""),
            code.replace("= 41, 7", "= 41, seven"),
            format!("{code} "),
            "return 1 + 1".into(),
        ];
        for c in changed {
            assert_eq!(parse_create_meshes(&c), None, "{c}");
        }
    }
}
