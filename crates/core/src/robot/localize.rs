//! A pose estimate kept true by the lines the camera sees: the layout's drawn lines are the
//! map, each line pixel's floor point is matched to the nearest line's centre, and the pose
//! is nudged (a damped least-squares step) so the points fall back onto their lines. Lines
//! fix the robot across them and its heading; along a straight line only the odometry
//! knows where it is, until a crossing or a turn shows another line.

use nalgebra::{Matrix3, Point2, Vector3};

use super::{Pose, wrap};
use crate::layout::runs::for_each_run;
use crate::layout::{Layout, passages};
use crate::maze::Grid;

/// A drawn line's centre, floor frame, from one end of its rectangle to the other.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Segment {
    a: Point2<f64>,
    b: Point2<f64>,
}

/// The drawn lines of a line layout, as the map a camera robot localizes against.
#[derive(Debug, Clone, PartialEq)]
pub struct LineMap {
    segments: Vec<Segment>,
}

/// How far a point may lie from its line to count, metres: beyond it, it is taken for
/// something else (another line's end, the markers, noise).
const GATE: f64 = 0.25;
/// Below this many matched points the view says too little to correct anything.
const MIN_POINTS: usize = 12;

impl LineMap {
    /// The map of `layout`'s lines (a line layout that passed validation).
    pub fn of(layout: &Layout) -> Result<Self, String> {
        let grid = Grid::new(layout.grid.columns.into(), layout.grid.rows.into())
            .map_err(|e| format!("grid: {e}"))?;
        let maze = passages::decode(grid, &layout.passages)?;
        let (cell, width) = (layout.grid.cell_size, layout.line.width);
        let (c, s) = (layout.grid.rotation.cos(), layout.grid.rotation.sin());
        let [ox, oy] = layout.grid.origin;
        let to_floor = |x: f64, y: f64| Point2::new(ox + c * x - s * y, oy + s * x + c * y);
        let mut segments = Vec::new();
        let Ok(()) = for_each_run::<std::convert::Infallible>(
            &maze,
            |run| {
                let [x0, y0, x1, y1] = run.rect(cell, width);
                let (mx, my) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
                let (a, b) = if x1 - x0 >= y1 - y0 {
                    (to_floor(x0, my), to_floor(x1, my))
                } else {
                    (to_floor(mx, y0), to_floor(mx, y1))
                };
                segments.push(Segment { a, b });
                Ok(())
            },
            |_| {},
        );
        Ok(Self { segments })
    }

    /// The nearest line to `q`: the closest point on its centre and whether it lies between
    /// the ends (then the residual is across the line).
    fn nearest(&self, q: Point2<f64>) -> Option<(Point2<f64>, nalgebra::Vector2<f64>, f64)> {
        let mut best: Option<(Point2<f64>, nalgebra::Vector2<f64>, f64)> = None;
        for s in &self.segments {
            let ab = s.b - s.a;
            let t = ((q - s.a).dot(&ab) / ab.norm_squared().max(f64::EPSILON)).clamp(0.0, 1.0);
            let c = s.a + ab * t;
            let d = (q - c).norm();
            if best.is_none_or(|(_, _, bd)| d < bd) {
                let normal = if t > 0.0 && t < 1.0 {
                    let n = nalgebra::Vector2::new(-ab.y, ab.x).normalize();
                    if n.dot(&(q - c)) < 0.0 { -n } else { n }
                } else if d > 1e-9 {
                    (q - c) / d
                } else {
                    nalgebra::Vector2::new(-ab.y, ab.x).normalize()
                };
                best = Some((c, normal, d));
            }
        }
        best
    }

    /// Mean distance from the floor points `points` (robot frame) seen at `pose` to their
    /// nearest lines, over those within the gate; `None` when too few are.
    pub fn mean_residual(&self, pose: Pose, points: &[[f64; 2]]) -> Option<f64> {
        let (sum, n) = points
            .iter()
            .filter_map(|p| self.nearest(to_floor(pose, *p)).map(|(_, _, d)| d))
            .filter(|d| *d <= GATE)
            .fold((0.0, 0usize), |(s, n), d| (s + d, n + 1));
        (n >= MIN_POINTS).then(|| sum / n as f64)
    }

    /// `pose` moved so that the line points `points` (robot frame) fall onto the map's
    /// lines: two damped Gauss-Newton steps, each at most 5 cm and 3 degrees. `pose`
    /// itself when too few points match.
    pub fn correct(&self, pose: Pose, points: &[[f64; 2]]) -> Pose {
        let mut estimate = pose;
        for _ in 0..2 {
            let mut h = Matrix3::<f64>::zeros();
            let mut g = Vector3::<f64>::zeros();
            let mut matched = 0usize;
            for p in points {
                let q = to_floor(estimate, *p);
                let Some((c, n, _)) = self.nearest(q) else {
                    continue;
                };
                let r = n.dot(&(q - c));
                if r.abs() > GATE {
                    continue;
                }
                let arm = q - Point2::new(estimate.x, estimate.y);
                let j = Vector3::new(n.x, n.y, n.x * -arm.y + n.y * arm.x);
                // Huber weights: a few far points (a line's end seen past a crossing) do
                // not pull the estimate away
                let w = if r.abs() < 0.05 { 1.0 } else { 0.05 / r.abs() };
                h += j * j.transpose() * w;
                g += j * (r * w);
                matched += 1;
            }
            if matched < MIN_POINTS {
                return estimate;
            }
            // a prior that holds what the view cannot see (along a lone straight line)
            h += Matrix3::from_diagonal(&Vector3::new(2.0, 2.0, 0.5));
            let Some(step) = h.try_inverse().map(|inv| -(inv * g)) else {
                return estimate;
            };
            let limit = |v: f64, m: f64| v.clamp(-m, m);
            estimate = Pose {
                x: estimate.x + limit(step.x, 0.05),
                y: estimate.y + limit(step.y, 0.05),
                yaw: wrap(estimate.yaw + limit(step.z, 3f64.to_radians())),
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
                if map.nearest(q).is_some_and(|(_, _, d)| d <= 0.05) {
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
        for _ in 0..10 {
            estimate = map.correct(estimate, &points);
        }
        assert!((estimate.y - truth.y).abs() < 0.01, "{estimate:?}");
        assert!(estimate.yaw.abs() < 0.01, "{estimate:?}");
        assert!(map.mean_residual(estimate, &points).unwrap() < 0.03);
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
        assert_eq!(map.mean_residual(pose, &[]), None);
    }
}
