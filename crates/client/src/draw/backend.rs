//! The drawing port: what a connection implements ([`Backend`], and the optional
//! [`Authoring`]), what it reports ([`ObjectInfo`], [`BoundingBox`], [`Survey`],
//! [`IdleRates`]), the edits it applies ([`Edit`]) and how it fails ([`BackendError`]).

use vrep_maze_core::layout::sizes::Sizes;
use vrep_maze_core::score::follow::Follower;

use super::error::BackendError;
use super::estimate;
use super::mesh;
use super::names::ObjectNames;
use super::survey::{SurveyHandles, SurveyNames, Traits};

/// One scene object as a backend reports it: world pose.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectInfo {
    /// The object's handle in this scene.
    pub handle: i32,
    /// Object name.
    pub name: String,
    /// Parent handle.
    pub parent: Option<i32>,
    /// World position.
    pub position: [f64; 3],
    /// World Euler angles.
    pub orientation: [f64; 3],
}

/// An object's bounding box in its own frame (`sim_objfloatparam_objbbox_*`, parameters
/// 15..20), as a simulator reports it: single precision, so compare sizes with
/// [`SIZE_TOLERANCE`](super::tolerance::SIZE_TOLERANCE).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoundingBox {
    /// Minimum x, y, z.
    pub min: [f64; 3],
    /// Maximum x, y, z.
    pub max: [f64; 3],
}

impl BoundingBox {
    /// Extent along x, y and z (a plane has z = 0).
    pub fn size(&self) -> [f64; 3] {
        [0, 1, 2].map(|k| self.max[k] - self.min[k])
    }
}

/// Everything [`apply()`](super::apply()) needs to know first, in one round trip.
#[derive(Debug, Clone, PartialEq)]
pub struct Survey {
    /// Handle of each name asked for, by role, `None` if missing.
    pub handles: SurveyHandles,
    /// The scene objects drawing needs: the named ones, the children of the maze dummy and
    /// parentless copies of the line template (a backend may list more). A pose a backend
    /// did not read is NaN: never in place, so it is set.
    pub objects: Vec<ObjectInfo>,
    /// Simulation not stopped.
    pub simulation_running: bool,
    /// What the backend read that tells a template's copy from the user's object named like
    /// one ([`Traits`]: types, and sizes and children where the name, type and copy
    /// record leave a doubt).
    pub traits: Traits,
}

/// The idle rate now and the user's rate recorded by an interrupted run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct IdleRates {
    /// Current `sim_intparam_idle_fps`.
    pub current: i32,
    /// The user's idle rate recorded by an `apply` that was interrupted before restoring it
    /// (the simulator keeps it as the integer signal [`SAVED_IDLE_FPS`](super::signals::SAVED_IDLE_FPS)).
    pub saved: Option<i32>,
}

/// A scene edit; [`Backend::edit`] applies a list of them in order, in one round trip.
#[derive(Debug, Clone, PartialEq)]
pub enum Edit {
    /// Set the parent (`None` = no parent).
    SetParent {
        /// The object to move in the hierarchy.
        handle: i32,
        /// Its new parent, `None` for the scene root.
        parent: Option<i32>,
        /// Keep the world pose (else the local pose is kept and the object moves).
        keep_in_place: bool,
    },
    /// Set position and orientation relative to another object.
    SetPose {
        /// The object to place.
        handle: i32,
        /// The object whose frame the pose is in (the floor).
        relative_to: i32,
        /// Position in that frame, metres.
        position: [f64; 3],
        /// CoppeliaSim Euler angles in that frame, radians.
        orientation: [f64; 3],
    },
    /// Remove an object.
    Remove(i32),
}

impl Edit {
    /// The objects that `edits` remove.
    pub fn removed(edits: &[Edit]) -> std::collections::HashSet<i32> {
        edits
            .iter()
            .filter_map(|e| match e {
                Edit::Remove(h) => Some(*h),
                _ => None,
            })
            .collect()
    }
}

/// A connection to a simulator that can draw: the operations [`apply()`](super::apply()), [`clear()`](super::clear()) and
/// [`verify()`](super::verify()) need.
///
/// Contract: each operation uses as few messages as its protocol allows (the legacy API sends
/// each call as one batched request; the ZeroMQ API has one call per object, sent together
/// where they do not depend on each other's answers, `Client::call_all`, and served by one
/// main-loop pass); [`Backend::round_trips`] reports the cost so far (ZeroMQ: requests). Errors leave the
/// scene in a state that a later [`apply()`](super::apply()) or [`clear()`](super::clear()) repairs.
pub trait Backend {
    /// Reads the idle rate and the record of the user's rate ([`IdleRates`]).
    fn idle_rates(&mut self) -> Result<IdleRates, BackendError>;
    /// Resolves `names`, lists the objects drawing needs ([`Survey::objects`]) and reads the
    /// simulation state. `names` are [`ObjectNames::survey`]'s: objects are listed only
    /// when the needed ones exist ([`SurveyHandles::needed_found`]), and the maze's copies
    /// of the other templates are named after them (so `ownership::foreign_copies` can tell
    /// them apart).
    fn survey(&mut self, names: &SurveyNames<'_>) -> Result<Survey, BackendError>;
    /// Lists the objects drawing needs, as [`Backend::survey`] does, with every pose: a
    /// backend may give a pose it set itself, acknowledged by the simulator, without reading
    /// it back (ZeroMQ, where each read is a call).
    fn objects(&mut self) -> Result<Vec<ObjectInfo>, BackendError>;
    /// [`Backend::objects`], every pose read from the scene now.
    fn objects_from_scene(&mut self) -> Result<Vec<ObjectInfo>, BackendError> {
        self.objects()
    }
    /// The bounding boxes of `handles` ([`BoundingBox`]), in the same order, `None` for an
    /// object that has none (gone, or a simulator that does not say): legacy in one request
    /// for all, ZeroMQ one call per parameter and object, all made by one request where the
    /// simulator runs our program of several calls.
    fn bounding_boxes(&mut self, handles: &[i32])
    -> Result<Vec<Option<BoundingBox>>, BackendError>;
    /// The sizes (bounding-box extents x, y, z) of `handles`, in the same order, `None` for
    /// an object that has none; by default from [`Backend::bounding_boxes`].
    fn sizes(&mut self, handles: &[i32]) -> Result<Vec<Option<[f64; 3]>>, BackendError> {
        Ok(self
            .bounding_boxes(handles)?
            .into_iter()
            .map(|b| b.map(|b| b.size()))
            .collect())
    }
    /// The ambient-diffuse colours (RGB, 0..1) of the shapes `handles`, in the same order,
    /// `None` for one the simulator gives none of; `Ok(None)` from an API that cannot read
    /// colours (the legacy API has no call for it).
    fn shape_colours(
        &mut self,
        handles: &[i32],
    ) -> Result<Option<Vec<Option<[f64; 3]>>>, BackendError> {
        let _ = handles;
        Ok(None)
    }
    /// Reads the integer signals `names` (`None`: not set), legacy in one request.
    fn int_signals(&mut self, names: &[&str]) -> Result<Vec<Option<i32>>, BackendError>;
    /// Sets (`Some`) or clears (`None`) integer signals in order, legacy in one request.
    fn set_int_signals(&mut self, signals: &[(&str, Option<i32>)]) -> Result<(), BackendError>;
    /// Copy-pastes each group; returns the new handles of each group.
    fn copy_paste(&mut self, groups: &[Vec<i32>]) -> Result<Vec<Vec<i32>>, BackendError>;
    /// Applies edits in order.
    fn edit(&mut self, edits: &[Edit]) -> Result<(), BackendError>;
    /// Sets `sim_intparam_idle_fps` and, in the same request, records `saved` (the user's
    /// rate, so that a later run can restore it if this one is interrupted) or, with `None`,
    /// deletes the record.
    fn set_idle_fps(&mut self, fps: i32, saved: Option<i32>) -> Result<(), BackendError>;
    /// Stops the simulation and waits until it is stopped.
    fn stop_simulation(&mut self) -> Result<(), BackendError>;
    /// Messages exchanged with the simulator so far (requests with their replies).
    fn round_trips(&self) -> usize;
    /// How many pieces (lines, walls or posts: a copy, or a parent and a pose) one request
    /// may carry so that the
    /// simulator answers in bounded time, given the objects in the scene (its per-object
    /// costs grow with them). Unbounded where each call is its own request (ZeroMQ).
    fn pieces_per_request(&self, objects_in_scene: usize) -> usize {
        let _ = objects_in_scene;
        usize::MAX
    }
    /// One line naming the API, where it answered and, if known, the simulator's version.
    fn describe(&self) -> String;
    /// Which remote API this is, for [`estimate::copies_draw`]; `None` for a backend that is
    /// neither (nothing is estimated).
    fn remote_api(&self) -> Option<estimate::RemoteApi> {
        None
    }
    /// Ends the connection the way the official client does, so the simulator is ready for
    /// the next client at once. Dropping a backend closes it too, ignoring errors.
    fn close(&mut self) -> Result<(), BackendError> {
        Ok(())
    }
    /// The scene-side record that tells concurrent runs apart ([`lease`](super::lease)). APIs that serve
    /// several clients at once (ZeroMQ) have one; the legacy server serves one client at a
    /// time, so it needs none.
    fn lease(&mut self) -> Option<&mut dyn Lease> {
        None
    }
    /// What this backend can do beyond drawing, if anything (the ZeroMQ API can create
    /// objects and save the scene; the legacy API cannot).
    fn authoring(&mut self) -> Option<&mut dyn Authoring> {
        None
    }
    /// Drawing a maze as mesh shapes ([`mesh::MeshDrawing`]), if this backend can.
    fn meshes(&mut self) -> Option<&mut dyn mesh::MeshDrawing> {
        None
    }
    /// A follower of a robot's run over this backend's connection, which stays open when
    /// the follower is closed (`score` in a session), if this backend can lend it.
    fn follower(&mut self) -> Option<Box<dyn Follower + '_>> {
        None
    }
    /// A driver of the scene's wheeled robot over this backend's connection, which stays
    /// open when the driver is done (`drive` in a session), if this backend can lend it.
    fn robot(&mut self) -> Option<Box<dyn crate::robot::RobotPort + '_>> {
        None
    }
    /// The bounding box, in its own frame, of the model whose base is the object `name`
    /// (an object that is no model base: its own box), for `draw::robot`'s check; `None`
    /// for no such object or an API that cannot say.
    fn model_box(&mut self, name: &str) -> Result<Option<BoundingBox>, BackendError> {
        let _ = name;
        Ok(None)
    }
}

/// Scene authoring that only some APIs offer: see [`Backend::authoring`].
pub trait Authoring {
    /// Creates the objects of `names` that the scene lacks, at the layout's `sizes` (the
    /// course's colours); returns the names it created.
    fn create_missing(
        &mut self,
        names: &ObjectNames,
        sizes: &Sizes,
    ) -> Result<Vec<String>, BackendError>;
    /// Saves the scene to `path` on the simulator's machine.
    fn save_scene(&mut self, path: &str) -> Result<(), BackendError>;
    /// Scales the object `handle` by `factors` along its x, y and z (`sim.scaleObject`: a
    /// shape's mesh or primitive grows, its pose stays).
    fn scale(&mut self, handle: i32, factors: [f64; 3]) -> Result<(), BackendError>;
}

/// What [`Lease::claim`] found: the token recorded before it wrote its own, and what reads
/// back after it did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Claimed {
    /// The token recorded before the claim, if any.
    pub previous: Option<i32>,
    /// The token read back after writing (`None`: the simulator did not keep it).
    pub read_back: Option<i32>,
}

/// The scene-side record of who is drawing ([`LEASE`](super::signals::LEASE)): see [`Backend::lease`].
pub trait Lease {
    /// Records `token` as the scene's current drawer, replacing any earlier record (an
    /// older version's too), and reads it back.
    fn claim(&mut self, token: i32) -> Result<Claimed, BackendError>;
    /// The token recorded now, if any.
    fn holder(&mut self) -> Result<Option<i32>, BackendError>;
    /// Removes the record (only called by the run that holds it).
    fn release(&mut self) -> Result<(), BackendError>;
    /// The simulator did not keep the lease: this connection stops reading and writing the
    /// scene's other signals too (they would be lost the same way).
    fn unkept(&mut self);
}

/// Creates the objects `layout` is drawn with that the scene lacks, at the layout's sizes
/// ([`Authoring::create_missing`]). Returns the names created.
pub fn create_missing_for(
    authoring: &mut dyn Authoring,
    names: &ObjectNames,
    layout: &vrep_maze_core::layout::Layout,
) -> Result<Vec<String>, BackendError> {
    authoring.create_missing(names, &Sizes::of(layout))
}

/// An object named `name` at the world origin, unturned: the unit tests' scenes.
#[cfg(test)]
pub(crate) fn object_at_origin(handle: i32, name: &str, parent: Option<i32>) -> ObjectInfo {
    ObjectInfo {
        handle,
        name: name.into(),
        parent,
        position: [0.0; 3],
        orientation: [0.0; 3],
    }
}
