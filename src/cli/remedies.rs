//! A drawing error in the command line's words: its roles ([`Role`]) name the options that
//! name their objects (`--floor`).

use crate::draw::{DrawError, Role};

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

/// `error`'s line, each role it names with its option.
pub fn message(error: &DrawError) -> String {
    error.message(role)
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
