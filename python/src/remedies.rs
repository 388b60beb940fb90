//! A drawing error in Python's words: its roles ([`Role`]) name the keyword arguments that
//! name their objects (`floor`).

use vrep_maze::draw::{DrawError, Role};

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
    error.message(role)
}
