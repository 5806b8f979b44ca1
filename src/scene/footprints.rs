//! The footprints a trace leaves on regolith (MODEL.md section 5.1): each time a footpad
//! pressed into the soil and lifted off again, where it was deepest.

use super::read::Scene;
use glam::DVec3;

/// A footprint: where a footpad sank deepest in one contact, left when it lifted off.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Footprint {
    /// The leg whose footpad pressed it.
    pub leg: usize,
    /// When the footpad lifted off (the footprint shows from then on), s.
    pub lifted_s: f64,
    /// The footprint's centre on the ground above the footpad's deepest point, in I.
    pub centre: DVec3,
    /// The footpad's deepest sinkage there, m.
    pub depth_m: f64,
}

impl Scene {
    /// Whether the footpads sink: the sample's surface is regolith.
    #[must_use]
    pub fn on_regolith(&self) -> bool {
        self.model.soil.is_some()
    }

    /// How deep the footpad of `leg` is sunk in the soil at `t`, m: its penetration below
    /// the surface, 0 where it is above it, on a rock (rocks do not give way) or off
    /// regolith.
    #[must_use]
    pub fn sinkage_m(&self, leg: usize, t: f64) -> f64 {
        if !self.on_regolith() {
            return 0.0;
        }
        let tr = &self.trace;
        let depth = tr.value(&format!("leg{leg}_penetration_m"), t);
        if depth.is_nan() || depth <= 0.0 {
            return 0.0;
        }
        let tip = ["x", "y", "z"].map(|a| tr.value(&format!("leg{leg}_tip_{a}_m"), t));
        let tip = DVec3::from_array(tip);
        if self.on_rock(tip) { 0.0 } else { depth }
    }

    /// Whether a footpad whose lowest point is at `tip` meets a rock deeper than the ground.
    fn on_rock(&self, tip: DVec3) -> bool {
        let s = &self.surface;
        tip.is_finite()
            && self.model.rock_field().is_some_and(|field| {
                let terrain = self.model.terrain.as_ref();
                s.contact_at(terrain, Some(&field), tip, s.normal.dot(tip))
                    .2
            })
    }

    /// The footprints of the trace, in order of lift-off: for every leg, every run of rows
    /// in which its footpad is below the surface (`leg{k}_penetration_m > 0`) that ends with
    /// it above again, at the row where it was deepest; a run whose deepest point is on a
    /// rock leaves none (rocks do not give way). None off regolith.
    #[must_use]
    pub fn footprints(&self) -> Vec<Footprint> {
        if !self.on_regolith() {
            return Vec::new();
        }
        let tr = &self.trace;
        let s = &self.surface;
        let mut out = Vec::new();
        for leg in 0..tr.legs {
            let depth = tr.column(&format!("leg{leg}_penetration_m"));
            let columns = ["x", "y", "z"].map(|a| tr.column(&format!("leg{leg}_tip_{a}_m")));
            // NaN where the file lacks a column (a trace written by hand).
            let tip = |i: usize| {
                DVec3::from_array(columns.map(|c| c.get(i).copied().unwrap_or(f64::NAN)))
            };
            // The deepest row of the run under way, if any.
            let mut deepest: Option<usize> = None;
            for (i, &d) in depth.iter().enumerate() {
                if d.is_finite() && d > 0.0 {
                    if deepest.is_none_or(|j| d > depth[j]) {
                        deepest = Some(i);
                    }
                    continue;
                }
                let Some(j) = deepest.take() else {
                    continue;
                };
                let p = tip(j);
                if !p.is_finite() || self.on_rock(p) {
                    continue;
                }
                let ground = s.height(self.model.terrain.as_ref(), p).0;
                out.push(Footprint {
                    leg,
                    lifted_s: tr.time[i],
                    centre: p - s.normal * (s.normal.dot(p) - ground),
                    depth_m: depth[j],
                });
            }
        }
        out.sort_by(|a, b| a.lifted_s.total_cmp(&b.lifted_s));
        out
    }
}
