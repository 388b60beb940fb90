//! A maze as a URDF robot (`.urdf`): one link `maze`, fixed to the `world` link (Gazebo's
//! way of making a model static), with one collision and one visual box per wall run and per
//! post, or one visual-only thin box per run of lines, the visuals `start` and `end`, and the
//! floor as a visual-only slab just below z = 0 (a simulator brings its own ground). The link
//! has a nominal inertial (1 kg, unit inertia): Gazebo's URDF reader (libsdformat) drops a
//! link without one, and being fixed to the world it never moves.
//!
//! Every `<origin>` is `xyz` in the world (the floor frame) and `rpy` radians.

use std::io;

use super::solids::{Part, Slab, Solids, num, nums};
use super::xml::{self, XmlWriter, declaration, same_line, title_comment};

/// The floor slab's thickness, metres: its top is at z = 0.
const FLOOR_THICKNESS: f64 = 0.001;

/// The URDF document.
pub(super) fn document(s: &Solids) -> String {
    xml::document(|xml| {
        declaration(xml)?;
        title_comment(xml, &s.title)?;
        xml.create_element("robot")
            .with_attribute(("name", "vrep_maze"))
            .write_inner_content(|xml| robot(xml, s))?;
        Ok(())
    })
}

/// The `world` link, the fixed joint, and the `maze` link with every box.
fn robot(xml: &mut XmlWriter, s: &Solids) -> io::Result<()> {
    xml.create_element("link")
        .with_attribute(("name", "world"))
        .write_empty()?;
    xml.create_element("joint")
        .with_attributes([("name", "maze_fixed"), ("type", "fixed")])
        .write_inner_content(|xml| {
            xml.create_element("parent")
                .with_attribute(("link", "world"))
                .write_empty()?;
            xml.create_element("child")
                .with_attribute(("link", "maze"))
                .write_empty()?;
            Ok(())
        })?;
    xml.create_element("link")
        .with_attribute(("name", "maze"))
        .write_inner_content(|xml| {
            inertial(xml)?;
            let floor = Slab {
                name: "floor".to_string(),
                part: Part::Marker,
                centre: [0.0, 0.0, -FLOOR_THICKNESS / 2.0],
                size: [s.floor[0], s.floor[1], FLOOR_THICKNESS],
                yaw: 0.0,
                rgb: s.floor_rgb,
            };
            for b in std::iter::once(&floor).chain(s.all()) {
                slab(xml, b)?;
            }
            Ok(())
        })?;
    Ok(())
}

/// The nominal inertial: 1 kg, unit inertia.
fn inertial(xml: &mut XmlWriter) -> io::Result<()> {
    xml.create_element("inertial").write_inner_content(|xml| {
        xml.create_element("mass")
            .with_attribute(("value", "1"))
            .write_empty()?;
        xml.create_element("inertia")
            .with_attributes([
                ("ixx", "1"),
                ("ixy", "0"),
                ("ixz", "0"),
                ("iyy", "1"),
                ("iyz", "0"),
                ("izz", "1"),
            ])
            .write_empty()?;
        Ok(())
    })?;
    Ok(())
}

/// A box's visual (with its own material) and, if it collides, its collision.
fn slab(xml: &mut XmlWriter, b: &Slab) -> io::Result<()> {
    xml.create_element("visual")
        .with_attribute(("name", b.name.as_str()))
        .write_inner_content(|xml| {
            origin_and_box(xml, b)?;
            xml.create_element("material")
                .with_attribute(("name", b.name.as_str()))
                .write_inner_content(|xml| {
                    same_line(xml)?;
                    xml.create_element("color")
                        .with_attribute(("rgba", format!("{} 1", nums(&b.rgb)).as_str()))
                        .write_empty()?;
                    same_line(xml)
                })?;
            Ok(())
        })?;
    if b.part.collides() {
        xml.create_element("collision")
            .with_attribute(("name", format!("{}_collision", b.name).as_str()))
            .write_inner_content(|xml| origin_and_box(xml, b))?;
    }
    Ok(())
}

/// `<origin>` and `<geometry><box>` of a box, on one line.
fn origin_and_box(xml: &mut XmlWriter, b: &Slab) -> io::Result<()> {
    xml.create_element("origin")
        .with_attributes([
            ("xyz", nums(&b.centre).as_str()),
            ("rpy", format!("0 0 {}", num(b.yaw)).as_str()),
        ])
        .write_empty()?;
    same_line(xml)?;
    xml.create_element("geometry").write_inner_content(|xml| {
        same_line(xml)?;
        xml.create_element("box")
            .with_attribute(("size", nums(&b.size).as_str()))
            .write_empty()?;
        same_line(xml)
    })?;
    Ok(())
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
