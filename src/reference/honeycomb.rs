//! Crushable honeycomb dampers (MODEL.md section 6): a rigid-plastic element in series
//! with the contact spring-damper of each leg.
//!
//! Below the crush force the cartridge is rigid. When the axial load exceeds it, the stroke
//! grows by the amount `ds` that brings the load back to the crush force. A stroke `ds`
//! lifts the footpad by `a ds` along the local normal (`a` = normal . strut direction), so
//! the spring relaxes by `k a ds` and, the footpad moving at `a ds / dt`, the damper by
//! `c a ds / dt`: solving for `ds` is implicit in both, stable at any damping.

use super::model::Honeycomb;

/// Strut directions closer than this to the surface plane (|a| below it) cannot relieve the
/// load by crushing; the cartridge then holds.
pub const MIN_STRUT_NORMAL: f64 = 0.05;

/// The crush force at stroke `s`, N: over the initial peak it falls linearly from the peak
/// to the first plateau (a cartridge that is not pre-crushed), then the stage plateaus;
/// beyond the usable stroke the cartridge is rigid (infinite force).
#[inline]
#[must_use]
pub fn crush_force(h: &Honeycomb, stroke_m: f64) -> f64 {
    if stroke_m < h.peak_stroke_m {
        let plateau = h.stages[0].1;
        return plateau + (h.peak_force_n - plateau) * (1.0 - stroke_m / h.peak_stroke_m);
    }
    h.stages
        .iter()
        .find(|(end, _)| stroke_m < *end)
        .map_or(f64::INFINITY, |(_, f)| *f)
}

/// The energy absorbed by crushing from stroke `s0` to `s1` (`s0 <= s1 <= usable`): the
/// integral of the crush force, J (exact: the force is linear over the peak, constant over
/// each stage).
#[must_use]
pub fn absorbed_between(h: &Honeycomb, s0: f64, s1: f64) -> f64 {
    let mut energy = 0.0;
    let lo = s0.min(h.peak_stroke_m);
    let hi = s1.min(h.peak_stroke_m);
    if hi > lo {
        energy += (hi - lo) * crush_force(h, 0.5 * (lo + hi));
    }
    let mut start = h.peak_stroke_m;
    for (end, force) in &h.stages {
        let lo = s0.max(start);
        let hi = s1.min(*end);
        if hi > lo {
            energy += force * (hi - lo);
        }
        start = start.max(*end);
    }
    energy
}

/// The end of the piece of the force curve that holds stroke `s`: the initial peak, a
/// stage, or the usable stroke. A step's crushing stops there, so that a stronger stage
/// holds from the step after.
#[inline]
#[must_use]
pub fn piece_end(h: &Honeycomb, stroke_m: f64) -> f64 {
    if stroke_m < h.peak_stroke_m {
        return h.peak_stroke_m;
    }
    h.stages
        .iter()
        .find(|(end, _)| stroke_m < *end)
        .map_or(h.usable_stroke_m(), |(end, _)| *end)
}

/// The friction of a leg's footpad as the damper crushes: the friction spring's force
/// (before its cap), its cap `mu N + passive` at normal force `N`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Friction {
    /// Magnitude of the friction spring's force, N.
    pub magnitude_n: f64,
    /// Its component along the strut (footpad to hip), N.
    pub along_strut_n: f64,
    /// Friction coefficient `mu`.
    pub mu: f64,
    /// What the cap holds besides `mu N` (regolith's passive pressure; 0 on the plane), N.
    pub passive_n: f64,
}

/// The stroke increment that caps the axial load at the crush force.
///
/// `normal_force_n` is the trial normal force `N`, `strut_normal` the cosine `a` between the
/// local normal and the strut direction (footpad to hip), `relief_n_per_m` the relief
/// `k + c/dt` of the contact per metre of footpad lift, `friction` the footpad's friction.
/// The axial load is `N a` plus the friction's share along the strut, the friction capped
/// at `mu N + passive`. Crushing lowers `N` to the value `N'` that brings the load to the
/// crush force: where the friction spring's force is within the cap at `N'` (a sticking
/// footpad) it stays as it is, `N' = (F_c - f_s) / a` (`f_s` its share along the strut);
/// otherwise it slips at the cap, `N' = (F_c - passive d) / (a + mu d)`, `d` the share
/// along the strut of its direction. (Scaling `N` by `F_c / load`, as before, is exact only
/// for a footpad that slips on the plane: where friction stuck, the load stayed above the
/// crush force by `f_s (1 - F_c / load)`, the more the longer the step.) Where the slip's
/// denominator is not positive (a strut far from the normal, friction against it: the load
/// does not fall with `N`), `N` scales by `F_c / load`; where the passive share alone holds
/// the strut above the crush force, `N'` is 0 (no normal force can bring the load lower:
/// the footpad then holds with its passive share). The increment stops at the end of
/// the piece of the force curve it starts in, so a stronger stage holds from the next
/// step. Returns the increment and the normal force after it.
#[inline]
#[must_use]
pub fn crush(
    h: &Honeycomb,
    stroke_m: f64,
    normal_force_n: f64,
    strut_normal: f64,
    relief_n_per_m: f64,
    friction: &Friction,
) -> (f64, f64) {
    let crush_n = crush_force(h, stroke_m);
    let cap = friction.mu * normal_force_n + friction.passive_n;
    let capped = cap / friction.magnitude_n.max(cap).max(f64::MIN_POSITIVE);
    let load_n = normal_force_n * strut_normal + friction.along_strut_n * capped;
    if load_n <= crush_n || strut_normal < MIN_STRUT_NORMAL || normal_force_n <= 0.0 {
        return (0.0, normal_force_n);
    }
    let sticking = (crush_n - friction.along_strut_n) / strut_normal;
    let along = friction.along_strut_n / friction.magnitude_n.max(f64::MIN_POSITIVE);
    let slip_denominator = friction.mu.mul_add(along, strut_normal);
    let target_n =
        if sticking >= 0.0 && friction.magnitude_n <= friction.mu * sticking + friction.passive_n {
            sticking
        } else if slip_denominator > 0.0 {
            ((crush_n - friction.passive_n * along) / slip_denominator).max(0.0)
        } else {
            normal_force_n * crush_n / load_n
        };
    let ds = ((normal_force_n - target_n) / (strut_normal * relief_n_per_m))
        .min(piece_end(h, stroke_m) - stroke_m)
        .max(0.0);
    (ds, normal_force_n - strut_normal * relief_n_per_m * ds)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_stage(peak: bool) -> Honeycomb {
        Honeycomb {
            area_m2: 1.0,
            initial_peak_factor: None,
            stages: vec![(0.02, 100.0), (0.05, 300.0)],
            peak_force_n: if peak { 175.0 } else { 100.0 },
            peak_stroke_m: if peak { 0.002 } else { 0.0 },
        }
    }

    #[test]
    fn force_follows_the_stages() {
        let h = two_stage(true);
        assert_eq!(crush_force(&h, 0.0), 175.0);
        assert!((crush_force(&h, 0.001) - 137.5).abs() < 1e-12);
        assert_eq!(crush_force(&h, 0.01), 100.0);
        assert_eq!(crush_force(&h, 0.03), 300.0);
        assert_eq!(crush_force(&h, 0.05), f64::INFINITY);
        assert_eq!(crush_force(&two_stage(false), 0.001), 100.0);
    }

    #[test]
    fn absorbed_energy_integrates_the_force() {
        let h = two_stage(true);
        // 2 mm falling from 175 N to 100 N, 18 mm at 100 N, 30 mm at 300 N.
        let whole = 0.002 * 137.5 + 0.018 * 100.0 + 0.03 * 300.0;
        assert!((absorbed_between(&h, 0.0, 0.05) - whole).abs() < 1e-12);
        let parts = absorbed_between(&h, 0.0, 0.0011) + absorbed_between(&h, 0.0011, 0.05);
        assert!((parts - whole).abs() < 1e-12);
        assert!(
            (absorbed_between(&h, 0.019, 0.021) - (0.001 * 100.0 + 0.001 * 300.0)).abs() < 1e-12
        );
    }

    #[test]
    fn pieces_end_at_the_peak_and_the_stages() {
        let h = two_stage(true);
        assert_eq!(piece_end(&h, 0.0), 0.002);
        assert_eq!(piece_end(&h, 0.002), 0.02);
        assert_eq!(piece_end(&h, 0.03), 0.05);
        assert_eq!(piece_end(&h, 0.05), 0.05);
    }

    /// No friction.
    const NONE: Friction = Friction {
        magnitude_n: 0.0,
        along_strut_n: 0.0,
        mu: 0.6,
        passive_n: 0.0,
    };

    #[test]
    fn crush_caps_the_load_and_stops_at_the_piece_end() {
        let h = two_stage(false);
        // Load 400 N against 100 N: the normal force falls to a quarter.
        let (ds, f) = crush(&h, 0.01, 400.0, 1.0, 5.0e4, &NONE);
        assert!((f - 100.0).abs() < 1e-9);
        assert!((ds - 300.0 / 5.0e4).abs() < 1e-12);
        // Near the end of the first stage the increment stops at the stage end.
        let (ds, f) = crush(&h, 0.0199, 400.0, 1.0, 5.0e4, &NONE);
        assert!((ds - 0.0001).abs() < 1e-12 && f > 100.0);
        let (ds, f) = crush(&h, 0.049, 4.0e4, 1.0, 5.0e4, &NONE);
        assert!((ds - 0.001).abs() < 1e-12 && f > 300.0);
        assert_eq!(crush(&h, 0.01, 90.0, 1.0, 5.0e4, &NONE), (0.0, 90.0));
    }

    /// The axial load after a crush, `N' a` plus the friction then (capped at `mu N'` on
    /// the plane), for a strut at cosine `a` to the normal.
    fn load_after(n: f64, a: f64, friction: &Friction) -> f64 {
        let cap = friction.mu * n + friction.passive_n;
        let scale = (cap / friction.magnitude_n).min(1.0);
        n * a + friction.along_strut_n * scale
    }

    /// With friction, the crush brings the axial load to the crush force exactly, whether
    /// the footpad keeps sticking (the friction stays), slips at the cap (the friction
    /// falls with `N`), or sticks before and slips after, at several strut angles, friction
    /// shares and a passive pressure: each case's load after the crush against the crush
    /// force (100 N) to 1e-9 N, a few roundings of the hundreds of newtons summed.
    #[test]
    fn crush_brings_the_load_to_the_crush_force_with_friction() {
        let h = two_stage(false);
        for a in [1.0, 0.9, 0.6] {
            // (friction magnitude, its share along the strut, passive, normal force)
            for (magnitude, along, passive, normal) in [
                (50.0, 30.0, 0.0, 400.0),   // sticks before and after
                (50.0, -30.0, 0.0, 400.0),  // sticks, pulling against the strut
                (300.0, 200.0, 0.0, 400.0), // slips before and after
                (200.0, 120.0, 0.0, 400.0), // sticks before (cap 240), slips after
                (80.0, 40.0, 30.0, 300.0),  // on regolith: the cap holds a passive share
            ] {
                let friction = Friction {
                    magnitude_n: magnitude,
                    along_strut_n: along,
                    mu: 0.6,
                    passive_n: passive,
                };
                let (ds, n) = crush(&h, 0.01, normal, a, 5.0e4, &friction);
                assert!(ds > 0.0, "a {a}, friction {magnitude}: no crush");
                let load = load_after(n, a, &friction);
                assert!(
                    (load - 100.0).abs() < 1e-9,
                    "a {a}, friction {magnitude} along {along}: load {load} after the crush"
                );
            }
        }
        // A passive share whose part along the strut alone passes the crush force (200 N of
        // passive pressure, friction along the strut): the normal force falls to 0, never
        // below.
        let passive = Friction {
            magnitude_n: 400.0,
            along_strut_n: 300.0,
            mu: 0.6,
            passive_n: 200.0,
        };
        let (ds, n) = crush(&h, 0.01, 400.0, 1.0, 5.0e4, &passive);
        assert!(
            ds > 0.0 && n.abs() < 1e-9,
            "normal force {n} after the crush"
        );
        // Scaling N by F_c / load, as before, left a sticking footpad's load above it: 400 N
        // normal and 30 N of sticking friction along a strut along the normal gave 430 N;
        // scaled, N = 93.0 N and the load 123.0 N.
        let scaled = 400.0 * 100.0 / 430.0;
        assert!(
            load_after(
                scaled,
                1.0,
                &Friction {
                    magnitude_n: 50.0,
                    along_strut_n: 30.0,
                    mu: 0.6,
                    passive_n: 0.0
                }
            ) > 120.0
        );
    }
}
