//! The outcome rules mean what they say (MODEL.md section 8): `stable` only where the
//! footpads stick, `tipped` before 90 deg only where running on cannot change it. Both in
//! the scalar reference and in the SIMD kernels.

use crate::common::SET_DOWN;
use kernels::outcome::SLIDE_EDGE_MARGIN;
use touchdown::reference::{self, Model, Outcome, Summary};
use touchdown::scenario::Scenario;
use touchdown::sweep;

/// The summaries of samples `0..n` from the kernels, in sample order.
fn kernel_run(scenario: &Scenario, n: u64) -> Vec<Summary> {
    let model = Model::new(scenario);
    let mut rows = Vec::new();
    sweep::run(scenario, &model, 0..n, 256, |r| {
        rows.extend(r);
        Ok(())
    })
    .unwrap();
    assert_eq!(rows.len() as u64, n, "every sample comes back once");
    rows.into_iter().map(|r| r.summary).collect()
}

/// The summary of sample `i` from the reference.
fn reference_run(scenario: &Scenario, i: u64) -> Summary {
    let model = Model::new(scenario);
    reference::run(&model, &touchdown::sampling::sample(scenario, i), |_| {})
}

/// A lander set down at rest (no clearance, no velocity, attitude and rates zero against
/// the surface normal) on slope grid `slopes`, side facing downhill along X, with an initial
/// downhill speed `speed_m_s`; 30 s. The early `sliding` rule is off: these tests follow
/// a slide to t_max (`set_down_at_rest_...` also runs it with the rule on).
fn set_down(legs: usize, mu: f64, slopes: [f64; 2], speed_m_s: f64) -> Scenario {
    Scenario::from_toml(&format!(
        r#"
[lander]
legs = {legs}
[surface]
friction_coefficient = {mu}
[initial]
attitude_reference = "surface"
clearance_m = 0.0
[inputs]
slope_deg = {{ dist = "grid", min = {}, max = {}, count = 2 }}
downhill_azimuth_deg = 0.0
{set_down}[simulation]
t_max_s = 30.0
[outcome]
early_sliding = false
"#,
        slopes[0],
        slopes[1],
        set_down = SET_DOWN.replace(
            "velocity_error_x_m_s = 0.0",
            &format!("velocity_error_x_m_s = {speed_m_s}")
        ),
    ))
    .unwrap()
}

#[test]
fn set_down_at_rest_stands_below_the_friction_angle_and_slides_above() {
    // 1 deg below atan(mu) the stick-slip friction holds the lander (MODEL.md section 12),
    // so it must end `stable` once the hold time has passed. 1 deg above it accelerates at
    // g0 (sin a - mu cos a) = 3e-4 m/s^2 or less: after the 2 s hold it moves at under
    // 1 mm/s, five times below the rest speed, so only the friction anchors show that it
    // slides; it must end `sliding` at t_max, having moved at least half of the Coulomb
    // distance g0 (sin a - mu cos a) t^2 / 2 (the stick phase and the settling of the
    // springs take some of the 30 s). Slopes up to 32 deg, below the static limits of both
    // gears (44.7 deg for four legs, 35.0 for three), and mu below r/h for both, so a
    // sliding lander cannot tip.
    let mut problems = Vec::new();
    for legs in [4, 3] {
        for mu in [0.2f64, 0.4, 0.6] {
            let friction_angle = mu.atan().to_degrees();
            let slopes = [friction_angle - 1.0, friction_angle + 1.0];
            let s = set_down(legs, mu, slopes, 0.0);
            let kernels = kernel_run(&s, 2);
            for (i, expected) in [(0, Outcome::Stable), (1, Outcome::Sliding)] {
                let r = reference_run(&s, i);
                let k = &kernels[i as usize];
                let case = format!("{legs} legs, mu {mu}, slope {:.3} deg", slopes[i as usize]);
                println!(
                    "{case}: reference {} at {:.3} s (moved {:.4} m), kernels {} at {:.3} s (moved {:.4} m)",
                    r.outcome.name(),
                    r.decided_s,
                    r.displacement_m,
                    k.outcome.name(),
                    k.decided_s,
                    k.displacement_m
                );
                for (who, got) in [("reference", &r), ("kernels", k)] {
                    if got.outcome != expected {
                        problems.push(format!("{case}: {who} {}", got.outcome.name()));
                    }
                }
                // The early rule: the same outcome; the slide decided before t_max where
                // the rule's tipping margin holds: SLIDE_EDGE_MARGIN mu below the ratio
                // r / h of the nearest edge, tan of the static limit with a side downhill
                // (44.7 deg for four legs, 35.0 for three: mu 0.6 is too close on three).
                let mut early_scenario = s.clone();
                early_scenario.outcome.early_sliding = true;
                let e = reference_run(&early_scenario, i);
                let static_limit_deg: f64 = if legs == 4 { 44.7 } else { 35.0 };
                let margin_holds = SLIDE_EDGE_MARGIN * mu < static_limit_deg.to_radians().tan();
                let early_expected = expected == Outcome::Sliding && margin_holds;
                let early = e.outcome == Outcome::Sliding && e.decided_s < s.simulation.t_max_s;
                if e.outcome != expected || early != early_expected {
                    problems.push(format!(
                        "{case}: with the early rule {} at {:.3} s",
                        e.outcome.name(),
                        e.decided_s
                    ));
                }
                if expected == Outcome::Sliding {
                    let a = slopes[1].to_radians();
                    let coulomb = 0.5
                        * s.gravity_m_s2
                        * (a.sin() - mu * a.cos())
                        * s.simulation.t_max_s.powi(2);
                    if r.displacement_m < 0.5 * coulomb {
                        problems.push(format!(
                            "{case}: slid {:.4} m, Coulomb {coulomb:.4} m",
                            r.displacement_m
                        ));
                    }
                }
            }
        }
    }
    assert!(problems.is_empty(), "{problems:#?}");
}

#[test]
fn a_slow_slider_is_sliding() {
    // Started at 1 mm/s downhill 0.5 deg above the friction angle, the lander moves slower
    // than the rest speed for the whole run (10 s): the rule of speeds alone called it
    // `stable` after the hold time. Its footpads slip all the way: `sliding`. At t_max too,
    // whichever step the run ends on: moving a few micrometres a step, it starts a rest
    // every other step (the footpads are checked from the second step of a rest), and the
    // classification at t_max must not take that first step for rest (before engine 0.4
    // it did, and the outcome went by the parity of the last step: this test failed).
    for (legs, mu) in [(4, 0.6f64), (3, 0.3)] {
        let slope = mu.atan().to_degrees() + 0.5;
        for t_max in [10.0, 10.001, 10.002, 10.003] {
            let mut s = set_down(legs, mu, [slope, slope], 0.001);
            s.simulation.t_max_s = t_max;
            let r = reference_run(&s, 0);
            let k = &kernel_run(&s, 1)[0];
            for (who, got) in [("reference", &r), ("kernels", k)] {
                assert_eq!(
                    got.outcome,
                    Outcome::Sliding,
                    "{legs} legs, mu {mu}, slope {slope:.2} deg, t_max {t_max} s: {who} decided {} at {:.3} s",
                    got.outcome.name(),
                    got.decided_s
                );
            }
        }
    }
}

/// The touchdown of the default lander with stiff contact (3e5 N/m per leg), mu 0.5,
/// attitude and velocity against the surface normal, 0.1-0.6 m/s into slopes up to 40 deg,
/// and 20 s to decide: many landers are still toppling slowly when the time runs out.
const STIFF_20_S: &str = r#"
seed = 7
[lander]
leg_tips_m = [[0.424265, 0.424265, -0.448936], [0.424265, -0.424265, -0.448936],
              [-0.424265, -0.424265, -0.448936], [-0.424265, 0.424265, -0.448936]]
[surface]
stiffness_n_per_m = 3.0e5
damping_n_s_per_m = 3.0e3
friction_coefficient = 0.5
friction_stiffness_n_per_m = 3.0e5
friction_damping_n_s_per_m = 3.0e3
[inputs]
slope_deg = { dist = "uniform", min = 0.0, max = 40.0 }
release_height_m = 0.0
velocity_error_x_m_s = { dist = "uniform", min = -0.0707, max = 0.0707 }
velocity_error_y_m_s = { dist = "uniform", min = -0.0707, max = 0.0707 }
velocity_error_z_m_s = { dist = "uniform", min = -0.6, max = -0.1 }
roll_deg = { dist = "uniform", min = -10.0, max = 10.0 }
pitch_deg = { dist = "uniform", min = -10.0, max = 10.0 }
yaw_deg = { dist = "uniform", min = 0.0, max = 360.0 }
rate_x_deg_s = { dist = "uniform", min = -2.8648, max = 2.8648 }
rate_y_deg_s = { dist = "uniform", min = -2.8648, max = 2.8648 }
rate_z_deg_s = { dist = "uniform", min = -2.8648, max = 2.8648 }
[initial]
attitude_reference = "surface"
clearance_m = 0.01
[simulation]
t_max_s = 20.0
"#;

/// How the early `tipped` calls of one scenario fared when run on.
#[derive(Debug, Default)]
struct RunOn {
    samples: usize,
    tipped: usize,
    /// Decided `tipped` before the tilt passed 90 deg.
    early: usize,
    /// ... and run on, passed 90 deg before t_max.
    confirmed: usize,
    /// ... and run on, passed 90 deg only after t_max (the band: past the point of no
    /// return, toppling slowly when the time ran out).
    after_t_max: usize,
    /// ... and run on to `STRETCH` t_max, never passed 90 deg.
    wrong: Vec<String>,
}

/// How much longer the run-on may take than the scenario's t_max.
const STRETCH: f64 = 5.0;

/// Runs `n` samples of `scenario` with the early rule and, run on with only the 90 deg
/// rule, to `STRETCH` times t_max; compares them sample by sample.
fn both_ways(scenario: &Scenario, n: u64) -> RunOn {
    assert!(scenario.outcome.early_tipping);
    // Only the tipping rule is under test here (the others have their own test below).
    let mut scenario = scenario.clone();
    scenario.outcome.early_sliding = false;
    scenario.outcome.early_bouncing = false;
    let scenario = &scenario;
    let early = kernel_run(scenario, n);
    let mut late_scenario = scenario.clone();
    late_scenario.outcome.early_tipping = false;
    late_scenario.simulation.t_max_s *= STRETCH;
    let late = kernel_run(&late_scenario, n);
    let t_max = scenario.simulation.t_max_s;
    let mut r = RunOn {
        samples: early.len(),
        ..RunOn::default()
    };
    for (i, (e, l)) in early.iter().zip(&late).enumerate() {
        let same = l.outcome == e.outcome && l.decided_s == e.decided_s;
        if e.outcome == Outcome::Tipped {
            r.tipped += 1;
        }
        if same {
            continue;
        }
        // Classified at t_max, from the state there: the run-on goes further.
        let at_t_max = e.outcome != Outcome::Tipped && e.decided_s >= t_max && l.decided_s >= t_max;
        if at_t_max {
            continue;
        }
        if e.outcome != Outcome::Tipped {
            r.wrong.push(format!(
                "sample {i}: {} at {:.3} s, run on {} at {:.3} s (the early rule must not change it)",
                e.outcome.name(),
                e.decided_s,
                l.outcome.name(),
                l.decided_s
            ));
            continue;
        }
        r.early += 1;
        match l.outcome {
            Outcome::Tipped if l.decided_s <= t_max => r.confirmed += 1,
            Outcome::Tipped => r.after_t_max += 1,
            _ => r.wrong.push(format!(
                "sample {i}: tipped at {:.3} s, run on {} at {:.3} s",
                e.decided_s,
                l.outcome.name(),
                l.decided_s
            )),
        }
    }
    r
}

#[test]
fn an_early_tipped_lander_tips_when_run_on() {
    // The point of no return of MODEL.md section 8 must be one: every sample the early rule
    // calls `tipped`, run on with only the 90 deg rule, passes 90 deg. Counted apart (the
    // band): those that pass 90 deg only after the scenario's t_max, landers past their
    // point of no return that topple slowly in milligravity (a fall from the static limit
    // to 90 deg takes tens of seconds at 0.0168 m/s^2). Run on to 5 t_max, none may fail
    // to tip. The scenarios cover the default sweep (fast touchdowns, no damper), stiff
    // contact with slopes above the friction angle, gentle set-downs with dampers on 0-60
    // deg (sliding and tipping), three legs, rough ground.
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios");
    let file = |name: &str| {
        Scenario::from_toml(&std::fs::read_to_string(dir.join(name)).unwrap()).unwrap()
    };
    let cases = [
        ("default", Scenario::default(), 4000),
        (
            "stiff, 20 s",
            Scenario::from_toml(STIFF_20_S).unwrap(),
            4000,
        ),
        ("scenarios/flat.toml", file("flat.toml"), 1500),
        ("scenarios/legs-3.toml", file("legs-3.toml"), 1500),
        ("scenarios/rough.toml", file("rough.toml"), 1000),
    ];
    let mut wrong = Vec::new();
    for (name, scenario, n) in cases {
        let r = both_ways(&scenario, n);
        println!(
            "{name}: {} samples, {} tipped, {} of them early: run on, {} passed 90 deg before t_max, {} after it (band), {} never",
            r.samples,
            r.tipped,
            r.early,
            r.confirmed,
            r.after_t_max,
            r.wrong.len()
        );
        wrong.extend(r.wrong.into_iter().map(|w| format!("{name}: {w}")));
    }
    assert!(wrong.is_empty(), "{wrong:#?}");
}

#[test]
fn early_sliding_and_bouncing_change_no_outcome() {
    // The early `sliding` and `bouncing` rules (MODEL.md section 8) end runs whose outcome
    // at t_max is already fixed. Every sample, run with them and without (to t_max), must
    // end with the same outcome, and no later. The scenarios: the MuJoCo-matched one
    // (stiff contact, slopes to 40 deg past the friction angle of 26.6: steady slides,
    // 20 s), the stiff 20 s one of this file, the default sweep (120 s), flat, three legs,
    // dampers of 50 psi (the rule stays on: no slide can crush them), rough ground (no
    // early sliding: the terrain changes under a slide).
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios");
    let file = |name: &str| {
        Scenario::from_toml(&std::fs::read_to_string(dir.join(name)).unwrap()).unwrap()
    };
    let cases = [
        (
            "scenarios/mujoco-matched.toml",
            file("mujoco-matched.toml"),
            6000,
        ),
        (
            "stiff, 20 s",
            Scenario::from_toml(STIFF_20_S).unwrap(),
            3000,
        ),
        ("default", Scenario::default(), 2000),
        ("scenarios/flat.toml", file("flat.toml"), 1500),
        ("scenarios/legs-3.toml", file("legs-3.toml"), 1500),
        (
            "scenarios/honeycomb-50psi.toml",
            file("honeycomb-50psi.toml"),
            1500,
        ),
        ("scenarios/rough.toml", file("rough.toml"), 1000),
    ];
    let mut wrong = Vec::new();
    let (mut slides, mut flights) = (0, 0);
    for (name, scenario, n) in cases {
        assert!(scenario.outcome.early_sliding && scenario.outcome.early_bouncing);
        let early = kernel_run(&scenario, n);
        let mut late_scenario = scenario.clone();
        late_scenario.outcome.early_sliding = false;
        late_scenario.outcome.early_bouncing = false;
        let late = kernel_run(&late_scenario, n);
        let t_max = scenario.simulation.t_max_s;
        let (mut slid, mut flew, mut steps, mut steps_late) = (0, 0, 0, 0);
        for (i, (e, l)) in early.iter().zip(&late).enumerate() {
            steps += e.steps;
            steps_late += l.steps;
            if e.outcome != l.outcome || e.decided_s > l.decided_s {
                wrong.push(format!(
                    "{name}, sample {i}: {} at {:.3} s, run to t_max {} at {:.3} s",
                    e.outcome.name(),
                    e.decided_s,
                    l.outcome.name(),
                    l.decided_s
                ));
            }
            let early_call = e.decided_s < t_max && e.decided_s < l.decided_s;
            slid += usize::from(early_call && e.outcome == Outcome::Sliding);
            flew += usize::from(early_call && e.outcome == Outcome::Bouncing);
        }
        println!(
            "{name}: {n} samples, {slid} decided sliding early, {flew} bouncing early, steps {:.1} % fewer",
            100.0 * (1.0 - steps as f64 / steps_late as f64)
        );
        if name == "scenarios/rough.toml" {
            assert_eq!(slid, 0, "no early sliding on rough ground");
        }
        slides += slid;
        flights += flew;
    }
    assert!(wrong.is_empty(), "{wrong:#?}");
    // The comparison means something only where the rules fire.
    assert!(slides >= 500, "only {slides} early slides");
    assert!(flights >= 20, "only {flights} early flights");
}
