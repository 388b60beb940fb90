//! The constants `zmqRemoteApi.info('sim')` advertises, from which the official clients build
//! `sim.handle_world` and friends.

use crate::coppelia::{
    HANDLE_ALL, HANDLE_PARENT, HANDLE_SCENE, HANDLE_WORLD, INTPARAM_IDLE_FPS,
    INTPARAM_PROGRAM_VERSION, SHAPEINTPARAM_RESPONDABLE, SHAPEINTPARAM_STATIC, SPECIAL_COLLIDABLE,
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
    ("primitiveshape_plane", 1),
    ("primitiveshape_disc", 2),
    ("primitiveshape_cuboid", 3),
    ("primitiveshape_spheroid", 4),
    ("primitiveshape_cylinder", 5),
    ("object_shape_type", 0),
    ("object_dummy_type", 4),
    ("simulation_stopped", 0),
    ("simulation_paused", 8),
    ("simulation_advancing_running", 17),
    ("colorcomponent_ambient_diffuse", 0),
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
