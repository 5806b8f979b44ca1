//! Every sample of a batched (SIMD) run against the same sample run alone by the scalar
//! reference (MODEL.md section 12, last check), over several scenarios, with every kernel
//! this CPU runs in f64 and in f32 lanes; and the kernels of one precision that fuse their
//! multiply-adds (AVX-512, AVX2) against each other, bit for bit.
//!
//! The kernels compute the same formulas in the same order, but not with the same rounding
//! (fused multiply-adds, another association of sums). A touchdown is chaotic, mostly
//! through its bounces, so differences of 1e-16 can grow; a sample whose outcome is
//! decided by a hair may then be decided the other way. Such disagreements are counted
//! and each one must be explained: the reference itself, nudged by one part in 1e9 of its
//! touchdown speed (f64 lanes; up to one part in 1e6 for f32 lanes, whose rounding is 2^29
//! times coarser), must be able to reach the kernel's outcome, or both must have been
//! classified at t_max (from states that rounding moved apart). Continuous
//! results of agreeing samples must agree within the tolerances below.

use kernels::isa::{Isa, KernelKind, Precision};
use std::sync::atomic::AtomicUsize;
use touchdown::reference::{self, Model, Outcome, Summary};
use touchdown::sampling;
use touchdown::scenario::Sample;
use touchdown::scenario::Scenario;
use touchdown::sweep;

/// Runs `n` samples through the reference and through every kernel this CPU has; returns,
/// per kernel, (samples, outcome disagreements, unexplained, drifted). Kernels that fuse
/// their multiply-adds must give the same rows in each precision, bit for bit.
fn compare(name: &str, scenario: &Scenario, n: u64) -> Vec<(KernelKind, [u64; 4])> {
    let model = Model::new(scenario);
    let samples: Vec<Sample> = (0..n).map(|i| sampling::sample(scenario, i)).collect();
    let reference: Vec<Summary> = samples
        .iter()
        .map(|s| reference::run(&model, s, |_| {}))
        .collect();
    let mut out = Vec::new();
    for precision in Precision::ALL {
        let mut scenario = scenario.clone();
        scenario.simulation.precision = precision;
        compare_kernels(name, &scenario, &model, &samples, &reference, &mut out);
    }
    out
}

/// `compare` in the precision of `scenario`.
fn compare_kernels(
    name: &str,
    scenario: &Scenario,
    model: &Model,
    samples: &[Sample],
    reference: &[Summary],
    out: &mut Vec<(KernelKind, [u64; 4])>,
) {
    let n = samples.len() as u64;
    let precision = scenario.simulation.precision;
    let mut fused_rows: Option<(Isa, Vec<String>)> = None;
    for isa in Isa::ALL.into_iter().filter(|i| i.available()) {
        let mut rows = Vec::new();
        let never = AtomicUsize::new(0);
        sweep::run_until(scenario, model, isa, 0..n, 256, &never, |r| {
            rows.extend(r);
            Ok(())
        })
        .unwrap();
        assert_eq!(rows.len() as u64, n, "{name}: every sample comes back once");
        if isa.fused() {
            let bits: Vec<String> = rows.iter().map(|r| format!("{:?}", r.summary)).collect();
            match &fused_rows {
                None => fused_rows = Some((isa, bits)),
                Some((first, first_bits)) => {
                    let differ = bits.iter().zip(first_bits).filter(|(a, b)| a != b).count();
                    assert_eq!(
                        differ,
                        0,
                        "{name}: {} rows of the {} {} kernel differ from the {} kernel's",
                        differ,
                        isa.key(),
                        precision.key(),
                        first.key()
                    );
                }
            }
        }
        let name = format!("{name}, kernel {} {}", isa.key(), precision.key());
        // A control loop in the fall (MODEL.md section 7) quantises its commands to
        // minimum impulse bits: where f32 rounding flips one, the lander's velocity moves
        // by an impulse bit's share (0.01 N s on 100 kg: 1e-4 m/s), its arrival after a
        // 30 s fall by millimetres, its first contact by milliseconds, and flips add up
        // over the hundreds of instants of a fall. There the first contact is no ballistic
        // arc's end: it drifts (counted) beyond 10 ms instead of failing beyond a step.
        let contact_within = if model.control.is_some() && precision == Precision::F32 {
            None
        } else {
            Some(1e-3 + 1e-9)
        };
        let (mut disagree, mut unexplained, mut drifted) = (0, 0, 0);
        let mut worst = [0.0f64; 5];
        for (i, (row, r)) in rows.iter().zip(reference).enumerate() {
            assert_eq!(row.sample.index, i as u64, "{name}: rows in sample order");
            let k = &row.summary;
            if r.outcome != k.outcome {
                disagree += 1;
                // Classified at t_max from a state that rounding has moved (a lander
                // hopping at 20 s touches at the last step or not, starts a rest or not):
                // the end of the run is the boundary.
                let at_t_max = r.decided_s >= model.t_max_s && k.decided_s >= model.t_max_s;
                let explained =
                    at_t_max || near_threshold(model, precision, &row.sample, r, k.outcome);
                if !explained {
                    unexplained += 1;
                }
                println!(
                    "{name}: sample {i}: reference {} at {:.3} s, kernel {} at {:.3} s -> {}",
                    r.outcome.name(),
                    r.decided_s,
                    k.outcome.name(),
                    k.decided_s,
                    if at_t_max {
                        "both at t_max"
                    } else if explained {
                        "near a threshold"
                    } else {
                        "UNEXPLAINED"
                    }
                );
                continue;
            }
            // Strut-load peaks: see `check_close`.
            let loads_within = match precision {
                Precision::F64 => 0.01,
                Precision::F32 => 0.1,
            };
            drifted += u64::from(check_close(
                &name,
                i,
                r,
                k,
                (contact_within, loads_within),
                &mut worst,
            ));
        }
        println!(
            "{name}: {n} samples, {disagree} outcome disagreements ({unexplained} unexplained), {drifted} drifted; worst agreeing |diff|: decided {:.2e} s, max tilt {:.2e} deg, peak accel {:.2e} (relative), stroke {:.2e} m, strut loads {:.2e} (relative)",
            worst[0], worst[1], worst[2], worst[3], worst[4]
        );
        out.push((isa.kernel(precision), [n, disagree, unexplained, drifted]));
    }
}

/// Whether the reference, nudged slightly, can reach `other` too: by up to 1e-8 of the
/// release height for f64 lanes; for f32 lanes, which round to 6e-8 and add up many such
/// roundings over the thousands of steps of a chaotic touchdown, by up to 1e-4 (0.5 mm of a
/// 5 m release height, against a sampled spread of 5 m), and the initial roll or pitch by
/// up to 1e-4 deg (against a sampled spread of 2 deg): a lander pivoting on one leg near
/// its tipping point for seconds tips or not by a nudge of attitude where one of height
/// does not (measured: MuJoCo-matched samples 672 and 684). For f32, a sample the reference
/// leaves undecided at t_max (still hopping or creeping) counts as well when its nudged
/// runs end in more than one way: its outcome is a matter of rounding.
fn near_threshold(
    model: &Model,
    precision: Precision,
    sample: &Sample,
    reference: &Summary,
    other: Outcome,
) -> bool {
    let nudges: &[f64] = match precision {
        Precision::F64 => &[-1e-9, 1e-9, -1e-8, 1e-8],
        Precision::F32 => &[
            -1e-9, 1e-9, -1e-8, 1e-8, -1e-7, 1e-7, -1e-6, 1e-6, -3e-6, 3e-6, -1e-5, 1e-5, -3e-5,
            3e-5, -1e-4, 1e-4,
        ],
    };
    let mut seen = vec![reference.outcome];
    // Nudges of the release height; for f32, of the initial roll and pitch too (by the
    // same fraction of a degree).
    let nudged = nudges.iter().flat_map(|&nudge| {
        let mut height = *sample;
        height.inputs.release_height_m *= 1.0 + nudge;
        let (mut roll, mut pitch) = (*sample, *sample);
        roll.inputs.roll_deg += nudge;
        pitch.inputs.pitch_deg += nudge;
        let attitude = (precision == Precision::F32).then_some([roll, pitch]);
        std::iter::once(height).chain(attitude.into_iter().flatten())
    });
    for s in nudged {
        let outcome = reference::run(model, &s, |_| {}).outcome;
        if outcome == other {
            return true;
        }
        if !seen.contains(&outcome) {
            seen.push(outcome);
        }
    }
    precision == Precision::F32 && reference.decided_s >= model.t_max_s && seen.len() > 1
}

/// Tolerances for samples with the same outcome. The first contact ends a ballistic arc,
/// which both integrate exactly: it agrees to within one step (a step boundary may fall on
/// either side of it by rounding): `contact_within` s, or, where a control loop acts in
/// the fall (`None`), a sample drifts when it differs by more than 10 ms. Later results pass through the chaos of the bounces:
/// a sample "drifts" when its decided time differs by more than 50 ms + 2 %, its maximum
/// tilt by more than 0.5 deg, its peak acceleration or a leg's peak axial or side load by
/// more than `loads_within` (of at least 1 N), or a leg bottoms in one and not the other.
/// Drifted samples are counted, not failed one by one; the caller bounds their share.
fn check_close(
    name: &str,
    i: usize,
    r: &Summary,
    k: &Summary,
    (contact_within, loads_within): (Option<f64>, f64),
    worst: &mut [f64; 5],
) -> bool {
    // Strut-load peaks relative to the larger of the peak and 1 N (a leg's share of the
    // default lander's weight is 0.42 N; impacts load a strut with tens to hundreds),
    // within `loads_within`: 1 % in f64 lanes; 10 % in f32 lanes, whose first contact
    // falls up to a step (1 ms) apart from the reference's, so that the steps sample a
    // leg's stiff impact (a few ms long) at other instants and its sampled peak moves by
    // percents (the peak acceleration, the sum of the legs' forces, moves less).
    // Their times are not compared: a crushing damper holds the axial load at its crush
    // force for many steps, and which of them reaches it first is a matter of rounding.
    let relative = |a: f64, b: f64| (a - b).abs() / a.abs().max(1.0);
    let mut struts_drift = false;
    let mut strut_loads = 0.0f64;
    for (a, b) in r.legs.iter().zip(&k.legs) {
        // On regolith, the footprints' depths and energies within `loads_within` (of at
        // least 0.1 mm and 1 mJ), as the peak loads: a footprint's depth is the deepest
        // sinkage less the unloading line's spring-back, a difference that f32 rounds
        // coarsely (measured against f64 on 4000 default regolith samples: 0.17 % at the
        // 90th percentile, 2.4 % at the 99th).
        struts_drift |= (a.sinkage_m - b.sinkage_m).abs() > loads_within * a.sinkage_m.max(1e-4)
            || (a.soil_absorbed_j - b.soil_absorbed_j).abs()
                > loads_within * a.soil_absorbed_j.max(1e-3);
        let loads = relative(a.peak_axial_force_n, b.peak_axial_force_n)
            .max(relative(a.peak_side_force_n, b.peak_side_force_n));
        strut_loads = strut_loads.max(loads);
        struts_drift |= loads > loads_within || a.bottomed != b.bottomed;
    }
    let d = [
        (r.decided_s - k.decided_s).abs(),
        (r.max_tilt_deg - k.max_tilt_deg).abs(),
        (r.peak_acceleration_m_s2 - k.peak_acceleration_m_s2).abs()
            / r.peak_acceleration_m_s2.max(1e-9),
        r.legs
            .iter()
            .zip(&k.legs)
            .map(|(a, b)| (a.stroke_m - b.stroke_m).abs())
            .fold(0.0, f64::max),
        strut_loads,
    ];
    for (w, x) in worst.iter_mut().zip(d) {
        *w = w.max(x);
    }
    let mut contact_drift = false;
    match (r.first_contact_s, k.first_contact_s, contact_within) {
        (Some(a), Some(b), Some(within)) => {
            assert!(
                (a - b).abs() <= within,
                "{name} sample {i}: first contact {a} vs {b}"
            );
            // The touchdown state is the state at the start of that step: one step apart
            // at most, over which gravity (0.0168 m/s^2) changes the speeds by 0.0168
            // `within`, and the body rates (at most a few deg/s) the tilt by a few
            // `within` deg; the rates change only by the gyroscopic term. 1e-5 (m/s,
            // deg/s) and 1e-3 deg above that cover f32 lanes' rounding. The first leg is
            // not compared: an upright lander on level ground touches with four at once.
            let (a, b) = (r.touchdown.unwrap(), k.touchdown.unwrap());
            let speeds = 0.0168 * within + 1e-5;
            assert!(
                (a.normal_speed_m_s - b.normal_speed_m_s).abs() <= speeds
                    && (a.tangential_speed_m_s - b.tangential_speed_m_s).abs() <= speeds
                    && (a.tilt_deg - b.tilt_deg).abs() <= 5.0 * within + 1e-3
                    && (0..3).all(|j| (a.rate_deg_s[j] - b.rate_deg_s[j]).abs() <= 1e-3),
                "{name} sample {i}: touchdown state {a:?} vs {b:?}"
            );
        }
        (Some(a), Some(b), None) => contact_drift = (a - b).abs() > 0.01,
        (a, b, _) => assert_eq!(a, b, "{name} sample {i}: first contact"),
    }
    contact_drift || struts_drift || d[0] > 0.05 + 0.02 * r.decided_s || d[1] > 0.5 || d[2] > 0.01
}

fn scenario(toml: &str) -> Scenario {
    Scenario::from_toml(toml).unwrap()
}

/// The shipped scenario `scenarios/NAME.toml`.
fn scenario_file(name: &str) -> Scenario {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenarios")
        .join(format!("{name}.toml"));
    scenario(&std::fs::read_to_string(path).unwrap())
}

/// `s` with the contact step's error control at 1e-4 m/s.
fn controlled(mut s: Scenario) -> Scenario {
    s.simulation.tolerance_m_s = Some(1e-4);
    s
}

#[test]
fn kernels_agree_with_the_reference() {
    let cases = [
        ("default slopes", scenario(""), 2000),
        (
            "flat, slow",
            scenario(
                "[inputs]\nslope_deg = 0.0\nrelease_height_m = { dist = \"uniform\", min = 0.3, max = 1.5 }",
            ),
            1000,
        ),
        (
            "rough",
            scenario("[surface.roughness]\nrms_height_m = 0.02"),
            1000,
        ),
        (
            "dampers 140 psi",
            scenario("[damper]\nenabled = true\ncrush_strength_psi = 140.0"),
            1000,
        ),
        (
            "elastic surface, 90 psi multi-stage, not pre-crushed",
            scenario(
                "[surface]\ndamping_n_s_per_m = 0.0\n[damper]\nenabled = true\npre_crushed = false\nstages = [{ stroke_m = 0.01, crush_strength_psi = 90.0 }, { stroke_m = 0.04, crush_strength_psi = 210.0 }]",
            ),
            1000,
        ),
        (
            // Every parameter that may be drawn per sample drawn: each lane steps with its
            // own mass, footpads, contact law and crush strength.
            "mass, CG height, contact law and crush strength drawn",
            scenario(
                "[lander]\nmass_kg = { dist = \"uniform\", min = 70.0, max = 130.0 }\n\
                 cg_height_m = { dist = \"uniform\", min = 0.33, max = 0.53 }\n\
                 [surface]\nstiffness_n_per_m = { dist = \"uniform\", min = 1.0e4, max = 1.0e5 }\n\
                 damping_n_s_per_m = { dist = \"uniform\", min = 0.0, max = 2000.0 }\n\
                 friction_coefficient = { dist = \"uniform\", min = 0.2, max = 1.0 }\n\
                 [damper]\nenabled = true\n\
                 crush_strength_psi = { dist = \"uniform\", min = 2.0, max = 60.0 }",
            ),
            1000,
        ),
        (
            // Each lane in its own gravity (a landing site's, `touchdown site`), with
            // dampers and regolith, whose cartridges and soil weight read it too.
            "gravity drawn, dampers, regolith",
            scenario(
                "gravity_m_s2 = { dist = \"uniform\", min = 0.004, max = 0.06 }\n\
                 [surface]\nkind = \"regolith\"\n[damper]\nenabled = true",
            ),
            600,
        ),
        (
            // Each lane on the terrain at its own roughness (tiles of the largest, scaled).
            "roughness drawn",
            scenario(
                "[surface.roughness]\nrms_height_m = { dist = \"uniform\", min = 0.0, max = 0.03 }",
            ),
            600,
        ),
        (
            // Regolith: footpads sink into the loading curve, spring back on the unloading
            // line, leave footprints and meet the passive earth pressure when they slide.
            "regolith",
            scenario("[surface]\nkind = \"regolith\""),
            600,
        ),
        (
            // Every soil parameter and the footpad area drawn, soft to stiffening soils.
            "regolith, soil drawn",
            scenario(
                "[lander]\nfootpad_area_m2 = { dist = \"uniform\", min = 0.01, max = 0.08 }\n\
                 [surface]\nkind = \"regolith\"\n[surface.regolith]\n\
                 bekker_k_c = { dist = \"uniform\", min = 0.0, max = 3000.0 }\n\
                 bekker_k_phi = { dist = \"uniform\", min = 1.0e5, max = 2.0e6 }\n\
                 bekker_n = { dist = \"uniform\", min = 0.6, max = 1.3 }\n\
                 unloading_modulus_pa_per_m = { dist = \"uniform\", min = 4.0e6, max = 4.0e7 }\n\
                 cohesion_pa = { dist = \"uniform\", min = 0.0, max = 1000.0 }\n\
                 friction_angle_deg = { dist = \"uniform\", min = 20.0, max = 45.0 }\n\
                 bulk_density_kg_m3 = { dist = \"uniform\", min = 500.0, max = 2000.0 }",
            ),
            600,
        ),
        (
            // Regolith with dampers: the crushing relieves the soil along its unloading line.
            "regolith and dampers 50 psi",
            scenario("[surface]\nkind = \"regolith\"\n[damper]\nenabled = true"),
            400,
        ),
        (
            // Rocks drawn per sample (the tiles of the largest abundance, thinned): footpads
            // land on them, strike their sides, and the lander starts above them.
            "rocks, abundance drawn",
            scenario("[surface.rocks]\nabundance = { dist = \"uniform\", min = 0.02, max = 0.2 }"),
            400,
        ),
        (
            // Rocks on regolith: a footpad on a rock meets the elastic law, off it the soil.
            "rocks on regolith",
            scenario("[surface]\nkind = \"regolith\"\n[surface.rocks]\nabundance = 0.15"),
            300,
        ),
        (
            // Stiff contact, slopes past the friction angle: the early `sliding` and
            // `bouncing` rules fire (in about 8 % of the samples).
            "MuJoCo-matched",
            scenario_file("mujoco-matched"),
            1000,
        ),
        (
            // Thrusters and a control loop: attitude hold through a stepped fall, sampled
            // hold-down thrust at contact, sensor noise and bias, thruster errors.
            "hold-down and attitude hold",
            scenario_file("hold-down"),
            400,
        ),
        (
            // The final burn: a descent braked by the loop and released into the fall.
            "descent",
            scenario_file("descent"),
            200,
        ),
        (
            // The contact step's error control (MODEL.md section 2.1): each lane halves and
            // doubles its own step, lands within `step_min_s` of a contact, and scales its
            // kicks where the step changes.
            "error control",
            scenario("[simulation]\ntolerance_m_s = 1e-4"),
            1000,
        ),
        (
            "error control, MuJoCo-matched",
            controlled(scenario_file("mujoco-matched")),
            600,
        ),
        (
            "error control, regolith and dampers 50 psi",
            scenario(
                "[surface]\nkind = \"regolith\"\n[damper]\nenabled = true\n\
                 [simulation]\ntolerance_m_s = 1e-4",
            ),
            300,
        ),
        (
            "error control, rough, rocks",
            scenario(
                "[surface.roughness]\nrms_height_m = 0.02\n[surface.rocks]\nabundance = 0.1\n\
                 [simulation]\ntolerance_m_s = 1e-4",
            ),
            300,
        ),
        (
            // Control events cut the steps: the error control measures none shorter than
            // `step_min_s`.
            "error control, hold-down",
            controlled(scenario_file("hold-down")),
            300,
        ),
    ];
    // Totals per kernel, passive scenarios apart from those with a control loop.
    let mut totals: Vec<((KernelKind, bool), [u64; 4])> = Vec::new();
    for (name, s, n) in &cases {
        let controlled = s.control.is_some();
        for (isa, counts) in compare(name, s, *n) {
            match totals.iter_mut().find(|(i, _)| *i == (isa, controlled)) {
                Some((_, t)) => t.iter_mut().zip(counts).for_each(|(a, b)| *a += b),
                None => totals.push(((isa, controlled), counts)),
            }
        }
    }
    for ((kernel, controlled), [total, disagree, unexplained, drifted]) in totals {
        let isa = format!(
            "{}{}",
            kernel.name(),
            if controlled { ", control loops" } else { "" }
        );
        println!(
            "kernel {isa}: {total} samples, {disagree} disagreements, {unexplained} unexplained, {drifted} drifted"
        );
        // f64 lanes round as the reference does, up to the order of sums: few samples
        // drift (4-7 of 8600; 1 of the 600 with a control loop, by a strut load; with the
        // regolith and rock scenarios 11-17 of 10900). f32
        // lanes round 2^29 times coarser, and a lander's bounces amplify it: measured
        // 3.6-3.7 % (252-257 of 7000) drift in f32 in the three instruction sets, and with
        // the strut loads' peaks compared (issue 30) 4.3-4.4 % (374-375 of 8600); with the
        // regolith and rock scenarios and their footprints 4.3-4.4 % (466-477 of 10900;
        // 10-17 of them in f64). A defect of the f32 lanes (a
        // constant rounded to 0, a threshold lost) shifts results in most samples that
        // meet it, not a few percent. A control loop in f32 amplifies more: every control
        // instant quantises on-times to minimum impulse bits, and a rounding that moves a
        // sensed value across a quantisation step changes a firing by a whole bit, then
        // the loop works from another state; a descent makes 300 such decisions before
        // the fall. Measured in f32 with AVX2 and SSE2: 49-52 of the 400 hold-down samples
        // and 119 of the 200 descent samples drift (28-29 %), with their outcomes agreeing
        // but for one sample each near a threshold. Bound: 2 in 5, a regression to
        // drifting everywhere still fails.
        let (limit, of) = match (kernel.precision, controlled) {
            (Precision::F64, _) => (1, 50),
            (Precision::F32, false) => (1, 20),
            (Precision::F32, true) => (2, 5),
        };
        assert!(
            drifted * of <= limit * total,
            "kernel {isa}: {drifted} of {total} samples drifted: more than {limit}/{of}"
        );
        assert_eq!(
            unexplained, 0,
            "kernel {isa}: every outcome disagreement must sit at a decision threshold"
        );
        assert!(
            disagree * 200 <= total,
            "kernel {isa}: {disagree} of {total} outcomes disagree: more than 0.5 % is not rounding"
        );
    }
}
