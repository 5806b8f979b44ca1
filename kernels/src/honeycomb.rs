//! Crushable honeycomb dampers, over lanes: the same law as the reference's `honeycomb`
//! (rigid-plastic in series with the contact, implicit stroke increment).

use crate::lane::{Lane, Mask};
use crate::params::HoneycombParams;

/// Strut directions closer than this to the surface plane cannot relieve the load.
pub const MIN_STRUT_NORMAL: f64 = 0.05;

/// The crush force at stroke `s`: over the initial peak falling linearly from the peak to
/// the first plateau, then the stage plateaus; infinite beyond the usable stroke.
#[inline(always)]
#[must_use]
pub fn crush_force<L: Lane>(h: &HoneycombParams<L>, stroke_m: L) -> L {
    let mut force = L::splat(f64::INFINITY);
    for (end, f) in h.stages.iter().rev() {
        force = stroke_m.simd_lt(*end).select(*f, force);
    }
    let plateau = h.stages[0].1;
    let peak = plateau + (h.peak_force_n - plateau) * (L::splat(1.0) - stroke_m / h.peak_stroke_m);
    stroke_m.simd_lt(h.peak_stroke_m).select(peak, force)
}

/// The energy absorbed from stroke `s0` to `s1`: the integral of the crush force, J.
#[inline(always)]
#[must_use]
pub fn absorbed_between<L: Lane>(h: &HoneycombParams<L>, s0: L, s1: L) -> L {
    let zero = L::splat(0.0);
    let lo = s0.min(h.peak_stroke_m);
    let hi = s1.min(h.peak_stroke_m);
    let on_peak = hi.simd_gt(lo);
    let mut energy = on_peak.select((hi - lo) * crush_force(h, L::splat(0.5) * (lo + hi)), zero);
    let mut start = h.peak_stroke_m;
    for (end, force) in &h.stages {
        let lo = s0.max(start);
        let hi = s1.min(*end);
        energy += (hi - lo).max(zero) * *force;
        start = start.max(*end);
    }
    energy
}

/// The end of the piece of the force curve that holds stroke `s` (see the reference).
#[inline(always)]
#[must_use]
pub fn piece_end<L: Lane>(h: &HoneycombParams<L>, stroke_m: L) -> L {
    let mut end = h.usable_stroke_m;
    for (stage_end, _) in h.stages.iter().rev() {
        end = stroke_m.simd_lt(*stage_end).select(*stage_end, end);
    }
    stroke_m
        .simd_lt(h.peak_stroke_m)
        .select(h.peak_stroke_m, end)
}

/// The stroke increment that caps the axial load at the crush force, and the normal force
/// after it (see the reference's `honeycomb::crush`). Lanes outside `mask` do not crush.
#[inline(always)]
#[must_use]
pub fn crush<L: Lane>(
    h: &HoneycombParams<L>,
    mask: L::Mask,
    stroke_m: L,
    load_n: L,
    normal_force_n: L,
    strut_normal: L,
    relief_n_per_m: L,
) -> (L, L) {
    let zero = L::splat(0.0);
    let crush_n = crush_force(h, stroke_m);
    let yields = mask
        & load_n.simd_gt(crush_n)
        & strut_normal.simd_ge(L::splat(MIN_STRUT_NORMAL))
        & normal_force_n.simd_gt(zero);
    let target_n = normal_force_n * crush_n / load_n;
    let ds = ((normal_force_n - target_n) / (strut_normal * relief_n_per_m))
        .min(piece_end(h, stroke_m) - stroke_m)
        .max(zero);
    let ds = yields.select(ds, zero);
    (ds, normal_force_n - strut_normal * relief_n_per_m * ds)
}
