//! The checks each segment gets on its own, as it arrives: finite numbers, its yaw and
//! height, and that it lies on the floor.

use super::Problems;
use crate::layout::build::{extent_needed, fits_within};
use crate::layout::geometry::{Geometry, rectangle_corners};
use crate::layout::limits::{self, show};
use crate::layout::{Layout, Pose};
use crate::maze::Grid;

/// What a segment's numbers are checked against.
pub(super) struct Numbers {
    line_z: f64,
}

impl Numbers {
    /// The checks for `layout`'s segments.
    pub fn new(layout: &Layout) -> Self {
        Self {
            line_z: layout.line.z,
        }
    }

    /// Checks one segment; `false` when a coordinate is not a finite number, which stops
    /// every check that places segments.
    pub fn check(&self, index: usize, pose: &Pose, problems: &mut Problems) -> bool {
        if ![pose.x, pose.y, pose.z, pose.yaw]
            .iter()
            .all(|v| v.is_finite())
        {
            problems.add(
                format!("segments[{index}]"),
                "has a coordinate that is not a finite number",
            );
            return false;
        }
        // The range is checked first so that a valid segment formats no name.
        if !limits::YAW.contains(pose.yaw)
            && let Some(v) =
                limits::check_range(format!("segments[{index}].yaw"), pose.yaw, limits::YAW)
        {
            problems.violation(&v);
        }
        if !limits::HEIGHT.contains(self.line_z) {
            // line.z itself is reported; judge the segment by the range alone.
            if !limits::HEIGHT.contains(pose.z)
                && let Some(v) =
                    limits::check_range(format!("segments[{index}].z"), pose.z, limits::HEIGHT)
            {
                problems.violation(&v);
            }
        } else if (pose.z - self.line_z).abs() > 2.0 * limits::ROUNDING {
            problems.add(
                format!("segments[{index}].z"),
                format!(
                    "{} m is not line.z {} m: every segment lies at the height of the lines",
                    show(pose.z),
                    show(self.line_z)
                ),
            );
        }
        true
    }
}

/// The floor every segment must lie on.
pub(super) struct Floor {
    size: [f64; 2],
    tolerance: f64,
    length: f64,
    width: f64,
    /// Half the template's diagonal: no corner lies farther from the centre.
    reach: f64,
}

impl Floor {
    /// The floor check for `layout`'s segments on `grid`.
    pub fn new(layout: &Layout, grid: Grid, geometry: &Geometry) -> Self {
        let (length, width) = (layout.line.length, layout.line.width);
        Self {
            size: layout.floor.size,
            tolerance: limits::floor_tolerance(geometry, grid),
            length,
            width,
            reach: length.hypot(width) / 2.0,
        }
    }

    /// Checks that segment `index` lies on the floor.
    pub fn check(&self, index: usize, pose: &Pose, problems: &mut Problems) {
        let within =
            |centre: f64, size: f64| 2.0 * (centre.abs() + self.reach) <= size + self.tolerance;
        if within(pose.x, self.size[0]) && within(pose.y, self.size[1]) {
            return;
        }
        let corners = rectangle_corners(pose, self.length, self.width);
        if !fits_within(extent_needed(&corners), self.size, self.tolerance) {
            problems.add(
                format!("segments[{index}]"),
                format!(
                    "at ({}, {}) reaches off the {} m x {} m floor",
                    pose.x,
                    pose.y,
                    show(self.size[0]),
                    show(self.size[1])
                ),
            );
        }
    }
}
