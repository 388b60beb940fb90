//! A robot's forward camera as a pinhole: which point of the floor each pixel shows, and
//! which pixels show a drawn line. Images are as CoppeliaSim's vision sensors give them: RGB,
//! 3 bytes a pixel, the bottom row first; a column index grows to the image's right, which is
//! the sensor's -x (the sensor looks along its +z with its +y up).

/// An RGB image, bottom row first (as `sim.getVisionSensorImg` and
/// `simxGetVisionSensorImage` give it).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Image {
    /// Pixels a row.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// `width * height * 3` bytes.
    pub rgb: Vec<u8>,
}

impl Image {
    /// Checks the buffer's length against the size; the error says both.
    pub fn new(width: usize, height: usize, rgb: Vec<u8>) -> Result<Self, String> {
        if width == 0 || height == 0 || rgb.len() != width * height * 3 {
            return Err(format!(
                "an image of {width} x {height} pixels needs {} bytes, got {}",
                width * height * 3,
                rgb.len()
            ));
        }
        Ok(Self { width, height, rgb })
    }

    /// The pixel at column `i` and row `j` (row 0 at the bottom).
    pub fn pixel(&self, i: usize, j: usize) -> [u8; 3] {
        let k = (j * self.width + i) * 3;
        [self.rgb[k], self.rgb[k + 1], self.rgb[k + 2]]
    }

    /// `true` when every byte is zero: what a camera gives when nothing renders (a
    /// simulator without a display).
    pub fn is_black(&self) -> bool {
        self.rgb.iter().all(|&b| b == 0)
    }
}

/// Where a camera sits on the robot and what it sees.
#[derive(Debug, Clone, PartialEq)]
pub struct CameraModel {
    /// Pixels a row.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// The perspective angle, radians: the field of view across the larger side.
    pub view_angle: f64,
    /// The camera's frame in the robot's: a 3x4 row-major matrix, as `sim.getObjectMatrix`
    /// gives it (rotation columns are the camera's axes, the last column its position).
    pub mount: [f64; 12],
    /// The floor's height in the robot's frame, metres (negative: the floor is below).
    pub floor_z: f64,
}

impl CameraModel {
    /// The floor point (robot frame x forward, y left) that pixel `(i, j)` shows, or `None`
    /// for a pixel that looks at or above the horizon.
    pub fn ground(&self, i: usize, j: usize) -> Option<[f64; 2]> {
        let scale = (self.view_angle / 2.0).tan() / (self.width.max(self.height) as f64 / 2.0);
        let cx = -((i as f64 + 0.5) - self.width as f64 / 2.0) * scale;
        let cy = ((j as f64 + 0.5) - self.height as f64 / 2.0) * scale;
        let m = &self.mount;
        let ray = [
            m[0] * cx + m[1] * cy + m[2],
            m[4] * cx + m[5] * cy + m[6],
            m[8] * cx + m[9] * cy + m[10],
        ];
        let origin = [m[3], m[7], m[11]];
        if ray[2] >= -1e-6 {
            return None;
        }
        let t = (self.floor_z - origin[2]) / ray[2];
        (t > 0.0).then(|| [origin[0] + t * ray[0], origin[1] + t * ray[1]])
    }

    /// The floor points of every `stride`-th pixel in both directions that lie within
    /// `range` metres ahead of the robot's centre: `(i, j, x, y)`. Worked out once a run.
    pub fn ground_table(&self, stride: usize, range: f64) -> Vec<(usize, usize, [f64; 2])> {
        let stride = stride.max(1);
        let mut table = Vec::new();
        for j in (0..self.height).step_by(stride) {
            for i in (0..self.width).step_by(stride) {
                if let Some(p) = self.ground(i, j)
                    && p[0].hypot(p[1]) <= range
                {
                    table.push((i, j, p));
                }
            }
        }
        table
    }
}

/// Tells a drawn line's pixels from the floor's by colour direction, whatever the light: a
/// scene lit only by ambient light renders a colour `c` as a fraction of `c`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineColour {
    line: [f64; 3],
    floor: [f64; 3],
}

impl LineColour {
    /// The line's and the floor's colours (0..1 each, as `sim.getShapeColor` gives them).
    /// An error when they are too alike to tell apart in an image.
    pub fn new(line: [f64; 3], floor: [f64; 3]) -> Result<Self, String> {
        let (l, f) = (unit(line), unit(floor));
        match (l, f) {
            (Some(l), Some(f)) if dot(l, f) < 0.97 => Ok(Self { line: l, floor: f }),
            (None, _) => Err("the line's colour is black: a camera cannot see it".into()),
            _ => Err(format!(
                "the line's colour {line:?} is too close to the floor's {floor:?} for a camera to tell them apart"
            )),
        }
    }

    /// `true` if the pixel shows the line: bright enough, close to the line's colour
    /// direction and closer to it than to the floor's.
    pub fn is_line(&self, pixel: [u8; 3]) -> bool {
        let p = [
            f64::from(pixel[0]),
            f64::from(pixel[1]),
            f64::from(pixel[2]),
        ];
        let Some(u) = unit(p) else { return false };
        let norm = dot(p, p).sqrt();
        let (to_line, to_floor) = (dot(u, self.line), dot(u, self.floor));
        norm >= 8.0 && to_line > 0.95 && to_line > to_floor
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn unit(v: [f64; 3]) -> Option<[f64; 3]> {
    let n = dot(v, v).sqrt();
    (n > 1e-9).then(|| [v[0] / n, v[1] / n, v[2] / n])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The course robot's camera as the real 4.10 reports it: 0.105 m ahead of the body's
    /// centre, 0.04 m above it, looking forward and 30 degrees down; the body's centre
    /// 0.06 m above the floor.
    pub(crate) fn course_camera() -> CameraModel {
        CameraModel {
            width: 256,
            height: 256,
            view_angle: 60f64.to_radians(),
            mount: [
                0.0, 0.5, 0.866_025, 0.105, 1.0, 0.0, 0.0, 0.0, 0.0, 0.866_025, -0.5, 0.04,
            ],
            floor_z: -0.06,
        }
    }

    #[test]
    fn the_image_centre_sees_the_floor_ahead_and_columns_grow_to_the_right() {
        let cam = course_camera();
        let centre = cam.ground(128, 128).unwrap();
        // the optical axis meets the floor 0.1 / tan 30 = 0.173 m ahead of the camera
        assert!(
            (centre[0] - 0.278).abs() < 0.01 && centre[1].abs() < 0.01,
            "{centre:?}"
        );
        let right = cam.ground(250, 128).unwrap();
        assert!(right[1] < -0.05, "{right:?}");
        let near = cam.ground(128, 0).unwrap();
        assert!(near[0] < centre[0]);
        assert!(cam.ground(128, 255).is_none() || cam.ground(128, 255).unwrap()[0] > 2.0);
    }

    #[test]
    fn line_pixels_are_told_by_colour_direction_not_brightness() {
        let green = LineColour::new([0.0, 1.0, 0.0], [1.0, 1.0, 1.0]).unwrap();
        assert!(green.is_line([0, 51, 0]));
        assert!(green.is_line([0, 200, 3]));
        assert!(!green.is_line([51, 51, 51]), "floor");
        assert!(!green.is_line([0, 0, 51]), "start marker");
        assert!(!green.is_line([51, 0, 0]), "end marker");
        assert!(!green.is_line([0, 3, 0]), "too dark to tell");
        let red = LineColour::new([1.0, 0.0, 0.0], [1.0, 1.0, 1.0]).unwrap();
        assert!(red.is_line([51, 0, 0]) && !red.is_line([0, 51, 0]));
        assert!(LineColour::new([0.9, 0.9, 0.9], [1.0, 1.0, 1.0]).is_err());
        assert!(LineColour::new([0.0, 0.0, 0.0], [1.0, 1.0, 1.0]).is_err());
    }

    #[test]
    fn images_check_their_size() {
        assert!(Image::new(2, 2, vec![0; 12]).unwrap().is_black());
        assert!(
            Image::new(2, 2, vec![0; 11])
                .unwrap_err()
                .contains("12 bytes")
        );
    }
}
