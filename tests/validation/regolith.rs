//! Regolith (MODEL.md section 5.1): a footpad pressed by a constant force sinks to the depth
//! where the law's pressure times the area equals it; a footpad dropped at speed v stops
//! at the depth its energy allows and gives back what the unloading line stores, the soil
//! keeping the rest; a sunk footpad resists sliding with the passive earth pressure;
//! footprints stay where they were pressed.

use super::{Sim, moving};
use crate::common::Table;
use crate::lander::quiet;
use glam::DVec3;
use touchdown::reference::contact::{LegState, leg_force};
use touchdown::reference::regolith::{self, Soil};
use touchdown::scenario::{Regolith, Scenario};

/// The default regolith (`[surface.regolith]` of an otherwise empty file).
fn default_soil() -> Regolith {
    Scenario::from_toml("[surface]\nkind = \"regolith\"")
        .unwrap()
        .surface
        .regolith
        .unwrap()
}

/// Bekker's soil `(k_c, k_phi, n)` with the default unloading modulus and passive law.
fn bekker(k_c: f64, k_phi: f64, n: f64) -> Regolith {
    Regolith {
        bekker_k_c: k_c,
        bekker_k_phi: k_phi,
        bekker_n: n,
        ..default_soil()
    }
}

/// The default lander on `soil` in gravity `g0`, normal damping `c`, footpads of `area`.
fn on_regolith(soil: Regolith, g0: f64, c: f64, area_m2: f64) -> Scenario {
    let mut s = Scenario::from_toml("[surface]\nkind = \"regolith\"").unwrap();
    s.gravity_m_s2 = g0;
    s.surface.regolith = Some(soil);
    s.surface.damping_n_s_per_m = c;
    s.lander.footpad_area_m2 = area_m2;
    s
}

/// `A (k_c / b + k_phi)` with `b` the radius of a round footpad of area `A`, worked out
/// here apart from the engine's `Soil::of`: the loading force is this times `z^n`.
fn loading_coefficient(soil: &Regolith, area_m2: f64) -> f64 {
    let b = (area_m2 / std::f64::consts::PI).sqrt();
    area_m2 * (soil.bekker_k_c / b + soil.bekker_k_phi)
}

/// The soils of the tests: the default (lunar-like, n = 1), a soft one with n = 0.8 and a
/// stiffening one with n = 1.2 (units N/m^(n+1), N/m^(n+2)).
fn soils() -> Vec<(&'static str, Regolith)> {
    vec![
        ("lunar-like, n 1", default_soil()),
        ("soft, n 0.8", bekker(500.0, 150_000.0, 0.8)),
        ("stiffening, n 1.2", bekker(2000.0, 4.0e6, 1.2)),
    ]
}

/// `soils`, and soils whose `A k_u` lies below the floor of the unloading slope
/// (`max(1, n) F_m / z_m`, MODEL.md section 5.1) at the depths of the drop test: n 0.6 (the
/// chord binds) and n 1.3 (the tangent binds), both with k_u = 3e5 Pa/m, where a line of
/// slope `A k_u` would give back more work than the loading took.
fn soils_and_weak_unloading() -> Vec<(&'static str, Regolith)> {
    let weak = |soil: Regolith| Regolith {
        unloading_modulus_pa_per_m: 3.0e5,
        ..soil
    };
    let mut all = soils();
    all.push(("soft, n 0.6, k_u 3e5", weak(bekker(500.0, 150_000.0, 0.6))));
    all.push((
        "stiffening, n 1.3, k_u 3e5",
        weak(bekker(2000.0, 4.0e6, 1.3)),
    ));
    all
}

#[test]
fn regolith_pressed_by_a_constant_force_sinks_to_the_law_s_depth() {
    // The lander set down flat in gravity g0, so heavily damped (c = 2e4 N s/m per leg,
    // 5-13 times critical on the loading curves here) that its footpads creep down
    // without overshooting: each footpad's soil bears its share F of the weight at rest
    // (m g0 / 4, less what the damping bears: below) and it must rest where the loading
    // curve A (k_c / b + k_phi) z^n equals it, z* = (F / (A K))^(1/n). After 90 s
    // (more than 90 time constants c / F'(z*)) nothing is left of the creep. Tolerance
    // 1e-3 of z*: measured 0.01-0.03 %, the lander's first millimetres of fall, stopped
    // by a damping this strong (4 c dt / m = 0.8 per step), press a few parts in 1e4 past
    // the creep's rest (it then rests on the unloading line just above); any error of the
    // law (a factor of the area, of b, of n) would be percents.
    let mut table = Table::new("regolith: sinkage under a constant force, closed form");
    for (name, soil) in soils() {
        for (g0, area) in [(1.62, 0.03), (0.5, 0.05)] {
            let mut s = on_regolith(soil, g0, 2.0e4, area);
            s.simulation.t_max_s = 90.0;
            let mut sim = Sim::of(&s, quiet());
            sim.advance_to(90.0);
            // At rest the kick-drift integrator (`rigid_body::integrate`) starts every step
            // at the velocity -g0 dt / 2 (the kick of the contact forces gives +g0 dt / 2,
            // the drift under gravity takes g0 dt: the position stays), so the damping bears
            // c g0 dt / 2 of each leg's load and the soil the rest.
            let dt = s.simulation.step_s;
            let load = s.lander.mass_kg * g0 / 4.0 - s.surface.damping_n_s_per_m * g0 * dt / 2.0;
            let z_star = (load / loading_coefficient(&soil, area)).powf(1.0 / soil.bekker_n);
            let case = format!("{name}, g0 {g0}, A {area} m^2");
            for (k, d) in sim.penetrations().iter().enumerate() {
                table.relative(&case, &format!("leg {k} sinkage (m)"), *d, z_star, 1e-3);
            }
            let deepest = sim
                .state
                .legs
                .iter()
                .map(|l| l.sinkage_max_m)
                .fold(0.0, f64::max);
            table.relative(&case, "deepest sinkage (m)", deepest, z_star, 1e-3);
        }
    }
    table.finish();
}

#[test]
fn regolith_drop_stops_within_the_energy_s_depth_and_keeps_the_rest() {
    // The lander dropped flat at v0 in zero gravity with no normal damping (c = 0): each
    // footpad takes m v0^2 / 8 along the loading curve and stops where its work
    // A K z^(n+1) / (n + 1) equals it. Then it springs back along the unloading line from
    // F_m = A K z_s^n, of slope K_u = max(A k_u, max(1, n) F_m / z_s) (MODEL.md 5.1),
    // giving back F_m^2 / (2 K_u) per leg: the lander leaves at v_out = 2 F_m / sqrt(K_u m),
    // and the soil keeps the rest (the legs' soil_absorbed_j), never a negative energy.
    // Tolerance 1 %: the footpads' motion is integrated by semi-implicit Euler, whose
    // energy error is O(omega dt) of the contact's energy at a step (omega dt = 0.03-0.1 on
    // these loading curves and unloading lines), small again at lift-off.
    let mut table = Table::new("regolith: drop, stopping depth and rebound, closed form");
    for (name, soil) in soils_and_weak_unloading() {
        for v0 in [0.3, 0.6] {
            let area = 0.03;
            let mut s = on_regolith(soil, 0.0, 0.0, area);
            s.simulation.t_max_s = 5.0;
            let mut sim = Sim::of(&s, moving([0.0, 0.0, -v0], [0.0; 3]));
            let m = s.lander.mass_kg;
            let e0 = 0.5 * m * v0 * v0;
            let mut deepest = 0.0f64;
            let mut touched = false;
            sim.advance_while(|sim| {
                let d = sim.penetrations().into_iter().fold(f64::MIN, f64::max);
                deepest = deepest.max(d);
                touched |= d > 0.0;
                !(touched && d <= 0.0)
            });
            let a_k = loading_coefficient(&soil, area);
            let n = soil.bekker_n;
            let z_s = ((n + 1.0) * (e0 / 4.0) / a_k).powf(1.0 / (n + 1.0));
            let f_m = a_k * z_s.powf(n);
            let k_u = (area * soil.unloading_modulus_pa_per_m).max(n.max(1.0) * f_m / z_s);
            let v_out = 2.0 * f_m / (k_u * m).sqrt();
            let soil_model = Soil::of(&soil, area, 0.0);
            let kept: f64 = sim
                .state
                .legs
                .iter()
                .map(|l| {
                    l.soil_absorbed_j
                        + regolith::absorbed(&soil_model, l.sinkage_max_m, l.soil_force_max_n)
                })
                .sum();
            let case = format!("{name}, v0 {v0}");
            table.relative(&case, "stopping depth (m)", deepest, z_s, 0.01);
            table.relative(
                &case,
                "rebound speed (m/s)",
                sim.state.body.velocity_m_s.z,
                v_out,
                0.01,
            );
            table.relative(
                &case,
                "energy kept by the soil (J)",
                kept,
                e0 - 0.5 * m * v_out * v_out,
                0.01,
            );
            table.relative(
                &case,
                "energy lost (J) vs kept by the soil",
                e0 - sim.translational_energy(),
                kept,
                0.01,
            );
            table.at_least(&case, "energy kept by the soil (J)", kept, 0.0);
        }
    }
    table.finish();
}

/// A small deterministic generator of uniform numbers on [0, 1) (splitmix64).
struct Uniform(u64);

impl Uniform {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        (z ^ (z >> 31)) as f64 / 2f64.powi(64)
    }
}

#[test]
fn regolith_energy_balance_closes_on_drawn_soils() {
    // The lander dropped flat at v0 = 0.05-0.3 m/s in zero gravity onto drawn soils over
    // the documented range and beyond it: n 0.5-1.3, k_c 0-1e4 N/m^(n+1), k_phi 1e4-1e7
    // N/m^(n+2) and k_u 1e5-1e8 Pa/m (both log-uniform), normal damping c 0-200 N s/m,
    // footpads of 0.01-0.1 m^2. It leaves the soil (or stops in it, by t_max = 20 s)
    // having lost E0 - E (kinetic energy, translational and rotational), which must be
    // what the soil kept, the legs' soil_absorbed_j and `absorbed` of their footprints
    // (plus, for a footpad still in its footprint at t_max, the energy its unloading line
    // still holds, F^2 / (2 K)), and what the damping took: the damping's share of each
    // step's normal force (the normal force less the soil's, the soil's law replayed on
    // the footprint before the step) times the footpad's way into the soil over the step.
    // Every soil keeps a non-negative energy, on every leg (a line steeper than the loading
    // curve's chord gave some soils negative ones). Tolerance 1 % of the energy lost: the
    // work of a force held over a step differs from its integral over the way by O(dt / T)
    // of it, T the contact's duration (a few ms on the stiffest soils here), so the step is
    // 2e-5 s here: measured at most 0.084 % (0.74 % with steps of 1e-4 s, the same soils:
    // the error is the step's).
    let mut table = Table::new("regolith: energy balance over drawn soils");
    let mut u = Uniform(45);
    for i in 0..60 {
        let soil = Regolith {
            bekker_n: 0.5 + 0.8 * u.next(),
            bekker_k_c: 1.0e4 * u.next(),
            bekker_k_phi: 10f64.powf(4.0 + 3.0 * u.next()),
            unloading_modulus_pa_per_m: 10f64.powf(5.0 + 3.0 * u.next()),
            ..default_soil()
        };
        let c = 200.0 * u.next();
        let area = 0.01 + 0.09 * u.next();
        let v0 = 0.05 + 0.25 * u.next();
        let mut s = on_regolith(soil, 0.0, c, area);
        s.simulation.step_s = 2.0e-5;
        s.simulation.t_max_s = 20.0;
        let mut sim = Sim::of(&s, moving([0.0, 0.0, -v0], [0.0; 3]));
        let soil_model = Soil::of(&soil, area, 0.0);
        let e0 = sim.mechanical_energy();
        let mut damping_j = 0.0;
        let mut touched = false;
        loop {
            let before = sim.penetrations();
            let mut footprints: Vec<(f64, f64)> = sim
                .state
                .legs
                .iter()
                .map(|l| (l.sinkage_max_m, l.soil_force_max_n))
                .collect();
            if !sim.advance() {
                break;
            }
            let after = sim.penetrations();
            for (k, (z_m, f_m)) in footprints.iter_mut().enumerate() {
                if before[k] > 0.0 {
                    let soil_n = regolith::soil_force(&soil_model, before[k], z_m, f_m);
                    damping_j += (sim.report.legs[k].normal_n - soil_n) * (after[k] - before[k]);
                }
            }
            touched |= after.iter().any(|d| *d > 0.0);
            if touched && after.iter().all(|d| *d <= 0.0) {
                break;
            }
        }
        let depths = sim.penetrations();
        let mut kept = 0.0;
        let case = format!(
            "{i}: n {:.2}, k_c {:.0}, k_phi {:.3e}, k_u {:.3e}, c {c:.0}, A {area:.3}, v0 {v0:.3}",
            soil.bekker_n, soil.bekker_k_c, soil.bekker_k_phi, soil.unloading_modulus_pa_per_m
        );
        for (l, d) in sim.state.legs.iter().zip(depths) {
            let leg = l.soil_absorbed_j
                + regolith::absorbed(&soil_model, l.sinkage_max_m, l.soil_force_max_n);
            table.at_least(&case, "a leg's soil energy (J)", leg, 0.0);
            kept += leg;
            if d > 0.0 {
                let slope =
                    regolith::unloading_slope(&soil_model, l.sinkage_max_m, l.soil_force_max_n);
                let force = (l.soil_force_max_n - slope * (l.sinkage_max_m - d)).max(0.0);
                kept += force * force / (2.0 * slope);
            }
        }
        let lost = e0 - sim.mechanical_energy();
        table.relative(
            &case,
            "energy lost (J) vs soil's and damping's",
            lost,
            kept + damping_j,
            0.01,
        );
    }
    table.finish();
}

#[test]
fn a_sunk_footpad_resists_sliding_with_the_passive_earth_pressure() {
    // A footpad sunk by d, pulled sideways far beyond its friction spring's reach: the
    // friction force is capped at mu F_N plus Rankine's passive earth pressure on its side,
    // D (gamma d^2 K_p / 2 + 2 c d sqrt(K_p)), D = 2 b the footpad's width, gamma = rho g0,
    // K_p = tan^2(45 deg + phi / 2). Worked out here with tan (the engine uses the sine
    // form); tolerance 1e-12 of the force: one formula, two roundings.
    let mut table = Table::new("regolith: lateral resistance of a sunk footpad");
    let contact = Scenario::default();
    let mu = contact.surface.friction_coefficient;
    for (c, phi, rho, g0, d, area) in [
        (170.0, 35.0, 1500.0, 1.62, 0.02f64, 0.03),
        (0.0, 30.0, 1200.0, 0.5, 0.05, 0.05),
        (1000.0, 40.0, 600.0, 0.0168, 0.01, 0.03),
        (50.0, 20.0, 1800.0, 3.7, 0.08, 0.1),
    ] {
        let soil = Regolith {
            cohesion_pa: c,
            friction_angle_deg: phi,
            bulk_density_kg_m3: rho,
            ..default_soil()
        };
        let model = touchdown::reference::Model::new(&on_regolith(soil, g0, 0.0, area));
        let soil_model = Soil::of(&soil, area, g0);
        let f_n = loading_coefficient(&soil, area) * d.powf(soil.bekker_n);
        let mut leg = LegState {
            anchored: true,
            sinkage_max_m: d,
            soil_force_max_n: f_n,
            ..LegState::default()
        };
        let tip = DVec3::new(1.0, 0.0, -d);
        let f = leg_force(
            &model.contact,
            Some(&soil_model),
            None,
            1e-3,
            d,
            DVec3::Z,
            tip,
            DVec3::ZERO,
            DVec3::Z,
            &mut leg,
        );
        let width = 2.0 * (area / std::f64::consts::PI).sqrt();
        let k_p = (45.0f64 + phi / 2.0).to_radians().tan().powi(2);
        let passive = width * (0.5 * rho * g0 * d * d * k_p + 2.0 * c * d * k_p.sqrt());
        let case = format!("c {c} Pa, phi {phi} deg, rho {rho}, g0 {g0}, d {d} m");
        table.relative(&case, "normal force (N)", f.normal_n, f_n, 1e-12);
        table.relative(
            &case,
            "friction cap (N)",
            f.friction_n,
            mu * f_n + passive,
            1e-12,
        );
        table.equal(&case, "slipping", f.slipping, true);
    }
    table.finish();
}

#[test]
fn footprints_stay_where_they_were_pressed() {
    // A footpad pressed to z1 and lifted, set down again inside its footprint, meets the
    // unloading line (no new plastic sinkage above z1); set down a footpad's radius and more
    // away it meets virgin soil, and the first footprint's energy is booked.
    let mut table = Table::new("regolith: footprints");
    let soil = default_soil();
    let area = 0.03;
    let model = touchdown::reference::Model::new(&on_regolith(soil, 0.0, 0.0, area));
    let s = Soil::of(&soil, area, 0.0);
    let press = |leg: &mut LegState, x: f64, d: f64| {
        leg_force(
            &model.contact,
            Some(&s),
            None,
            1e-3,
            d,
            DVec3::Z,
            DVec3::new(x, 0.0, -d),
            DVec3::ZERO,
            DVec3::Z,
            leg,
        )
        .normal_n
    };
    let mut leg = LegState::default();
    let z1 = 0.01;
    let f1 = press(&mut leg, 0.0, z1);
    table.relative(
        "first press",
        "force (N)",
        f1,
        loading_coefficient(&soil, area) * z1,
        1e-12,
    );
    leg.anchored = false;
    let back = press(&mut leg, 0.5 * s.pad_radius_m, 0.9 * z1);
    let unloading = f1 - area * soil.unloading_modulus_pa_per_m * 0.1 * z1;
    table.relative(
        "same footprint, 0.9 z1",
        "force (N) on the unloading line",
        back,
        unloading.max(0.0) + 1e-300,
        1e-12,
    );
    table.equal(
        "same footprint",
        "deepest sinkage (m)",
        leg.sinkage_max_m,
        z1,
    );
    leg.anchored = false;
    let first_energy = regolith::absorbed(&s, leg.sinkage_max_m, leg.soil_force_max_n);
    let virgin = press(
        &mut leg,
        0.5 * s.pad_radius_m + 1.01 * s.pad_radius_m,
        0.5 * z1,
    );
    table.relative(
        "elsewhere, 0.5 z1",
        "force (N) on virgin soil",
        virgin,
        loading_coefficient(&soil, area) * 0.5 * z1,
        1e-12,
    );
    table.equal(
        "elsewhere",
        "earlier footprints' energy (J)",
        leg.soil_absorbed_j,
        first_energy,
    );
    table.at_least(
        "elsewhere",
        "earlier footprints' energy (J)",
        leg.soil_absorbed_j,
        1e-6,
    );
    table.finish();
}
