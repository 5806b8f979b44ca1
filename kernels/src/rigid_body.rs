//! The 6-DOF rigid body over lanes: the reference's `rigid_body`, line for line.

use crate::lane::Lane;
use crate::vec3::{Quat, Vec3};

/// Advances position, velocity, rates and attitude of every lane by its own `dt` (0 leaves
/// a lane as it is). Divisions by the mass and the moments of inertia are multiplications
/// by their reciprocals, computed once per sweep. The contact force `force_n` kicks the
/// velocity first (symplectic Euler); gravity and, with `THRUST`, the thrust `thrust_n`
/// (in I, constant over the step) enter exactly, as constant accelerations.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub fn integrate<L: Lane, const THRUST: bool>(
    position_m: &mut Vec3<L>,
    velocity_m_s: &mut Vec3<L>,
    attitude: &mut Quat<L>,
    rate_rad_s: &mut Vec3<L>,
    inverse_mass_per_kg: L,
    inverse_inertia: Vec3<L>,
    gyroscopic: Vec3<L>,
    gravity_m_s2: L,
    force_n: Vec3<L>,
    thrust_n: Vec3<L>,
    moment_n_m: Vec3<L>,
    dt: L,
) {
    let acceleration = force_n * inverse_mass_per_kg;
    let kicked = acceleration.mul_add(dt, *velocity_m_s);
    let half_dt_squared = L::splat(0.5) * dt * dt;
    let fall = gravity_m_s2 * half_dt_squared;
    *position_m = kicked.mul_add(dt, *position_m);
    position_m.z -= fall;
    *velocity_m_s = kicked;
    velocity_m_s.z = gravity_m_s2.mul_neg_add(dt, velocity_m_s.z);
    if THRUST {
        let pushed = thrust_n * inverse_mass_per_kg;
        *position_m = pushed.mul_add(half_dt_squared, *position_m);
        *velocity_m_s = pushed.mul_add(dt, *velocity_m_s);
    }

    // Euler's equations by the implicit midpoint rule, as the reference: the rates kicked
    // by the moment, then each pass one multiply and one multiply-add per axis.
    let w0 = *rate_rad_s;
    let half_dt = L::splat(0.5) * dt;
    let inv = inverse_inertia;
    let kick = Vec3::new(
        (inv.x * half_dt).mul_add(moment_n_m.x, w0.x),
        (inv.y * half_dt).mul_add(moment_n_m.y, w0.y),
        (inv.z * half_dt).mul_add(moment_n_m.z, w0.z),
    );
    let spin = gyroscopic * half_dt;
    let mut mid = w0;
    for _ in 0..MIDPOINT_PASSES {
        mid = Vec3::new(
            spin.x.mul_add(mid.y * mid.z, kick.x),
            spin.y.mul_add(mid.z * mid.x, kick.y),
            spin.z.mul_add(mid.x * mid.y, kick.z),
        );
    }
    *rate_rad_s = mid.mul_add(L::splat(2.0), -w0);

    let increment = rotation_increment(mid, dt);
    // |q dq|^2 = |q|^2 |dq|^2: the norms of the factors, found while the product is formed.
    let length_squared = attitude.length_squared() * increment.length_squared();
    *attitude = (*attitude * increment).renormalize(length_squared);
}

/// Fixed-point passes of the implicit midpoint rule for the body rates.
pub const MIDPOINT_PASSES: usize = 3;

/// `exp(w dt / 2)` as a quaternion, by the same Taylor series as the reference.
#[inline(always)]
#[must_use]
pub fn rotation_increment<L: Lane>(w: Vec3<L>, dt: L) -> Quat<L> {
    let half = L::splat(0.5) * dt;
    let theta2 = w.length_squared() * (half * half);
    // 1 - theta2 (c2 - theta2 (c4 - theta2 c6)), from the inside out, each step one fused
    // multiply-add.
    let series = |c2: f64, c4: f64, c6: f64| {
        let inner = theta2.mul_neg_add(L::splat(c6), L::splat(c4));
        let inner = theta2.mul_neg_add(inner, L::splat(c2));
        theta2.mul_neg_add(inner, L::splat(1.0))
    };
    let cos = series(1.0 / 2.0, 1.0 / 24.0, 1.0 / 720.0);
    let sinc = series(1.0 / 6.0, 1.0 / 120.0, 1.0 / 5040.0);
    let v = w * (half * sinc);
    Quat {
        x: v.x,
        y: v.y,
        z: v.z,
        w: cos,
    }
}
