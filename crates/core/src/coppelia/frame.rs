//! Frames and CoppeliaSim's Euler convention (alpha, beta, gamma with R = Rx * Ry * Rz).

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

/// A rigid transform (position + rotation), as CoppeliaSim stores an object's pose.
pub type Frame = Isometry3<f64>;

/// Rotation of CoppeliaSim Euler angles `[alpha, beta, gamma]`: R = Rx(alpha) * Ry(beta) * Rz(gamma).
pub fn rotation_from_euler(e: [f64; 3]) -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Vector3::x_axis(), e[0])
        * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), e[1])
        * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), e[2])
}

/// CoppeliaSim Euler angles of a rotation (inverse of [`rotation_from_euler`]);
/// beta in [-pi/2, pi/2], at gimbal lock alpha is 0.
pub fn euler_from_rotation(q: &UnitQuaternion<f64>) -> [f64; 3] {
    let m = q.to_rotation_matrix();
    let r = m.matrix();
    let sb = r[(0, 2)].clamp(-1.0, 1.0);
    let beta = sb.asin();
    if sb.abs() < 1.0 - 1e-12 {
        let alpha = (-r[(1, 2)]).atan2(r[(2, 2)]);
        let gamma = (-r[(0, 1)]).atan2(r[(0, 0)]);
        [alpha, beta, gamma]
    } else {
        [0.0, beta, r[(1, 0)].atan2(r[(1, 1)])]
    }
}

/// A frame from a position and CoppeliaSim Euler angles.
pub fn frame(position: [f64; 3], euler: [f64; 3]) -> Frame {
    Isometry3::from_parts(
        Translation3::new(position[0], position[1], position[2]),
        rotation_from_euler(euler),
    )
}

/// Position and Euler angles of a frame.
pub fn position_euler(f: &Frame) -> ([f64; 3], [f64; 3]) {
    let t = f.translation.vector;
    ([t.x, t.y, t.z], euler_from_rotation(&f.rotation))
}

/// Wraps an angle into (-pi, pi].
pub fn wrap_angle(a: f64) -> f64 {
    let two_pi = std::f64::consts::TAU;
    let mut x = a.rem_euclid(two_pi);
    if x > std::f64::consts::PI {
        x -= two_pi;
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() < tol)
    }

    #[test]
    fn euler_round_trip() {
        for e in [
            [0.1, 0.2, 0.3],
            [-1.0, 0.5, 2.5],
            [0.0, 0.0, FRAC_PI_2],
            [3.0, -1.2, -3.0],
        ] {
            let back = euler_from_rotation(&rotation_from_euler(e));
            assert!(close(back, e, 1e-9), "{e:?} -> {back:?}");
        }
    }

    /// The test vector measured on a real CoppeliaSim 4.5.1 (issue 3).
    #[test]
    fn real_simulator_test_vector() {
        let a = frame([1.0, 2.0, 0.001], [0.0, 0.0, FRAC_PI_2]);
        let b_rel = frame([0.5, 0.0, 0.0], [0.1, 0.2, 0.3]);
        let b = a * b_rel;
        let (p, e) = position_euler(&b);
        assert!(close(p, [1.0, 2.5, 0.001], 1e-9), "{p:?}");
        assert!(close(e, [-0.2010, 0.0980, 1.8907], 1e-4), "{e:?}");
        let (a_in_b, _) = position_euler(&(b.inverse() * a));
        assert!(
            close(a_in_b, [-0.4681, 0.1448, -0.0993], 1e-4),
            "{a_in_b:?}"
        );
    }

    #[test]
    fn wrap() {
        assert!((wrap_angle(3.0 * std::f64::consts::PI) - std::f64::consts::PI).abs() < 1e-12);
        assert!((wrap_angle(-FRAC_PI_2) + FRAC_PI_2).abs() < 1e-12);
    }
}
