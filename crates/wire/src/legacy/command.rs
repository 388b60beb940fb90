//! Command IDs, operation modes, group-data constants, and the typed [`Command`]s we use with
//! their payload encodings (the client encodes them, the server decodes them).

use super::wire::{Block, status};

/// Raw command IDs (`simx_cmd_*`).
pub mod id {
    /// `simx_cmd_synchronous_enable`.
    pub const SYNCHRONOUS_ENABLE: u16 = 0x0001;
    /// `simx_cmd_synchronous_disable`.
    pub const SYNCHRONOUS_DISABLE: u16 = 0x0002;
    /// `simx_cmd_synchronous_next`: the trigger of one simulation step.
    pub const SYNCHRONOUS_NEXT: u16 = 0x0003;
    /// `simx_cmd_get_joint_position`.
    pub const GET_JOINT_POSITION: u16 = 0x1001;
    /// `simx_cmd_get_vision_sensor_image_bw` (one byte a pixel).
    pub const GET_VISION_SENSOR_IMAGE_BW: u16 = 0x1003;
    /// `simx_cmd_get_vision_sensor_image_rgb` (three bytes a pixel).
    pub const GET_VISION_SENSOR_IMAGE_RGB: u16 = 0x1004;
    /// `simx_cmd_set_joint_target_velocity`.
    pub const SET_JOINT_TARGET_VELOCITY: u16 = 0x1008;
    /// `simx_cmd_get_object_int_parameter`.
    pub const GET_OBJECT_INT_PARAMETER: u16 = 0x2008;
    /// `simx_cmd_get_object_child`.
    pub const GET_OBJECT_CHILD: u16 = 0x200B;
    /// `simx_cmd_kill_connection`.
    pub const KILL_CONNECTION: u16 = 0x000A;
    /// `simx_cmd_start_pause_stop_simulation` (ID data 0 start, 1 pause, 2 stop).
    pub const START_PAUSE_STOP_SIMULATION: u16 = 0x1007;
    /// `simx_cmd_get_object_parent`.
    pub const GET_OBJECT_PARENT: u16 = 0x1012;
    /// `simx_cmd_get_object_orientation` (old 4-byte form).
    pub const GET_OBJECT_ORIENTATION_OLD: u16 = 0x1018;
    /// `simx_cmd_get_object_position` (old 4-byte form).
    pub const GET_OBJECT_POSITION_OLD: u16 = 0x1019;
    /// `simx_cmd_set_object_orientation`.
    pub const SET_OBJECT_ORIENTATION: u16 = 0x101A;
    /// `simx_cmd_set_object_position`.
    pub const SET_OBJECT_POSITION: u16 = 0x101B;
    /// `simx_cmd_set_object_parent`.
    pub const SET_OBJECT_PARENT: u16 = 0x101C;
    /// `simx_cmd_get_integer_parameter`.
    pub const GET_INTEGER_PARAMETER: u16 = 0x1021;
    /// `simx_cmd_set_integer_parameter`.
    pub const SET_INTEGER_PARAMETER: u16 = 0x1022;
    /// `simx_cmd_remove_object`.
    pub const REMOVE_OBJECT: u16 = 0x1028;
    /// `simx_cmd_get_objects`.
    pub const GET_OBJECTS: u16 = 0x102A;
    /// `simx_cmd_copy_paste_objects`.
    pub const COPY_PASTE_OBJECTS: u16 = 0x102E;
    /// `simx_cmd_get_object_float_parameter`.
    pub const GET_OBJECT_FLOAT_PARAMETER: u16 = 0x2007;
    /// `simx_cmd_get_object_group_data`.
    pub const GET_OBJECT_GROUP_DATA: u16 = 0x200C;
    /// `simx_cmd_get_object_orientation2`.
    pub const GET_OBJECT_ORIENTATION: u16 = 0x200D;
    /// `simx_cmd_get_object_position2`.
    pub const GET_OBJECT_POSITION: u16 = 0x200E;
    /// `simx_cmd_get_object_handle`.
    pub const GET_OBJECT_HANDLE: u16 = 0x3001;
    /// `simx_cmd_get_object_quaternion`.
    pub const GET_OBJECT_QUATERNION: u16 = 0x2801;
    /// `simx_cmd_load_model`.
    pub const LOAD_MODEL: u16 = 0x3003;
    /// `simx_cmd_transfer_file`.
    pub const TRANSFER_FILE: u16 = 0x3004;
    /// `simx_cmd_erase_file`.
    pub const ERASE_FILE: u16 = 0x3006;
    /// `simx_cmd_clear_integer_signal`.
    pub const CLEAR_INTEGER_SIGNAL: u16 = 0x300E;
    /// `simx_cmd_get_integer_signal`.
    pub const GET_INTEGER_SIGNAL: u16 = 0x3011;
    /// `simx_cmd_set_integer_signal`.
    pub const SET_INTEGER_SIGNAL: u16 = 0x3014;
    /// `simx_cmd_get_string_signal`.
    pub const GET_STRING_SIGNAL: u16 = 0x3012;
    /// `simx_cmd_set_string_signal`.
    pub const SET_STRING_SIGNAL: u16 = 0x3015;
}

/// Operation modes (high bits of the `cmd` word).
pub mod opmode {
    /// Execute once, don't wait.
    pub const ONESHOT: u32 = 0x00000;
    /// Execute once and wait for the reply.
    pub const BLOCKING: u32 = 0x10000;
    /// Keep the command and re-execute it every pass, at most once per `delay` ms.
    pub const STREAMING: u32 = 0x20000;
    /// Split transfer, once.
    pub const ONESHOT_SPLIT: u32 = 0x30000;
    /// Split transfer, streaming.
    pub const STREAMING_SPLIT: u32 = 0x40000;
    /// End the stream of the same identity (echoed once, not executed).
    pub const DISCONTINUE: u32 = 0x50000;
}

/// `sim_appobj_object_type`: as the object type of `simxGetObjectGroupData`, all objects.
pub const ALL_OBJECTS: i32 = 109;
/// Smallest object type code (`sim_object_*_type`: 0 shape, 4 dummy, ...) that
/// `simxGetObjectGroupData` accepts as a filter.
pub const FIRST_OBJECT_TYPE: i32 = 0;
/// Largest such code; CoppeliaSim reads other values than these and [`ALL_OBJECTS`] as a
/// collection handle (we have no collections).
pub const LAST_OBJECT_TYPE: i32 = 107;

/// `simxGetObjectGroupData` data types: what the reply carries for each object. "Absolute"
/// is in the world frame, "relative" in the parent's frame.
pub mod group {
    /// Object names (one string each).
    pub const NAMES: i32 = 0;
    /// Object type codes (one int each).
    pub const TYPES: i32 = 1;
    /// Parent handles, -1 for none (one int each).
    pub const PARENTS: i32 = 2;
    /// Absolute positions (3 floats each).
    pub const ABSOLUTE_POSITIONS: i32 = 3;
    /// Relative positions (3 floats each).
    pub const RELATIVE_POSITIONS: i32 = 4;
    /// Absolute Euler angles (3 floats each).
    pub const ABSOLUTE_ORIENTATIONS: i32 = 5;
    /// Relative Euler angles (3 floats each).
    pub const RELATIVE_ORIENTATIONS: i32 = 6;
    /// Absolute quaternions x, y, z, w (4 floats each).
    pub const ABSOLUTE_QUATERNIONS: i32 = 7;
    /// Relative quaternions x, y, z, w (4 floats each).
    pub const RELATIVE_QUATERNIONS: i32 = 8;
    /// Absolute position then Euler angles (6 floats each).
    pub const ABSOLUTE_POSES: i32 = 9;
    /// Relative position then Euler angles (6 floats each).
    pub const RELATIVE_POSES: i32 = 10;
    /// Aliases (one string each).
    pub const ALIASES: i32 = 20;
    /// Full object paths such as `/Maze/Line[1]` (one string each).
    pub const FULL_PATHS: i32 = 21;
}

/// Simulation control for [`Command::Simulation`]; the value is the identification data.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SimControl {
    /// `simxStartSimulation` (0).
    Start = 0,
    /// `simxPauseSimulation` (1).
    Pause = 1,
    /// `simxStopSimulation` (2).
    Stop = 2,
}

/// A typed request of the commands we implement (client builds, server decodes).
#[derive(Debug, Clone, PartialEq)]
pub enum Command {
    /// `simxGetObjectHandle(name)`.
    GetObjectHandle(String),
    /// `simxGetObjects(type)`: handles of the objects of a type code, or of all objects with
    /// [`vrep_maze_core::coppelia::HANDLE_ALL`].
    GetObjects(i32),
    /// `simxGetObjectGroupData(objectType, dataType)`.
    GetObjectGroupData {
        /// [`ALL_OBJECTS`], or an object type code from [`FIRST_OBJECT_TYPE`] to
        /// [`LAST_OBJECT_TYPE`].
        object_type: i32,
        /// What to return for each object (see [`group`]).
        data_type: i32,
    },
    /// `simxGetObjectParent(handle)`.
    GetObjectParent(i32),
    /// `simxSetObjectParent(handle, parent, keepInPlace)`.
    SetObjectParent {
        /// The object to move in the tree.
        handle: i32,
        /// Its new parent, [`vrep_maze_core::coppelia::HANDLE_WORLD`] (-1) for none.
        parent: i32,
        /// Keep the object's world pose (else keep its pose relative to the parent).
        keep_in_place: bool,
    },
    /// `simxCopyPasteObjects(handles)` (sent with the do-not-overwrite bit).
    CopyPaste(Vec<i32>),
    /// `simxSetObjectPosition(handle, rel, xyz)`.
    SetPosition {
        /// The object to move.
        handle: i32,
        /// Frame of `xyz`: [`vrep_maze_core::coppelia::HANDLE_WORLD`], [`vrep_maze_core::coppelia::HANDLE_PARENT`]
        /// or an object handle.
        relative_to: i32,
        /// The new position in metres.
        xyz: [f32; 3],
    },
    /// `simxGetObjectPosition(handle, rel)`: reply x, y, z.
    GetPosition {
        /// The object asked about.
        handle: i32,
        /// Frame of the reply (as for [`Command::SetPosition`]).
        relative_to: i32,
    },
    /// `simxSetObjectOrientation(handle, rel, euler)`.
    SetOrientation {
        /// The object to turn.
        handle: i32,
        /// Frame of `euler` (as for [`Command::SetPosition`]).
        relative_to: i32,
        /// The new orientation as CoppeliaSim Euler angles in radians
        /// ([`vrep_maze_core::coppelia::frame`]).
        euler: [f32; 3],
    },
    /// `simxGetObjectOrientation(handle, rel)`: reply Euler angles.
    GetOrientation {
        /// The object asked about.
        handle: i32,
        /// Frame of the reply (as for [`Command::SetPosition`]).
        relative_to: i32,
    },
    /// `simxGetObjectQuaternion(handle, rel)`: reply x, y, z, w.
    GetQuaternion {
        /// The object asked about.
        handle: i32,
        /// Frame of the reply (as for [`Command::SetPosition`]).
        relative_to: i32,
    },
    /// `simxGetObjectFloatParameter(handle, param)`: reply one f32 (e.g. the bounding box,
    /// [`vrep_maze_core::coppelia::OBJFLOATPARAM_BBOX`]).
    GetObjectFloatParam {
        /// The object asked about.
        handle: i32,
        /// The parameter ID (`sim_objfloatparam_*`).
        param: i32,
    },
    /// `simxRemoveObject(handle)`.
    RemoveObject(i32),
    /// `simxGetIntegerParameter(param)`.
    GetIntParam(i32),
    /// `simxSetIntegerParameter(param, value)`.
    SetIntParam(i32, i32),
    /// `simxStart/Pause/StopSimulation`.
    Simulation(SimControl),
    /// `simxGetIntegerSignal(name)`.
    GetIntSignal(String),
    /// `simxSetIntegerSignal(name, value)`.
    SetIntSignal(String, i32),
    /// `simxClearIntegerSignal(name)`.
    ClearIntSignal(String),
    /// `simxGetStringSignal(name)`: reply the signal's bytes.
    GetStringSignal(String),
    /// `simxSetStringSignal(name, value)`.
    SetStringSignal(String, Vec<u8>),
    /// `simxLoadModel(path, 0)`: loads a model file on the server's machine (names starting
    /// with [`TEMP_FILE_PREFIX`] are in the server's folder for transferred files); reply
    /// the model base's handle.
    LoadModel(String),
    /// `simxTransferFile`: writes `data` to the file `name` in the server's folder for
    /// transferred files.
    TransferFile {
        /// The file's name on the server (no folder).
        name: String,
        /// The file's bytes.
        data: Vec<u8>,
    },
    /// `simxEraseFile(name)`: removes a file the client transferred.
    EraseFile(String),
    /// `simxSynchronous(enable)`: stepping (synchronous) mode on or off for this
    /// connection; refused (status 1) on a port not authorised for it.
    Synchronous(bool),
    /// `simxSynchronousTrigger`: lets one simulation step run (synchronous mode, simulation
    /// advancing).
    SynchronousTrigger,
    /// `simxGetJointPosition(handle)`: reply one f32.
    GetJointPosition(i32),
    /// `simxSetJointTargetVelocity(handle, velocity)`.
    SetJointTargetVelocity {
        /// The joint.
        handle: i32,
        /// Its target velocity, rad/s (m/s for a prismatic joint).
        velocity: f32,
    },
    /// `simxGetVisionSensorImage(handle, options)`: reply i32 width, i32 height, then the
    /// pixels ([`decode_image`]).
    GetVisionSensorImage {
        /// The vision sensor.
        handle: i32,
        /// Options bit 0: one byte a pixel (grey) instead of three (RGB); the client picks
        /// the command ID by it.
        greyscale: bool,
    },
    /// `simxGetObjectChild(handle, index)`: reply the child's handle, -1 for none.
    GetObjectChild {
        /// The parent.
        handle: i32,
        /// Which child, from 0.
        index: i32,
    },
    /// `simxGetObjectIntParameter(handle, param)`: reply one i32 (e.g. a vision sensor's
    /// resolution, `sim_visionintparam_resolution_x` 1002).
    GetObjectIntParam {
        /// The object asked about.
        handle: i32,
        /// The parameter ID (`sim_objintparam_*`, `sim_visionintparam_*`).
        param: i32,
    },
    /// The kill block `simxFinish` sends.
    KillConnection,
}

/// Server-side file names starting with this are in the server's folder for transferred
/// files (simExtRemoteApi `simxCmd.cpp`, `simx_cmd_load_model`).
pub const TEMP_FILE_PREFIX: &str = "REMOTE_API_TEMPFILE_";

fn cstr(s: &str) -> Vec<u8> {
    let mut b: Vec<u8> = s.bytes().filter(|&c| c != 0).collect();
    b.push(0);
    b
}

fn i32s(values: &[i32]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

fn f32s(values: &[f32]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// Reads the `n`-th little-endian i32 of `b`.
pub fn read_i32(b: &[u8], n: usize) -> Option<i32> {
    b.get(n * 4..n * 4 + 4)
        .map(|s| i32::from_le_bytes([s[0], s[1], s[2], s[3]]))
}

/// Reads the `n`-th little-endian f32 of `b`.
pub fn read_f32(b: &[u8], n: usize) -> Option<f32> {
    b.get(n * 4..n * 4 + 4)
        .map(|s| f32::from_le_bytes([s[0], s[1], s[2], s[3]]))
}

/// Decodes a `simxGetVisionSensorImage` reply with `bytes_per_pixel` (1 grey, 3 RGB): width,
/// height and the pixels, rows as the sensor gives them (the bottom row first); `None` when
/// the sizes do not add up.
pub fn decode_image(b: &[u8], bytes_per_pixel: usize) -> Option<(usize, usize, &[u8])> {
    let width = usize::try_from(read_i32(b, 0)?).ok()?;
    let height = usize::try_from(read_i32(b, 1)?).ok()?;
    let pixels = &b[8..];
    (width.checked_mul(height)?.checked_mul(bytes_per_pixel)? == pixels.len())
        .then_some((width, height, pixels))
}

/// Reads three f32 from `b` starting at byte `at`.
pub fn read_f32x3(b: &[u8], at: usize) -> Option<[f32; 3]> {
    let f = |k: usize| {
        b.get(at + 4 * k..at + 4 * k + 4)
            .map(|s| f32::from_le_bytes([s[0], s[1], s[2], s[3]]))
    };
    Some([f(0)?, f(1)?, f(2)?])
}

impl Command {
    /// Raw command ID.
    pub fn raw_id(&self) -> u16 {
        use Command::*;
        match self {
            GetObjectHandle(_) => id::GET_OBJECT_HANDLE,
            GetObjects(_) => id::GET_OBJECTS,
            GetObjectGroupData { .. } => id::GET_OBJECT_GROUP_DATA,
            GetObjectParent(_) => id::GET_OBJECT_PARENT,
            SetObjectParent { .. } => id::SET_OBJECT_PARENT,
            CopyPaste(_) => id::COPY_PASTE_OBJECTS,
            SetPosition { .. } => id::SET_OBJECT_POSITION,
            GetPosition { .. } => id::GET_OBJECT_POSITION,
            SetOrientation { .. } => id::SET_OBJECT_ORIENTATION,
            GetOrientation { .. } => id::GET_OBJECT_ORIENTATION,
            GetQuaternion { .. } => id::GET_OBJECT_QUATERNION,
            GetObjectFloatParam { .. } => id::GET_OBJECT_FLOAT_PARAMETER,
            RemoveObject(_) => id::REMOVE_OBJECT,
            GetIntParam(_) => id::GET_INTEGER_PARAMETER,
            SetIntParam(..) => id::SET_INTEGER_PARAMETER,
            Simulation(_) => id::START_PAUSE_STOP_SIMULATION,
            GetIntSignal(_) => id::GET_INTEGER_SIGNAL,
            SetIntSignal(..) => id::SET_INTEGER_SIGNAL,
            ClearIntSignal(_) => id::CLEAR_INTEGER_SIGNAL,
            GetStringSignal(_) => id::GET_STRING_SIGNAL,
            SetStringSignal(..) => id::SET_STRING_SIGNAL,
            LoadModel(_) => id::LOAD_MODEL,
            TransferFile { .. } => id::TRANSFER_FILE,
            EraseFile(_) => id::ERASE_FILE,
            Synchronous(true) => id::SYNCHRONOUS_ENABLE,
            Synchronous(false) => id::SYNCHRONOUS_DISABLE,
            SynchronousTrigger => id::SYNCHRONOUS_NEXT,
            GetJointPosition(_) => id::GET_JOINT_POSITION,
            SetJointTargetVelocity { .. } => id::SET_JOINT_TARGET_VELOCITY,
            GetVisionSensorImage {
                greyscale: true, ..
            } => id::GET_VISION_SENSOR_IMAGE_BW,
            GetVisionSensorImage {
                greyscale: false, ..
            } => id::GET_VISION_SENSOR_IMAGE_RGB,
            GetObjectChild { .. } => id::GET_OBJECT_CHILD,
            GetObjectIntParam { .. } => id::GET_OBJECT_INT_PARAMETER,
            KillConnection => id::KILL_CONNECTION,
        }
    }

    /// The request block in operation mode `opmode` (identification data + pure data as the C
    /// client encodes them).
    pub fn to_block(&self, opmode: u32) -> Block {
        use Command::*;
        let (id_data, data, status) = match self {
            GetObjectHandle(name)
            | GetIntSignal(name)
            | ClearIntSignal(name)
            | GetStringSignal(name)
            | LoadModel(name)
            | EraseFile(name) => (cstr(name), vec![], 0),
            TransferFile { name, data } | SetStringSignal(name, data) => {
                (cstr(name), data.clone(), 0)
            }
            SetIntSignal(name, v) => (cstr(name), i32s(&[*v]), 0),
            GetObjects(t) => (i32s(&[*t]), vec![], 0),
            GetObjectGroupData {
                object_type,
                data_type,
            } => (i32s(&[*object_type, *data_type]), vec![], 0),
            GetObjectParent(h)
            | RemoveObject(h)
            | GetIntParam(h)
            | GetJointPosition(h)
            | GetVisionSensorImage { handle: h, .. } => (i32s(&[*h]), vec![], 0),
            Synchronous(_) | SynchronousTrigger => (vec![], vec![], 0),
            SetJointTargetVelocity { handle, velocity } => {
                (i32s(&[*handle]), f32s(&[*velocity]), 0)
            }
            GetObjectChild { handle, index: p } | GetObjectIntParam { handle, param: p } => {
                (i32s(&[*handle, *p]), vec![], 0)
            }
            SetObjectParent {
                handle,
                parent,
                keep_in_place,
            } => {
                let mut d = i32s(&[*parent]);
                d.push(*keep_in_place as u8);
                (i32s(&[*handle]), d, 0)
            }
            CopyPaste(hs) => (i32s(&[0]), i32s(hs), status::DO_NOT_OVERWRITE),
            SetPosition {
                handle,
                relative_to,
                xyz: v,
            }
            | SetOrientation {
                handle,
                relative_to,
                euler: v,
            } => {
                let mut d = i32s(&[*relative_to]);
                d.extend(f32s(v));
                (i32s(&[*handle]), d, 0)
            }
            GetPosition {
                handle,
                relative_to,
            }
            | GetOrientation {
                handle,
                relative_to,
            }
            | GetQuaternion {
                handle,
                relative_to,
            } => (i32s(&[*handle, *relative_to]), vec![], 0),
            GetObjectFloatParam { handle, param } => (i32s(&[*handle, *param]), vec![], 0),
            SetIntParam(p, v) => (i32s(&[*p]), i32s(&[*v]), 0),
            Simulation(c) => (i32s(&[*c as i32]), vec![], 0),
            KillConnection => (vec![], i32s(&[0]), 0),
        };
        Block {
            cmd: self.raw_id() as u32 | opmode,
            delay: 0,
            sim_time: 0,
            status,
            id_data,
            data,
            split: None,
        }
    }

    /// Decodes a request block (server side). `None` for commands we do not implement or
    /// malformed payloads.
    pub fn from_block(b: &Block) -> Option<Command> {
        let idn = |n| read_i32(&b.id_data, n);
        let dn = |n| read_i32(&b.data, n);
        let name = |b: &Block| {
            b.id_data
                .strip_suffix(&[0])
                .map(|s| String::from_utf8_lossy(s).into_owned())
        };
        Some(match b.raw_id() {
            id::GET_OBJECT_HANDLE => {
                let s = b.id_data.strip_suffix(&[0])?;
                Command::GetObjectHandle(String::from_utf8_lossy(s).into_owned())
            }
            id::GET_INTEGER_SIGNAL => Command::GetIntSignal(name(b)?),
            id::SET_INTEGER_SIGNAL => Command::SetIntSignal(name(b)?, dn(0)?),
            id::CLEAR_INTEGER_SIGNAL => Command::ClearIntSignal(name(b)?),
            id::GET_STRING_SIGNAL => Command::GetStringSignal(name(b)?),
            id::SET_STRING_SIGNAL => Command::SetStringSignal(name(b)?, b.data.clone()),
            id::LOAD_MODEL => Command::LoadModel(name(b)?),
            id::TRANSFER_FILE => Command::TransferFile {
                name: name(b)?,
                data: b.data.clone(),
            },
            id::ERASE_FILE => Command::EraseFile(name(b)?),
            id::GET_OBJECTS => Command::GetObjects(idn(0)?),
            id::GET_OBJECT_GROUP_DATA => Command::GetObjectGroupData {
                object_type: idn(0)?,
                data_type: idn(1)?,
            },
            id::GET_OBJECT_PARENT => Command::GetObjectParent(idn(0)?),
            id::SET_OBJECT_PARENT => Command::SetObjectParent {
                handle: idn(0)?,
                parent: dn(0)?,
                keep_in_place: *b.data.get(4)? != 0,
            },
            id::COPY_PASTE_OBJECTS => Command::CopyPaste(
                b.data
                    .chunks_exact(4)
                    .map(|c| i32::from_le_bytes([c[0], c[1], c[2], c[3]]))
                    .collect(),
            ),
            id::SET_OBJECT_POSITION => Command::SetPosition {
                handle: idn(0)?,
                relative_to: dn(0)?,
                xyz: read_f32x3(&b.data, 4)?,
            },
            id::SET_OBJECT_ORIENTATION => Command::SetOrientation {
                handle: idn(0)?,
                relative_to: dn(0)?,
                euler: read_f32x3(&b.data, 4)?,
            },
            id::GET_OBJECT_POSITION => Command::GetPosition {
                handle: idn(0)?,
                relative_to: idn(1)?,
            },
            id::GET_OBJECT_ORIENTATION => Command::GetOrientation {
                handle: idn(0)?,
                relative_to: idn(1)?,
            },
            id::GET_OBJECT_QUATERNION => Command::GetQuaternion {
                handle: idn(0)?,
                relative_to: idn(1)?,
            },
            id::GET_OBJECT_POSITION_OLD => Command::GetPosition {
                handle: idn(0)?,
                relative_to: dn(0)?,
            },
            id::GET_OBJECT_ORIENTATION_OLD => Command::GetOrientation {
                handle: idn(0)?,
                relative_to: dn(0)?,
            },
            id::GET_OBJECT_FLOAT_PARAMETER => Command::GetObjectFloatParam {
                handle: idn(0)?,
                param: idn(1)?,
            },
            id::REMOVE_OBJECT => Command::RemoveObject(idn(0)?),
            id::GET_INTEGER_PARAMETER => Command::GetIntParam(idn(0)?),
            id::SET_INTEGER_PARAMETER => Command::SetIntParam(idn(0)?, dn(0)?),
            id::START_PAUSE_STOP_SIMULATION => Command::Simulation(match idn(0)? {
                0 => SimControl::Start,
                1 => SimControl::Pause,
                2 => SimControl::Stop,
                _ => return None,
            }),
            id::SYNCHRONOUS_ENABLE => Command::Synchronous(true),
            id::SYNCHRONOUS_DISABLE => Command::Synchronous(false),
            id::SYNCHRONOUS_NEXT => Command::SynchronousTrigger,
            id::GET_JOINT_POSITION => Command::GetJointPosition(idn(0)?),
            id::SET_JOINT_TARGET_VELOCITY => Command::SetJointTargetVelocity {
                handle: idn(0)?,
                velocity: read_f32(&b.data, 0)?,
            },
            id::GET_VISION_SENSOR_IMAGE_BW | id::GET_VISION_SENSOR_IMAGE_RGB => {
                Command::GetVisionSensorImage {
                    handle: idn(0)?,
                    greyscale: b.raw_id() == id::GET_VISION_SENSOR_IMAGE_BW,
                }
            }
            id::GET_OBJECT_CHILD => Command::GetObjectChild {
                handle: idn(0)?,
                index: idn(1)?,
            },
            id::GET_OBJECT_INT_PARAMETER => Command::GetObjectIntParam {
                handle: idn(0)?,
                param: idn(1)?,
            },
            id::KILL_CONNECTION => Command::KillConnection,
            _ => return None,
        })
    }
}

/// Group data as returned by `simxGetObjectGroupData`: the objects' handles, then what the
/// data type asked for, object after object in handle order (see [`group`] for how many
/// values each object contributes to which list).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct GroupData {
    /// Object handles.
    pub handles: Vec<i32>,
    /// Integer values (types, parents).
    pub ints: Vec<i32>,
    /// Float values (positions, angles, quaternions).
    pub floats: Vec<f32>,
    /// String values (names, aliases, paths).
    pub strings: Vec<String>,
}

impl GroupData {
    /// Encodes the reply payload.
    pub fn encode(&self) -> Vec<u8> {
        let mut out = i32s(&[
            self.handles.len() as i32,
            self.ints.len() as i32,
            self.floats.len() as i32,
            self.strings.len() as i32,
        ]);
        out.extend(i32s(&self.handles));
        out.extend(i32s(&self.ints));
        out.extend(f32s(&self.floats));
        for s in &self.strings {
            out.extend_from_slice(s.as_bytes());
            out.push(0);
        }
        out
    }

    /// Decodes a reply payload; `None` when sizes do not add up.
    pub fn decode(b: &[u8]) -> Option<GroupData> {
        let count = |n| {
            read_i32(b, n)
                .and_then(|v| usize::try_from(v).ok())
                .filter(|&v| v <= b.len())
        };
        let (nh, ni, nf, ns) = (count(0)?, count(1)?, count(2)?, count(3)?);
        let ints_at = |from: usize, n: usize| -> Option<Vec<i32>> {
            (0..n).map(|k| read_i32(b, from + k)).collect()
        };
        let handles = ints_at(4, nh)?;
        let ints = ints_at(4 + nh, ni)?;
        let fl_at = (4 + nh + ni) * 4;
        let floats = (0..nf)
            .map(|k| {
                b.get(fl_at + 4 * k..fl_at + 4 * k + 4)
                    .map(|s| f32::from_le_bytes([s[0], s[1], s[2], s[3]]))
            })
            .collect::<Option<Vec<f32>>>()?;
        let mut rest = b.get(fl_at + 4 * nf..)?;
        let mut strings = Vec::with_capacity(ns);
        for _ in 0..ns {
            let end = rest.iter().position(|&c| c == 0)?;
            strings.push(String::from_utf8_lossy(&rest[..end]).into_owned());
            rest = &rest[end + 1..];
        }
        Some(GroupData {
            handles,
            ints,
            floats,
            strings,
        })
    }
}

/// Decodes a handle-list reply (count + handles: copy-paste, `simxGetObjects`).
pub fn decode_handle_list(b: &[u8]) -> Option<Vec<i32>> {
    let n = usize::try_from(read_i32(b, 0)?).ok()?;
    if b.len() != 4 + 4 * n {
        return None;
    }
    (1..=n).map(|k| read_i32(b, k)).collect()
}

/// Encodes a handle-list reply (the server side of [`decode_handle_list`]).
pub fn encode_handle_list(handles: &[i32]) -> Vec<u8> {
    let mut out = i32s(&[handles.len() as i32]);
    out.extend(i32s(handles));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn commands_round_trip_through_blocks() {
        let all = [
            Command::GetObjectHandle("Floor".into()),
            Command::GetObjects(vrep_maze_core::coppelia::HANDLE_ALL),
            Command::GetObjectGroupData {
                object_type: ALL_OBJECTS,
                data_type: group::ABSOLUTE_POSES,
            },
            Command::GetObjectParent(3),
            Command::SetObjectParent {
                handle: 3,
                parent: -1,
                keep_in_place: true,
            },
            Command::CopyPaste(vec![1, 2, 3]),
            Command::SetPosition {
                handle: 1,
                relative_to: -1,
                xyz: [0.1, 0.2, 0.3],
            },
            Command::GetPosition {
                handle: 1,
                relative_to: 5,
            },
            Command::SetOrientation {
                handle: 1,
                relative_to: 4,
                euler: [0.0, 1.0, 2.0],
            },
            Command::GetOrientation {
                handle: 1,
                relative_to: -11,
            },
            Command::GetQuaternion {
                handle: 2,
                relative_to: -1,
            },
            Command::RemoveObject(9),
            Command::GetObjectFloatParam {
                handle: 16,
                param: 18,
            },
            Command::GetIntParam(26),
            Command::SetIntParam(26, 0),
            Command::Simulation(SimControl::Stop),
            Command::GetIntSignal("s".into()),
            Command::SetIntSignal("vrep-maze".into(), 8),
            Command::ClearIntSignal("x".into()),
            Command::GetStringSignal("s".into()),
            Command::SetStringSignal("vrep-maze.copies".into(), b"Line:12-40".to_vec()),
            Command::LoadModel("/tmp/m.simmodel.xml".into()),
            Command::TransferFile {
                name: "REMOTE_API_TEMPFILE_1.simmodel.xml".into(),
                data: b"<CoppeliaSim/>".to_vec(),
            },
            Command::EraseFile("REMOTE_API_TEMPFILE_1.simmodel.xml".into()),
            Command::Synchronous(true),
            Command::Synchronous(false),
            Command::SynchronousTrigger,
            Command::GetJointPosition(21),
            Command::SetJointTargetVelocity {
                handle: 21,
                velocity: -4.5,
            },
            Command::GetVisionSensorImage {
                handle: 30,
                greyscale: false,
            },
            Command::GetVisionSensorImage {
                handle: 30,
                greyscale: true,
            },
            Command::GetObjectChild {
                handle: 21,
                index: 0,
            },
            Command::GetObjectIntParam {
                handle: 30,
                param: 1002,
            },
            Command::KillConnection,
        ];
        for c in all {
            let b = c.to_block(opmode::BLOCKING);
            assert_eq!(Command::from_block(&b).as_ref(), Some(&c));
        }
        let cp = Command::CopyPaste(vec![5]).to_block(0);
        assert_eq!(cp.status, 1, "copy-paste is sent with do-not-overwrite");
        let sp = Command::SetObjectParent {
            handle: 3,
            parent: 7,
            keep_in_place: false,
        }
        .to_block(0);
        assert_eq!(sp.data, [7, 0, 0, 0, 0]);
    }

    fn hex(s: &str) -> Vec<u8> {
        s.split_whitespace()
            .map(|b| u8::from_str_radix(b, 16).unwrap())
            .collect()
    }

    /// The message bytes of one blocking command in message 7, client time 0x12345 (the
    /// layout of the spec's section 13 examples; sections 5.1, 5.2 and 12.22 for these IDs).
    fn on_the_wire(c: &Command) -> Vec<u8> {
        use crate::legacy::wire::{MAX_PACKET_SIZE, Message, MessageHeader, packetize};
        let m = Message {
            header: MessageHeader {
                message_id: 7,
                client_time: 0x12345,
                ..Default::default()
            },
            blocks: vec![c.to_block(opmode::BLOCKING)],
        };
        packetize(&m.encode(), MAX_PACKET_SIZE)
    }

    #[test]
    fn vectors_load_model_transfer_file_erase_file() {
        // simxLoadModel("m.simmodel.xml", 0, blocking): 1-string class, ID = the path,
        // no pure data; block 26 + 15 = 0x29 bytes, off0 = 15, cmd 0x00013003.
        let load = hex(
            "01 00 3b 00 00 00 00 00 0b 07 00 00 00 45 23 01 00 00 00 00 00 00 00 00
             29 00 00 00 29 00 00 00 0f 00 00 00 00 00 03 30 01 00 00 00 00 00 00 00 00 00
             6d 2e 73 69 6d 6d 6f 64 65 6c 2e 78 6d 6c 00",
        );
        assert_eq!(
            on_the_wire(&Command::LoadModel("m.simmodel.xml".into())),
            load
        );
        // simxTransferFile(.., "f.simmodel.xml", blocking) of the 4 bytes "<x/>": ID = the
        // server-side name, pure data = the file; block 26 + 15 + 4 = 0x2d bytes.
        let transfer = hex(
            "01 00 3f 00 00 00 00 00 0b 07 00 00 00 45 23 01 00 00 00 00 00 00 00 00
             2d 00 00 00 2d 00 00 00 0f 00 00 00 00 00 04 30 01 00 00 00 00 00 00 00 00 00
             66 2e 73 69 6d 6d 6f 64 65 6c 2e 78 6d 6c 00 3c 78 2f 3e",
        );
        let file = Command::TransferFile {
            name: "f.simmodel.xml".into(),
            data: b"<x/>".to_vec(),
        };
        assert_eq!(on_the_wire(&file), transfer);
        // simxEraseFile("f.simmodel.xml", blocking): cmd 0x00013006.
        let erase = hex(
            "01 00 3b 00 00 00 00 00 0b 07 00 00 00 45 23 01 00 00 00 00 00 00 00 00
             29 00 00 00 29 00 00 00 0f 00 00 00 00 00 06 30 01 00 00 00 00 00 00 00 00 00
             66 2e 73 69 6d 6d 6f 64 65 6c 2e 78 6d 6c 00",
        );
        assert_eq!(
            on_the_wire(&Command::EraseFile("f.simmodel.xml".into())),
            erase
        );
    }

    /// `simxGetObjectFloatParameter(16, 15 = bounding box min x, blocking)` as the C client
    /// sends it (spec 12.15 in the block layout of section 13: ID = handle, parameter), and
    /// the reply block carrying -0.3.
    #[test]
    fn vector_get_object_float_parameter() {
        use super::super::wire::{Message, MessageHeader};
        let hex = |s: &str| -> Vec<u8> {
            s.split_whitespace()
                .map(|b| u8::from_str_radix(b, 16).unwrap())
                .collect()
        };
        let request = Command::GetObjectFloatParam {
            handle: 16,
            param: 15,
        }
        .to_block(opmode::BLOCKING);
        let bytes = Message {
            header: MessageHeader::default(),
            blocks: vec![request.clone()],
        }
        .encode();
        let want = hex("22 00 00 00 22 00 00 00 08 00 00 00 00 00 07 20 01 00 00 00
             00 00 00 00 00 00 10 00 00 00 0f 00 00 00");
        assert_eq!(&bytes[18..], &want[..]);
        assert_eq!(
            Command::from_block(&request),
            Some(Command::GetObjectFloatParam {
                handle: 16,
                param: 15
            })
        );
        let reply = super::super::wire::Block {
            data: (-0.3f32).to_le_bytes().to_vec(),
            ..request
        };
        let bytes = Message {
            header: MessageHeader::default(),
            blocks: vec![reply],
        }
        .encode();
        let want = hex("26 00 00 00 26 00 00 00 08 00 00 00 00 00 07 20 01 00 00 00
             00 00 00 00 00 00 10 00 00 00 0f 00 00 00 9a 99 99 be");
        assert_eq!(&bytes[18..], &want[..]);
    }

    /// The stepping commands in the layout of the spec's section 13 (message 7, client time
    /// 0x12345), their IDs and payloads from sections 11.2, 12.21 and 12.25.
    #[test]
    fn vectors_synchronous_trigger_and_joint_velocity() {
        // simxSynchronousTrigger: a null-class block of 26 bytes, cmd 0x00010003 (always
        // blocking), no identification or pure data.
        let trigger = hex(
            "01 00 2c 00 00 00 00 00 0b 07 00 00 00 45 23 01 00 00 00 00 00 00 00 00
             1a 00 00 00 1a 00 00 00 00 00 00 00 00 00 03 00 01 00 00 00 00 00 00 00 00 00",
        );
        assert_eq!(on_the_wire(&Command::SynchronousTrigger), trigger);
        // simxSynchronous(true): the same with cmd 0x00010001
        let mut enable = trigger.clone();
        enable[38] = 0x01;
        assert_eq!(on_the_wire(&Command::Synchronous(true)), enable);
        // simxSetJointTargetVelocity(16, 4.0): ID = handle, pure data = f32 4.0;
        // block 26 + 4 + 4 = 0x22 bytes, off0 = 4, cmd 0x00011008
        let velocity = hex(
            "01 00 34 00 00 00 00 00 0b 07 00 00 00 45 23 01 00 00 00 00 00 00 00 00
             22 00 00 00 22 00 00 00 04 00 00 00 00 00 08 10 01 00 00 00 00 00 00 00 00 00
             10 00 00 00 00 00 80 40",
        );
        let set = Command::SetJointTargetVelocity {
            handle: 16,
            velocity: 4.0,
        };
        assert_eq!(on_the_wire(&set), velocity);
        // simxGetVisionSensorImage(16, options 0 / 1): cmd 0x1004 (RGB) / 0x1003 (grey)
        let rgb = Command::GetVisionSensorImage {
            handle: 16,
            greyscale: false,
        }
        .to_block(opmode::STREAMING);
        assert_eq!(
            (rgb.cmd, rgb.id_data.as_slice()),
            (0x0002_1004, &[16, 0, 0, 0][..])
        );
        let grey = Command::GetVisionSensorImage {
            handle: 16,
            greyscale: true,
        }
        .to_block(opmode::STREAMING);
        assert_eq!(grey.cmd, 0x0002_1003);
    }

    #[test]
    fn image_replies_decode_only_when_their_sizes_add_up() {
        let mut reply = i32s(&[2, 1]);
        reply.extend([1, 2, 3, 4, 5, 6]);
        assert_eq!(
            decode_image(&reply, 3),
            Some((2, 1, &[1, 2, 3, 4, 5, 6][..]))
        );
        assert_eq!(decode_image(&reply, 1), None);
        assert_eq!(decode_image(&reply[..10], 3), None);
        assert_eq!(decode_image(&i32s(&[-1, 1]), 3), None);
        assert_eq!(read_f32(&4.0f32.to_le_bytes(), 0), Some(4.0));
    }

    #[test]
    fn group_data_round_trip() {
        let g = GroupData {
            handles: vec![1, 2],
            ints: vec![-1, 1],
            floats: vec![0.5; 6],
            strings: vec!["Floor".into(), "Line0".into()],
        };
        assert_eq!(GroupData::decode(&g.encode()), Some(g));
        assert_eq!(
            decode_handle_list(&encode_handle_list(&[4, 5])),
            Some(vec![4, 5])
        );
        assert_eq!(decode_handle_list(&[1, 0, 0, 0]), None);
    }

    proptest! {
        #[test]
        fn payload_decoders_never_panic(b in proptest::collection::vec(any::<u8>(), 0..200)) {
            let _ = GroupData::decode(&b);
            let _ = decode_handle_list(&b);
            let _ = read_f32x3(&b, 3);
            let _ = decode_image(&b, 3);
        }
    }
}
