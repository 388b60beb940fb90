//! [`MeshDrawing`] over the legacy remote API, which cannot create shapes: the meshes are
//! written as a CoppeliaSim XML model ([`vrep_maze_core::coppelia::xml`], the writer `export` uses)
//! and loaded with `simxLoadModel`. When the simulator is on this machine (a loopback
//! host), the model is a temporary file that the server reads by its path; otherwise it is
//! sent with `simxTransferFile` under a name that keeps the `.simmodel.xml` ending (the
//! official client's `simxLoadModel` option 1 names it `.ttm`, which a real 4.5.1 then fails
//! to read: `../shared/spec/real-coppeliasim-4.5.1.md`, "One object instead of thousands"),
//! loaded and erased in the same message. The loaded meshes are then put under the maze's
//! holder and the temporary file removed.
//!
//! The legacy API reads neither colours nor meshes: a template's look is the course's
//! (lines green, boxes grey, by whether the template is flat), and a mesh is verified by its
//! name (which carries its fingerprint), pose and bounding box (float parameters 15-20).

use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};

use super::{LegacyBackend, bounding_box_commands, bounding_box_of};
use crate::draw::error::BackendError;
use crate::draw::mesh::{
    FoundMesh, FoundMeshes, HOLDER, Look, MeshDrawing, MeshPlace, MeshReadback, NewMesh,
    parse_mesh_name,
};
use crate::draw::names::ObjectNames;
use crate::legacy::client::Reply;
use crate::legacy::command::{ALL_OBJECTS, Command, GroupData, TEMP_FILE_PREFIX, group, read_i32};
use vrep_maze_core::coppelia::xml::{self, Document, FileKind, XmlObject};
use vrep_maze_core::coppelia::{
    HANDLE_WORLD, SPECIAL_COLLIDABLE, SPECIAL_DETECTABLE, SPECIAL_MEASURABLE, SPECIAL_RENDERABLE,
};

/// The look of line meshes: the course scene's green `Line`, collidable, measurable,
/// detectable and renderable.
const LINE_LOOK: Look = Look {
    colour: [0.0, 1.0, 0.0],
    special: SPECIAL_COLLIDABLE | SPECIAL_MEASURABLE | SPECIAL_DETECTABLE | SPECIAL_RENDERABLE,
};
/// The look of wall and post meshes: the emulator's wall template grey (77/255).
const BOX_LOOK: Look = Look {
    colour: [0.302, 0.302, 0.302],
    special: LINE_LOOK.special,
};

/// Tells apart the temporary files of one process.
static NEXT_FILE: AtomicU64 = AtomicU64::new(0);

/// A name no other run uses: the process, a counter and the clock.
fn unique_stem() -> String {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos());
    format!(
        "vrep-maze-{}-{}-{nanos}",
        std::process::id(),
        NEXT_FILE.fetch_add(1, Ordering::Relaxed)
    )
}

/// The model to load: the holder dummy (the model base) on the floor's world pose, the
/// meshes on the holder's frame (their vertices are Floor coordinates).
fn model(meshes: &[NewMesh<'_>], floor: ([f64; 3], [f64; 3])) -> Result<Document, BackendError> {
    let (position, euler) = floor;
    let rotation = vrep_maze_core::coppelia::frame::rotation_from_euler(euler);
    let mut holder = XmlObject::dummy(0, None, HOLDER, 0.01, [1.0, 0.8, 0.55]);
    holder.model_base = true;
    holder.position = position;
    let q = rotation.quaternion();
    holder.quaternion = [q.w, q.i, q.j, q.k];
    let mut objects = vec![holder];
    for (handle, m) in (1..).zip(meshes) {
        let mesh = xml::Mesh::from_flat(m.vertices, m.indices).ok_or_else(|| {
            BackendError::Remote(format!(
                "mesh `{}`: vertices and indices do not fit",
                m.name
            ))
        })?;
        let colour = m.look.colour.map(|c| c as f32);
        objects.push(XmlObject::static_mesh(
            handle,
            Some(0),
            m.name,
            mesh,
            (colour, m.look.special),
            m.respondable,
        ));
    }
    Ok(Document {
        kind: FileKind::Model,
        objects,
    })
}

impl LegacyBackend {
    /// Every object's parent and alias (two group-data reads in one request).
    fn parents_and_aliases(&mut self) -> Result<Vec<(i32, Option<i32>, String)>, BackendError> {
        let r = self.call(&[group::PARENTS, group::ALIASES].map(|data_type| {
            Command::GetObjectGroupData {
                object_type: ALL_OBJECTS,
                data_type,
            }
        }))?;
        let decode = |k: usize| {
            GroupData::decode(&r[k].data)
                .filter(|_| !r[k].remote_error)
                .ok_or_else(|| BackendError::Transport("malformed group data reply".into()))
        };
        let (parents, aliases) = (decode(0)?, decode(1)?);
        if parents.handles != aliases.handles
            || parents.ints.len() != parents.handles.len()
            || aliases.strings.len() != aliases.handles.len()
        {
            return Err(BackendError::Transport(
                "group data replies disagree".into(),
            ));
        }
        Ok(parents
            .handles
            .iter()
            .zip(&parents.ints)
            .zip(aliases.strings)
            .map(|((&h, &p), a)| (h, (p >= 0).then_some(p), a))
            .collect())
    }

    /// World position and Euler angles of `handle`.
    fn world_pose_of(&mut self, handle: i32) -> Result<([f64; 3], [f64; 3]), BackendError> {
        let r = self.call(&pose_commands(handle))?;
        pose_of(&r).ok_or_else(|| BackendError::Remote(format!("reading the pose of {handle}")))
    }

    /// Loads the model text: from a temporary file on this machine, or sent to the server.
    /// Returns the model base's handle.
    fn load_model_text(&mut self, text: &str) -> Result<i32, BackendError> {
        let name = format!("{}{}", unique_stem(), FileKind::Model.extension());
        let reply = if self.local {
            let path: PathBuf = std::env::temp_dir().join(&name);
            std::fs::write(&path, text).map_err(|e| {
                BackendError::Transport(format!("{}: cannot write: {e}", path.display()))
            })?;
            let loaded = self.call(&[Command::LoadModel(path.display().to_string())]);
            let _ = std::fs::remove_file(&path);
            loaded?.remove(0)
        } else {
            let name = format!("{TEMP_FILE_PREFIX}{name}");
            let mut r = self.call(&[
                Command::TransferFile {
                    name: name.clone(),
                    data: text.as_bytes().to_vec(),
                },
                Command::LoadModel(name.clone()),
                Command::EraseFile(name),
            ])?;
            if r[0].remote_error {
                return Err(BackendError::Remote(
                    "simxTransferFile of the mesh model failed".into(),
                ));
            }
            r.remove(1)
        };
        match read_i32(&reply.data, 0) {
            Some(base) if !reply.remote_error && base >= 0 => Ok(base),
            _ => Err(BackendError::Remote(
                "simxLoadModel of the mesh model failed".into(),
            )),
        }
    }
}

impl MeshDrawing for LegacyBackend {
    fn look(&mut self, template: i32) -> Result<Look, BackendError> {
        let boxes = crate::draw::Backend::bounding_boxes(self, &[template])?;
        let flat = boxes
            .first()
            .copied()
            .flatten()
            .is_none_or(|b| b.size()[2] < 1e-6);
        Ok(if flat { LINE_LOOK } else { BOX_LOOK })
    }

    fn find(
        &mut self,
        _names: &ObjectNames,
        parent: i32,
        _surveyed: Option<i32>,
    ) -> Result<FoundMeshes, BackendError> {
        let objects = self.parents_and_aliases()?;
        let elsewhere: Vec<String> = objects
            .iter()
            .filter(|(_, p, a)| p.is_none() && parse_mesh_name(a).is_some())
            .map(|(_, _, a)| a.clone())
            .collect();
        let Some(holder) = objects
            .iter()
            .find(|(_, p, a)| *p == Some(parent) && a == HOLDER)
            .map(|(h, _, _)| *h)
        else {
            return Ok(FoundMeshes {
                elsewhere,
                ..Default::default()
            });
        };
        // everything under the holder, at any depth
        let mut inside = vec![holder];
        let mut meshes = Vec::new();
        let mut grew = true;
        while grew {
            grew = false;
            for (h, p, a) in &objects {
                if p.is_some_and(|p| inside.contains(&p)) && !inside.contains(h) {
                    inside.push(*h);
                    meshes.push(FoundMesh {
                        handle: *h,
                        name: a.clone(),
                        parent: *p,
                    });
                    grew = true;
                }
            }
        }
        Ok(FoundMeshes {
            holder: Some(holder),
            meshes,
            users: Vec::new(),
            elsewhere,
        })
    }

    fn create(
        &mut self,
        place: &MeshPlace,
        meshes: &[NewMesh<'_>],
    ) -> Result<(i32, Vec<i32>), BackendError> {
        let floor = match place.floor_pose {
            Some(pose) => pose,
            None => self.world_pose_of(place.floor)?,
        };
        let text = xml::write(&model(meshes, floor)?);
        let base = self.load_model_text(&text)?;
        let objects = self.parents_and_aliases()?;
        let loaded: Vec<i32> = meshes
            .iter()
            .map(|m| {
                objects
                    .iter()
                    .find(|(_, p, a)| *p == Some(base) && a == m.name)
                    .map(|(h, _, _)| *h)
                    .ok_or_else(|| {
                        BackendError::Remote(format!(
                            "the loaded model has no mesh `{}` under its base",
                            m.name
                        ))
                    })
            })
            .collect::<Result<_, _>>()?;
        let (holder, mut cmds) = match place.holder {
            // the loaded holder goes under the maze dummy, in place
            None => (
                base,
                vec![Command::SetObjectParent {
                    handle: base,
                    parent: place.parent,
                    keep_in_place: true,
                }],
            ),
            // the meshes go under the holder the scene has, and the loaded one goes
            Some(h) => (
                h,
                loaded
                    .iter()
                    .map(|&m| Command::SetObjectParent {
                        handle: m,
                        parent: h,
                        keep_in_place: true,
                    })
                    .collect(),
            ),
        };
        if place.holder.is_some() {
            cmds.push(Command::RemoveObject(base));
        }
        let r = self.call(&cmds)?;
        if r.iter().any(|r| r.remote_error) {
            return Err(BackendError::Remote(
                "putting the loaded meshes under the maze failed".into(),
            ));
        }
        Ok((holder, loaded))
    }

    fn read(&mut self, handle: i32) -> Result<MeshReadback, BackendError> {
        self.read_all(&[handle])?
            .into_iter()
            .next()
            .ok_or_else(|| BackendError::Transport(format!("no reply reading mesh {handle}")))
    }

    /// Every mesh's bounding box and world pose, all in one message.
    fn read_all(&mut self, handles: &[i32]) -> Result<Vec<MeshReadback>, BackendError> {
        let cmds: Vec<Command> = handles
            .iter()
            .flat_map(|&h| bounding_box_commands(h).chain(pose_commands(h)))
            .collect();
        let r = self.call(&cmds)?;
        handles
            .iter()
            .zip(r.chunks(8))
            .map(|(&handle, eight)| {
                let (bbox, pose) = eight.split_at(6.min(eight.len()));
                Ok(MeshReadback {
                    vertices: None,
                    indices: None,
                    bounding_box: bounding_box_of(bbox).map(|b| (b.min, b.max)),
                    colour: None,
                    pose: pose_of(pose).ok_or_else(|| {
                        BackendError::Remote(format!("reading the pose of {handle}"))
                    })?,
                    layer: None,
                })
            })
            .collect()
    }

    fn read_shapes(&mut self, handles: &[i32]) -> Result<Vec<MeshReadback>, BackendError> {
        self.read_all(handles)
    }
}

/// `handle`'s world position and Euler angles.
fn pose_commands(handle: i32) -> [Command; 2] {
    [
        Command::GetPosition {
            handle,
            relative_to: HANDLE_WORLD,
        },
        Command::GetOrientation {
            handle,
            relative_to: HANDLE_WORLD,
        },
    ]
}

/// The pose the two replies to [`pose_commands`] give; `None` if either failed.
fn pose_of(two: &[Reply]) -> Option<([f64; 3], [f64; 3])> {
    let three = |r: &Reply| {
        crate::legacy::command::read_f32x3(&r.data, 0)
            .filter(|_| !r.remote_error)
            .map(|v| v.map(f64::from))
    };
    match two {
        [position, euler] => Some((three(position)?, three(euler)?)),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_model_puts_the_holder_on_the_floor_and_the_meshes_on_the_holder() {
        let vertices = [
            0.0f32, 0.0, 0.001, 1.0, 0.0, 0.001, 1.0, 0.1, 0.001, 0.0, 0.1, 0.001,
        ];
        let indices = [0, 1, 2, 0, 2, 3];
        let mesh = NewMesh {
            name: "MazeMesh_l_0000000000000001",
            vertices: &vertices,
            indices: &indices,
            look: LINE_LOOK,
            respondable: false,
        };
        let doc = model(&[mesh], ([1.0, 2.0, 0.0], [0.0, 0.0, 0.0])).unwrap();
        assert_eq!(doc.objects.len(), 2);
        assert!(doc.objects[0].model_base && doc.objects[0].alias == HOLDER);
        assert_eq!(doc.objects[0].position, [1.0, 2.0, 0.0]);
        assert_eq!(doc.objects[1].parent, Some(0));
        assert_eq!(doc.objects[1].position, [0.0; 3]);
        let back = xml::read(&xml::write(&doc)).unwrap();
        assert_eq!(back.objects[1].alias, "MazeMesh_l_0000000000000001");
        let xml::Body::Shape(s) = &back.objects[1].body else {
            panic!("a shape")
        };
        assert_eq!(s.mesh.indices, [0, 1, 2, 0, 2, 3]);
        assert!(s.is_static && !s.respondable && s.colour == [0.0, 1.0, 0.0]);
        let bad = NewMesh {
            indices: &[0, 1, 9],
            ..mesh
        };
        assert!(model(&[bad], ([0.0; 3], [0.0; 3])).is_err());
    }
}
