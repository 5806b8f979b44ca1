//! Structure-of-arrays 3-vectors and quaternions over lanes, with the few operations the
//! physics needs (no trigonometry).

use crate::lane::lane;
use crate::lane::{Lane, Mask};
use std::ops::{Add, AddAssign, Mul, Neg, Sub};

/// A 3-vector per lane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Vec3<L> {
    /// x of every lane.
    pub x: L,
    /// y of every lane.
    pub y: L,
    /// z of every lane.
    pub z: L,
}

impl<L: Lane> Vec3<L> {
    /// The zero vector in every lane.
    pub const ZERO: Vec3<L> = Vec3 {
        x: L::ZERO,
        y: L::ZERO,
        z: L::ZERO,
    };

    /// From components.
    #[inline(always)]
    #[must_use]
    pub fn new(x: L, y: L, z: L) -> Vec3<L> {
        Vec3 { x, y, z }
    }

    /// The same vector in every lane.
    #[inline(always)]
    #[must_use]
    pub fn splat(v: [f64; 3]) -> Vec3<L> {
        Vec3::new(lane(v[0]), lane(v[1]), lane(v[2]))
    }

    /// Dot product per lane.
    #[inline(always)]
    #[must_use]
    pub fn dot(self, o: Vec3<L>) -> L {
        self.x.mul_add(o.x, self.y.mul_add(o.y, self.z * o.z))
    }

    /// Dot product of the projections on the XY plane, per lane.
    #[inline(always)]
    #[must_use]
    pub fn dot_xy(self, o: Vec3<L>) -> L {
        self.x.mul_add(o.x, self.y * o.y)
    }

    /// Cross product per lane.
    #[inline(always)]
    #[must_use]
    pub fn cross(self, o: Vec3<L>) -> Vec3<L> {
        Vec3::new(
            self.y.mul_sub(o.z, self.z * o.y),
            self.z.mul_sub(o.x, self.x * o.z),
            self.x.mul_sub(o.y, self.y * o.x),
        )
    }

    /// `self * s + c` per lane, each component one fused multiply-add.
    #[inline(always)]
    #[must_use]
    pub fn mul_add(self, s: L, c: Vec3<L>) -> Vec3<L> {
        Vec3::new(
            self.x.mul_add(s, c.x),
            self.y.mul_add(s, c.y),
            self.z.mul_add(s, c.z),
        )
    }

    /// `c - self * s` per lane, each component one fused multiply-add.
    #[inline(always)]
    #[must_use]
    pub fn mul_neg_add(self, s: L, c: Vec3<L>) -> Vec3<L> {
        Vec3::new(
            self.x.mul_neg_add(s, c.x),
            self.y.mul_neg_add(s, c.y),
            self.z.mul_neg_add(s, c.z),
        )
    }

    /// Squared length per lane.
    #[inline(always)]
    #[must_use]
    pub fn length_squared(self) -> L {
        self.dot(self)
    }

    /// Length per lane.
    #[inline(always)]
    #[must_use]
    pub fn length(self) -> L {
        self.dot(self).sqrt()
    }

    /// `mask ? a : b` per lane.
    #[inline(always)]
    #[must_use]
    pub fn select(mask: L::Mask, a: Vec3<L>, b: Vec3<L>) -> Vec3<L> {
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
        [self.x.lane(i), self.y.lane(i), self.z.lane(i)]
    }

    /// Sets one lane.
    #[inline]
    pub fn set_lane(&mut self, i: usize, v: [f64; 3]) {
        self.x.set_lane(i, v[0]);
        self.y.set_lane(i, v[1]);
        self.z.set_lane(i, v[2]);
    }
}

impl<L: Lane> Add for Vec3<L> {
    type Output = Vec3<L>;
    #[inline(always)]
    fn add(self, o: Vec3<L>) -> Vec3<L> {
        Vec3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl<L: Lane> AddAssign for Vec3<L> {
    #[inline(always)]
    fn add_assign(&mut self, o: Vec3<L>) {
        *self = *self + o;
    }
}

impl<L: Lane> Sub for Vec3<L> {
    type Output = Vec3<L>;
    #[inline(always)]
    fn sub(self, o: Vec3<L>) -> Vec3<L> {
        Vec3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl<L: Lane> Neg for Vec3<L> {
    type Output = Vec3<L>;
    #[inline(always)]
    fn neg(self) -> Vec3<L> {
        Vec3::new(-self.x, -self.y, -self.z)
    }
}

impl<L: Lane> Mul<L> for Vec3<L> {
    type Output = Vec3<L>;
    #[inline(always)]
    fn mul(self, s: L) -> Vec3<L> {
        Vec3::new(self.x * s, self.y * s, self.z * s)
    }
}

/// A rotation matrix per lane, by columns (the images of the body axes).
#[derive(Debug, Clone, Copy)]
pub struct Mat3<L> {
    /// Image of X_B.
    pub x_axis: Vec3<L>,
    /// Image of Y_B.
    pub y_axis: Vec3<L>,
    /// Image of Z_B.
    pub z_axis: Vec3<L>,
}

impl<L: Lane> Mat3<L> {
    /// `M v`.
    #[inline(always)]
    #[must_use]
    pub fn mul_vec3(&self, v: Vec3<L>) -> Vec3<L> {
        let (a, b, c) = (self.x_axis, self.y_axis, self.z_axis);
        Vec3::new(
            c.x.mul_add(v.z, b.x.mul_add(v.y, a.x * v.x)),
            c.y.mul_add(v.z, b.y.mul_add(v.y, a.y * v.x)),
            c.z.mul_add(v.z, b.z.mul_add(v.y, a.z * v.x)),
        )
    }

    /// Sets one lane from columns.
    #[inline]
    pub fn set_lane(&mut self, i: usize, columns: [[f64; 3]; 3]) {
        self.x_axis.set_lane(i, columns[0]);
        self.y_axis.set_lane(i, columns[1]);
        self.z_axis.set_lane(i, columns[2]);
    }

    /// `M^T v`.
    #[inline(always)]
    #[must_use]
    pub fn transpose_mul_vec3(&self, v: Vec3<L>) -> Vec3<L> {
        Vec3::new(self.x_axis.dot(v), self.y_axis.dot(v), self.z_axis.dot(v))
    }
}

/// The rotation matrix of one quaternion `[x, y, z, w]`, by columns: `Quat::to_mat3` of one
/// lane, operation for operation (the same bits), for code outside the kernels.
#[must_use]
pub fn mat3_of(q: [f64; 4]) -> [[f64; 3]; 3] {
    let [x, y, z, w] = q;
    let (x2, y2, z2) = (x * 2.0, y * 2.0, z * 2.0);
    let (xx, xy, xz) = (x * x2, x * y2, x * z2);
    let (yy, yz, zz) = (y * y2, y * z2, z * z2);
    let (wx, wy, wz) = (w * x2, w * y2, w * z2);
    [
        [1.0 - (yy + zz), xy + wz, xz - wy],
        [xy - wz, 1.0 - (xx + zz), yz + wx],
        [xz + wy, yz - wx, 1.0 - (xx + yy)],
    ]
}

/// A unit quaternion per lane (`w` scalar part).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Quat<L> {
    /// x of every lane.
    pub x: L,
    /// y of every lane.
    pub y: L,
    /// z of every lane.
    pub z: L,
    /// Scalar part of every lane.
    pub w: L,
}

impl<L: Lane> Quat<L> {
    /// `|q|^2`.
    #[inline(always)]
    #[must_use]
    pub fn length_squared(self) -> L {
        self.w.mul_add(
            self.w,
            self.z
                .mul_add(self.z, self.y.mul_add(self.y, self.x * self.x)),
        )
    }

    /// Brought back to unit length by one Newton step, `q (3 - |q|^2) / 2`, given `|q|^2`
    /// (the reference's `renormalize`: see there).
    #[inline(always)]
    #[must_use]
    pub fn renormalize(self, length_squared: L) -> Quat<L> {
        let k = length_squared.mul_neg_add(L::splat(0.5), L::splat(1.5));
        Quat {
            x: self.x * k,
            y: self.y * k,
            z: self.z * k,
            w: self.w * k,
        }
    }

    /// The rotation matrix (as glam's `DMat3::from_quat`).
    #[inline(always)]
    #[must_use]
    pub fn to_mat3(self) -> Mat3<L> {
        let two = L::splat(2.0);
        let one = L::splat(1.0);
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
            self.x.lane(i),
            self.y.lane(i),
            self.z.lane(i),
            self.w.lane(i),
        ]
    }

    /// Sets one lane from `[x, y, z, w]`.
    #[inline]
    pub fn set_lane(&mut self, i: usize, q: [f64; 4]) {
        self.x.set_lane(i, q[0]);
        self.y.set_lane(i, q[1]);
        self.z.set_lane(i, q[2]);
        self.w.set_lane(i, q[3]);
    }
}

impl<L: Lane> Mul for Quat<L> {
    type Output = Quat<L>;
    /// Hamilton product `self * o`.
    #[inline(always)]
    fn mul(self, o: Quat<L>) -> Quat<L> {
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
