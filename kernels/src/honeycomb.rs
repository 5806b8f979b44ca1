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

/// The friction of a leg's footpad as the damper crushes (the reference's
/// `honeycomb::Friction`): the friction spring's force before its cap, its cap
/// `mu N + passive`.
#[derive(Clone, Copy)]
pub struct Friction<L: Lane> {
    /// Magnitude of the friction spring's force, N.
    pub magnitude_n: L,
    /// Its component along the strut (footpad to hip), N.
    pub along_strut_n: L,
    /// Friction coefficient `mu`.
    pub mu: L,
    /// What the cap holds besides `mu N` (regolith's passive pressure; 0 on the plane), N.
    pub passive_n: L,
}

/// The stroke increment that brings the axial load to the crush force, the friction
/// sticking or slipping after it, and the normal force after it (see the reference's
/// `honeycomb::crush`, which says why). Lanes outside `mask` do not crush.
#[inline(always)]
#[must_use]
pub fn crush<L: Lane>(
    h: &HoneycombParams<L>,
    mask: L::Mask,
    stroke_m: L,
    normal_force_n: L,
    strut_normal: L,
    relief_n_per_m: L,
    friction: &Friction<L>,
) -> (L, L) {
    let zero = L::splat(0.0);
    let tiny = L::splat(L::MIN_POSITIVE);
    let crush_n = crush_force(h, stroke_m);
    let cap = friction.mu.mul_add(normal_force_n, friction.passive_n);
    let capped = cap / friction.magnitude_n.max(cap).max(tiny);
    let load_n = normal_force_n.mul_add(strut_normal, friction.along_strut_n * capped);
    let yields = mask
        & load_n.simd_gt(crush_n)
        & strut_normal.simd_ge(L::splat(MIN_STRUT_NORMAL))
        & normal_force_n.simd_gt(zero);
    let sticking = (crush_n - friction.along_strut_n) / strut_normal;
    let along = friction.along_strut_n / friction.magnitude_n.max(tiny);
    let slip_denominator = friction.mu.mul_add(along, strut_normal);
    let sticks = sticking.simd_ge(zero)
        & friction
            .magnitude_n
            .simd_le(friction.mu.mul_add(sticking, friction.passive_n));
    let target_n = sticks.select(
        sticking,
        slip_denominator.simd_gt(zero).select(
            (friction.passive_n.mul_neg_add(along, crush_n) / slip_denominator).max(zero),
            normal_force_n * crush_n / load_n,
        ),
    );
    let ds = ((normal_force_n - target_n) / (strut_normal * relief_n_per_m))
        .min(piece_end(h, stroke_m) - stroke_m)
        .max(zero);
    let ds = yields.select(ds, zero);
    (ds, normal_force_n - strut_normal * relief_n_per_m * ds)
}
