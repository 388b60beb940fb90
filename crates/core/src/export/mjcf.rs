//! A maze as a MuJoCo MJCF model (`.mjcf`, `.mujoco.xml`): the floor as a plane geom, the
//! maze as one body without joints (welded to the world) holding one box geom per wall run
//! and per post, or one thin box per run of lines that collides with nothing
//! (`contype="0" conaffinity="0"`), and `start` and `end` as box sites.
//!
//! MJCF box sizes are half-extents; angles are radians (`<compiler angle="radian"/>`), a
//! box's yaw is `euler="0 0 yaw"`.

use super::solids::{Part, Slab, Solids, line, num, nums, xml_escape};

/// The MJCF document.
pub(super) fn document(s: &Solids) -> String {
    let mut out = String::new();
    line(
        &mut out,
        format_args!("<mujoco model=\"{}\">", xml_escape(&s.title)),
    );
    line(&mut out, format_args!("  <compiler angle=\"radian\"/>"));
    line(&mut out, format_args!("  <asset>"));
    line(
        &mut out,
        format_args!(
            "    <material name=\"floor\" rgba=\"{} 1\"/>",
            nums(&s.floor_rgb)
        ),
    );
    for part in [Part::Wall, Part::Post, Part::Line] {
        if let Some(b) = s.maze.iter().find(|b| b.part == part) {
            line(
                &mut out,
                format_args!(
                    "    <material name=\"{}\" rgba=\"{} 1\"/>",
                    part.material(),
                    nums(&b.rgb)
                ),
            );
        }
    }
    line(&mut out, format_args!("  </asset>"));
    line(&mut out, format_args!("  <worldbody>"));
    line(
        &mut out,
        format_args!(
            "    <light name=\"sun\" pos=\"0 0 10\" dir=\"0 0 -1\" directional=\"true\"/>"
        ),
    );
    line(
        &mut out,
        format_args!(
            "    <geom name=\"floor\" type=\"plane\" size=\"{} {} 0.1\" material=\"floor\"/>",
            num(s.floor[0] / 2.0),
            num(s.floor[1] / 2.0)
        ),
    );
    line(&mut out, format_args!("    <body name=\"maze\">"));
    for b in &s.maze {
        let contact = if b.part.collides() {
            ""
        } else {
            " contype=\"0\" conaffinity=\"0\""
        };
        line(
            &mut out,
            format_args!(
                "      <geom name=\"{}\" type=\"box\" {}{contact} material=\"{}\"/>",
                b.name,
                placement(b),
                b.part.material()
            ),
        );
    }
    line(&mut out, format_args!("    </body>"));
    for m in [&s.start, &s.end] {
        line(
            &mut out,
            format_args!(
                "    <site name=\"{}\" type=\"box\" {} rgba=\"{} 1\"/>",
                m.name,
                placement(m),
                nums(&m.rgb)
            ),
        );
    }
    line(&mut out, format_args!("  </worldbody>"));
    line(&mut out, format_args!("</mujoco>"));
    out
}

/// `pos="..." euler="0 0 yaw" size="..."`: centre, yaw and half-extents.
fn placement(b: &Slab) -> String {
    format!(
        "pos=\"{}\" euler=\"0 0 {}\" size=\"{}\"",
        nums(&b.centre),
        num(b.yaw),
        nums(&b.size.map(|v| v / 2.0))
    )
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
