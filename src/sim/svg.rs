//! Top view of a scene as SVG: every shape as its (rotated) footprint in its colour, lowest
//! first, so a drawn maze can be looked at without CoppeliaSim (`vrep-maze render DUMP.json`).

use std::fmt::Write;

use nalgebra::Point3;

use super::scene::{ObjectType, Scene};

/// A shape's footprint: world z (drawing order), colour, corners in the xy plane.
type Footprint = (f64, [u8; 3], Vec<(f64, f64)>);

/// SVG of the scene seen from above (+x right, +y up), `width` pixels wide.
pub fn scene_svg(scene: &Scene, width: f64) -> String {
    let mut shapes: Vec<Footprint> = Vec::new();
    for o in scene
        .objects()
        .filter(|o| o.kind == ObjectType::Shape && o.size[0] > 0.0 && o.size[1] > 0.0)
    {
        let Ok(world) = scene.world(o.handle) else {
            continue;
        };
        let (hx, hy) = (o.size[0] / 2.0, o.size[1] / 2.0);
        let corners = [(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy)]
            .iter()
            .map(|&(x, y)| {
                let p = world * Point3::new(x, y, 0.0);
                (p.x, p.y)
            })
            .collect();
        shapes.push((world.translation.vector.z, o.colour, corners));
    }
    shapes.sort_by(|a, b| a.0.total_cmp(&b.0));
    let pts = || shapes.iter().flat_map(|s| s.2.iter().copied());
    let (min_x, max_x) = pts().fold((f64::MAX, f64::MIN), |(lo, hi), (x, _)| {
        (lo.min(x), hi.max(x))
    });
    let (min_y, max_y) = pts().fold((f64::MAX, f64::MIN), |(lo, hi), (_, y)| {
        (lo.min(y), hi.max(y))
    });
    let (min_x, max_x, min_y, max_y) = if shapes.is_empty() {
        (-1.0, 1.0, -1.0, 1.0)
    } else {
        (min_x, max_x, min_y, max_y)
    };
    let span_x = (max_x - min_x).max(1e-6);
    let span_y = (max_y - min_y).max(1e-6);
    let scale = width / span_x;
    let height = span_y * scale;
    let mut out = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width:.0}\" height=\"{height:.0}\" viewBox=\"0 0 {width:.2} {height:.2}\">\n"
    );
    for (_, c, corners) in &shapes {
        let points: Vec<String> = corners
            .iter()
            .map(|(x, y)| format!("{:.2},{:.2}", (x - min_x) * scale, (max_y - y) * scale))
            .collect();
        let _ = writeln!(
            out,
            "  <polygon points=\"{}\" fill=\"rgb({},{},{})\"/>",
            points.join(" "),
            c[0],
            c[1],
            c[2]
        );
    }
    out.push_str("</svg>\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn course_scene_svg_has_every_shape_in_its_colour() {
        let svg = scene_svg(&Scene::course(), 400.0);
        assert_eq!(svg.matches("<polygon").count(), 4);
        assert!(
            svg.contains("rgb(0,255,0)")
                && svg.contains("rgb(0,0,255)")
                && svg.contains("rgb(255,0,0)")
        );
        // the floor (lowest) is drawn first
        assert!(svg.find("rgb(128,128,128)") < svg.find("rgb(0,255,0)"));
    }
}
