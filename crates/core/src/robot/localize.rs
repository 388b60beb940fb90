//! A pose estimate kept true by the lines the camera sees: the layout's drawn lines are the
//! map, every line pixel's floor point should lie on a drawn line, and the pose is nudged (a
//! damped least-squares step) so that the points seen off every line fall back onto the
//! nearest one. A point on a line says nothing, so a junction's overlapping lines pull no
//! way; the band's edges fix the robot across a line and its heading. Along a straight line
//! only the odometry knows where it is, until a crossing or a turn shows another line.

use nalgebra::{Matrix3, Point2, Vector3};

use super::{Pose, wrap};
use crate::layout::runs::for_each_run;
use crate::layout::{Layout, passages};
use crate::maze::Grid;

/// The drawn lines of a line layout, as the map a camera robot localizes against: the
/// lines' rectangles in the maze frame, and where that frame lies on the floor.
#[derive(Debug, Clone, PartialEq)]
pub struct LineMap {
    /// `[x0, y0, x1, y1]`, maze frame (axis-aligned there).
    rects: Vec<[f64; 4]>,
    origin: [f64; 2],
    /// Cosine and sine of the maze's rotation on the floor.
    rotation: [f64; 2],
}

/// How far a point may lie from every line to count, metres: beyond it, it is taken for
/// something else (a marker's edge, noise).
const GATE: f64 = 0.2;
/// Below this many points off the lines the view says too little to correct anything.
const MIN_POINTS: usize = 8;

impl LineMap {
    /// The map of `layout`'s lines (a line layout that passed validation).
    pub fn of(layout: &Layout) -> Result<Self, String> {
        let grid = Grid::new(layout.grid.columns.into(), layout.grid.rows.into())
            .map_err(|e| format!("grid: {e}"))?;
        let maze = passages::decode(grid, &layout.passages)?;
        let (cell, width) = (layout.grid.cell_size, layout.line.width);
        let mut rects = Vec::new();
        let Ok(()) = for_each_run::<std::convert::Infallible>(
            &maze,
            |run| {
                rects.push(run.rect(cell, width));
                Ok(())
            },
            |_| {},
        );
        let angle = layout.grid.rotation;
        Ok(Self {
            rects,
            origin: layout.grid.origin,
            rotation: [angle.cos(), angle.sin()],
        })
    }

    /// How far the floor point `q` lies off the drawn lines, and the unit direction (floor
    /// frame) from the nearest line towards it; `None` on a line (or with no lines).
    fn off_lines(&self, q: Point2<f64>) -> Option<([f64; 2], f64)> {
        let [c, s] = self.rotation;
        let (dx, dy) = (q.x - self.origin[0], q.y - self.origin[1]);
        // into the maze frame, where the rectangles are axis-aligned
        let (mx, my) = (c * dx + s * dy, -s * dx + c * dy);
        let mut best: Option<([f64; 2], f64)> = None;
        for [x0, y0, x1, y1] in &self.rects {
            let ox = if mx < *x0 {
                mx - x0
            } else if mx > *x1 {
                mx - x1
            } else {
                0.0
            };
            let oy = if my < *y0 {
                my - y0
            } else if my > *y1 {
                my - y1
            } else {
                0.0
            };
            let d = ox.hypot(oy);
            if d == 0.0 {
                return None;
            }
            if best.is_none_or(|(_, bd)| d < bd) {
                best = Some(([ox / d, oy / d], d));
            }
        }
        // the direction back on the floor
        best.map(|([nx, ny], d)| ([c * nx - s * ny, s * nx + c * ny], d))
    }

    /// The share of the floor points `points` (robot frame) seen at `pose` that lie on a
    /// drawn line; `None` for no points.
    pub fn on_lines(&self, pose: Pose, points: &[[f64; 2]]) -> Option<f64> {
        let on = points
            .iter()
            .filter(|p| self.off_lines(to_floor(pose, **p)).is_none())
            .count();
        (!points.is_empty()).then(|| on as f64 / points.len() as f64)
    }

    /// `pose` moved so that the line points `points` (robot frame) seen off every line fall
    /// back onto the nearest: two damped Gauss-Newton steps, each at most 2 cm and 2
    /// degrees. `pose` itself when too few points lie off the lines (it is right, or the
    /// view says too little).
    pub fn correct(&self, pose: Pose, points: &[[f64; 2]]) -> Pose {
        let mut estimate = pose;
        for _ in 0..2 {
            // the normal equations of the 3 unknowns (dx, dy, dyaw), in plain numbers: this
            // runs for every point of every frame
            let mut h = [[0.0f64; 3]; 3];
            let mut g = [0.0f64; 3];
            let mut matched = 0usize;
            for p in points {
                let q = to_floor(estimate, *p);
                let Some((n, r)) = self.off_lines(q) else {
                    continue;
                };
                if r > GATE {
                    continue;
                }
                let (ax, ay) = (q.x - estimate.x, q.y - estimate.y);
                let j = [n[0], n[1], -n[0] * ay + n[1] * ax];
                for a in 0..3 {
                    for b in 0..3 {
                        h[a][b] += j[a] * j[b];
                    }
                    g[a] += j[a] * r;
                }
                matched += 1;
            }
            if matched < MIN_POINTS {
                return estimate;
            }
            // a prior that holds what the view cannot see (along a lone straight line)
            for (a, prior) in [4.0, 4.0, 0.5].into_iter().enumerate() {
                h[a][a] += prior;
            }
            let Some(step) = Matrix3::from_fn(|a, b| h[a][b])
                .try_inverse()
                .map(|inv| -(inv * Vector3::from(g)))
            else {
                return estimate;
            };
            let limit = |v: f64, m: f64| v.clamp(-m, m);
            estimate = Pose {
                x: estimate.x + limit(step.x, 0.02),
                y: estimate.y + limit(step.y, 0.02),
                yaw: wrap(estimate.yaw + limit(step.z, 2f64.to_radians())),
            };
        }
        estimate
    }
}

/// A robot-frame point in the floor frame, for the robot at `pose`.
pub fn to_floor(pose: Pose, p: [f64; 2]) -> Point2<f64> {
    let (c, s) = (pose.yaw.cos(), pose.yaw.sin());
    Point2::new(pose.x + c * p[0] - s * p[1], pose.y + s * p[0] + c * p[1])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::Algorithm;
    use crate::layout::{GenerateSpec, build_layout};

    fn course() -> Layout {
        let grid = Grid::new(9, 9).unwrap();
        build_layout(&GenerateSpec::course(grid, Algorithm::Dfs, 42)).unwrap()
    }

    /// The floor points (robot frame) of line pixels a robot at `truth` would see: a grid
    /// of points over the lines' rectangles within 1 m ahead.
    fn seen_from(map: &LineMap, truth: Pose) -> Vec<[f64; 2]> {
        let mut points = Vec::new();
        for i in 0..40 {
            for k in -20..=20 {
                let p = [0.1 + f64::from(i) * 0.02, f64::from(k) * 0.02];
                let q = to_floor(truth, p);
                if map.off_lines(q).is_none() {
                    points.push(p);
                }
            }
        }
        points
    }

    #[test]
    fn a_wrong_estimate_is_pulled_back_across_the_line_and_in_heading() {
        let layout = course();
        let map = LineMap::of(&layout).unwrap();
        // at Start (-4, -4) facing +x along the first line
        let truth = Pose {
            x: -3.8,
            y: -4.0,
            yaw: 0.0,
        };
        let points = seen_from(&map, truth);
        assert!(points.len() > 50);
        let mut estimate = Pose {
            x: -3.8,
            y: -3.95,
            yaw: 0.05,
        };
        for _ in 0..20 {
            estimate = map.correct(estimate, &points);
        }
        assert!((estimate.y - truth.y).abs() < 0.01, "{estimate:?}");
        assert!(estimate.yaw.abs() < 0.01, "{estimate:?}");
        assert!(map.on_lines(estimate, &points).unwrap() > 0.97);
    }

    #[test]
    fn too_few_points_change_nothing() {
        let map = LineMap::of(&course()).unwrap();
        let pose = Pose {
            x: 0.3,
            y: 0.2,
            yaw: 1.0,
        };
        assert_eq!(map.correct(pose, &[[0.2, 0.0]; 3]), pose);
        assert_eq!(map.on_lines(pose, &[]), None);
    }
}
