//! Backend-neutral drawing of a maze into a CoppeliaSim scene.
//!
//! A backend ([`crate::legacy::LegacyBackend`], [`crate::zmq_api::ZmqBackend`]) implements
//! [`Backend`]: a handful of scene operations, batched where the protocol allows. [`apply()`] draws a
//! [`Drawing`] (reusing earlier copies of the `Line` template, or of `Wall` and `Post`, pasting
//! only the missing ones, removing the surplus), [`clear()`] removes a drawn maze and
//! [`verify()`] compares the scene with a drawing. The pure decisions are tested without a
//! simulator: [`ownership`] (which objects belong to the maze), [`paste`] (what to reuse,
//! paste and remove), [`pose`] (poses on the floor) and [`tolerance`] (what counts as the
//! same).
//!
//! This file is the table of contents: the port is in [`backend`], the errors in [`error`],
//! the objects' names and handles in [`names`], what a copies draw places in [`drawing`].

pub mod apply;
pub mod backend;
pub mod clear;
pub mod connection;
pub mod drawing;
pub mod error;
pub mod estimate;
pub mod extent;
pub mod first_line;
pub mod fit;
pub mod floor;
pub mod home;
pub mod lease;
pub mod markers_home;
pub mod mesh;
pub mod names;
pub mod options;
pub mod ownership;
pub mod paste;
pub mod pose;
pub mod record;
pub mod remedy;
pub mod report;
pub mod robot;
pub mod role;
pub mod run;
pub mod session;
pub mod signals;
pub mod survey;
pub mod tolerance;
pub mod verify;

pub use apply::apply;
pub use backend::{
    Authoring, Backend, BoundingBox, Claimed, Edit, IdleRates, Lease, ObjectInfo, Survey,
    create_missing_for,
};
pub use clear::{ClearOptions, ClearReport, clear};
pub use connection::{Session, SessionError};
pub use drawing::Drawing;
pub use error::{BackendError, DrawError};
pub use names::{Handles, ObjectNames};
pub use options::ApplyOptions;
pub use pose::{euler, position};
pub use remedy::Remedy;
pub use report::{ApplyReport, DrawMode, Stage, left_alone_line};
pub use role::Role;
pub use run::{Job, Picture, Report, RunError, run};
pub use session::resolve_handles;
pub use survey::{SurveyHandles, SurveyNames, SurveyRoles};
pub use verify::verify;
pub use vrep_maze_core::layout::sizes::{Sizes, TemplateUse};
pub use vrep_maze_core::layout::{Pose, Style};
