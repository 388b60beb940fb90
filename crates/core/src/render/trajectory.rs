//! A robot's run drawn over the maze (`render --trajectory`): its path in the floor frame
//! as a few polylines, each coloured by the time it was driven, from dark purple at the
//! start to yellow at the end (a plasma-like ramp that stands out on the grey floor, the
//! green lines and the orange solution).

use super::figure::Colour;
use crate::score::Sample;

/// How many colour bands the path is drawn in.
const BANDS: usize = 32;

/// Width of the drawn path, as a share of the line width (or wall thickness).
pub(super) const WIDTH_SHARE: f64 = 0.6;

/// Stops of the colour ramp, from the first sample's time to the last one's.
const RAMP: [[f64; 3]; 4] = [
    [0x3d as f64, 0x04 as f64, 0x9b as f64],
    [0xcc as f64, 0x47 as f64, 0x78 as f64],
    [0xf8 as f64, 0x95 as f64, 0x40 as f64],
    [0xf0 as f64, 0xf9 as f64, 0x21 as f64],
];

/// The ramp's colour at `f` in 0..=1.
pub(super) fn colour_at(f: f64) -> Colour {
    let f = f.clamp(0.0, 1.0) * (RAMP.len() - 1) as f64;
    let k = (f.floor() as usize).min(RAMP.len() - 2);
    let u = f - k as f64;
    let (a, b) = (RAMP[k], RAMP[k + 1]);
    Colour(std::array::from_fn(|i| {
        (a[i] + u * (b[i] - a[i])).round() as u8
    }))
}

/// The path as at most [`BANDS`] polylines of floor points `[x, y]`, by time, each with the
/// colour of its middle time; neighbours share their end point, so the path has no gaps.
pub(super) fn bands(samples: &[Sample]) -> Vec<(Vec<[f64; 2]>, Colour)> {
    let (Some(first), Some(last)) = (samples.first(), samples.last()) else {
        return Vec::new();
    };
    let span = (last.t - first.t).max(f64::MIN_POSITIVE);
    let per_band = samples.len().div_ceil(BANDS).max(1);
    let mut out = Vec::new();
    let mut start = 0;
    while start + 1 < samples.len() || (start == 0 && samples.len() == 1) {
        let end = (start + per_band).min(samples.len() - 1);
        let points = samples[start..=end].iter().map(|s| [s.x, s.y]).collect();
        let middle = (samples[start].t + samples[end].t) / 2.0;
        out.push((points, colour_at((middle - first.t) / span)));
        if end == start {
            break;
        }
        start = end;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ramp_runs_from_purple_to_yellow() {
        assert_eq!(colour_at(0.0), Colour([0x3d, 0x04, 0x9b]));
        assert_eq!(colour_at(1.0), Colour([0xf0, 0xf9, 0x21]));
        assert_eq!(colour_at(2.0), colour_at(1.0));
    }

    #[test]
    fn bands_cover_the_path_without_gaps_and_get_later_colours() {
        let samples: Vec<Sample> = (0..100)
            .map(|k| Sample {
                t: f64::from(k),
                x: f64::from(k),
                y: 0.0,
                yaw: 0.0,
            })
            .collect();
        let bands = bands(&samples);
        assert!(bands.len() <= BANDS && bands.len() > 1);
        for pair in bands.windows(2) {
            assert_eq!(pair[0].0.last(), pair[1].0.first(), "no gap");
        }
        let points: usize = bands.iter().map(|(p, _)| p.len() - 1).sum();
        assert_eq!(points, 99, "every segment once");
        assert_eq!(bands[0].0[0], [0.0, 0.0]);
        assert_eq!(bands.last().unwrap().0.last(), Some(&[99.0, 0.0]));
        assert!(
            bands[0].1.0[2] > bands.last().unwrap().1.0[2],
            "purple before yellow"
        );
        assert_eq!(super::bands(&[]).len(), 0);
        assert_eq!(super::bands(&samples[..1]).len(), 1);
    }
}
