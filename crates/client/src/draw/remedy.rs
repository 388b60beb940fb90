//! What the user can do about a failed drawing ([`Remedy`], from [`DrawError::remedies`]), as
//! data: the library decides which remedies apply, each adapter words them with its own option
//! names (the command line `--resize-floor`, Python `resize_floor=True`).

use super::error::DrawError;
use super::extent::{FloorShort, Resize};
use super::role::Role;
use super::verify;
use vrep_maze_core::layout::sizes::Sizes;

/// One thing the user can do about a [`DrawError`]; an adapter words each as one line.
#[derive(Debug, Clone, PartialEq)]
pub enum Remedy {
    /// Create the missing objects in CoppeliaSim, or name the scene's own objects for their
    /// roles (with each role's option).
    CreateOrName {
        /// The roles of the missing objects.
        roles: Vec<Role>,
    },
    /// How to make one missing object ([`Role::how_to_create`]).
    HowToCreate {
        /// What the object is to the drawing.
        role: Role,
        /// Its name.
        name: String,
        /// The layout's sizes, when a layout is drawn.
        sizes: Option<Sizes>,
    },
    /// Let `apply` grow the floor to the layout's size, as far as this connection can
    /// (`resize`: it can, the legacy API cannot, no scale makes the floor larger, the floor
    /// is no shape, or the simulator did not grow it).
    ResizeFloor {
        /// The floor's name.
        floor: String,
        /// Its size and the layout's.
        short: FloorShort,
        /// Whether this connection can resize it.
        resize: Resize,
    },
    /// Or resize the floor in CoppeliaSim to at least the layout's size
    /// ([`FloorShort::resized`]).
    ResizeFloorByHand {
        /// The floor's name.
        floor: String,
        /// Its size and the layout's.
        short: FloorShort,
    },
    /// Stop the simulation, or let the drawing stop it first.
    StopSimulation,
    /// Reset the pose of the object the maze hangs from (the maze dummy or the floor), which
    /// a re-run does not repair, then run the same command again.
    ResetBrokenPose,
    /// Make the templates the layout's sizes, or a layout for theirs: a drawing copies them
    /// as they are.
    MatchTemplateSizes,
    /// Name the template or marker itself: a path into the maze finds one of its copies.
    NameTheObject,
    /// Give each role its own object.
    OneObjectPerRole,
    /// Run the same command again: it repairs what differs.
    RunAgain,
    /// Run one apply or clear at a time on a scene; one run alone repairs it.
    OneRunAtATime,
    /// Run the same apply again to finish the maze, or clear to remove it.
    FinishOrClear,
}

impl DrawError {
    /// What the user can do about the error, in the order to say it (not part of `Display`).
    pub fn remedies(&self) -> Vec<Remedy> {
        match self {
            DrawError::Missing { objects, sizes } => {
                let roles = objects.iter().map(|(role, _)| *role).collect();
                let how = objects.iter().map(|(role, name)| Remedy::HowToCreate {
                    role: *role,
                    name: name.clone(),
                    sizes: sizes.as_deref().cloned(),
                });
                std::iter::once(Remedy::CreateOrName { roles })
                    .chain(how)
                    .collect()
            }
            // a floor that is no shape cannot be resized to the layout's, by hand either
            DrawError::Floor {
                floor,
                short,
                resize: resize @ Resize::NotAShape { .. },
            } => vec![Remedy::ResizeFloor {
                floor: floor.clone(),
                short: *short,
                resize: *resize,
            }],
            DrawError::Floor {
                floor,
                short,
                resize,
            } => vec![
                Remedy::ResizeFloor {
                    floor: floor.clone(),
                    short: *short,
                    resize: *resize,
                },
                Remedy::ResizeFloorByHand {
                    floor: floor.clone(),
                    short: *short,
                },
            ],
            DrawError::SimulationRunning => vec![Remedy::StopSimulation],
            // the floor or the maze dummy at NaN: every copy reads back so
            DrawError::Verify(problems)
                if problems
                    .iter()
                    .any(|p| p.to_string().contains(verify::BROKEN_POSE)) =>
            {
                vec![Remedy::ResetBrokenPose]
            }
            DrawError::Verify(_) => vec![Remedy::RunAgain],
            DrawError::Sizes(_) => vec![Remedy::MatchTemplateSizes],
            DrawError::OurCopy { .. } => vec![Remedy::NameTheObject],
            DrawError::SameObject { .. } => vec![Remedy::OneObjectPerRole],
            DrawError::Concurrent { .. } => vec![Remedy::OneRunAtATime],
            DrawError::Interrupted { .. } => vec![Remedy::FinishOrClear],
            DrawError::Backend(_) | DrawError::NoMeshes { .. } => vec![],
        }
    }
}
