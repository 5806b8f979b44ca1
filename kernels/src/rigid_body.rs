//! The 6-DOF rigid body over lanes: the reference's `rigid_body`, line for line.

use crate::lane::{Lane, splat};
use crate::vec3::{Quat, Vec3};

/// Advances position, velocity, rates and attitude of every lane by its own `dt` (0 leaves
/// a lane as it is).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub fn integrate(
    position_m: &mut Vec3,
    velocity_m_s: &mut Vec3,
    attitude: &mut Quat,
    rate_rad_s: &mut Vec3,
    mass_kg: Lane,
    inertia_kg_m2: Vec3,
    gravity_m_s2: Lane,
    force_n: Vec3,
    moment_n_m: Vec3,
    dt: Lane,
) {
    let acceleration = force_n * (splat(1.0) / mass_kg);
    let kicked = *velocity_m_s + acceleration * dt;
    let fall = gravity_m_s2 * (splat(0.5) * dt * dt);
    *position_m = *position_m + kicked * dt;
    position_m.z = position_m.z - fall;
    *velocity_m_s = kicked;
    velocity_m_s.z = velocity_m_s.z - gravity_m_s2 * dt;

    // Euler's equations by the implicit midpoint rule, as the reference.
    let i = inertia_kg_m2;
    let w0 = *rate_rad_s;
    let half_dt = splat(0.5) * dt;
    let mut mid = w0;
    for _ in 0..MIDPOINT_PASSES {
        let gyro = mid.cross(Vec3::new(i.x * mid.x, i.y * mid.y, i.z * mid.z));
        let torque = moment_n_m - gyro;
        mid = w0 + Vec3::new(torque.x / i.x, torque.y / i.y, torque.z / i.z) * half_dt;
    }
    *rate_rad_s = mid * splat(2.0) - w0;

    *attitude = attitude.mul(rotation_increment(mid, dt)).normalize();
}

/// Fixed-point passes of the implicit midpoint rule for the body rates.
pub const MIDPOINT_PASSES: usize = 3;

/// `exp(w dt / 2)` as a quaternion, by the same Taylor series as the reference.
#[inline(always)]
#[must_use]
pub fn rotation_increment(w: Vec3, dt: Lane) -> Quat {
    let half = splat(0.5) * dt;
    let theta2 = w.length_squared() * half * half;
    let t4 = theta2 * theta2;
    let t6 = t4 * theta2;
    let cos = splat(1.0) - theta2 / splat(2.0) + t4 / splat(24.0) - t6 / splat(720.0);
    let sinc = splat(1.0) - theta2 / splat(6.0) + t4 / splat(120.0) - t6 / splat(5040.0);
    let v = w * (half * sinc);
    Quat {
        x: v.x,
        y: v.y,
        z: v.z,
        w: cos,
    }
}
