//! Scenario parameters drawn per sample (`Scenario::sampled`): a sample with a drawn value
//! runs exactly as the same sample of a scenario that fixes that value, in the kernels and
//! in the reference; the drawn values come out as columns; bad draws are refused.

use crate::common::{TempDir, arrow_column as column, touchdown};
use touchdown::reference::{self, Model};
use touchdown::sampling;
use touchdown::scenario::{Parameter, Scenario};
use touchdown::sweep;

/// Every parameter drawn, over ranges that keep the default lander landing in every way it
/// can (stable, tipped, sliding at the low frictions, crushing its dampers at the low crush
/// strengths), on the default slopes and attitudes.
const DRAWN: &str = "[lander]
mass_kg = { dist = \"uniform\", min = 70.0, max = 130.0 }
cg_height_m = { dist = \"normal\", mean = 0.43, sd = 0.04, min = 0.33, max = 0.53 }
[surface]
stiffness_n_per_m = { dist = \"uniform\", min = 1.0e4, max = 1.0e5 }
damping_n_s_per_m = { dist = \"uniform\", min = 0.0, max = 2000.0 }
friction_coefficient = { dist = \"uniform\", min = 0.2, max = 1.0 }
[damper]
enabled = true
crush_strength_psi = { dist = \"uniform\", min = 2.0, max = 60.0 }
[simulation]
t_max_s = 40.0
";

/// `text` with every drawn parameter fixed at `values` (indexed by `Parameter`), written
/// as numbers that read back to the same bits.
fn fixed(text: &str, values: &[f64]) -> String {
    let mut text = text.to_string();
    for p in Parameter::ALL {
        let Some(line) = text
            .lines()
            .find(|l| l.starts_with(&format!("{} = {{", p.name())))
            .map(str::to_string)
        else {
            continue;
        };
        text = text.replace(&line, &format!("{} = {:?}", p.name(), values[p as usize]));
    }
    text
}

#[test]
fn a_drawn_parameter_runs_as_the_same_value_fixed_row_for_row() {
    let drawn = Scenario::from_toml(DRAWN).expect("a valid scenario");
    assert_eq!(
        drawn.sampled.iter().filter(|d| d.is_some()).count(),
        6,
        "all six but the roughness drawn"
    );
    let model = Model::new(&drawn);
    let n = 48;
    let mut rows = Vec::new();
    sweep::run(&drawn, &model, 0..n, 16, |r| {
        rows.extend(r);
        Ok(())
    })
    .expect("the sweep runs");
    assert_eq!(rows.len() as u64, n);
    let mut outcomes = std::collections::BTreeSet::new();
    let mut crushed = 0;
    for row in &rows {
        let i = row.sample.index;
        let values = row.sample.parameters;
        // Each value drawn from its own distribution's support...
        for p in Parameter::ALL {
            let Some(dist) = drawn.sampled[p as usize] else {
                continue;
            };
            let (lo, hi) = dist.support();
            let x = values[p as usize];
            assert!((lo..=hi).contains(&x), "sample {i}: {} = {x}", p.name());
        }
        // ...and the sample of the scenario that fixes those values is the same sample: the
        // inputs (their streams do not depend on the parameters) and, in the kernels and in
        // the reference, every result, bit for bit.
        let one = Scenario::from_toml(&fixed(DRAWN, &values)).expect("the fixed scenario");
        assert!(one.sampled.iter().all(Option::is_none));
        let one_model = Model::new(&one);
        let mut alone = Vec::new();
        sweep::run(&one, &one_model, i..i + 1, 1, |r| {
            alone.extend(r);
            Ok(())
        })
        .expect("the sample runs alone");
        let (a, b) = (&row.sample, &alone[0].sample);
        assert_eq!(a.inputs, b.inputs, "sample {i}: inputs");
        assert_eq!(a.parameters, b.parameters, "sample {i}: parameters");
        assert_eq!(
            format!("{:?}", row.summary),
            format!("{:?}", alone[0].summary),
            "sample {i}: kernel results"
        );
        let s = sampling::sample(&drawn, i);
        assert_eq!(
            format!("{:?}", reference::run(&model, &s, |_| {})),
            format!("{:?}", reference::run(&one_model, &s, |_| {})),
            "sample {i}: reference results"
        );
        outcomes.insert(row.summary.outcome.name());
        crushed += usize::from(row.summary.legs.iter().any(|l| l.stroke_m > 0.0));
    }
    // The comparison means something only where the parameters act: several outcomes, and
    // dampers that crushed.
    assert!(outcomes.len() >= 2, "outcomes {outcomes:?}");
    assert!(crushed >= 5, "{crushed} samples crushed a damper");
}

#[test]
fn a_drawn_roughness_scales_the_terrain_to_the_same_value_fixed() {
    // The tiles are built once, for the largest roughness, and scaled to each sample's:
    // the same surface as tiles built for that value, up to rounding (both are the same
    // Gaussian field times a roughness over its own rms).
    let text =
        "[surface.roughness]\nrms_height_m = { dist = \"uniform\", min = 0.0, max = 0.03 }\n";
    let drawn = Scenario::from_toml(text).expect("a valid scenario");
    let model = Model::new(&drawn);
    assert!(model.terrain.is_some());
    for i in 0..20 {
        let s = sampling::sample(&drawn, i);
        let rms = s.parameters[Parameter::RmsHeightM as usize];
        assert!((0.0..=0.03).contains(&rms));
        let one_scenario = Scenario::from_toml(&fixed(text, &s.parameters)).unwrap();
        let one = Model::new(&one_scenario);
        // The same tile and offset: the terrain draws do not depend on the roughness.
        let t = sampling::sample(&one_scenario, i);
        assert_eq!(
            (s.terrain_tile, s.terrain_offset_m, s.inputs),
            (t.terrain_tile, t.terrain_offset_m, t.inputs)
        );
        let mine = model.for_sample(&s);
        let (a, b) = (
            mine.terrain.as_ref().unwrap(),
            one.terrain.as_ref().unwrap(),
        );
        for k in 0..50 {
            let (u, v) = (0.37 * f64::from(k), 0.11 * f64::from(k * k % 17));
            let (x, y) = (a.height(1, u, v), b.height(1, u, v));
            for (p, q) in [(x.0, y.0), (x.1, y.1), (x.2, y.2)] {
                assert!(
                    (p - q).abs() <= 1e-12 * (1.0 + q.abs()),
                    "sample {i}: {p} vs {q}"
                );
            }
        }
        assert!((a.height_max_m() - b.height_max_m()).abs() < 1e-12);
    }
}

#[test]
fn drawn_parameters_are_columns_and_bad_draws_are_refused() {
    let dir = TempDir::new("parameters");
    dir.write(
        "two.toml",
        "[surface]\nstiffness_n_per_m = { dist = \"uniform\", min = 2.0e4, max = 8.0e4 }\n\
         friction_coefficient = { dist = \"normal\", mean = 0.6, sd = 0.1, min = 0.3, max = 0.9 }\n\
         [simulation]\nt_max_s = 20.0\n",
    );
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--quiet",
            "--scenario",
            "two.toml",
            "--samples",
            "200",
            "--out",
            "a.arrow",
        ],
    );
    assert!(dir.join("a.arrow").is_file(), "{run}");
    let k = column(&dir.join("a.arrow"), "stiffness_n_per_m").expect("a stiffness column");
    let mu = column(&dir.join("a.arrow"), "friction_coefficient").expect("a friction column");
    assert_eq!((k.len(), mu.len()), (200, 200));
    assert!(k.iter().all(|x| (2.0e4..=8.0e4).contains(x)));
    assert!(mu.iter().all(|x| (0.3..=0.9).contains(x)));
    // Spread over the range: a uniform's sample mean is within 5 standard errors (1.7e4 /
    // sqrt(200) = 1.2e3) of the middle.
    let mean = k.iter().sum::<f64>() / 200.0;
    assert!((mean - 5.0e4).abs() < 5.0 * 1.2e3, "mean stiffness {mean}");
    // Only the drawn parameters are columns.
    assert!(column(&dir.join("a.arrow"), "mass_kg").is_none());
    // `trace` runs a sample with its drawn values, and shows them.
    let trace = touchdown(
        dir.path(),
        &[
            "trace",
            "--scenario",
            "two.toml",
            "--sample",
            "7",
            "--out",
            "t.arrow",
        ],
    );
    let k7 = format!("{:.6}", k[7]);
    assert!(
        trace.stdout.contains("stiffness_n_per_m") && trace.stdout.contains(&k7),
        "{trace}"
    );

    for (name, text, expect) in [
        (
            "a crush strength drawn without a damper",
            "[damper]\ncrush_strength_psi = { dist = \"uniform\", min = 30.0, max = 90.0 }\n",
            vec!["`damper.crush_strength_psi`", "damper.enabled = false"],
        ),
        (
            "a stiffness drawn below 0",
            "[surface]\nstiffness_n_per_m = { dist = \"uniform\", min = -1.0, max = 5.0 }\n",
            vec!["`surface.stiffness_n_per_m`", "values greater than 0"],
        ),
        (
            "an untruncated normal friction",
            "[surface]\nfriction_coefficient = { dist = \"normal\", mean = 0.6, sd = 0.1 }\n",
            vec!["`surface.friction_coefficient`", "give min and max"],
        ),
    ] {
        refused(&dir, name, text, &expect);
    }
}

#[test]
fn gravity_is_drawn_per_sample_and_each_lander_falls_in_its_own() {
    let dir = TempDir::new("gravity-drawn");
    // A vertical fall onto a flat plane: nothing else drawn.
    let fall = "[inputs]\nslope_deg = 0.0\nrelease_height_m = 1.0\nvelocity_error_x_m_s = 0.0\n\
                velocity_error_y_m_s = 0.0\nvelocity_error_z_m_s = 0.0\nroll_deg = 0.0\n\
                pitch_deg = 0.0\nrate_x_deg_s = 0.0\nrate_y_deg_s = 0.0\nrate_z_deg_s = 0.0\n";
    dir.write(
        "g.toml",
        &format!("gravity_m_s2 = {{ dist = \"uniform\", min = 0.005, max = 0.05 }}\n{fall}"),
    );
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--quiet",
            "--scenario",
            "g.toml",
            "--samples",
            "300",
            "--out",
            "g.arrow",
        ],
    );
    assert!(dir.join("g.arrow").is_file(), "{run}");
    let g = column(&dir.join("g.arrow"), "gravity_m_s2").expect("a gravity column");
    let v = column(&dir.join("g.arrow"), "touchdown_normal_speed_m_s").expect("speeds");
    assert!(g.iter().all(|x| (0.005..=0.05).contains(x)));
    // Released 1 m above initial.clearance_m = 1 mm, each lander meets the plane at
    // `sqrt(2 g (h + clearance))` of its own g (a tenfold range: a lane stepping in another
    // lane's gravity would be off by up to 3x). The column is the velocity at the start of
    // the step that touches, whose position the kick-drift integrator finds within a step
    // of the exact fall: off by at most one 1 ms step's `g dt` either way.
    for (i, (g, v)) in g.iter().zip(&v).enumerate() {
        let exact = (2.0 * g * 1.001).sqrt();
        assert!(
            (v - exact).abs() <= g * 1e-3,
            "sample {i}: g = {g}, v = {v}, expected {exact} within g dt"
        );
    }
    // `trace` runs a sample in its drawn gravity and shows it.
    let trace = touchdown(
        dir.path(),
        &[
            "trace",
            "--scenario",
            "g.toml",
            "--sample",
            "7",
            "--out",
            "t.arrow",
        ],
    );
    assert!(
        trace.stdout.contains("gravity_m_s2") && trace.stdout.contains(&format!("{:.6}", g[7])),
        "{trace}"
    );

    for (name, text, expect) in [
        (
            "a gravity drawn down to 0",
            "gravity_m_s2 = { dist = \"uniform\", min = 0.0, max = 0.05 }\n",
            vec!["`gravity_m_s2`", "a gravity greater than 0"],
        ),
        (
            "a gravity drawn with a control loop",
            "gravity_m_s2 = { dist = \"uniform\", min = 0.01, max = 0.05 }\n\
             [control.hold_down]\nthrust_n = 2.0\nduration_s = 5.0\n",
            vec!["`gravity_m_s2`", "control loop"],
        ),
    ] {
        refused(&dir, name, text, &expect);
    }
}

/// A sweep of the scenario `text` is refused with exit code 2, its message holding each of
/// `expect`, and writes no file.
fn refused(dir: &TempDir, name: &str, text: &str, expect: &[&str]) {
    dir.write("bad.toml", text);
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--quiet",
            "--scenario",
            "bad.toml",
            "--samples",
            "10",
            "--out",
            "bad.arrow",
        ],
    );
    assert_eq!(run.code, Some(2), "{name}: {run}");
    for e in expect {
        assert!(run.stderr.contains(e), "{name}: no {e:?} in {run}");
    }
    assert!(!dir.join("bad.arrow").exists(), "{name}");
}
