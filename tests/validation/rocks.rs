//! Rocks (MODEL.md section 4, "Rocks"): a footpad set on a rock's top rests at the rock's
//! height; beside a rock, at the height its sphere meets the hemisphere.

use super::Sim;
use crate::common::Table;
use crate::lander::quiet;
use glam::DVec3;
use kernels::rocks::{Rock, Rocks};
use touchdown::reference::Model;
use touchdown::scenario::Scenario;
use touchdown::slope::{RockField, Surface};

/// One tile of side 8 m holding `rocks` (centres in tile coordinates, radii), all present at
/// any abundance.
fn tile(rocks: &[(f64, f64, f64)]) -> Rocks {
    let rocks = rocks
        .iter()
        .map(|&(u_m, v_m, radius_m)| Rock {
            u_m,
            v_m,
            radius_m,
            threshold: 0.0,
        })
        .collect();
    Rocks::new(8.0, 16, vec![rocks])
}

#[test]
fn a_footpad_set_on_a_rock_rests_at_the_rock_s_height() {
    // The default lander, flat, set down with a rock of radius R under each footpad (the
    // rocks' centres under the footpads' lowest points): each footpad must come to rest on
    // its rock's top, at the height R less the elastic contact's give under its share of
    // the weight, (m g0 / 4 - c g0 dt / 2) / k (the kick-drift integrator's rest starts each
    // step at -g0 dt / 2, so the damping bears c g0 dt / 2 of the load: see the regolith
    // test). Tolerance 1e-3 of the give (8e-6 to 8e-4 m here; measured 1e-4 of it), far
    // below the footpad's radius (0.1 m) and the rocks' radii: a footpad resting on the
    // rock's side, on its centre's height or on the ground would be off by centimetres.
    let mut table = Table::new("rocks: footpads on rock tops");
    for (radius, g0) in [(0.05, 0.0168), (0.2, 0.0168), (0.3, 1.62)] {
        let mut s = Scenario {
            gravity_m_s2: g0,
            ..Scenario::default()
        };
        s.simulation.t_max_s = 30.0;
        let mut model = Model::new(&s);
        // Flat: the footpads' lowest points over the origin's tile coordinates (u = x,
        // v = y on a level surface; the sample's rock offset is 0).
        let centres: Vec<(f64, f64, f64)> = model
            .legs
            .iter()
            .map(|l| (l.tip_m.x.rem_euclid(8.0), l.tip_m.y.rem_euclid(8.0), radius))
            .collect();
        model.rocks = Some(tile(&centres));
        model.rock_abundance = 0.1;
        let mut sim = Sim::new(model, quiet());
        sim.advance_to(30.0);
        let (k, c, m) = (
            s.surface.stiffness_n_per_m,
            s.surface.damping_n_s_per_m,
            s.lander.mass_kg,
        );
        let give = (m * g0 / 4.0 - c * g0 * s.simulation.step_s / 2.0) / k;
        let case = format!("R {radius} m, g0 {g0}");
        let rotation = sim.rotation();
        for (i, leg) in sim.model.legs.iter().enumerate() {
            let tip = sim.state.body.position_m + rotation * leg.tip_m;
            let height = format!("leg {i} height (m)");
            table.close(&case, &height, tip.z, radius - give, 1e-3 * give);
        }
    }
    table.finish();
}

#[test]
fn the_rest_height_beside_a_rock_is_where_the_spheres_meet() {
    // A footpad (a sphere of radius r whose lowest point is the footpad) a distance rho
    // across from a rock of radius R rests at h = sqrt((R + r)^2 - rho^2) - r where the
    // spheres meet (rho < R + r), on the ground beyond; on top (rho = 0) at R. Tolerance
    // 1e-12 m: a closed form against a few passes of another.
    let mut table = Table::new("rocks: rest height of a footpad beside a rock");
    let surface = Surface::of(&crate::lander::sample_of(quiet()));
    for (radius, r) in [(0.1, 0.0977), (0.5, 0.05), (0.8, 0.2)] {
        let rocks = tile(&[(4.0, 4.0, radius)]);
        let field = RockField {
            rocks: &rocks,
            abundance: 0.1,
            pad_radius_m: r,
        };
        for rho in [0.0, 0.3 * radius, 0.9 * (radius + r), 1.1 * (radius + r)] {
            let h = surface.rock_height(&field, DVec3::new(4.0 + rho, 4.0, 0.0));
            let expected = if rho < radius + r {
                ((radius + r).powi(2) - rho * rho).sqrt() - r
            } else {
                0.0
            };
            let case = format!("R {radius}, r {r}, rho {rho:.3}");
            table.close(&case, "rest height (m)", h, expected.max(0.0), 1e-12);
        }
    }
    table.finish();
}

#[test]
fn the_flight_step_over_rocks_is_bounded_by_the_rocks_near_the_footpads() {
    // The default lander, level and at rest, its footpads h = 1 cm above the plane in
    // milligravity (g0 = 0.0168): the flight rule's fastest approach is g0 flight_step_max_s
    // (no speed, no rate), so a footpad clear of everything by c may take half of c over
    // it (MODEL.md section 2.1: rock_clearance). A rock of 1 m, 4 m from every footpad, is
    // no bound (the step is the longest flight step, 50 ms: before, the highest rock of the
    // tile held it to the fixed 1 ms); a rock of 0.2 m beside footpad 0 at a gap g between
    // the spheres bounds it at g / (2 g0 flight_step_max_s), fixed step or error control.
    // Tolerance 1e-9 of the step: the gap is rebuilt from the distance (rounding of 1e-16 m
    // in 1e-5 m).
    let mut table = Table::new("rocks: the flight step near rocks");
    for tolerance in [None, Some(1e-4)] {
        let mut s = Scenario {
            gravity_m_s2: 0.0168,
            ..Scenario::default()
        };
        s.simulation.tolerance_m_s = tolerance;
        let base = Model::new(&s);
        let (h, radius, pad) = (0.01, 0.2, base.pad_radius_m());
        let speed = s.gravity_m_s2 * s.simulation.flight_step_max_s;
        let tip0 = base.legs[0].tip_m;
        let (u0, v0) = (tip0.x.rem_euclid(8.0), tip0.y.rem_euclid(8.0));
        let mode = if tolerance.is_some() {
            "controlled"
        } else {
            "fixed"
        };
        let mut cases = vec![(
            "far 1 m rock".to_string(),
            (4.0, 4.0, 1.0),
            s.simulation.flight_step_max_s,
        )];
        for gap in [1e-5, 2e-5, 3e-5] {
            let d = ((gap + radius + pad).powi(2) - (h + pad).powi(2)).sqrt();
            let expected = 0.5 * gap / speed;
            cases.push((format!("gap {gap:e} m"), (u0 + d, v0, radius), expected));
        }
        for (name, rock, expected) in cases {
            let mut model = base.clone();
            model.rocks = Some(tile(&[rock]));
            model.rock_abundance = 0.1;
            let mut sim = Sim::new(model, quiet());
            let body = &mut sim.state.body;
            body.attitude = glam::DQuat::IDENTITY;
            body.velocity_m_s = DVec3::ZERO;
            body.rate_rad_s = DVec3::ZERO;
            body.position_m = DVec3::new(0.0, 0.0, h - tip0.z);
            let dt = touchdown::reference::step::step_size(&sim.model, &sim.surface, &sim.state);
            table.close(
                &format!("{mode}, {name}"),
                "step (s)",
                dt,
                expected,
                1e-9 * expected,
            );
        }
    }
    table.finish();
}
