//! A maze as a URDF robot (`.urdf`): one link `maze`, fixed to the `world` link (Gazebo's
//! way of making a model static), with one collision and one visual box per wall run and per
//! post, or one visual-only thin box per run of lines, the visuals `start` and `end`, and the
//! floor as a visual-only slab just below z = 0 (a simulator brings its own ground). The link
//! has a nominal inertial (1 kg, unit inertia): Gazebo's URDF reader (libsdformat) drops a
//! link without one, and being fixed to the world it never moves.
//!
//! Every `<origin>` is `xyz` in the world (the floor frame) and `rpy` radians.

use super::solids::{Slab, Solids, line, num, nums, xml_escape};

/// The floor slab's thickness, metres: its top is at z = 0.
const FLOOR_THICKNESS: f64 = 0.001;

/// The URDF document.
pub(super) fn document(s: &Solids) -> String {
    let mut out = String::new();
    line(&mut out, format_args!("<?xml version=\"1.0\"?>"));
    line(
        &mut out,
        format_args!("<!-- {} -->", xml_escape(&s.title).replace("--", "- -")),
    );
    line(&mut out, format_args!("<robot name=\"vrep_maze\">"));
    line(&mut out, format_args!("  <link name=\"world\"/>"));
    line(
        &mut out,
        format_args!("  <joint name=\"maze_fixed\" type=\"fixed\">"),
    );
    line(&mut out, format_args!("    <parent link=\"world\"/>"));
    line(&mut out, format_args!("    <child link=\"maze\"/>"));
    line(&mut out, format_args!("  </joint>"));
    line(&mut out, format_args!("  <link name=\"maze\">"));
    line(&mut out, format_args!("    <inertial>"));
    line(&mut out, format_args!("      <mass value=\"1\"/>"));
    line(
        &mut out,
        format_args!(
            "      <inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/>"
        ),
    );
    line(&mut out, format_args!("    </inertial>"));
    let floor = Slab {
        name: "floor".to_string(),
        part: super::solids::Part::Marker,
        centre: [0.0, 0.0, -FLOOR_THICKNESS / 2.0],
        size: [s.floor[0], s.floor[1], FLOOR_THICKNESS],
        yaw: 0.0,
        rgb: s.floor_rgb,
    };
    for b in std::iter::once(&floor).chain(s.all()) {
        line(&mut out, format_args!("    <visual name=\"{}\">", b.name));
        line(&mut out, format_args!("      {}", origin_and_box(b)));
        line(
            &mut out,
            format_args!(
                "      <material name=\"{}\"><color rgba=\"{} 1\"/></material>",
                b.name,
                nums(&b.rgb)
            ),
        );
        line(&mut out, format_args!("    </visual>"));
        if b.part.collides() {
            line(
                &mut out,
                format_args!("    <collision name=\"{}_collision\">", b.name),
            );
            line(&mut out, format_args!("      {}", origin_and_box(b)));
            line(&mut out, format_args!("    </collision>"));
        }
    }
    line(&mut out, format_args!("  </link>"));
    line(&mut out, format_args!("</robot>"));
    out
}

/// `<origin>` and `<geometry><box>` of a box.
fn origin_and_box(b: &Slab) -> String {
    format!(
        "<origin xyz=\"{}\" rpy=\"0 0 {}\"/><geometry><box size=\"{}\"/></geometry>",
        nums(&b.centre),
        num(b.yaw),
        nums(&b.size)
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::export::solids::tests::{line_layout, post_layout, solids};

    #[test]
    fn one_fixed_link_with_a_collision_and_a_visual_per_wall_box() {
        let s = solids(&post_layout(45.0));
        let walls = document(&s);
        assert_eq!(walls.matches("<link ").count(), 2);
        assert_eq!(walls.matches("<joint ").count(), 1);
        assert!(walls.contains("type=\"fixed\""));
        assert_eq!(walls.matches("<collision ").count(), s.maze.len());
        assert_eq!(walls.matches("<visual ").count(), s.maze.len() + 3);
        assert!(walls.contains("<visual name=\"start\">"));
        assert!(walls.contains("<box size=\"10 10 0.001\"/>"));
        assert!(walls.contains("rpy=\"0 0 0.785398\""));

        let lines = document(&solids(&line_layout(0.0)));
        assert_eq!(lines.matches("<collision ").count(), 0);
        assert!(lines.contains("<visual name=\"line_0\">"));
    }
}
