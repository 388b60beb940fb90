//! What counts as the same: how far apart two positions, angles, sizes or colours of scene
//! objects may be and still be one (a simulator keeps them in single precision).

/// Tolerance on positions (metres) for "already in place" and verification.
pub const POSITION_TOLERANCE: f64 = 1e-4;
/// Tolerance on angles (radians).
pub const ANGLE_TOLERANCE: f64 = 1e-4;

/// Tolerance on sizes (metres): a template's bounding box may differ from the layout's
/// size by this much. CoppeliaSim keeps sizes in single precision (about 1e-7 relative: 0.1
/// micrometre on a metre) and its object dialogs set sizes in millimetres, so half a
/// millimetre is far above the simulator's noise and far below what a camera sees.
pub const SIZE_TOLERANCE: f64 = 5e-4;

/// How far apart (per channel, 0..1) two colours may be and still be one: a copy has its
/// template's colour exactly; the colour dialogs step by 0.01.
pub const COLOUR_TOLERANCE: f64 = 0.01;

/// `true` if two lengths are equal within [`SIZE_TOLERANCE`] (never with a NaN).
pub(crate) fn same_size(a: f64, b: f64) -> bool {
    (a - b).abs() <= SIZE_TOLERANCE
}

/// `true` if `a` and `b` are the same extents within [`SIZE_TOLERANCE`] along each axis
/// (never with a NaN): a copy has exactly its template's bounding box, both kept in single
/// precision.
pub fn same_extents(a: [f64; 3], b: [f64; 3]) -> bool {
    a.iter().zip(b).all(|(x, y)| same_size(*x, y))
}

/// `true` if two colours are one within [`COLOUR_TOLERANCE`] per channel (never with NaN).
pub fn same_colour(a: [f64; 3], b: [f64; 3]) -> bool {
    a.iter()
        .zip(b)
        .all(|(x, y)| (x - y).abs() <= COLOUR_TOLERANCE)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_a_millimetre_and_a_colour_step_are_the_same_a_nan_never() {
        let line = [0.6, 0.1, 0.0];
        assert!(same_extents(line, [0.6, 0.1, 4.9e-4]));
        assert!(!same_extents(line, [0.6, 0.1, 5.1e-4]));
        assert!(!same_extents(line, [f64::NAN, 0.1, 0.0]));
        let green = [0.0, 1.0, 0.0];
        assert!(same_colour(green, [0.0, 0.995, 0.0]));
        assert!(!same_colour(green, [f64::NAN, 1.0, 0.0]));
    }
}
