//! The constants `zmqRemoteApi.info('sim')` advertises, from which the official clients build
//! `sim.handle_world` and friends.

use vrep_maze_core::coppelia::{
    COLORCOMPONENT_AMBIENT_DIFFUSE, HANDLE_ALL, HANDLE_PARENT, HANDLE_SCENE, HANDLE_WORLD,
    INTPARAM_IDLE_FPS, INTPARAM_PROGRAM_VERSION, OBJECT_DUMMY_TYPE, OBJECT_SHAPE_TYPE,
    PRIMITIVESHAPE_CUBOID, PRIMITIVESHAPE_CYLINDER, PRIMITIVESHAPE_DISC, PRIMITIVESHAPE_PLANE,
    PRIMITIVESHAPE_SPHEROID, SHAPEINTPARAM_RESPONDABLE, SHAPEINTPARAM_STATIC,
    SIMULATION_ADVANCING_RUNNING, SIMULATION_PAUSED, SIMULATION_STOPPED, SPECIAL_COLLIDABLE,
    SPECIAL_DETECTABLE, SPECIAL_MEASURABLE, SPECIAL_RENDERABLE,
};

/// `sim.*` constant names (without the `sim.`) and values, in the order advertised.
pub(super) const SIM_CONSTANTS: &[(&str, i64)] = &[
    ("handle_world", HANDLE_WORLD as i64),
    ("handle_all", HANDLE_ALL as i64),
    ("handle_parent", HANDLE_PARENT as i64),
    ("handle_scene", HANDLE_SCENE as i64),
    ("intparam_program_version", INTPARAM_PROGRAM_VERSION as i64),
    ("intparam_idle_fps", INTPARAM_IDLE_FPS as i64),
    ("primitiveshape_plane", PRIMITIVESHAPE_PLANE as i64),
    ("primitiveshape_disc", PRIMITIVESHAPE_DISC as i64),
    ("primitiveshape_cuboid", PRIMITIVESHAPE_CUBOID as i64),
    ("primitiveshape_spheroid", PRIMITIVESHAPE_SPHEROID as i64),
    ("primitiveshape_cylinder", PRIMITIVESHAPE_CYLINDER as i64),
    ("object_shape_type", OBJECT_SHAPE_TYPE as i64),
    ("object_dummy_type", OBJECT_DUMMY_TYPE as i64),
    ("simulation_stopped", SIMULATION_STOPPED as i64),
    ("simulation_paused", SIMULATION_PAUSED as i64),
    (
        "simulation_advancing_running",
        SIMULATION_ADVANCING_RUNNING as i64,
    ),
    (
        "colorcomponent_ambient_diffuse",
        COLORCOMPONENT_AMBIENT_DIFFUSE as i64,
    ),
    ("shapeintparam_static", SHAPEINTPARAM_STATIC as i64),
    (
        "shapeintparam_respondable",
        SHAPEINTPARAM_RESPONDABLE as i64,
    ),
    (
        "objectspecialproperty_collidable",
        SPECIAL_COLLIDABLE as i64,
    ),
    (
        "objectspecialproperty_measurable",
        SPECIAL_MEASURABLE as i64,
    ),
    (
        "objectspecialproperty_detectable",
        SPECIAL_DETECTABLE as i64,
    ),
    (
        "objectspecialproperty_renderable",
        SPECIAL_RENDERABLE as i64,
    ),
];
