//! The slope one sample lands on: its plane through the origin with the plane's normal and
//! tangent axes, from the sample's slope and downhill azimuth, and where on the terrain tile
//! it lands. The reference, the control loop and the kernels' set-up all take it from here.

use crate::scenario::Sample;
use glam::{DQuat, DVec3};
use kernels::rocks::Rocks;
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
    /// Index of the rock tile the sample lands on (unused without rocks).
    pub rock_tile: usize,
    /// Where the origin falls on the rock tile, along `tangent_u` and `tangent_v`, m.
    pub rock_offset_m: [f64; 2],
}

/// The rocks a sample's footpads may meet: the tiles, the sample's abundance and the
/// footpads' radius (`Rocks::contact`).
#[derive(Debug, Clone, Copy)]
pub struct RockField<'a> {
    /// The rock tiles, built for the sweep's largest abundance.
    pub rocks: &'a Rocks,
    /// The sample's rock abundance `k`.
    pub abundance: f64,
    /// The radius of a footpad, m.
    pub pad_radius_m: f64,
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
            rock_tile: sample.rock_tile as usize,
            rock_offset_m: sample.rock_offset_m,
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

    /// The height above the local ground at which a footpad whose lowest point is at `p`'s
    /// place on the slope (its tangent coordinates) rests on the rocks of `field`, m (0
    /// where it meets none): raised onto the deepest rock it meets at its height, again
    /// until it meets none. A footpad set on a rock's top rests at the rock's height.
    #[must_use]
    pub fn rock_height(&self, field: &RockField<'_>, p: DVec3) -> f64 {
        let (u, v) = (
            self.tangent_u.dot(p) + self.rock_offset_m[0],
            self.tangent_v.dot(p) + self.rock_offset_m[1],
        );
        let r = field.pad_radius_m;
        let mut h = 0.0;
        // Each pass rests the footpad on one rock more (a few at most: rocks are apart).
        for _ in 0..64 {
            let (depth, _, _, n_n) =
                field
                    .rocks
                    .contact(self.rock_tile, u, v, h, r, field.abundance);
            if depth <= 0.0 {
                break;
            }
            // The footpad's centre is `c` from the rock's, `|c| = (h + r) / n_n`; it rests
            // where `|c| = R + r = depth + |c|`, at the same distance across.
            let c = (h + r) / n_n;
            let reach = depth + c;
            let across_squared = (c * c - (h + r) * (h + r)).max(0.0);
            h = (reach * reach - across_squared).sqrt() - r;
        }
        h
    }

    /// `penetration_at` of a footpad at `p` among `rocks` too: the deeper of its contact
    /// with the ground and with a rock (MODEL.md section 4, "Rocks"), that contact's normal,
    /// and whether it is the rock's (whose contact law is the elastic one, also on regolith).
    #[inline]
    #[must_use]
    pub fn contact_at(
        &self,
        terrain: Option<&Terrain>,
        rocks: Option<&RockField<'_>>,
        p: DVec3,
        height: f64,
    ) -> (f64, DVec3, bool) {
        let (penetration, normal) = self.penetration_at(terrain, p, height);
        let Some(field) = rocks else {
            return (penetration, normal, false);
        };
        // The rock stands on the local ground: the footpad's height above it is its
        // clearance there.
        let (rock, n_u, n_v, n_n) = field.rocks.contact(
            self.rock_tile,
            self.tangent_u.dot(p) + self.rock_offset_m[0],
            self.tangent_v.dot(p) + self.rock_offset_m[1],
            -penetration,
            field.pad_radius_m,
            field.abundance,
        );
        if rock > penetration {
            let n = self.tangent_u * n_u + self.tangent_v * n_v + self.normal * n_n;
            (rock, n, true)
        } else {
            (penetration, normal, false)
        }
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
