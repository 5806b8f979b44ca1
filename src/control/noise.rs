//! The draws of one lander's control loop: its sensors' noise and biases and its thrusters'
//! errors (normal, or normal truncated at three standard deviations), and the small
//! rotation an attitude error or noise makes.

use crate::dist::{normal_quantile, quantile};
use crate::rng::uniform_open01;
use crate::scenario::Dist;
use glam::{DQuat, DVec3};
use rand_xoshiro::Xoshiro256PlusPlus;

/// A normal draw with standard deviation `sd` (0 draws nothing).
pub(super) fn normal(rng: &mut Xoshiro256PlusPlus, sd: f64) -> f64 {
    if sd > 0.0 {
        sd * normal_quantile(uniform_open01(rng))
    } else {
        0.0
    }
}

/// Three independent normal draws of standard deviation `sd`.
pub(super) fn normal3(rng: &mut Xoshiro256PlusPlus, sd: f64) -> DVec3 {
    DVec3::new(normal(rng, sd), normal(rng, sd), normal(rng, sd))
}

/// A normal draw truncated at three standard deviations (0 for `sd` 0).
pub(super) fn truncated(rng: &mut Xoshiro256PlusPlus, sd: f64) -> f64 {
    if sd > 0.0 {
        let d = Dist::Normal {
            mean: 0.0,
            sd,
            min: -3.0 * sd,
            max: 3.0 * sd,
        };
        quantile(&d, uniform_open01(rng), 0)
    } else {
        0.0
    }
}

/// The unit quaternion of a small rotation vector `v` (rad), without trigonometry:
/// `(v / 2, 1)` normalised, within `|v|^3 / 48` of the exact rotation.
pub(super) fn small_rotation(v: DVec3) -> DQuat {
    let h = v * 0.5;
    DQuat::from_xyzw(h.x, h.y, h.z, 1.0).normalize()
}
