//! Structure-of-arrays 3-vectors and quaternions over lanes, with the few operations the
//! physics needs (no trigonometry).

use crate::lane::{Lane, splat};
use std::ops::{Add, AddAssign, Mul, Neg, Sub};

/// A 3-vector per lane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Vec3 {
    /// x of every lane.
    pub x: Lane,
    /// y of every lane.
    pub y: Lane,
    /// z of every lane.
    pub z: Lane,
}

impl Vec3 {
    /// The zero vector in every lane.
    pub const ZERO: Vec3 = Vec3 {
        x: Lane::ZERO,
        y: Lane::ZERO,
        z: Lane::ZERO,
    };

    /// From components.
    #[inline(always)]
    #[must_use]
    pub fn new(x: Lane, y: Lane, z: Lane) -> Vec3 {
        Vec3 { x, y, z }
    }

    /// The same vector in every lane.
    #[inline(always)]
    #[must_use]
    pub fn splat(v: [f64; 3]) -> Vec3 {
        Vec3::new(splat(v[0]), splat(v[1]), splat(v[2]))
    }

    /// Dot product per lane.
    #[inline(always)]
    #[must_use]
    pub fn dot(self, o: Vec3) -> Lane {
        self.x.mul_add(o.x, self.y.mul_add(o.y, self.z * o.z))
    }

    /// Cross product per lane.
    #[inline(always)]
    #[must_use]
    pub fn cross(self, o: Vec3) -> Vec3 {
        Vec3::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }

    /// Squared length per lane.
    #[inline(always)]
    #[must_use]
    pub fn length_squared(self) -> Lane {
        self.dot(self)
    }

    /// Length per lane.
    #[inline(always)]
    #[must_use]
    pub fn length(self) -> Lane {
        self.dot(self).sqrt()
    }

    /// `mask ? a : b` per lane.
    #[inline(always)]
    #[must_use]
    pub fn select(mask: Lane, a: Vec3, b: Vec3) -> Vec3 {
        Vec3::new(
            mask.select(a.x, b.x),
            mask.select(a.y, b.y),
            mask.select(a.z, b.z),
        )
    }

    /// One lane as an array.
    #[inline]
    #[must_use]
    pub fn lane(&self, i: usize) -> [f64; 3] {
        [
            self.x.as_array()[i],
            self.y.as_array()[i],
            self.z.as_array()[i],
        ]
    }

    /// Sets one lane.
    #[inline]
    pub fn set_lane(&mut self, i: usize, v: [f64; 3]) {
        self.x.as_mut_array()[i] = v[0];
        self.y.as_mut_array()[i] = v[1];
        self.z.as_mut_array()[i] = v[2];
    }
}

impl Add for Vec3 {
    type Output = Vec3;
    #[inline(always)]
    fn add(self, o: Vec3) -> Vec3 {
        Vec3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl AddAssign for Vec3 {
    #[inline(always)]
    fn add_assign(&mut self, o: Vec3) {
        *self = *self + o;
    }
}

impl Sub for Vec3 {
    type Output = Vec3;
    #[inline(always)]
    fn sub(self, o: Vec3) -> Vec3 {
        Vec3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl Neg for Vec3 {
    type Output = Vec3;
    #[inline(always)]
    fn neg(self) -> Vec3 {
        Vec3::new(-self.x, -self.y, -self.z)
    }
}

impl Mul<Lane> for Vec3 {
    type Output = Vec3;
    #[inline(always)]
    fn mul(self, s: Lane) -> Vec3 {
        Vec3::new(self.x * s, self.y * s, self.z * s)
    }
}

/// A rotation matrix per lane, by columns (the images of the body axes).
#[derive(Debug, Clone, Copy)]
pub struct Mat3 {
    /// Image of X_B.
    pub x_axis: Vec3,
    /// Image of Y_B.
    pub y_axis: Vec3,
    /// Image of Z_B.
    pub z_axis: Vec3,
}

impl Mat3 {
    /// `M v`.
    #[inline(always)]
    #[must_use]
    pub fn mul_vec3(&self, v: Vec3) -> Vec3 {
        self.x_axis * v.x + self.y_axis * v.y + self.z_axis * v.z
    }

    /// `M^T v`.
    #[inline(always)]
    #[must_use]
    pub fn transpose_mul_vec3(&self, v: Vec3) -> Vec3 {
        Vec3::new(self.x_axis.dot(v), self.y_axis.dot(v), self.z_axis.dot(v))
    }
}

/// A unit quaternion per lane (`w` scalar part).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Quat {
    /// x of every lane.
    pub x: Lane,
    /// y of every lane.
    pub y: Lane,
    /// z of every lane.
    pub z: Lane,
    /// Scalar part of every lane.
    pub w: Lane,
}

impl Quat {
    /// Hamilton product `self * o`.
    #[inline(always)]
    #[must_use]
    pub fn mul(self, o: Quat) -> Quat {
        Quat {
            w: self.w * o.w - self.x * o.x - self.y * o.y - self.z * o.z,
            x: self.w * o.x + self.x * o.w + self.y * o.z - self.z * o.y,
            y: self.w * o.y - self.x * o.z + self.y * o.w + self.z * o.x,
            z: self.w * o.z + self.x * o.y - self.y * o.x + self.z * o.w,
        }
    }

    /// Renormalised to unit length.
    #[inline(always)]
    #[must_use]
    pub fn normalize(self) -> Quat {
        let inv = splat(1.0)
            / (self.x * self.x + self.y * self.y + self.z * self.z + self.w * self.w).sqrt();
        Quat {
            x: self.x * inv,
            y: self.y * inv,
            z: self.z * inv,
            w: self.w * inv,
        }
    }

    /// The rotation matrix (as glam's `DMat3::from_quat`).
    #[inline(always)]
    #[must_use]
    pub fn to_mat3(self) -> Mat3 {
        let two = splat(2.0);
        let one = splat(1.0);
        let (x2, y2, z2) = (self.x * two, self.y * two, self.z * two);
        let (xx, xy, xz) = (self.x * x2, self.x * y2, self.x * z2);
        let (yy, yz, zz) = (self.y * y2, self.y * z2, self.z * z2);
        let (wx, wy, wz) = (self.w * x2, self.w * y2, self.w * z2);
        Mat3 {
            x_axis: Vec3::new(one - (yy + zz), xy + wz, xz - wy),
            y_axis: Vec3::new(xy - wz, one - (xx + zz), yz + wx),
            z_axis: Vec3::new(xz + wy, yz - wx, one - (xx + yy)),
        }
    }

    /// One lane as `[x, y, z, w]`.
    #[inline]
    #[must_use]
    pub fn lane(&self, i: usize) -> [f64; 4] {
        [
            self.x.as_array()[i],
            self.y.as_array()[i],
            self.z.as_array()[i],
            self.w.as_array()[i],
        ]
    }

    /// Sets one lane from `[x, y, z, w]`.
    #[inline]
    pub fn set_lane(&mut self, i: usize, q: [f64; 4]) {
        self.x.as_mut_array()[i] = q[0];
        self.y.as_mut_array()[i] = q[1];
        self.z.as_mut_array()[i] = q[2];
        self.w.as_mut_array()[i] = q[3];
    }
}
