//! The rocks drawn under a trace: those of the sample's rock tile present at its abundance
//! (MODEL.md section 4, "Rocks"), placed on the ground patch as hemispheres in I.
//!
//! A rock of the tile at `(u_m, v_m)` lies on the slope wherever `tangent_u . p +
//! rock_offset_m[0] = u_m` and `tangent_v . p + rock_offset_m[1] = v_m` modulo the tile's
//! side: the tile repeats, so a patch wider than a tile holds several images of one rock.

use super::ground::Ground;
use super::read::Scene;
use glam::DVec3;

/// A rock as drawn: a hemisphere whose centre sits on the local ground.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RockShape {
    /// The centre of the hemisphere's base, in I (on the ground, rough terrain included).
    pub centre: DVec3,
    /// Radius (and height) of the hemisphere, m.
    pub radius_m: f64,
}

impl Scene {
    /// The rocks present in the sample (threshold at most its abundance) whose centres lie
    /// within the patch `ground`, each periodic image of a tile's rock once; none without
    /// rocks. Sorted by the tile's order, then along `u` and `v` of the image.
    #[must_use]
    pub fn rocks(&self, ground: &Ground) -> Vec<RockShape> {
        let Some(rocks) = self.model.rocks.as_ref() else {
            return Vec::new();
        };
        let s = &self.surface;
        let size = rocks.tile_size_m();
        let abundance = self.model.rock_abundance;
        let (u0, v0) = (
            ground.origin.dot(s.tangent_u),
            ground.origin.dot(s.tangent_v),
        );
        let u1 = u0 + (ground.nu.saturating_sub(1)) as f64 * ground.spacing_m;
        let v1 = v0 + (ground.nv.saturating_sub(1)) as f64 * ground.spacing_m;
        let [du, dv] = s.rock_offset_m;
        // The images `m` of a coordinate `x` of the tile whose place `x - offset + m size`
        // lies in `[lo, hi]`.
        let images = |x: f64, offset: f64, lo: f64, hi: f64| {
            let first = ((lo + offset - x) / size).ceil() as i64;
            let last = ((hi + offset - x) / size).floor() as i64;
            (first..=last.max(first - 1)).map(move |m| x - offset + m as f64 * size)
        };
        let mut out = Vec::new();
        for rock in rocks.rocks(s.rock_tile.min(rocks.tiles() - 1)) {
            if rock.threshold > abundance {
                continue;
            }
            for u in images(rock.u_m, du, u0, u1) {
                for v in images(rock.v_m, dv, v0, v1) {
                    let p = s.tangent_u * u + s.tangent_v * v;
                    let h = s.height(self.model.terrain.as_ref(), p).0;
                    out.push(RockShape {
                        centre: p + s.normal * h,
                        radius_m: rock.radius_m,
                    });
                }
            }
        }
        out
    }
}
