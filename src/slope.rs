//! The slope one sample lands on: its plane through the origin with the plane's normal and
//! tangent axes, from the sample's slope and downhill azimuth, and where on the terrain tile
//! it lands. The reference, the control loop and the kernels' set-up all take it from here.

use crate::scenario::Sample;
use glam::{DQuat, DVec3};
use kernels::terrain::Terrain;

/// The surface one sample lands on: a plane through the origin with its tangent axes,
/// and the terrain tile and offset it uses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Surface {
    /// Unit normal of the slope plane, `(sin a cos b, sin a sin b, cos a)`.
    pub normal: DVec3,
    /// Unit downhill direction in the plane.
    pub tangent_u: DVec3,
    /// `normal x tangent_u`, horizontal.
    pub tangent_v: DVec3,
    /// Index of the terrain tile the sample lands on (unused on a bare plane).
    pub tile: usize,
    /// Where the origin falls on that tile, along `tangent_u` and `tangent_v`, m.
    pub offset_m: [f64; 2],
}

impl Surface {
    /// The surface of a sample.
    #[must_use]
    pub fn of(sample: &Sample) -> Surface {
        let (sa, ca) = libm::sincos(sample.inputs.slope_deg.to_radians());
        let (sb, cb) = libm::sincos(sample.inputs.downhill_azimuth_deg.to_radians());
        let normal = DVec3::new(sa * cb, sa * sb, ca);
        let tangent_u = DVec3::new(ca * cb, ca * sb, -sa);
        Surface {
            normal,
            tangent_u,
            tangent_v: normal.cross(tangent_u),
            tile: sample.terrain_tile as usize,
            offset_m: sample.terrain_offset_m,
        }
    }

    /// The rotation that takes `Z_I` onto the surface normal by the shortest arc.
    #[must_use]
    pub fn alignment(&self) -> DQuat {
        DQuat::from_rotation_arc(DVec3::Z, self.normal)
    }

    /// Height of the terrain at `p` along the normal, and its slopes along the tangents.
    #[inline]
    #[must_use]
    pub fn height(&self, terrain: Option<&Terrain>, p: DVec3) -> (f64, f64, f64) {
        match terrain {
            None => (0.0, 0.0, 0.0),
            Some(t) => t.height(
                self.tile,
                self.tangent_u.dot(p) + self.offset_m[0],
                self.tangent_v.dot(p) + self.offset_m[1],
            ),
        }
    }

    /// Penetration of `p` below the local surface along the local normal (> 0 in
    /// contact), and that local unit normal.
    #[inline]
    #[must_use]
    pub fn penetration(&self, terrain: Option<&Terrain>, p: DVec3) -> (f64, DVec3) {
        self.penetration_at(terrain, p, self.normal.dot(p))
    }

    /// `penetration` of `p`, given its height above the base plane (`normal . p`, which
    /// the step finds another way: `step::footpad_height`).
    #[inline]
    #[must_use]
    pub fn penetration_at(&self, terrain: Option<&Terrain>, p: DVec3, height: f64) -> (f64, DVec3) {
        let Some(terrain) = terrain else {
            // The plane itself: no height, and its normal is already a unit vector.
            return (-height, self.normal);
        };
        let (h, dh_du, dh_dv) = self.height(Some(terrain), p);
        let m = self.normal - self.tangent_u * dh_du - self.tangent_v * dh_dv;
        let inv = 1.0 / m.length();
        ((h - height) * inv, m * inv)
    }
}
