//! A maze as a MuJoCo MJCF model (`.mjcf`, `.mujoco.xml`): the floor as a plane geom, the
//! maze as one body without joints (welded to the world) holding one box geom per wall run
//! and per post, or one thin box per run of lines that collides with nothing
//! (`contype="0" conaffinity="0"`), and `start` and `end` as box sites.
//!
//! MJCF box sizes are half-extents; angles are radians (`<compiler angle="radian"/>`), a
//! box's yaw is `euler="0 0 yaw"`.

use std::io;

use super::solids::{Part, Slab, Solids, num, nums};
use super::xml::{self, XmlWriter};

/// The MJCF document.
pub(super) fn document(s: &Solids) -> String {
    xml::document(|xml| {
        xml.create_element("mujoco")
            .with_attribute(("model", s.title.as_str()))
            .write_inner_content(|xml| {
                xml.create_element("compiler")
                    .with_attribute(("angle", "radian"))
                    .write_empty()?;
                xml.create_element("asset")
                    .write_inner_content(|xml| materials(xml, s))?;
                xml.create_element("worldbody")
                    .write_inner_content(|xml| world(xml, s))?;
                Ok(())
            })?;
        Ok(())
    })
}

/// The floor's material and one for each part the maze has (wall, post, line).
fn materials(xml: &mut XmlWriter, s: &Solids) -> io::Result<()> {
    material(xml, "floor", &s.floor_rgb)?;
    for part in [Part::Wall, Part::Post, Part::Line] {
        if let Some(b) = s.maze.iter().find(|b| b.part == part) {
            material(xml, part.material(), &b.rgb)?;
        }
    }
    Ok(())
}

fn material(xml: &mut XmlWriter, name: &str, rgb: &[f64; 3]) -> io::Result<()> {
    xml.create_element("material")
        .with_attributes([("name", name), ("rgba", &format!("{} 1", nums(rgb)))])
        .write_empty()?;
    Ok(())
}

/// The sun, the floor plane, the maze body with its boxes, and the start and end sites.
fn world(xml: &mut XmlWriter, s: &Solids) -> io::Result<()> {
    xml.create_element("light")
        .with_attributes([
            ("name", "sun"),
            ("pos", "0 0 10"),
            ("dir", "0 0 -1"),
            ("directional", "true"),
        ])
        .write_empty()?;
    let size = format!("{} {} 0.1", num(s.floor[0] / 2.0), num(s.floor[1] / 2.0));
    xml.create_element("geom")
        .with_attributes([
            ("name", "floor"),
            ("type", "plane"),
            ("size", &size),
            ("material", "floor"),
        ])
        .write_empty()?;
    xml.create_element("body")
        .with_attribute(("name", "maze"))
        .write_inner_content(|xml| {
            for b in &s.maze {
                let mut geom = xml
                    .create_element("geom")
                    .with_attributes([("name", b.name.as_str()), ("type", "box")])
                    .with_attributes(placement(b).iter().map(|(k, v)| (*k, v.as_str())));
                if !b.part.collides() {
                    geom = geom.with_attributes([("contype", "0"), ("conaffinity", "0")]);
                }
                geom.with_attribute(("material", b.part.material()))
                    .write_empty()?;
            }
            Ok(())
        })?;
    for m in [&s.start, &s.end] {
        xml.create_element("site")
            .with_attributes([("name", m.name.as_str()), ("type", "box")])
            .with_attributes(placement(m).iter().map(|(k, v)| (*k, v.as_str())))
            .with_attribute(("rgba", format!("{} 1", nums(&m.rgb)).as_str()))
            .write_empty()?;
    }
    Ok(())
}

/// `pos`, `euler` (`0 0 yaw`) and `size`: centre, yaw and half-extents.
fn placement(b: &Slab) -> [(&'static str, String); 3] {
    [
        ("pos", nums(&b.centre)),
        ("euler", format!("0 0 {}", num(b.yaw))),
        ("size", nums(&b.size.map(|v| v / 2.0))),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::export::solids::tests::{line_layout, post_layout, solids};

    #[test]
    fn walls_collide_lines_do_not_and_markers_are_sites() {
        let walls = document(&solids(&post_layout(30.0)));
        let boxes = walls.matches("type=\"box\" pos=").count();
        assert_eq!(walls.matches("<geom ").count(), boxes - 2 + 1);
        assert!(!walls.contains("contype"));
        assert!(walls.contains("<site name=\"start\" type=\"box\""));
        assert!(walls.contains("<site name=\"end\" type=\"box\""));
        assert!(walls.contains("euler=\"0 0 0.523599\""));
        assert!(walls.contains("<material name=\"post\""));
        assert!(walls.contains("size=\"5 5 0.1\""));

        let lines = document(&solids(&line_layout(0.0)));
        let geoms = lines.matches("<geom name=\"line_").count();
        assert!(geoms > 0);
        assert_eq!(
            lines.matches("contype=\"0\" conaffinity=\"0\"").count(),
            geoms
        );
        assert!(lines.contains("<material name=\"line\" rgba=\"0 1 0 1\"/>"));
        assert!(!lines.contains("name=\"wall"));
    }
}
