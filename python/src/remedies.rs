//! A drawing error in Python's words: its roles ([`Role`]) and remedies ([`Remedy`]) name the
//! keyword arguments that name or do them (`floor`, `resize_floor=True`); a remedy that names
//! no option reads as the command line says it.

use vrep_maze::cli::remedies as cli;
use vrep_maze::draw::extent::Resize;
use vrep_maze::draw::extent::extents;
use vrep_maze::draw::{DrawError, Remedy, Role};

/// The keyword argument that names `role`'s object.
fn keyword(role: Role) -> &'static str {
    match role {
        Role::Floor => "floor",
        Role::Parent => "parent",
        Role::Line => "line",
        Role::Wall => "wall",
        Role::Post => "post",
        Role::Start => "start",
        Role::End => "end",
    }
}

/// `role` with its keyword: "the floor (floor)".
fn role(role: Role) -> String {
    format!("{role} ({})", keyword(role))
}

/// `error`'s line, each role it names with its keyword.
pub fn message(error: &DrawError) -> String {
    error.message(role, &crate::wording::Keywords)
}

/// What the user can do about `error`, one remedy per line: a `SimulatorError`'s `hints`.
pub fn hints(error: &DrawError) -> Vec<String> {
    error.remedies().iter().map(hint).collect()
}

/// One remedy as a line of `hints`.
fn hint(remedy: &Remedy) -> String {
    match remedy {
        Remedy::CreateOrName { roles } => {
            let them = if roles.len() == 1 { "it" } else { "them" };
            let keywords: Vec<&str> = Role::ALL.into_iter().map(keyword).collect();
            format!(
                "create {them} in CoppeliaSim, or pass the names your scene uses with {}",
                keywords.join(", ")
            )
        }
        Remedy::HowToCreate { role, name, sizes } => {
            role.how_to_create(name, sizes.as_ref())
        }
        Remedy::ResizeFloor {
            floor,
            short,
            resize: Resize::Offered,
        } => format!(
            "pass resize_floor=True: apply scales `{floor}` to {} m and clear puts it back to {} m",
            extents(&short.resized()),
            extents(&short.have)
        ),
        Remedy::ResizeFloor {
            resize: Resize::NoApi,
            ..
        } => "the legacy remote API cannot resize objects: pass resize_floor=True with api=\"zmq\" (and the ZeroMQ port, 23000 by default, if you gave port): CoppeliaSim 4.5.1 serves both APIs on one scene".into(),
        Remedy::ResizeFloor {
            short,
            resize: Resize::NotAShape { .. },
            ..
        } => format!(
            "use a plane or cuboid of at least {} m as the floor and pass its name with floor",
            extents(&short.resized())
        ),
        Remedy::ResizeFloor {
            floor,
            short,
            resize: Resize::DidNotGrow,
        } => format!(
            "clear puts `{floor}` back to its size before apply resize_floor=True; then use a plane or cuboid of at least {} m as the floor and pass its name with floor",
            extents(&short.need)
        ),
        Remedy::StopSimulation => "stop it in CoppeliaSim, or pass stop_simulation=True".into(),
        Remedy::ResetBrokenPose => format!(
            "a pose read back is not a number (NaN): the object the maze hangs from (the {} dummy, or the {}) has a broken pose, which a re-run does not repair (vrep-maze never moves those objects): reset its position and orientation in CoppeliaSim, then run the same command again",
            keyword(Role::Parent),
            keyword(Role::Floor)
        ),
        Remedy::MatchTemplateSizes => "a drawing copies the templates as they are: their sizes must be the layout's (see `help(vrep_maze.generate)`)".into(),
        Remedy::OneObjectPerRole => "give each role its own object: pass the right name to one of the two keywords (see `help(vrep_maze.apply)` for the defaults)".into(),
        // these name no option
        Remedy::ResizeFloor {
            resize: Resize::NoExtent,
            ..
        }
        | Remedy::ResizeFloorByHand { .. }
        | Remedy::NameTheObject
        | Remedy::RunAgain
        | Remedy::OneRunAtATime
        | Remedy::FinishOrClear => cli::hint(remedy),
    }
}
