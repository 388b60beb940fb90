//! What each command does to the simulator: [`execute`] one stored command in a pass, its
//! modeled server work ([`cost`]), and the group data of `simxGetObjectGroupData`.

use std::path::PathBuf;
use vrep_maze_core::coppelia::frame::rotation_from_euler;
use vrep_maze_core::coppelia::{HANDLE_ALL, HANDLE_PARENT, HANDLE_WORLD};

use crate::legacy::command::{
    ALL_OBJECTS, Command, FIRST_OBJECT_TYPE, GroupData, LAST_OBJECT_TYPE, SimControl,
    TEMP_FILE_PREFIX, encode_handle_list, group,
};
use crate::legacy::wire::Block;
use crate::sim::Simulator;
use crate::sim::cost::{self, Op};
use crate::sim::model::{self, Loaded};

fn f32x3(v: [f64; 3]) -> Vec<u8> {
    v.iter().flat_map(|x| (*x as f32).to_le_bytes()).collect()
}

fn widen(v: [f32; 3]) -> [f64; 3] {
    [v[0] as f64, v[1] as f64, v[2] as f64]
}

/// The work a real CoppeliaSim 4.5.1 does for one command, from the scene as it is before
/// the command (`vrep_maze_core::coppelia::cost`, spec "Costs that grow with the scene"): a paste grows
/// with the objects in the scene (repeated handles are pasted once: the plugin selects them,
/// simExtRemoteApi@coppeliasim-v4.5.1-rev4 `simxCmd.cpp:1891-1921`), a set-parent with the
/// new parent's children and the parentless objects, a removal with the objects in the scene;
/// a position or orientation is half a pose. Other commands do no work the spec has a figure
/// for (their pass still takes the pass floor).
pub(super) fn ops(sim: &Simulator, block: &Block) -> Vec<Op> {
    let scene = &sim.scene;
    let work = match Command::from_block(block) {
        Some(Command::CopyPaste(hs)) => cost::paste(scene, &hs),
        Some(Command::SetObjectParent { parent, .. }) => {
            cost::set_parent(scene, (parent != HANDLE_WORLD).then_some(parent))
        }
        Some(Command::SetPosition { .. } | Command::SetOrientation { .. }) => {
            cost::pose(scene, true)
        }
        Some(Command::RemoveObject(h)) => cost::remove(scene, &[h]),
        _ => return vec![],
    };
    vec![Op::LegacyCommand, work]
}

/// Executes one command; returns (success, reply pure data, the work it made the simulator
/// do). The work is [`ops`] from the scene before the command, plus for `simxLoadModel` the
/// loading of what the file turned out to hold ([`Op::LoadModel`]).
pub(super) fn execute_with_ops(sim: &mut Simulator, block: &Block) -> (bool, Vec<u8>, Vec<Op>) {
    let mut work = ops(sim, block);
    if let Some(Command::LoadModel(path)) = Command::from_block(block) {
        let (ok, data, triangles) = load_model(sim, &path);
        work.push(Op::LoadModel { triangles });
        return (ok, data, work);
    }
    let (ok, data) = execute(sim, block);
    (ok, data, work)
}

/// Where a file name of a load, transfer or erase command is on the server's machine: names
/// starting with [`TEMP_FILE_PREFIX`] (and every transferred or erased file) in the folder
/// for transferred files, other paths as given. A transferred or erased name must be a plain
/// file name.
fn server_path(sim: &Simulator, name: &str, transferred: bool) -> Option<PathBuf> {
    let plain = !name.is_empty() && !name.contains(['/', '\\']) && name != "..";
    if transferred || name.starts_with(TEMP_FILE_PREFIX) {
        plain.then(|| sim.temp_dir.join(name))
    } else {
        Some(PathBuf::from(name))
    }
}

/// `simxLoadModel(path, 0)`: (success, the base handle or -1, triangles loaded). Like
/// CoppeliaSim, the reader is chosen by the ending: only `.simmodel.xml` files are read (a
/// `.ttm` is CoppeliaSim's binary format, which the emulator does not read; spec "One object
/// instead of thousands": an XML model sent under a `.ttm` name failed with return code 8).
fn load_model(sim: &mut Simulator, path: &str) -> (bool, Vec<u8>, usize) {
    let failed = (false, (-1i32).to_le_bytes().to_vec(), 0);
    let Some(file) = server_path(sim, path, false) else {
        return failed;
    };
    if !path.ends_with(vrep_maze_core::coppelia::xml::FileKind::Model.extension()) {
        return failed;
    }
    let Ok(text) = vrep_maze_core::coppelia::xml::read_file(&file) else {
        return failed;
    };
    let Ok(doc) = vrep_maze_core::coppelia::xml::read(&text) else {
        return failed;
    };
    match model::load(&mut sim.scene, &doc) {
        Ok(Loaded {
            base, triangles, ..
        }) => (true, base.to_le_bytes().to_vec(), triangles),
        Err(_) => failed,
    }
}

/// Executes one command; returns (success, reply pure data).
pub(super) fn execute(sim: &mut Simulator, block: &Block) -> (bool, Vec<u8>) {
    let Some(cmd) = Command::from_block(block) else {
        return (false, block.data.clone());
    };
    let i32le = |v: i32| v.to_le_bytes().to_vec();
    let scene = &mut sim.scene;
    match cmd {
        Command::GetObjectHandle(name) => match scene.resolve(&name) {
            Ok(h) => (true, i32le(h)),
            Err(_) => (false, i32le(-1)),
        },
        Command::GetObjects(t) => {
            let hs: Vec<i32> = scene
                .objects()
                .filter(|o| t == HANDLE_ALL || o.kind.code() == t)
                .map(|o| o.handle)
                .collect();
            (true, encode_handle_list(&hs))
        }
        Command::GetObjectGroupData {
            object_type,
            data_type,
        } => match group_data(sim, object_type, data_type) {
            Some(g) => (true, g.encode()),
            None => (false, vec![]),
        },
        Command::GetObjectParent(h) => (
            true,
            i32le(
                scene
                    .get(h)
                    .ok()
                    .and_then(|o| o.parent)
                    .unwrap_or(HANDLE_WORLD),
            ),
        ),
        Command::SetObjectParent {
            handle,
            parent,
            keep_in_place,
        } => {
            let parent = (parent != HANDLE_WORLD).then_some(parent);
            (
                scene.set_parent(handle, parent, keep_in_place).is_ok(),
                vec![],
            )
        }
        Command::CopyPaste(hs) => (
            true,
            encode_handle_list(&scene.copy_paste(&hs).unwrap_or_default()),
        ),
        Command::SetPosition {
            handle,
            relative_to,
            xyz,
        } => (
            scene.set_position(handle, relative_to, widen(xyz)).is_ok(),
            vec![],
        ),
        Command::SetOrientation {
            handle,
            relative_to,
            euler,
        } => (
            scene
                .set_orientation(handle, relative_to, widen(euler))
                .is_ok(),
            vec![],
        ),
        Command::GetPosition {
            handle,
            relative_to,
        } => match scene.pose(handle, relative_to) {
            Ok((p, _)) => (true, f32x3(p)),
            Err(_) => (false, vec![]),
        },
        Command::GetOrientation {
            handle,
            relative_to,
        } => match scene.pose(handle, relative_to) {
            Ok((_, e)) => (true, f32x3(e)),
            Err(_) => (false, vec![]),
        },
        Command::GetQuaternion {
            handle,
            relative_to,
        } => match scene.pose(handle, relative_to) {
            Ok((_, e)) => {
                let q = rotation_from_euler(e);
                (
                    true,
                    [q.i, q.j, q.k, q.w]
                        .iter()
                        .flat_map(|x| (*x as f32).to_le_bytes())
                        .collect(),
                )
            }
            Err(_) => (false, vec![]),
        },
        Command::GetObjectFloatParam { handle, param } => {
            // failure when the simulator call fails (unknown object or parameter), spec 12.15
            match scene.get(handle).ok().and_then(|o| o.float_param(param)) {
                Some(v) => (true, (v as f32).to_le_bytes().to_vec()),
                None => (false, vec![]),
            }
        }
        Command::RemoveObject(h) => (scene.remove(h).is_ok(), vec![]),
        Command::GetIntParam(p) => match sim.int_param(p) {
            Some(v) => (true, i32le(v)),
            None => (false, vec![]),
        },
        Command::SetIntParam(p, v) => (sim.set_int_param(p, v), vec![]),
        Command::Simulation(c) => {
            let ok = match c {
                SimControl::Start => sim.start(),
                SimControl::Pause => sim.pause(),
                SimControl::Stop => sim.stop(),
            };
            (ok, vec![])
        }
        Command::GetIntSignal(name) => match sim.int_signals.get(&name) {
            Some(v) => (true, i32le(*v)),
            None => (false, vec![]),
        },
        Command::SetIntSignal(name, v) => {
            sim.int_signals.insert(name, v);
            (true, vec![])
        }
        Command::ClearIntSignal(name) => {
            if name.is_empty() {
                sim.int_signals.clear();
            } else {
                sim.int_signals.remove(&name);
            }
            (true, vec![])
        }
        Command::GetStringSignal(name) => match sim.string_signals.get(&name) {
            Some(v) => (true, v.clone()),
            None => (false, vec![]),
        },
        Command::SetStringSignal(name, v) => {
            sim.string_signals.insert(name, v);
            (true, vec![])
        }
        Command::LoadModel(path) => {
            let (ok, data, _) = load_model(sim, &path);
            (ok, data)
        }
        Command::TransferFile { name, data } => {
            let written = server_path(sim, &name, true)
                .is_some_and(|file| std::fs::write(file, &data).is_ok());
            (written, vec![])
        }
        Command::EraseFile(name) => {
            let erased = server_path(sim, &name, true)
                .is_some_and(|file| std::fs::remove_file(file).is_ok());
            (erased, vec![])
        }
        // no physics, joints or cameras here: refused as the real server refuses what it
        // cannot do (synchronous mode: a port not authorised for it)
        Command::Synchronous(_)
        | Command::SynchronousTrigger
        | Command::GetJointPosition(_)
        | Command::SetJointTargetVelocity { .. }
        | Command::GetVisionSensorImage { .. }
        | Command::GetObjectChild { .. }
        | Command::GetObjectIntParam { .. } => (false, block.data.clone()),
        Command::KillConnection => (true, vec![]),
    }
}

/// `simxGetObjectGroupData` over the scene; `None` = failure (unknown object or data type).
fn group_data(sim: &Simulator, object_type: i32, data_type: i32) -> Option<GroupData> {
    let scene = &sim.scene;
    let objects: Vec<_> = match object_type {
        ALL_OBJECTS => scene.objects().collect(),
        FIRST_OBJECT_TYPE..=LAST_OBJECT_TYPE => scene
            .objects()
            .filter(|o| o.kind.code() == object_type)
            .collect(),
        _ => return None,
    };
    let mut g = GroupData {
        handles: objects.iter().map(|o| o.handle).collect(),
        ..Default::default()
    };
    for o in &objects {
        let rel = |abs: bool| if abs { HANDLE_WORLD } else { HANDLE_PARENT };
        let pose = |abs: bool| scene.pose(o.handle, rel(abs)).ok();
        let push3 = |g: &mut GroupData, v: [f64; 3]| g.floats.extend(v.iter().map(|x| *x as f32));
        match data_type {
            group::NAMES => g.strings.push(o.name.clone()),
            group::TYPES => g.ints.push(o.kind.code()),
            group::PARENTS => g.ints.push(o.parent.unwrap_or(HANDLE_WORLD)),
            group::ABSOLUTE_POSITIONS | group::RELATIVE_POSITIONS => {
                push3(&mut g, pose(data_type == group::ABSOLUTE_POSITIONS)?.0)
            }
            group::ABSOLUTE_ORIENTATIONS | group::RELATIVE_ORIENTATIONS => {
                push3(&mut g, pose(data_type == group::ABSOLUTE_ORIENTATIONS)?.1)
            }
            group::ABSOLUTE_QUATERNIONS | group::RELATIVE_QUATERNIONS => {
                let q = rotation_from_euler(pose(data_type == group::ABSOLUTE_QUATERNIONS)?.1);
                g.floats
                    .extend([q.i, q.j, q.k, q.w].iter().map(|x| *x as f32));
            }
            group::ABSOLUTE_POSES | group::RELATIVE_POSES => {
                let (p, e) = pose(data_type == group::ABSOLUTE_POSES)?;
                push3(&mut g, p);
                push3(&mut g, e);
            }
            group::ALIASES => g.strings.push(o.alias.clone()),
            group::FULL_PATHS => g.strings.push(scene.path(o.handle).ok()?),
            _ => return None,
        }
    }
    Some(g)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::legacy::command::{decode_handle_list, opmode, read_i32};
    use crate::sim::Scene;

    /// The course scene with `Maze` moved and turned a quarter about z, and `Line` made its
    /// child in place, so that `Line`'s absolute and relative data differ.
    fn sim() -> (Simulator, i32, i32) {
        let mut sim = Simulator::new(Scene::course(), 0);
        let maze = sim.scene.resolve("Maze").unwrap();
        let line = sim.scene.resolve("Line").unwrap();
        let s = &mut sim.scene;
        s.set_position(maze, HANDLE_WORLD, [1.0, 2.0, 0.0]).unwrap();
        s.set_orientation(maze, HANDLE_WORLD, [0.0, 0.0, std::f64::consts::FRAC_PI_2])
            .unwrap();
        s.set_parent(line, Some(maze), true).unwrap();
        (sim, maze, line)
    }

    /// Executes `cmd` as a blocking command: `Some(reply data)` on success.
    fn run(sim: &mut Simulator, cmd: Command) -> Option<Vec<u8>> {
        let (ok, data) = execute(sim, &cmd.to_block(opmode::BLOCKING));
        ok.then_some(data)
    }

    fn group_of(sim: &mut Simulator, object_type: i32, data_type: i32) -> Option<GroupData> {
        let data = run(
            sim,
            Command::GetObjectGroupData {
                object_type,
                data_type,
            },
        )?;
        Some(GroupData::decode(&data).expect("well-formed group data"))
    }

    fn floats(v: &[f64]) -> Vec<f32> {
        v.iter().map(|x| *x as f32).collect()
    }

    /// Parameters 15..20 of the course `Line` are its bounding box as the real 4.5.1 gives
    /// it; an unknown parameter or object fails.
    #[test]
    fn float_parameters_15_to_20_are_the_bounding_box() {
        let (mut sim, _, line) = sim();
        let got: Vec<f32> = (15..=20)
            .map(|param| {
                let data = run(
                    &mut sim,
                    Command::GetObjectFloatParam {
                        handle: line,
                        param,
                    },
                )
                .expect("a bounding-box parameter");
                f32::from_le_bytes(data[..4].try_into().unwrap())
            })
            .collect();
        assert_eq!(got, [-0.3, -0.05, 0.0, 0.3, 0.05, 0.0]);
        for (handle, param) in [(line, 14), (line, 21), (9999, 15)] {
            assert_eq!(
                run(&mut sim, Command::GetObjectFloatParam { handle, param }),
                None
            );
        }
    }

    #[test]
    fn group_data_types_carry_what_their_names_say() {
        let (mut sim, maze, line) = sim();
        let handles: Vec<i32> = sim.scene.objects().map(|o| o.handle).collect();
        let mut all = |data_type| group_of(&mut sim, ALL_OBJECTS, data_type).unwrap();
        let names = all(group::NAMES);
        assert_eq!(names.handles, handles);
        assert_eq!(names.strings, ["Floor", "Maze", "Line", "Start", "End"]);
        assert_eq!(all(group::TYPES).ints, [0, 4, 0, 0, 0]);
        assert_eq!(all(group::PARENTS).ints, [-1, -1, maze, -1, -1]);
        assert_eq!(all(group::ALIASES).strings, names.strings);
        assert_eq!(
            all(group::FULL_PATHS).strings,
            ["/Floor", "/Maze", "/Maze/Line", "/Start", "/End"]
        );

        let per_object = |g: GroupData, n: usize| {
            assert!(g.ints.is_empty() && g.strings.is_empty());
            assert_eq!(g.floats.len(), n * handles.len());
            g.floats[n * 2..n * 3].to_vec() // Line's values
        };
        let (abs_p, abs_e) = sim.scene.pose(line, HANDLE_WORLD).unwrap();
        let (rel_p, rel_e) = sim.scene.pose(line, HANDLE_PARENT).unwrap();
        assert_ne!(floats(&abs_p), floats(&rel_p));
        assert_ne!(floats(&abs_e), floats(&rel_e));
        let quaternion = |e| {
            let q = rotation_from_euler(e);
            floats(&[q.i, q.j, q.k, q.w])
        };
        let mut all = |data_type| group_of(&mut sim, ALL_OBJECTS, data_type).unwrap();
        let cases = [
            (group::ABSOLUTE_POSITIONS, 3, floats(&abs_p)),
            (group::RELATIVE_POSITIONS, 3, floats(&rel_p)),
            (group::ABSOLUTE_ORIENTATIONS, 3, floats(&abs_e)),
            (group::RELATIVE_ORIENTATIONS, 3, floats(&rel_e)),
            (group::ABSOLUTE_QUATERNIONS, 4, quaternion(abs_e)),
            (group::RELATIVE_QUATERNIONS, 4, quaternion(rel_e)),
            (group::ABSOLUTE_POSES, 6, floats(&[abs_p, abs_e].concat())),
            (group::RELATIVE_POSES, 6, floats(&[rel_p, rel_e].concat())),
        ];
        for (data_type, n, want) in cases {
            assert_eq!(per_object(all(data_type), n), want, "data type {data_type}");
        }
    }

    #[test]
    fn group_data_filters_by_object_type_and_rejects_the_rest() {
        let (mut sim, maze, _) = sim();
        let dummy = sim.scene.get(maze).unwrap().kind.code();
        assert_eq!(
            group_of(&mut sim, dummy, group::NAMES).unwrap().strings,
            ["Maze"]
        );
        let none = group_of(&mut sim, LAST_OBJECT_TYPE, group::NAMES).unwrap();
        assert_eq!(none, GroupData::default(), "a valid type without objects");
        for object_type in [FIRST_OBJECT_TYPE - 1, LAST_OBJECT_TYPE + 1, HANDLE_ALL] {
            assert_eq!(group_of(&mut sim, object_type, group::NAMES), None);
        }
        for data_type in [-1, 11, 19, 22] {
            assert_eq!(group_of(&mut sim, ALL_OBJECTS, data_type), None);
        }
    }

    #[test]
    fn get_objects_takes_handle_all_or_a_type() {
        let (mut sim, maze, _) = sim();
        let all: Vec<i32> = sim.scene.objects().map(|o| o.handle).collect();
        let list = |sim: &mut Simulator, t| {
            decode_handle_list(&run(sim, Command::GetObjects(t)).unwrap()).unwrap()
        };
        assert_eq!(list(&mut sim, HANDLE_ALL), all);
        let dummy = sim.scene.get(maze).unwrap().kind.code();
        assert_eq!(list(&mut sim, dummy), [maze]);
    }

    #[test]
    fn drawing_commands_do_the_work_the_model_prices_from_the_scene_counts() {
        let (sim, maze, line) = sim();
        let block = |c: Command| c.to_block(opmode::BLOCKING);
        // 5 objects; pasting `line` twice is one copy
        assert_eq!(
            ops(&sim, &block(Command::CopyPaste(vec![line, line]))),
            [
                Op::LegacyCommand,
                Op::Paste {
                    copies: 1,
                    objects: 5
                }
            ]
        );
        // `Maze` has one child (`Line`); 4 objects are parentless
        let to_maze = Command::SetObjectParent {
            handle: line,
            parent: maze,
            keep_in_place: true,
        };
        assert_eq!(
            ops(&sim, &block(to_maze)),
            [
                Op::LegacyCommand,
                Op::SetParent {
                    children: 1,
                    parentless: 4
                }
            ]
        );
        let at = Command::SetPosition {
            handle: line,
            relative_to: HANDLE_WORLD,
            xyz: [0.0; 3],
        };
        assert_eq!(
            ops(&sim, &block(at)),
            [Op::LegacyCommand, Op::HalfPose { objects: 5 }]
        );
        assert_eq!(
            ops(&sim, &block(Command::RemoveObject(line))),
            [
                Op::LegacyCommand,
                Op::Remove {
                    count: 1,
                    objects: 5
                }
            ]
        );
        assert!(ops(&sim, &block(Command::GetIntParam(0))).is_empty());
    }

    #[test]
    fn a_transferred_model_loads_by_its_temporary_name_and_is_erased() {
        let (mut sim, _, _) = sim();
        let dir = tempfile::tempdir().unwrap();
        sim.temp_dir = dir.path().to_path_buf();
        let text =
            include_str!("../../../../../tests/coppeliasim-xml/mesh-two-rects-4.5.1.simmodel.xml");
        let name = "REMOTE_API_TEMPFILE_42.simmodel.xml";
        let sent = Command::TransferFile {
            name: name.into(),
            data: text.as_bytes().to_vec(),
        };
        assert!(run(&mut sim, sent).is_some());
        assert_eq!(
            std::fs::read_to_string(dir.path().join(name)).unwrap(),
            text
        );
        let before = sim.scene.len();
        let load = Command::LoadModel(name.into()).to_block(opmode::BLOCKING);
        let (ok, data, work) = execute_with_ops(&mut sim, &load);
        assert!(ok);
        let base = read_i32(&data, 0).unwrap();
        assert_eq!(sim.scene.get(base).unwrap().alias, "MazeMesh");
        assert_eq!(sim.scene.len(), before + 1);
        assert_eq!(
            work,
            [Op::LoadModel { triangles: 4 }],
            "two rectangles: four triangles"
        );
        assert!(run(&mut sim, Command::EraseFile(name.into())).is_some());
        assert!(!dir.path().join(name).exists());
        assert!(run(&mut sim, Command::EraseFile(name.into())).is_none());
        assert!(run(&mut sim, Command::LoadModel(name.into())).is_none());
    }

    #[test]
    fn loads_and_transfers_that_cannot_work_fail_and_add_nothing() {
        let (mut sim, _, _) = sim();
        let dir = tempfile::tempdir().unwrap();
        sim.temp_dir = dir.path().to_path_buf();
        let text =
            include_str!("../../../../../tests/coppeliasim-xml/mesh-two-rects-4.5.1.simmodel.xml");
        // The official client's temporary name for option 1 ends in .ttm: not read as XML.
        let ttm = dir.path().join("REMOTE_API_TEMPFILE_1234.ttm");
        std::fs::write(&ttm, text).unwrap();
        let xml_path = dir.path().join("m.simmodel.xml");
        std::fs::write(&xml_path, "<CoppeliaSim><filetype>exhaustiveModel").unwrap();
        let scene = dir.path().join("s.simmodel.xml");
        std::fs::write(
            &scene,
            include_str!("../../../../../tests/coppeliasim-xml/course-4.5.1.simscene.xml"),
        )
        .unwrap();
        let before = sim.scene.len();
        for path in [
            "REMOTE_API_TEMPFILE_1234.ttm".to_string(),
            xml_path.display().to_string(),
            scene.display().to_string(),
            dir.path()
                .join("missing.simmodel.xml")
                .display()
                .to_string(),
        ] {
            let (ok, data) = execute(&mut sim, &Command::LoadModel(path.clone()).to_block(0));
            assert!(!ok, "{path}");
            assert_eq!(read_i32(&data, 0), Some(-1));
        }
        assert_eq!(sim.scene.len(), before);
        for name in ["../escape.simmodel.xml", "a/b", ""] {
            let sent = Command::TransferFile {
                name: name.into(),
                data: vec![1],
            };
            assert!(run(&mut sim, sent).is_none(), "{name}");
        }
    }

    #[test]
    fn removing_a_removed_object_is_still_an_error() {
        // simInternal-old.cpp:5593-5597: the legacy remove command checks the handle
        let (mut sim, _, line) = sim();
        assert!(run(&mut sim, Command::RemoveObject(line)).is_some());
        assert!(run(&mut sim, Command::RemoveObject(line)).is_none());
    }

    #[test]
    fn unknown_or_malformed_commands_fail_and_echo_their_data() {
        let (mut sim, _, _) = sim();
        let mut block = Command::GetIntParam(0).to_block(opmode::BLOCKING);
        block.cmd = 0x2FFF | opmode::BLOCKING;
        block.data = vec![1, 2, 3];
        assert_eq!(execute(&mut sim, &block), (false, vec![1, 2, 3]));
        let floor = run(&mut sim, Command::GetObjectHandle("Floor".into())).unwrap();
        assert_eq!(read_i32(&floor, 0), sim.scene.resolve("Floor").ok());
        let missing = Command::GetObjectHandle("Nope".into()).to_block(opmode::BLOCKING);
        assert_eq!(
            execute(&mut sim, &missing),
            (false, (-1i32).to_le_bytes().to_vec())
        );
    }
}
