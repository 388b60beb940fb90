//! A maze as a Gazebo world in SDFormat 1.6 (`.sdf`, `.world`): a sun, a static
//! `ground_plane` model of the floor's size, and the maze as one static model `maze` of one
//! link holding a collision and a visual box per wall run and per post, or a visual-only
//! thin box per run of lines, and the visuals `start` and `end`.
//!
//! Every pose is `x y z roll pitch yaw` in the world (the floor frame), metres and radians.
//! Names are unique among siblings (libsdformat's check): a box's visual is `wall_0`, its
//! collision `wall_0_collision`.

use super::solids::{Slab, Solids, line, num, nums, xml_escape};

/// The SDF document.
pub(super) fn document(s: &Solids) -> String {
    let mut out = String::new();
    line(&mut out, format_args!("<?xml version=\"1.0\"?>"));
    line(&mut out, format_args!("<sdf version=\"1.6\">"));
    line(&mut out, format_args!("  <world name=\"vrep_maze\">"));
    line(
        &mut out,
        format_args!("    <!-- {} -->", xml_escape(&s.title).replace("--", "- -")),
    );
    for text in [
        "    <light type=\"directional\" name=\"sun\">",
        "      <cast_shadows>true</cast_shadows>",
        "      <pose>0 0 10 0 0 0</pose>",
        "      <diffuse>0.8 0.8 0.8 1</diffuse>",
        "      <specular>0.2 0.2 0.2 1</specular>",
        "      <direction>-0.5 0.1 -0.9</direction>",
        "    </light>",
        "    <model name=\"ground_plane\">",
        "      <static>true</static>",
        "      <link name=\"link\">",
        "        <collision name=\"collision\">",
    ] {
        line(&mut out, format_args!("{text}"));
    }
    let plane = format!(
        "<geometry><plane><normal>0 0 1</normal><size>{}</size></plane></geometry>",
        nums(&s.floor)
    );
    line(&mut out, format_args!("          {plane}"));
    line(&mut out, format_args!("        </collision>"));
    line(&mut out, format_args!("        <visual name=\"visual\">"));
    line(&mut out, format_args!("          {plane}"));
    line(
        &mut out,
        format_args!("          {}", material(&s.floor_rgb)),
    );
    line(&mut out, format_args!("        </visual>"));
    line(&mut out, format_args!("      </link>"));
    line(&mut out, format_args!("    </model>"));
    line(&mut out, format_args!("    <model name=\"maze\">"));
    line(&mut out, format_args!("      <static>true</static>"));
    line(&mut out, format_args!("      <link name=\"maze\">"));
    for b in s.all() {
        if b.part.collides() {
            line(
                &mut out,
                format_args!("        <collision name=\"{}_collision\">", b.name),
            );
            line(&mut out, format_args!("          {}", pose_and_box(b)));
            line(&mut out, format_args!("        </collision>"));
        }
        line(
            &mut out,
            format_args!("        <visual name=\"{}\">", b.name),
        );
        line(&mut out, format_args!("          {}", pose_and_box(b)));
        line(&mut out, format_args!("          {}", material(&b.rgb)));
        line(&mut out, format_args!("        </visual>"));
    }
    line(&mut out, format_args!("      </link>"));
    line(&mut out, format_args!("    </model>"));
    line(&mut out, format_args!("  </world>"));
    line(&mut out, format_args!("</sdf>"));
    out
}

/// `<pose>` and `<geometry><box>` of a box.
fn pose_and_box(b: &Slab) -> String {
    format!(
        "<pose>{} 0 0 {}</pose><geometry><box><size>{}</size></box></geometry>",
        nums(&b.centre),
        num(b.yaw),
        nums(&b.size)
    )
}

/// A plain material of one colour.
fn material(rgb: &[f64; 3]) -> String {
    let c = nums(rgb);
    format!("<material><ambient>{c} 1</ambient><diffuse>{c} 1</diffuse></material>")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::export::solids::tests::{line_layout, post_layout, solids};

    #[test]
    fn a_world_with_a_ground_plane_and_one_static_maze_model() {
        let s = solids(&post_layout(0.0));
        let walls = document(&s);
        assert_eq!(walls.matches("<model ").count(), 2);
        assert_eq!(walls.matches("<static>true</static>").count(), 2);
        // the ground plane's collision and one per wall run and post
        assert_eq!(walls.matches("<collision ").count(), 1 + s.maze.len());
        assert_eq!(walls.matches("<visual ").count(), 1 + s.maze.len() + 2);
        assert!(walls.contains("<visual name=\"start\">"));
        assert!(walls.contains("<visual name=\"end\">"));
        assert!(walls.contains("<size>10 10</size>"));

        let lines = document(&solids(&line_layout(0.0)));
        assert_eq!(lines.matches("<collision ").count(), 1);
        assert!(lines.contains("<visual name=\"line_0\">"));
    }
}
