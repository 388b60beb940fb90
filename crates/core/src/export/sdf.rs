//! A maze as a Gazebo world in SDFormat 1.6 (`.sdf`, `.world`): a sun, a static
//! `ground_plane` model of the floor's size, and the maze as one static model `maze` of one
//! link holding a collision and a visual box per wall run and per post, or a visual-only
//! thin box per run of lines, and the visuals `start` and `end`.
//!
//! Every pose is `x y z roll pitch yaw` in the world (the floor frame), metres and radians.
//! Names are unique among siblings (libsdformat's check): a box's visual is `wall_0`, its
//! collision `wall_0_collision`.

use std::io;

use quick_xml::events::BytesText;

use super::solids::{Slab, Solids, num, nums};
use super::xml::{self, XmlWriter, declaration, same_line, title_comment};

/// The SDF document.
pub(super) fn document(s: &Solids) -> String {
    xml::document(|xml| {
        declaration(xml)?;
        xml.create_element("sdf")
            .with_attribute(("version", "1.6"))
            .write_inner_content(|xml| {
                xml.create_element("world")
                    .with_attribute(("name", "vrep_maze"))
                    .write_inner_content(|xml| world(xml, s))?;
                Ok(())
            })?;
        Ok(())
    })
}

/// The title, the sun, the ground plane and the maze.
fn world(xml: &mut XmlWriter, s: &Solids) -> io::Result<()> {
    title_comment(xml, &s.title)?;
    xml.create_element("light")
        .with_attributes([("type", "directional"), ("name", "sun")])
        .write_inner_content(|xml| {
            text(xml, "cast_shadows", "true")?;
            text(xml, "pose", "0 0 10 0 0 0")?;
            text(xml, "diffuse", "0.8 0.8 0.8 1")?;
            text(xml, "specular", "0.2 0.2 0.2 1")?;
            text(xml, "direction", "-0.5 0.1 -0.9")
        })?;
    xml.create_element("model")
        .with_attribute(("name", "ground_plane"))
        .write_inner_content(|xml| {
            text(xml, "static", "true")?;
            xml.create_element("link")
                .with_attribute(("name", "link"))
                .write_inner_content(|xml| {
                    xml.create_element("collision")
                        .with_attribute(("name", "collision"))
                        .write_inner_content(|xml| plane(xml, &s.floor))?;
                    xml.create_element("visual")
                        .with_attribute(("name", "visual"))
                        .write_inner_content(|xml| {
                            plane(xml, &s.floor)?;
                            material(xml, &s.floor_rgb)
                        })?;
                    Ok(())
                })?;
            Ok(())
        })?;
    xml.create_element("model")
        .with_attribute(("name", "maze"))
        .write_inner_content(|xml| {
            text(xml, "static", "true")?;
            xml.create_element("link")
                .with_attribute(("name", "maze"))
                .write_inner_content(|xml| s.all().try_for_each(|b| slab(xml, b)))?;
            Ok(())
        })?;
    Ok(())
}

/// A box's collision (if it collides) and its visual.
fn slab(xml: &mut XmlWriter, b: &Slab) -> io::Result<()> {
    if b.part.collides() {
        xml.create_element("collision")
            .with_attribute(("name", format!("{}_collision", b.name).as_str()))
            .write_inner_content(|xml| pose_and_box(xml, b))?;
    }
    xml.create_element("visual")
        .with_attribute(("name", b.name.as_str()))
        .write_inner_content(|xml| {
            pose_and_box(xml, b)?;
            material(xml, &b.rgb)
        })?;
    Ok(())
}

/// `<name>text</name>`.
fn text(xml: &mut XmlWriter, name: &str, text: &str) -> io::Result<()> {
    xml.create_element(name)
        .write_text_content(BytesText::new(text))?;
    Ok(())
}

/// `<geometry><plane>` of the floor's size, on one line.
fn plane(xml: &mut XmlWriter, floor: &[f64; 2]) -> io::Result<()> {
    xml.create_element("geometry").write_inner_content(|xml| {
        same_line(xml)?;
        xml.create_element("plane").write_inner_content(|xml| {
            same_line(xml)?;
            text(xml, "normal", "0 0 1")?;
            same_line(xml)?;
            text(xml, "size", &nums(floor))?;
            same_line(xml)
        })?;
        same_line(xml)
    })?;
    Ok(())
}

/// `<pose>` and `<geometry><box>` of a box, on one line.
fn pose_and_box(xml: &mut XmlWriter, b: &Slab) -> io::Result<()> {
    text(
        xml,
        "pose",
        &format!("{} 0 0 {}", nums(&b.centre), num(b.yaw)),
    )?;
    same_line(xml)?;
    xml.create_element("geometry").write_inner_content(|xml| {
        same_line(xml)?;
        xml.create_element("box").write_inner_content(|xml| {
            same_line(xml)?;
            text(xml, "size", &nums(&b.size))?;
            same_line(xml)
        })?;
        same_line(xml)
    })?;
    Ok(())
}

/// A plain material of one colour, on one line.
fn material(xml: &mut XmlWriter, rgb: &[f64; 3]) -> io::Result<()> {
    let colour = format!("{} 1", nums(rgb));
    xml.create_element("material").write_inner_content(|xml| {
        same_line(xml)?;
        text(xml, "ambient", &colour)?;
        same_line(xml)?;
        text(xml, "diffuse", &colour)?;
        same_line(xml)
    })?;
    Ok(())
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
