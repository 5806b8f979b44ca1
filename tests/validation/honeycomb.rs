//! Honeycomb dampers: energy (MODEL.md sections 6 and 12): the energy balance, the stroke
//! in closed form, bottoming out at the usable stroke.

use super::{Sim, moving};
use crate::common::Table;
use touchdown::scenario::{PSI_PA, Scenario, Stage};

/// The default lander on a completely elastic, frictionless-damping surface, with
/// cartridges of `stages` (stroke m, crush strength psi), in gravity `g0`.
fn crushing(stages: &[(f64, f64)], pre_crushed: bool, g0: f64) -> Scenario {
    let mut s = Scenario {
        gravity_m_s2: g0,
        ..Scenario::default()
    };
    s.surface.damping_n_s_per_m = 0.0;
    s.surface.friction_damping_n_s_per_m = 0.0;
    s.damper.enabled = true;
    s.damper.pre_crushed = pre_crushed;
    s.damper.stages = stages
        .iter()
        .map(|&(stroke_m, crush_strength_psi)| Stage {
            stroke_m,
            crush_strength_psi,
        })
        .collect();
    s
}

/// Crush force of `psi` on the default cartridge section, N.
fn crush_force_n(psi: f64) -> f64 {
    psi * PSI_PA * Scenario::default().damper.area_cm2 * 1e-4
}

/// What a drop did: energy balance at its last lift-off and the dampers' strokes.
struct Crush {
    /// Mechanical energy lost (kinetic + potential) from start to the last lift-off, J.
    lost_j: f64,
    absorbed_j: f64,
    /// Largest stroke of any leg at any step, m.
    max_stroke_m: f64,
    /// Final stroke of every leg, m.
    strokes_m: Vec<f64>,
    /// Rebound speed after the last lift-off, m/s.
    v_out_m_s: f64,
}

/// Drops the lander of `scenario` flat at `v0` and steps it to `duration_s`, or until the
/// first lift-off in zero gravity (it never comes back).
fn crush_drop(scenario: &Scenario, v0: f64, duration_s: f64) -> Crush {
    let mut s = scenario.clone();
    s.simulation.t_max_s = duration_s;
    let mut sim = Sim::of(&s, moving([0.0, 0.0, -v0], [0.0; 3]));
    let e0 = sim.mechanical_energy();
    let mut out = Crush {
        lost_j: 0.0,
        absorbed_j: 0.0,
        max_stroke_m: 0.0,
        strokes_m: Vec::new(),
        v_out_m_s: 0.0,
    };
    let mut was_in_contact = false;
    sim.advance_while(|sim| {
        let in_contact = sim.in_contact();
        let stroke = sim
            .state
            .legs
            .iter()
            .map(|l| l.stroke_m)
            .fold(0.0, f64::max);
        out.max_stroke_m = out.max_stroke_m.max(stroke);
        if was_in_contact && !in_contact {
            out.lost_j = e0 - sim.mechanical_energy();
            out.absorbed_j = sim.absorbed_j();
            out.v_out_m_s = sim.state.body.velocity_m_s.z;
        }
        was_in_contact = in_contact;
        !(sim.model.gravity_m_s2 == 0.0 && out.v_out_m_s > 0.0)
    });
    out.strokes_m = sim.state.legs.iter().map(|l| l.stroke_m).collect();
    out
}

#[test]
fn honeycomb_energy_balance() {
    // Elastic surface (c = 0) and no friction damping: the only dissipation is crushing, so
    // the mechanical energy lost between the start and the last lift-off equals the sum
    // of the legs' absorbed_j (MODEL.md section 12). Tolerance 1 %: the contact springs are
    // integrated by semi-implicit Euler, whose energy error is bounded (O(omega dt) of the
    // spring energy while in contact, omega dt = 0.045) and small again at lift-off; the
    // crush work on a plateau is exact (the stroke is solved implicitly within the step).
    // Every case crushes without bottoming out (stroke between 1 and 49 mm): single-stage
    // pre-crushed cartridges at 50, 90 and 210 psi and two drop speeds each, a cartridge
    // with the initial peak (1.75 x over 2 mm), a two-stage cartridge, and one drop in
    // gravity, which hops (its balance is taken at its last lift-off within 60 s).
    let mut table = Table::new("honeycomb: energy lost = energy absorbed (elastic surface)");
    let single = |psi| vec![(0.05, psi)];
    let cases: Vec<(String, Scenario, f64)> = vec![
        (
            "50 psi pre-crushed".into(),
            crushing(&single(50.0), true, 0.0),
            0.3,
        ),
        (
            "50 psi pre-crushed".into(),
            crushing(&single(50.0), true, 0.0),
            0.6,
        ),
        (
            "90 psi pre-crushed".into(),
            crushing(&single(90.0), true, 0.0),
            0.5,
        ),
        (
            "90 psi pre-crushed".into(),
            crushing(&single(90.0), true, 0.0),
            0.9,
        ),
        (
            "210 psi pre-crushed".into(),
            crushing(&single(210.0), true, 0.0),
            0.8,
        ),
        (
            "210 psi pre-crushed".into(),
            crushing(&single(210.0), true, 0.0),
            1.3,
        ),
        (
            "2 stages 10 mm 50 + 40 mm 140 psi".into(),
            crushing(&[(0.01, 50.0), (0.04, 140.0)], true, 0.0),
            0.9,
        ),
        (
            "90 psi pre-crushed, g0 0.0168".into(),
            crushing(&single(90.0), true, 0.0168),
            0.8,
        ),
    ];
    for (name, s, v0) in cases {
        let duration = if s.gravity_m_s2 > 0.0 { 60.0 } else { 5.0 };
        let c = crush_drop(&s, v0, duration);
        let case = format!("{name}, v0 {v0}");
        table.relative(
            &case,
            "energy lost (J) vs absorbed",
            c.lost_j,
            c.absorbed_j,
            0.01,
        );
        table.at_least(&case, "stroke (m): crushed", c.max_stroke_m, 1e-3);
        table.at_most(
            &case,
            "stroke (m): not bottomed",
            c.max_stroke_m,
            0.05 - 1e-3,
        );
    }
    // A cartridge that is not pre-crushed first holds the initial peak (1.75 x the plateau,
    // falling to it over 2 mm). While the force falls, each contact spring relaxes from the
    // peak load to the plateau, and the footpad, having no mass, cannot carry that energy
    // into the crushing: it is lost unbooked. The balance must then be off by no more than
    // that release, ((1.75 F_c)^2 - F_c^2) / (2 k) per leg, and never the other way.
    for v0 in [0.5, 0.8] {
        let s = crushing(&single(50.0), false, 0.0);
        let c = crush_drop(&s, v0, 5.0);
        let f = crush_force_n(50.0);
        let k = s.surface.stiffness_n_per_m;
        let release = 4.0 * ((1.75 * f).powi(2) - f * f) / (2.0 * k);
        let case = format!("50 psi not pre-crushed, v0 {v0}");
        table.at_least(
            &case,
            "energy lost - absorbed (J)",
            c.lost_j - c.absorbed_j,
            0.0,
        );
        table.at_most(
            &case,
            "energy lost - absorbed (J)",
            c.lost_j - c.absorbed_j,
            release,
        );
    }
    table.finish();
}

#[test]
fn honeycomb_stroke_closed_form() {
    // A pre-crushed single-stage cartridge, g0 = 0, flat drop: each contact spring loads to
    // the crush force F_c, the four cartridges then crush at F_c until the lander stops,
    // and the springs give back their 4 F_c^2 / (2k). So v_out = 2 F_c / sqrt(k m) and the
    // stroke of each leg is s = (m v0^2 / 2 - 2 F_c^2 / k) / (4 F_c). Tolerance 1 %, as the
    // energy balance (the crush plateau itself is exact).
    let mut table = Table::new("honeycomb: stroke and rebound, closed form");
    for (psi, v0) in [(50.0, 0.3), (50.0, 0.6), (90.0, 0.9), (210.0, 1.3)] {
        let s = crushing(&[(0.05, psi)], true, 0.0);
        let (k, m, f) = (
            s.surface.stiffness_n_per_m,
            s.lander.mass_kg,
            crush_force_n(psi),
        );
        let c = crush_drop(&s, v0, 5.0);
        let case = format!("{psi} psi (F_c {f:.1} N) v0 {v0}");
        let stroke = (0.5 * m * v0 * v0 - 2.0 * f * f / k) / (4.0 * f);
        for (i, leg) in c.strokes_m.iter().enumerate() {
            table.relative(&case, &format!("stroke leg {i} (m)"), *leg, stroke, 0.01);
        }
        table.relative(
            &case,
            "stroke = absorbed / (4 F_c)",
            c.absorbed_j / (4.0 * f),
            stroke,
            0.01,
        );
        table.relative(
            &case,
            "v_out (m/s)",
            c.v_out_m_s,
            2.0 * f / (k * m).sqrt(),
            0.01,
        );
    }
    table.finish();
}

#[test]
fn honeycomb_bottoms_out_at_usable_stroke() {
    // Drops hard enough to use up the 50 mm stroke: no leg's stroke may ever exceed it
    // (to rounding, 1e-12 m), every leg ends at it, each absorbed F_c times it (1e-9
    // relative), and the energy balance still holds (1 %, as above).
    let mut table = Table::new("honeycomb: bottoming out");
    for (psi, v0) in [(50.0, 1.2), (50.0, 1.6), (90.0, 1.5)] {
        let s = crushing(&[(0.05, psi)], true, 0.0);
        let c = crush_drop(&s, v0, 5.0);
        let case = format!("{psi} psi v0 {v0}");
        table.at_most(&case, "max stroke (m)", c.max_stroke_m, 0.05 + 1e-12);
        let least = c.strokes_m.iter().copied().fold(f64::INFINITY, f64::min);
        table.close(&case, "least final stroke (m)", least, 0.05, 1e-12);
        let full = 4.0 * crush_force_n(psi) * 0.05;
        table.relative(
            &case,
            "absorbed (J) vs 4 F_c s_max",
            c.absorbed_j,
            full,
            1e-9,
        );
        table.relative(
            &case,
            "energy lost (J) vs absorbed",
            c.lost_j,
            c.absorbed_j,
            0.01,
        );
    }
    table.finish();
}
