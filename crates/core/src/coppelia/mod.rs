//! CoppeliaSim's own numbers and conventions, shared by our clients and our emulator.
//!
//! Neither side imports the other: the clients (`vrep_maze_client::legacy::client`,
//! `vrep_maze_client::zmq_api::client` and their drawing backends) and the emulator
//! (`vrep_maze_emulator::sim` and the two servers) both take CoppeliaSim's constants from
//! here, and its Euler convention from [`frame`]. Values are those of CoppeliaSim's `simConst`
//! tables (the same in the legacy remote API's `sim_*` names and the ZeroMQ API's `sim.*`
//! names).

pub mod cost;
pub mod frame;
pub mod lua;
pub mod model_cost;
pub mod names;
pub mod shape_cost;
pub mod vertex_merge;
pub mod xml;

/// `sim_handle_world`: "absolute" for poses, "no parent" for set-parent.
pub const HANDLE_WORLD: i32 = -1;
/// `sim_handle_all`: every object (e.g. the object type filter of `simxGetObjects`).
pub const HANDLE_ALL: i32 = -2;
/// `sim_handle_parent`: relative to the object's parent frame.
pub const HANDLE_PARENT: i32 = -11;
/// `sim.handle_scene`: the whole scene, the root of `sim.getObjectsInTree`.
pub const HANDLE_SCENE: i32 = -12;

/// `sim_intparam_program_version`: e.g. 40501 for CoppeliaSim 4.5.1.
pub const INTPARAM_PROGRAM_VERSION: i32 = 1;
/// `sim_intparam_idle_fps`: main-loop passes per second while the simulation is stopped.
pub const INTPARAM_IDLE_FPS: i32 = 26;
/// `sim.boolparam_dynamics_handling_enabled` (6 in 4.5.1 and 4.10): whether the physics
/// engine runs. Turned off while the simulation runs, it ends the engine's world (all its
/// state); turned on again, a fresh world is made from the scene as it stands, as at a start.
pub const BOOLPARAM_DYNAMICS_HANDLING_ENABLED: i32 = 6;
/// CoppeliaSim's default idle rate (`sim_intparam_idle_fps` of a fresh instance).
pub const DEFAULT_IDLE_FPS: i32 = 8;

/// `sim_objfloatparam_objbbox_min_x`: the first of the six object float parameters 15..20
/// that give an object's bounding box in its own frame: min x, min y, min z, max x, max y,
/// max z (`sim.getObjectFloatParam`, legacy `simxGetObjectFloatParameter`).
pub const OBJFLOATPARAM_BBOX: i32 = 15;

/// `sim_objfloatparam_modelbbox_min_x`: the first of the six object float parameters 21..26
/// that give the bounding box of the model whose base the object is (its own box if it is
/// no model base), in its own frame, ordered as [`OBJFLOATPARAM_BBOX`]'s.
pub const OBJFLOATPARAM_MODELBBOX: i32 = 21;
/// `sim_objintparam_visibility_layer`: the bits of the layers an object is shown on (0:
/// hidden). A shape made by `sim.createShape` / `sim.createMeshShape` is on layer 1, a dummy
/// on 4 (both real builds, `docs/measurements.md` "Kept meshes read back in one request").
pub const OBJINTPARAM_VISIBILITY_LAYER: i32 = 10;
/// The visibility layer of a new shape ([`OBJINTPARAM_VISIBILITY_LAYER`]).
pub const SHAPE_LAYER: i32 = 1;
/// The visibility layer of a new dummy ([`OBJINTPARAM_VISIBILITY_LAYER`]).
pub const DUMMY_LAYER: i32 = 4;

/// `sim.shapeintparam_static`: 1 = the shape is not dynamic.
pub const SHAPEINTPARAM_STATIC: i32 = 3003;
/// `sim.shapeintparam_respondable`: 1 = the shape collides in the physics engine.
pub const SHAPEINTPARAM_RESPONDABLE: i32 = 3004;

/// `sim.objectspecialproperty_collidable`.
pub const SPECIAL_COLLIDABLE: i32 = 1;
/// `sim.objectspecialproperty_measurable`.
pub const SPECIAL_MEASURABLE: i32 = 2;
/// `sim.objectspecialproperty_detectable` (all proximity-sensor kinds).
pub const SPECIAL_DETECTABLE: i32 = 496;
/// `sim.objectspecialproperty_renderable` (seen by vision sensors: the robot's camera).
pub const SPECIAL_RENDERABLE: i32 = 2048;

/// `sim_object_shape_type`: the object type of shapes (planes, the floor).
pub const OBJECT_SHAPE_TYPE: i32 = 0;
/// `sim_object_dummy_type`: the object type of dummies (the `Maze` parent).
pub const OBJECT_DUMMY_TYPE: i32 = 4;

/// `sim.primitiveshape_plane` (`sim.createPrimitiveShape`).
pub const PRIMITIVESHAPE_PLANE: i32 = 1;
/// `sim.primitiveshape_disc`.
pub const PRIMITIVESHAPE_DISC: i32 = 2;
/// `sim.primitiveshape_cuboid`.
pub const PRIMITIVESHAPE_CUBOID: i32 = 3;
/// `sim.primitiveshape_spheroid`.
pub const PRIMITIVESHAPE_SPHEROID: i32 = 4;
/// `sim.primitiveshape_cylinder`.
pub const PRIMITIVESHAPE_CYLINDER: i32 = 5;

/// `sim.simulation_stopped` (`sim.getSimulationState`).
pub const SIMULATION_STOPPED: i32 = 0;
/// `sim.simulation_paused`.
pub const SIMULATION_PAUSED: i32 = 8;
/// `sim.simulation_advancing_running`: the state of a running simulation.
pub const SIMULATION_ADVANCING_RUNNING: i32 = 17;

/// `sim.colorcomponent_ambient_diffuse` (`sim.setShapeColor`).
pub const COLORCOMPONENT_AMBIENT_DIFFUSE: i32 = 0;
