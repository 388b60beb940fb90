//! Models from CoppeliaSim XML files in the emulated scene: what `simxLoadModel` and
//! `sim.loadModel` do with a [`Document`] (its dummies and mesh shapes become scene objects
//! under their parents, keeping their local poses, aliases and colours).

use nalgebra::{Quaternion, UnitQuaternion};
use vrep_maze_core::coppelia::frame::euler_from_rotation;
use vrep_maze_core::coppelia::xml::{Body, Document, FileKind};

use super::mesh::Mesh;
use super::{NewObject, ObjectType, Scene, SimError};

/// What loading a model added.
#[derive(Debug, Clone, PartialEq)]
pub struct Loaded {
    /// The model base (the file's first object without a parent): what `simxLoadModel`
    /// answers.
    pub base: i32,
    /// Every added object, in the file's order.
    pub handles: Vec<i32>,
    /// The triangles of all its meshes (what the load costs, [`vrep_maze_core::coppelia::model_cost`]).
    pub triangles: usize,
}

/// Adds the objects of the model `doc` to `scene`. A scene file or an empty model is
/// refused before anything is added.
pub fn load(scene: &mut Scene, doc: &Document) -> Result<Loaded, SimError> {
    if doc.kind != FileKind::Model {
        return Err(SimError::BadScene(
            "the file is a scene (exhaustiveScene), not a model".to_string(),
        ));
    }
    let Some(base_index) = doc.objects.iter().position(|o| o.parent.is_none()) else {
        return Err(SimError::BadScene("the model has no objects".to_string()));
    };
    let mut handles = Vec::with_capacity(doc.objects.len());
    let mut triangles = 0;
    let mut meshes = Vec::new();
    for o in &doc.objects {
        let [w, x, y, z] = o.quaternion;
        let rotation = UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z));
        let (kind, size, colour) = match &o.body {
            Body::Dummy(d) => (ObjectType::Dummy, [d.size; 3], d.colour),
            Body::Shape(s) => {
                triangles += s.mesh.triangles();
                let (lo, hi) = s.mesh.bounds().unwrap_or(([0.0; 3], [0.0; 3]));
                (
                    ObjectType::Shape,
                    std::array::from_fn(|k| hi[k] - lo[k]),
                    s.colour,
                )
            }
        };
        let handle = scene.add_loaded(
            &o.alias,
            NewObject {
                kind,
                parent: None,
                position: o.position,
                orientation: euler_from_rotation(&rotation),
                size,
                colour: colour.map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8),
            },
        );
        if let Body::Shape(s) = &o.body
            && s.mesh.triangles() > 0
        {
            meshes.push((handle, scene_mesh(&s.mesh)));
        }
        handles.push(handle);
    }
    for (handle, mesh) in meshes {
        scene.set_mesh(handle, mesh)?;
    }
    for (o, &handle) in doc.objects.iter().zip(&handles) {
        let Some(parent) = o.parent else { continue };
        let index = doc.objects.iter().position(|p| p.handle == parent);
        let parent_handle = index
            .map(|i| handles[i])
            .ok_or_else(|| SimError::BadScene(format!("'{}' has an unknown parent", o.alias)))?;
        scene.set_parent(handle, Some(parent_handle), false)?;
    }
    Ok(Loaded {
        base: handles[base_index],
        handles,
        triangles,
    })
}

/// The file's triangles as the scene keeps them (relative to the shape's frame, as loaded:
/// a loaded mesh is not merged as a created one is).
fn scene_mesh(m: &vrep_maze_core::coppelia::xml::Mesh) -> Mesh {
    Mesh {
        vertices: m.vertices.iter().flatten().copied().collect(),
        indices: m.indices.iter().map(|&i| i as i32).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vrep_maze_core::coppelia::xml::read;

    const TWO_RECTS: &str =
        include_str!("../../../../tests/coppeliasim-xml/mesh-two-rects-4.5.1.simmodel.xml");

    #[test]
    fn the_reference_mesh_model_enters_the_scene_as_one_green_shape() {
        let mut scene = Scene::course();
        let doc = read(TWO_RECTS).unwrap();
        let loaded = load(&mut scene, &doc).unwrap();
        assert_eq!(loaded.handles, [loaded.base]);
        assert_eq!(loaded.triangles, 4);
        let o = scene.get(loaded.base).unwrap();
        assert_eq!(
            (o.name.as_str(), o.alias.as_str()),
            ("MazeMesh", "MazeMesh")
        );
        assert_eq!((o.kind, o.colour), (ObjectType::Shape, [0, 255, 0]));
        assert!((o.size[0] - 1.4).abs() < 1e-6 && (o.size[1] - 1.1).abs() < 1e-6);
        let mesh = o.mesh.as_ref().expect("the loaded triangles are kept");
        assert_eq!(mesh.indices.len(), 12);
        let (lo, hi) = o.bounding_box();
        assert!((lo[0] + 0.35).abs() < 1e-6 && (hi[1] - 1.05).abs() < 1e-6);
        // A second load keeps the alias and names the object as a paste would.
        let again = load(&mut scene, &doc).unwrap();
        assert_eq!(scene.get(again.base).unwrap().name, "MazeMesh0");
        assert_eq!(scene.get(again.base).unwrap().alias, "MazeMesh");
    }

    #[test]
    fn children_keep_their_local_pose_under_their_parent_and_scenes_are_refused() {
        let course = include_str!("../../../../tests/coppeliasim-xml/course-4.5.1.simscene.xml");
        let mut doc = read(course).unwrap();
        let mut scene = Scene::empty();
        assert!(load(&mut scene, &doc).is_err());
        assert!(scene.is_empty(), "nothing added");
        doc.kind = FileKind::Model;
        doc.objects.truncate(3); // Floor, Maze, Line
        doc.objects[2].parent = Some(doc.objects[1].handle);
        doc.objects[1].position = [1.0, 2.0, 0.0];
        let loaded = load(&mut scene, &doc).unwrap();
        let line = loaded.handles[2];
        assert_eq!(scene.get(line).unwrap().parent, Some(loaded.handles[1]));
        let (p, _) = scene
            .pose(line, vrep_maze_core::coppelia::HANDLE_WORLD)
            .unwrap();
        assert!(
            (p[0] - 1.0).abs() < 1e-9 && (p[1] - 2.0).abs() < 1e-9 && (p[2] - 0.001).abs() < 1e-9
        );
        assert_eq!(loaded.base, loaded.handles[0], "Floor is the first root");
    }
}
