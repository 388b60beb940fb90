//! Does the scene's robot fit the maze drawn? After a draw, the robot's footprint width (the
//! one given, or read from the scene's object of that name by [`Backend::model_box`]) is
//! held against the layout's narrowest passage ([`vrep_maze_core::validate::robot_fit`]); a
//! robot that does not fit is a warning of the draw's report, never a failure. No object
//! of that name, or an API that cannot say, and nothing is said.

use vrep_maze_core::layout::Layout;
use vrep_maze_core::validate::robot_fit;

use super::{Backend, BoundingBox};

/// The robot a drawing is checked against ([`super::ApplyOptions::robot`]).
#[derive(Debug, Clone, PartialEq)]
pub struct RobotCheck {
    /// The robot's object in the scene, read when no `width` is given.
    pub name: String,
    /// Its footprint width in metres; `None` reads it from the scene.
    pub width: Option<f64>,
}

impl Default for RobotCheck {
    /// The course robot's name, `Robot`, read from the scene.
    fn default() -> Self {
        RobotCheck {
            name: "Robot".into(),
            width: None,
        }
    }
}

/// The footprint width of a robot whose model bounding box is `model`: the narrower of its
/// two horizontal sides, the least room it needs whichever way it faces (so a robot that
/// could pass is never warned of); `None` for a box without extent.
pub fn footprint_width(model: &BoundingBox) -> Option<f64> {
    let [x, y, _] = model.size();
    let width = x.min(y);
    (width.is_finite() && width > 0.0).then_some(width)
}

/// The warning when `check`'s robot does not fit the passages of `layout`; `None` when it
/// fits or its width is not known (no such object, an API that cannot say, or a failed
/// read: the drawing is done either way).
pub fn warning(scene: &mut dyn Backend, check: &RobotCheck, layout: &Layout) -> Option<String> {
    match check.width {
        Some(width) => robot_fit(layout, width),
        None => {
            let model = scene.model_box(&check.name).ok().flatten()?;
            let width = footprint_width(&model)?;
            robot_fit(layout, width).map(|w| {
                format!(
                    "`{}` in the scene (its model's bounding box): {w}",
                    check.name
                )
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_footprint_is_the_narrower_horizontal_side() {
        // the course robot's model box on the real 4.10: body, wheels and camera
        let course = BoundingBox {
            min: [-0.1, -0.115, -0.06],
            max: [0.11, 0.115, 0.0687],
        };
        let width = footprint_width(&course).unwrap();
        assert!((width - 0.21).abs() < 1e-9, "{width}");
        let flat = BoundingBox {
            min: [0.0, -0.5, 0.0],
            max: [0.0, 0.5, 0.0],
        };
        assert_eq!(footprint_width(&flat), None);
    }
}
