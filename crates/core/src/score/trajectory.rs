//! A robot's trajectory: timed poses in the `Floor` frame, and the CSV file that holds one
//! (header `t,x,y,yaw`, one sample a row: seconds, metres, metres, radians).

use std::fmt::Write as _;

/// One pose of the robot at one simulation time, in the `Floor` frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Simulation time, seconds.
    pub t: f64,
    /// Metres along the floor's x.
    pub x: f64,
    /// Metres along the floor's y.
    pub y: f64,
    /// Heading about the floor's z, radians.
    pub yaw: f64,
}

/// The header line every trajectory file starts with.
pub const HEADER: &str = "t,x,y,yaw";

/// Reads a trajectory file's text: the header, then rows of four finite numbers with
/// non-decreasing times. Blank lines are skipped. The error names the line and the field.
pub fn parse_csv(text: &str) -> Result<Vec<Sample>, String> {
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty());
    match lines.next() {
        Some((_, header)) if header.trim().replace(' ', "") == HEADER => {}
        Some((n, other)) => {
            return Err(format!(
                "line {}: the header must be `{HEADER}`, not `{}`",
                n + 1,
                other.trim()
            ));
        }
        None => return Err(format!("empty: the header `{HEADER}` is missing")),
    }
    let mut samples: Vec<Sample> = Vec::new();
    for (n, line) in lines {
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let [t, x, y, yaw] = fields[..] else {
            return Err(format!(
                "line {}: {} fields, expected 4 ({HEADER})",
                n + 1,
                fields.len()
            ));
        };
        let number = |name: &str, text: &str| {
            text.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| format!("line {}: {name} `{text}` is not a finite number", n + 1))
        };
        let sample = Sample {
            t: number("t", t)?,
            x: number("x", x)?,
            y: number("y", y)?,
            yaw: number("yaw", yaw)?,
        };
        if let Some(last) = samples.last()
            && sample.t < last.t
        {
            return Err(format!(
                "line {}: t {} goes back in time (the row before is at {})",
                n + 1,
                sample.t,
                last.t
            ));
        }
        samples.push(sample);
    }
    Ok(samples)
}

/// The trajectory as a file's text: the header and one row per sample.
pub fn to_csv(samples: &[Sample]) -> String {
    let mut text = String::with_capacity(32 * (samples.len() + 1));
    text.push_str(HEADER);
    text.push('\n');
    for s in samples {
        let _ = writeln!(text, "{},{},{},{}", s.t, s.x, s.y, s.yaw);
    }
    text
}

/// The pose at time `t` on the polyline through `waypoints` (sorted by time): linear
/// between the two waypoints around `t` (yaw along the shorter turn), the first before
/// the first and the last after the last. `None` if there are no waypoints.
pub fn interpolate(waypoints: &[Sample], t: f64) -> Option<Sample> {
    let after = waypoints.partition_point(|w| w.t <= t);
    let (a, b) = match after {
        0 => return waypoints.first().map(|w| Sample { t, ..*w }),
        n if n == waypoints.len() => return waypoints.last().map(|w| Sample { t, ..*w }),
        n => (waypoints[n - 1], waypoints[n]),
    };
    let f = (t - a.t) / (b.t - a.t);
    let turn = (b.yaw - a.yaw + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
        - std::f64::consts::PI;
    let yaw = a.yaw + f * turn;
    Some(Sample {
        t,
        x: a.x + f * (b.x - a.x),
        y: a.y + f * (b.y - a.y),
        yaw: (yaw + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_reads_back_what_was_written() {
        let samples = vec![
            Sample {
                t: 0.0,
                x: -1.0,
                y: 0.0,
                yaw: 0.0,
            },
            Sample {
                t: 0.05,
                x: -0.975,
                y: 0.25,
                yaw: 1.5,
            },
        ];
        assert_eq!(parse_csv(&to_csv(&samples)).unwrap(), samples);
    }

    #[test]
    fn bad_files_name_the_line_and_field() {
        assert!(parse_csv("").unwrap_err().contains("header"));
        assert!(parse_csv("a,b\n").unwrap_err().contains("line 1"));
        let e = parse_csv("t,x,y,yaw\n0,1,2\n").unwrap_err();
        assert!(e.contains("line 2") && e.contains("3 fields"), "{e}");
        let e = parse_csv("t,x,y,yaw\n0,1,nan,0\n").unwrap_err();
        assert!(e.contains("line 2: y"), "{e}");
        let e = parse_csv("t,x,y,yaw\n1,0,0,0\n0.5,0,0,0\n").unwrap_err();
        assert!(e.contains("line 3") && e.contains("back in time"), "{e}");
    }

    #[test]
    fn interpolation_is_linear_and_clamped() {
        let w = [
            Sample {
                t: 1.0,
                x: 0.0,
                y: 0.0,
                yaw: 3.0,
            },
            Sample {
                t: 3.0,
                x: 2.0,
                y: -4.0,
                yaw: -3.0,
            },
        ];
        let mid = interpolate(&w, 2.0).unwrap();
        assert_eq!((mid.x, mid.y), (1.0, -2.0));
        // 3 rad to -3 rad turns the short way, through pi
        assert!(
            (mid.yaw.abs() - std::f64::consts::PI).abs() < 1e-12,
            "{}",
            mid.yaw
        );
        assert_eq!(interpolate(&w, 0.0).unwrap().x, 0.0);
        assert_eq!(interpolate(&w, 9.0).unwrap().y, -4.0);
        assert_eq!(interpolate(&[], 1.0), None);
    }
}
