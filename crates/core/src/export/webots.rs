//! A maze as a Webots world (`.wbt`, Webots R2023b, ENU axes, z up): a background and its
//! light, the floor as a `Solid` plane, and the maze as one `Solid` without `physics`
//! (static) named `maze`: its children are one `Pose` with a box `Shape` per wall run, post
//! or run of lines (`DEF wall_0`, `DEF line_3`, ... for a supervisor to find), and the marker
//! solids `start` and `end`; its `boundingObject` holds the
//! walls' and posts' boxes only, so lines and markers collide with nothing.
//!
//! Translations are metres, rotations axis-angle `0 0 1 yaw` in radians. No Webots parser
//! can be installed from a package registry, so only the structure is tested.

use std::fmt::Write;

use super::solids::{Slab, Solids, num, nums};

/// The Webots release whose node set the world uses (`Pose` appeared in R2023b).
const RELEASE: &str = "R2023b";

/// The `.wbt` document.
pub(super) fn document(s: &Solids) -> String {
    let mut out = String::new();
    world(&mut out, s);
    floor_solid(&mut out, s);
    maze_solid(&mut out, s);
    out
}

/// The header, the world info, the viewpoint above the floor and the background.
fn world(out: &mut String, s: &Solids) {
    line(out, format_args!("#VRML_SIM {RELEASE} utf8"));
    line(out, format_args!(""));
    for proto in ["TexturedBackground", "TexturedBackgroundLight"] {
        line(
            out,
            format_args!(
                "EXTERNPROTO \"https://raw.githubusercontent.com/cyberbotics/webots/{RELEASE}/projects/objects/backgrounds/protos/{proto}.proto\""
            ),
        );
    }
    line(out, format_args!(""));
    line(out, format_args!("WorldInfo {{"));
    line(out, format_args!("  info [ {} ]", quoted(&s.title)));
    line(out, format_args!("}}"));
    let height = s.floor[0].max(s.floor[1]);
    line(out, format_args!("Viewpoint {{"));
    line(out, format_args!("  orientation 0 1 0 1.5708"));
    line(out, format_args!("  position 0 0 {}", num(height)));
    line(out, format_args!("}}"));
    line(out, format_args!("TexturedBackground {{"));
    line(out, format_args!("}}"));
    line(out, format_args!("TexturedBackgroundLight {{"));
    line(out, format_args!("}}"));
}

/// The floor: a plane that collides.
fn floor_solid(out: &mut String, s: &Solids) {
    line(out, format_args!("Solid {{"));
    line(out, format_args!("  name \"floor\""));
    line(out, format_args!("  children ["));
    let plane = format!("Plane {{ size {} }}", nums(&s.floor));
    line(
        out,
        format_args!(
            "    Shape {{ appearance {} geometry {plane} }}",
            look(&s.floor_rgb)
        ),
    );
    line(out, format_args!("  ]"));
    line(out, format_args!("  boundingObject {plane}"));
    line(out, format_args!("}}"));
}

/// The maze's walls or lines and the two markers, one solid whose bounding object is the
/// parts that collide.
fn maze_solid(out: &mut String, s: &Solids) {
    line(out, format_args!("Solid {{"));
    line(out, format_args!("  name \"maze\""));
    line(out, format_args!("  children ["));
    for b in &s.maze {
        line(
            out,
            format_args!(
                "    DEF {} Pose {{ {} children [ Shape {{ appearance {} geometry Box {{ size {} }} }} ] }}",
                b.name,
                placement(b),
                look(&b.rgb),
                nums(&b.size)
            ),
        );
    }
    for m in [&s.start, &s.end] {
        line(
            out,
            format_args!(
                "    Solid {{ name \"{}\" {} children [ Shape {{ appearance {} geometry Box {{ size {} }} }} ] }}",
                m.name,
                placement(m),
                look(&m.rgb),
                nums(&m.size)
            ),
        );
    }
    line(out, format_args!("  ]"));
    let solid: Vec<_> = s.maze.iter().filter(|b| b.part.collides()).collect();
    if !solid.is_empty() {
        line(out, format_args!("  boundingObject Group {{"));
        line(out, format_args!("    children ["));
        for b in solid {
            line(
                out,
                format_args!(
                    "      Pose {{ {} children [ Box {{ size {} }} ] }}",
                    placement(b),
                    nums(&b.size)
                ),
            );
        }
        line(out, format_args!("    ]"));
        line(out, format_args!("  }}"));
    }
    line(out, format_args!("}}"));
}

/// `translation x y z rotation 0 0 1 yaw`.
fn placement(b: &Slab) -> String {
    format!(
        "translation {} rotation 0 0 1 {}",
        nums(&b.centre),
        num(b.yaw)
    )
}

/// A matte `PBRAppearance` of one colour.
fn look(rgb: &[f64; 3]) -> String {
    format!(
        "PBRAppearance {{ baseColor {} roughness 1 metalness 0 }}",
        nums(rgb)
    )
}

/// A VRML string literal.
fn quoted(text: &str) -> String {
    format!("\"{}\"", text.replace('\\', "\\\\").replace('"', "\\\""))
}

/// Appends a formatted line to a document being built (writing to a `String` cannot fail).
fn line(out: &mut String, args: std::fmt::Arguments<'_>) {
    out.write_fmt(args)
        .expect("writing to a String cannot fail");
    out.push('\n');
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::export::solids::tests::{line_layout, post_layout, solids};

    /// Braces and brackets balance and never close before they open.
    fn balanced(text: &str) -> bool {
        let mut stack = Vec::new();
        for c in text.chars() {
            match c {
                '{' | '[' => stack.push(c),
                '}' if stack.pop() != Some('{') => return false,
                ']' if stack.pop() != Some('[') => return false,
                _ => {}
            }
        }
        stack.is_empty()
    }

    #[test]
    fn one_static_maze_solid_whose_bounding_object_holds_only_walls_and_posts() {
        let s = solids(&post_layout(0.0));
        let walls = document(&s);
        assert!(walls.starts_with("#VRML_SIM R2023b utf8\n"));
        assert!(balanced(&walls));
        assert!(!walls.contains("physics"));
        assert_eq!(walls.matches("Box {").count(), 2 * s.maze.len() + 2);
        assert_eq!(walls.matches("boundingObject Group").count(), 1);
        assert!(walls.contains("Solid { name \"start\""));
        assert!(walls.contains("Solid { name \"end\""));

        let lines = document(&solids(&line_layout(0.0)));
        assert!(balanced(&lines));
        assert!(!lines.contains("boundingObject Group"));
        assert!(lines.contains("baseColor 0 1 0"));
        assert!(!balanced("Solid { children [ }"));
    }
}
