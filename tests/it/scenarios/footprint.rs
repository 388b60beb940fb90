//! What a camera above the floor sees of a maze: the set of floor points covered by the
//! layout's lines (or walls and posts), compared point by point with the triangles of every
//! shape above the floor that the observer read back. Points within [`EDGE`] of a drawn
//! rectangle's border are not judged (single-precision vertices, rotated grids).

use fixedbitset::FixedBitSet;
use vrep_maze::layout::{Layout, Style};

use super::observer::Triangle;

/// Points this close to the border of an expected rectangle are not judged (metres).
const EDGE: f64 = 0.001;

/// One rectangle the layout asks for: centre, yaw, half sizes.
#[derive(Debug, Clone, Copy)]
struct Rect {
    x: f64,
    y: f64,
    yaw: f64,
    half: [f64; 2],
}

impl Rect {
    /// -1 surely outside, 1 surely inside, 0 on the border.
    fn classify(&self, px: f64, py: f64) -> i8 {
        let (s, c) = self.yaw.sin_cos();
        let (dx, dy) = (px - self.x, py - self.y);
        let (lx, ly) = ((c * dx + s * dy).abs(), (-s * dx + c * dy).abs());
        if lx <= self.half[0] - EDGE && ly <= self.half[1] - EDGE {
            1
        } else if lx >= self.half[0] + EDGE || ly >= self.half[1] + EDGE {
            -1
        } else {
            0
        }
    }

    fn reach(&self) -> f64 {
        self.half[0].hypot(self.half[1]) + EDGE
    }
}

/// The rectangles a layout draws, seen from above.
fn expected(layout: &Layout) -> Vec<Rect> {
    match layout.style {
        Style::Lines => layout
            .segments
            .iter()
            .map(|p| Rect {
                x: p.x,
                y: p.y,
                yaw: p.yaw,
                half: [layout.line.length / 2.0, layout.line.width / 2.0],
            })
            .collect(),
        Style::Walls => {
            let wall = layout.wall.as_ref().expect("a wall layout has a wall");
            let mut r: Vec<Rect> = layout
                .walls
                .iter()
                .map(|p| Rect {
                    x: p.x,
                    y: p.y,
                    yaw: p.yaw,
                    half: [wall.length / 2.0, wall.thickness / 2.0],
                })
                .collect();
            if let Some(post) = &layout.post {
                r.extend(layout.posts.iter().map(|p| Rect {
                    x: p.x,
                    y: p.y,
                    yaw: p.yaw,
                    half: [post.size / 2.0; 2],
                }));
            }
            r
        }
    }
}

/// A regular grid of sample points, offset so that none lies on a micrometre-rounded border.
struct Samples {
    x0: f64,
    y0: f64,
    step: f64,
    nx: usize,
    ny: usize,
}

impl Samples {
    fn point(&self, i: usize, j: usize) -> (f64, f64) {
        (
            self.x0 + (i as f64 + 0.373) * self.step,
            self.y0 + (j as f64 + 0.373) * self.step,
        )
    }

    /// The sample indices whose points may lie within `[x0, x1] x [y0, y1]`.
    fn span(
        &self,
        x0: f64,
        x1: f64,
        y0: f64,
        y1: f64,
    ) -> (std::ops::Range<usize>, std::ops::Range<usize>) {
        let idx =
            |v: f64, o: f64, n: usize| (((v - o) / self.step).floor().max(0.0) as usize).min(n);
        (
            idx(x0, self.x0, self.nx)..(idx(x1, self.x0, self.nx) + 1).min(self.nx),
            idx(y0, self.y0, self.ny)..(idx(y1, self.y0, self.ny) + 1).min(self.ny),
        )
    }
}

fn inside(t: &Triangle, px: f64, py: f64) -> bool {
    let d = |a: [f64; 3], b: [f64; 3]| (px - b[0]) * (a[1] - b[1]) - (a[0] - b[0]) * (py - b[1]);
    let (d1, d2, d3) = (d(t[0], t[1]), d(t[1], t[2]), d(t[2], t[0]));
    let neg = d1 < 0.0 || d2 < 0.0 || d3 < 0.0;
    let pos = d1 > 0.0 || d2 > 0.0 || d3 > 0.0;
    !(neg && pos)
}

/// Compares what `layout` draws with `triangles` (every shape above the floor, floor frame)
/// on the layout's floor (a template may stand beside it): `Ok` with the number of points
/// judged, or the first differences.
pub fn compare(layout: &Layout, triangles: &[Triangle]) -> Result<usize, String> {
    let rects = expected(layout);
    let [fx, fy] = layout.floor.size.map(|s| s / 2.0);
    let on_floor = |p: &[f64; 3]| p[0].abs() <= fx && p[1].abs() <= fy;
    let visible: Vec<&Triangle> = triangles
        .iter()
        .filter(|t| t.iter().any(|p| p[2] > 1e-6) && t.iter().any(on_floor))
        .collect();
    let smallest = rects
        .iter()
        .map(|r| r.half[0].min(r.half[1]))
        .fold(f64::INFINITY, f64::min);
    let step = (smallest / 2.0).clamp(0.002, 0.01);
    let (mut x0, mut y0, mut x1, mut y1) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
    for r in &rects {
        x0 = x0.min(r.x - r.reach());
        x1 = x1.max(r.x + r.reach());
        y0 = y0.min(r.y - r.reach());
        y1 = y1.max(r.y + r.reach());
    }
    for t in &visible {
        for p in t.iter() {
            x0 = x0.min(p[0]);
            x1 = x1.max(p[0]);
            y0 = y0.min(p[1]);
            y1 = y1.max(p[1]);
        }
    }
    let s = Samples {
        x0: (x0 / 0.01).floor() * 0.01,
        y0: (y0 / 0.01).floor() * 0.01,
        step,
        nx: ((x1 - x0) / step).ceil() as usize + 2,
        ny: ((y1 - y0) / step).ceil() as usize + 2,
    };
    assert!(
        s.nx * s.ny < 400_000_000,
        "a footprint of {} x {} samples",
        s.nx,
        s.ny
    );
    let mut want = FixedBitSet::with_capacity(s.nx * s.ny);
    let mut border = FixedBitSet::with_capacity(s.nx * s.ny);
    for r in &rects {
        let (is, js) = s.span(
            r.x - r.reach(),
            r.x + r.reach(),
            r.y - r.reach(),
            r.y + r.reach(),
        );
        for j in js {
            for i in is.clone() {
                let (px, py) = s.point(i, j);
                match r.classify(px, py) {
                    1 => want.insert(j * s.nx + i),
                    0 => border.insert(j * s.nx + i),
                    _ => {}
                }
            }
        }
    }
    let mut seen = FixedBitSet::with_capacity(s.nx * s.ny);
    for t in &visible {
        let (lo_x, hi_x) = (
            t.iter().map(|p| p[0]).fold(f64::MAX, f64::min),
            t.iter().map(|p| p[0]).fold(f64::MIN, f64::max),
        );
        let (lo_y, hi_y) = (
            t.iter().map(|p| p[1]).fold(f64::MAX, f64::min),
            t.iter().map(|p| p[1]).fold(f64::MIN, f64::max),
        );
        let (is, js) = s.span(lo_x, hi_x, lo_y, hi_y);
        for j in js {
            for i in is.clone() {
                let (px, py) = s.point(i, j);
                if px.abs() <= fx && py.abs() <= fy && inside(t, px, py) {
                    seen.insert(j * s.nx + i);
                }
            }
        }
    }
    // a border point of one rectangle can be surely inside another (a joint): it counts
    border.difference_with(&want);
    let mut missing = want.clone();
    missing.difference_with(&seen);
    let mut extra = seen;
    extra.difference_with(&want);
    extra.difference_with(&border);
    if missing.is_clear() && extra.is_clear() {
        return Ok(want.count_ones(..));
    }
    let at = |k: usize| {
        let (x, y) = s.point(k % s.nx, k / s.nx);
        format!("({x:.3}, {y:.3})")
    };
    let show = |set: &FixedBitSet| set.ones().take(5).map(at).collect::<Vec<_>>().join(" ");
    Err(format!(
        "the floor shows {} point(s) the layout does not draw (e.g. {}) and misses {} it draws (e.g. {}), of {} drawn, {step} m apart",
        extra.count_ones(..),
        show(&extra),
        missing.count_ones(..),
        show(&missing),
        want.count_ones(..),
    ))
}
