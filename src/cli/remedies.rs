//! A drawing error in the command line's words: its roles ([`Role`]) and remedies
//! ([`Remedy`]) name the options that name or do them (`--floor`, `--resize-floor`).

use crate::draw::extent::{Resize, extents};
use crate::draw::{DrawError, Remedy, Role};

/// The option that names `role`'s object.
pub(crate) fn option(role: Role) -> &'static str {
    match role {
        Role::Floor => "--floor",
        Role::Parent => "--parent",
        Role::Line => "--line",
        Role::Wall => "--wall",
        Role::Post => "--post",
        Role::Start => "--start",
        Role::End => "--end",
    }
}

/// `role` with its option: "the floor (--floor)".
fn role(role: Role) -> String {
    format!("{role} ({})", option(role))
}

/// `error`'s line, each role it names with its option, and each option as its flag.
pub fn message(error: &DrawError) -> String {
    error.message(role, &super::wording::Flags)
}

/// What the user can do about `error`, one remedy per line: its `hint:` lines.
pub fn hints(error: &DrawError) -> Vec<String> {
    error.remedies().iter().map(hint).collect()
}

/// One remedy as a hint line.
pub fn hint(remedy: &Remedy) -> String {
    match remedy {
        Remedy::CreateOrName { roles } => {
            let them = if roles.len() == 1 { "it" } else { "them" };
            let options: Vec<&str> = Role::ALL.into_iter().map(option).collect();
            format!(
                "create {them} in CoppeliaSim, or pass the names your scene uses with {}",
                options.join(", ")
            )
        }
        Remedy::HowToCreate { role, name, sizes } => {
            role.how_to_create(name, sizes.as_ref())
        }
        Remedy::ResizeFloor {
            floor,
            short,
            resize,
        } => match resize {
            Resize::Offered => format!(
                "pass --resize-floor: apply scales `{floor}` to {} m and clear puts it back to {} m",
                extents(&short.resized()),
                extents(&short.have)
            ),
            Resize::NoApi => "the legacy remote API cannot resize objects: pass --resize-floor with --api zmq (and the ZeroMQ port, 23000 by default, if you gave --port): CoppeliaSim 4.5.1 serves both APIs on one scene".into(),
            Resize::NoExtent => format!(
                "`{floor}` has no extent along x or y, so no scale makes it larger: use a plane or cuboid as the floor"
            ),
            Resize::NotAShape { .. } => format!(
                "use a plane or cuboid of at least {} m as the floor and pass its name with --floor",
                extents(&short.resized())
            ),
            Resize::DidNotGrow => format!(
                "clear puts `{floor}` back to its size before apply --resize-floor; then use a plane or cuboid of at least {} m as the floor and pass its name with --floor",
                extents(&short.need)
            ),
        },
        Remedy::ResizeFloorByHand { floor, short } => format!(
            "or resize `{floor}` in CoppeliaSim to at least {} m",
            extents(&short.resized())
        ),
        Remedy::StopSimulation => "stop it in CoppeliaSim, or pass --stop-simulation".into(),
        Remedy::ResetBrokenPose => format!(
            "a pose read back is not a number (NaN): the object the maze hangs from (the {} dummy, or the {}) has a broken pose, which a re-run does not repair (vrep-maze never moves those objects): reset its position and orientation in CoppeliaSim, then run the same command again",
            option(Role::Parent),
            option(Role::Floor)
        ),
        Remedy::MatchTemplateSizes => "a drawing copies the templates as they are: their sizes must be the layout's (see `vrep-maze generate --help`)".into(),
        Remedy::NameTheObject => "name the object itself (the course scene's `Line`, `Start`, `End`): a path into the maze dummy (`/Maze/Line`, `/Line[1]`) finds a copy, whose path changes with every draw".into(),
        Remedy::OneObjectPerRole => "give each role its own object: pass the right name to one of the two options (see --help for the defaults)".into(),
        Remedy::RunAgain => "run the same command again: it repairs what differs".into(),
        Remedy::OneRunAtATime => {
            "run one apply or clear at a time on a scene; running one again alone repairs it".into()
        }
        Remedy::FinishOrClear => "the scene holds part of the maze; run the same apply again to finish it, or clear to remove it".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::draw::ObjectNames;

    #[test]
    fn a_role_is_said_with_its_option() {
        let names = ObjectNames {
            end: "/Floor".into(),
            ..Default::default()
        };
        let e = message(&names.check_roles().unwrap_err());
        assert!(
            e.contains("`Floor` and `/Floor`") && e.contains("(--floor)") && e.contains("(--end)"),
            "{e}"
        );
        let names = ObjectNames {
            post: "Line".into(),
            ..Default::default()
        };
        let e = message(&names.check_roles().unwrap_err());
        assert!(
            e.starts_with(
                "`Line` would be both the line template (--line) and the post template (--post)"
            ),
            "{e}"
        );
    }
}
