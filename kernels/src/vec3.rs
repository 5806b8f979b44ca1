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

    /// Dot product of the projections on the XY plane, per lane.
    #[inline(always)]
    #[must_use]
    pub fn dot_xy(self, o: Vec3) -> Lane {
        self.x.mul_add(o.x, self.y * o.y)
    }

    /// Cross product per lane.
    #[inline(always)]
    #[must_use]
    pub fn cross(self, o: Vec3) -> Vec3 {
        Vec3::new(
            self.y.mul_sub(o.z, self.z * o.y),
            self.z.mul_sub(o.x, self.x * o.z),
            self.x.mul_sub(o.y, self.y * o.x),
        )
    }

    /// `self * s + c` per lane, each component one fused multiply-add.
    #[inline(always)]
    #[must_use]
    pub fn mul_add(self, s: Lane, c: Vec3) -> Vec3 {
        Vec3::new(
            self.x.mul_add(s, c.x),
            self.y.mul_add(s, c.y),
            self.z.mul_add(s, c.z),
        )
    }

    /// `c - self * s` per lane, each component one fused multiply-add.
    #[inline(always)]
    #[must_use]
    pub fn mul_neg_add(self, s: Lane, c: Vec3) -> Vec3 {
        Vec3::new(
            self.x.mul_neg_add(s, c.x),
            self.y.mul_neg_add(s, c.y),
            self.z.mul_neg_add(s, c.z),
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
        let (a, b, c) = (self.x_axis, self.y_axis, self.z_axis);
        Vec3::new(
            c.x.mul_add(v.z, b.x.mul_add(v.y, a.x * v.x)),
            c.y.mul_add(v.z, b.y.mul_add(v.y, a.y * v.x)),
            c.z.mul_add(v.z, b.z.mul_add(v.y, a.z * v.x)),
        )
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
    /// Renormalised to unit length.
    #[inline(always)]
    #[must_use]
    pub fn normalize(self) -> Quat {
        let length_squared = self.w.mul_add(
            self.w,
            self.z
                .mul_add(self.z, self.y.mul_add(self.y, self.x * self.x)),
        );
        let inv = splat(1.0) / length_squared.sqrt();
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

impl Mul for Quat {
    type Output = Quat;
    /// Hamilton product `self * o`.
    #[inline(always)]
    fn mul(self, o: Quat) -> Quat {
        // Term after term as written, each product fused with the sum before it.
        let (a, b) = (self, o);
        Quat {
            w: b.z
                .mul_neg_add(a.z, b.y.mul_neg_add(a.y, b.x.mul_neg_add(a.x, a.w * b.w))),
            x: b.y
                .mul_neg_add(a.z, a.y.mul_add(b.z, a.x.mul_add(b.w, a.w * b.x))),
            y: a.z
                .mul_add(b.x, a.y.mul_add(b.w, b.z.mul_neg_add(a.x, a.w * b.y))),
            z: a.z
                .mul_add(b.w, b.x.mul_neg_add(a.y, a.x.mul_add(b.y, a.w * b.z))),
        }
    }
}
