//! The ground through the command line (MODEL.md sections 4 and 5.1): a sweep on regolith
//! writes each leg's footprint and the energy the soil kept, and the soil's drawn values;
//! one on the elastic plane writes none of them; a sample's sweep row is its reference run.

use crate::common::{BadInput, TempDir, arrow_column, bad_scenario, check_bad_input, touchdown};
use touchdown::reference::{self, Model};
use touchdown::scenario::Scenario;

const REGOLITH: &str = "[surface]\nkind = \"regolith\"\n[surface.regolith]\n\
    cohesion_pa = { dist = \"uniform\", min = 0.0, max = 500.0 }\n\
    bekker_n = { dist = \"uniform\", min = 0.8, max = 1.2 }\n";

/// Sweeps `samples` samples of `REGOLITH` into `r.arrow` and 50 of the default scenario
/// (the elastic plane) into `e.arrow`, in `dir`.
fn regolith_and_elastic(dir: &TempDir, samples: &str) {
    dir.write("regolith.toml", REGOLITH);
    for (args, out) in [
        (
            &["--scenario", "regolith.toml", "--samples", samples][..],
            "r.arrow",
        ),
        (&["--samples", "50"][..], "e.arrow"),
    ] {
        let run = touchdown(
            dir.path(),
            &[&["sweep", "--quiet", "--out", out], args].concat(),
        );
        assert_eq!(run.code, Some(0), "{run}");
    }
}

#[test]
fn a_regolith_sweep_writes_footprints_and_the_soil_s_values() {
    let dir = TempDir::new("ground-regolith-sweep");
    regolith_and_elastic(&dir, "300");
    let r = dir.join("r.arrow");
    let e = dir.join("e.arrow");
    let scenario = Scenario::from_toml(REGOLITH).unwrap();
    let model = Model::new(&scenario);
    let deepest = arrow_column(&r, "max_penetration_m").unwrap();
    for k in 0..4 {
        let sinkage = arrow_column(&r, &format!("leg{k}_sinkage_m")).unwrap();
        let energy = arrow_column(&r, &format!("leg{k}_soil_absorbed_j")).unwrap();
        // A footprint is never deeper than the deepest penetration, and never negative; a
        // footpad that touched left energy in the soil.
        for (i, ((z, e), d)) in sinkage.iter().zip(&energy).zip(&deepest).enumerate() {
            assert!(
                *z >= 0.0 && *z <= d + 1e-12,
                "sample {i} leg {k}: sinkage {z}, deepest {d}"
            );
            assert!(*e >= 0.0, "sample {i} leg {k}: energy {e}");
        }
        assert!(
            sinkage.iter().any(|z| *z > 1e-4),
            "leg {k}: no footprint deeper than 0.1 mm"
        );
        assert!(arrow_column(&e, &format!("leg{k}_sinkage_m")).is_none());
        // The sweep's rows are the reference's (f64 lanes: within the agreement test's 1 %).
        for i in [0u64, 7, 123] {
            let sample = touchdown::sampling::sample(&scenario, i);
            let s = reference::run(&model.for_sample(&sample), &sample, |_| {});
            let (a, b) = (s.legs[k].sinkage_m, sinkage[i as usize]);
            assert!(
                (a - b).abs() <= 0.01 * a.max(1e-4),
                "sample {i} leg {k}: {a} vs {b}"
            );
            let (a, b) = (s.legs[k].soil_absorbed_j, energy[i as usize]);
            assert!(
                (a - b).abs() <= 0.01 * a.max(1e-3),
                "sample {i} leg {k}: {a} vs {b}"
            );
        }
    }
    for name in ["cohesion_pa", "bekker_n"] {
        let v = arrow_column(&r, name).unwrap();
        assert!(
            v.iter().any(|x| (*x - v[0]).abs() > 1e-9),
            "{name} drawn: {v:?}"
        );
        assert!(arrow_column(&e, name).is_none());
    }
    assert!(
        arrow_column(&r, "bekker_k_phi").is_none(),
        "fixed: no column"
    );
}

#[test]
fn a_regolith_report_gives_the_footprints_and_the_soil_s_energy() {
    // Per sample the deepest leg's footprint (mm) and the energy all legs' soil kept:
    // the report's mean and largest of each are those of the file's columns; a sweep on
    // the elastic plane has no such section.
    let dir = TempDir::new("ground-regolith-report");
    regolith_and_elastic(&dir, "200");
    let r = dir.join("r.arrow");
    let legs: Vec<[Vec<f64>; 2]> = (0..4)
        .map(|k| {
            ["sinkage_m", "soil_absorbed_j"]
                .map(|c| arrow_column(&r, &format!("leg{k}_{c}")).unwrap())
        })
        .collect();
    let n = legs[0][0].len();
    let deepest: Vec<f64> = (0..n)
        .map(|i| 1e3 * legs.iter().map(|l| l[0][i]).fold(0.0, f64::max))
        .collect();
    let kept: Vec<f64> = (0..n).map(|i| legs.iter().map(|l| l[1][i]).sum()).collect();
    let json = touchdown(dir.path(), &["report", "r.arrow", "--json"]);
    json.assert_ok();
    let j: serde_json::Value = serde_json::from_str(&json.stdout).unwrap();
    for (key, values) in [("sinkage_mm", &deepest), ("soil_absorbed_j", &kept)] {
        let q = &j["regolith"][key];
        let mean = values.iter().sum::<f64>() / n as f64;
        let max = values.iter().copied().fold(0.0, f64::max);
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1.0);
        assert!(
            close(q["mean"].as_f64().unwrap(), mean),
            "{key}: {q} against {mean}"
        );
        assert!(
            close(q["max"].as_f64().unwrap(), max),
            "{key}: {q} against {max}"
        );
        assert!(max > 0.0, "{key}: none in the soil");
    }
    let markdown = touchdown(dir.path(), &["report", "r.arrow"]);
    markdown.assert_ok();
    let max = deepest.iter().copied().fold(0.0, f64::max);
    let row = "| footprint depth once unloaded (deepest leg) (mm) |";
    let line = markdown.stdout.lines().find(|l| l.starts_with(row));
    assert!(
        markdown.stdout.contains("\n## Regolith\n")
            && line.is_some_and(|l| l.ends_with(&format!(" {max:.4} |"))),
        "{markdown}"
    );
    let elastic = touchdown(dir.path(), &["report", "e.arrow"]);
    elastic.assert_ok();
    assert!(!elastic.stdout.contains("Regolith"), "{elastic}");
}

/// Gentle level touchdowns on regolith: a fall of 0.05-0.15 m/s (`sqrt(2 g h)`) onto
/// level ground, no velocity errors, the default attitude errors and rates.
const GENTLE: &str = "[surface]\nkind = \"regolith\"\n\
    [surface.regolith]\n{SOIL}\n\
    [inputs]\nslope_deg = 0.0\n\
    release_height_m = { dist = \"uniform\", min = 0.0744, max = 0.670 }\n\
    velocity_error_x_m_s = 0.0\nvelocity_error_y_m_s = 0.0\nvelocity_error_z_m_s = 0.0\n\
    [simulation]\nt_max_s = 60.0\n";

#[test]
fn soils_of_any_exponent_and_unloading_modulus_never_give_energy() {
    // 400 gentle touchdowns on soils with n drawn on 0.5-1.3 and k_u on 3e5-8e6 Pa/m
    // (MODEL.md 5.1's range of n; k_u below and up to the default): no leg's soil keeps a
    // negative energy, and no more landers end `bouncing` than on the default soil (n = 1,
    // k_u = 8e6), the same samples: none. With an unloading line of slope A k_u alone,
    // 578 of the 1,600 legs' energies were negative (down to -0.35 J) and 138 landers
    // ended bouncing.
    let dir = TempDir::new("ground-soil-energy");
    let drawn = "bekker_n = { dist = \"uniform\", min = 0.5, max = 1.3 }\n\
                 unloading_modulus_pa_per_m = { dist = \"uniform\", min = 3.0e5, max = 8.0e6 }";
    dir.write("drawn.toml", &GENTLE.replace("{SOIL}", drawn));
    dir.write(
        "default.toml",
        &GENTLE.replace(
            "{SOIL}",
            "bekker_n = 1.0\nunloading_modulus_pa_per_m = 8.0e6",
        ),
    );
    for name in ["drawn", "default"] {
        let run = touchdown(
            dir.path(),
            &[
                "sweep",
                "--quiet",
                "--scenario",
                &format!("{name}.toml"),
                "--samples",
                "400",
                "--out",
                &format!("{name}.arrow"),
            ],
        );
        assert_eq!(run.code, Some(0), "{run}");
    }
    let bounces = |name: &str| {
        let file = std::fs::File::open(dir.join(&format!("{name}.arrow"))).unwrap();
        let mut n = 0;
        for b in arrow_ipc::reader::FileReader::try_new(file, None).unwrap() {
            let b = b.unwrap();
            let o = b.column_by_name("outcome").unwrap();
            n += crate::common::texts(o.as_ref())
                .iter()
                .filter(|o| *o == "bouncing")
                .count();
        }
        n
    };
    let drawn = dir.join("drawn.arrow");
    let mut negative = Vec::new();
    for k in 0..4 {
        let energy = arrow_column(&drawn, &format!("leg{k}_soil_absorbed_j")).unwrap();
        negative.extend(
            energy
                .iter()
                .enumerate()
                .filter(|(_, e)| **e < 0.0)
                .map(|(i, e)| (i, k, *e)),
        );
    }
    assert!(
        negative.is_empty(),
        "{} legs kept a negative energy (sample, leg, J): {:?}",
        negative.len(),
        &negative[..negative.len().min(10)]
    );
    assert!(
        bounces("drawn") <= bounces("default"),
        "{} landers bounced on the drawn soils, {} on the default",
        bounces("drawn"),
        bounces("default")
    );
}

#[test]
fn a_regolith_trace_prints_the_footprints_of_its_sweep_row() {
    let dir = TempDir::new("ground-regolith-trace");
    dir.write("regolith.toml", REGOLITH);
    let sweep = touchdown(
        dir.path(),
        &[
            "sweep",
            "--quiet",
            "--scenario",
            "regolith.toml",
            "--samples",
            "16",
            "--out",
            "r.arrow",
        ],
    );
    assert_eq!(sweep.code, Some(0), "{sweep}");
    let trace = touchdown(
        dir.path(),
        &[
            "trace",
            "--scenario",
            "regolith.toml",
            "--sample",
            "5",
            "--out",
            "t.arrow",
        ],
    );
    assert_eq!(trace.code, Some(0), "{trace}");
    assert!(
        trace.stdout.contains("footprint mm   soil kept J"),
        "{trace}"
    );
    for k in 0..4 {
        // The printout rounds to a micrometre and 0.1 mJ; the sweep (f64 lanes) agrees with
        // the reference within 1 % (tests/agreement.rs).
        let z = arrow_column(&dir.join("r.arrow"), &format!("leg{k}_sinkage_m")).unwrap()[5];
        let row = trace
            .stdout
            .lines()
            .find(|l| {
                l.trim_start().starts_with(&format!("{k} ")) && l.split_whitespace().count() == 6
            })
            .unwrap_or_else(|| panic!("leg {k} row in {trace}"));
        let printed: f64 = row.split_whitespace().nth(4).unwrap().parse().unwrap();
        assert!(
            (printed - z * 1e3).abs() <= 1e-3 + 0.01 * z * 1e3,
            "leg {k}: {printed} mm, sweep {z}"
        );
    }
    let elastic = touchdown(dir.path(), &["trace", "--sample", "5", "--out", "e.arrow"]);
    assert!(!elastic.stdout.contains("footprint"), "{elastic}");
}

/// Bad grounds: each refused with exit 2, naming the key and what it allows.
const BAD_GROUNDS: &[BadInput] = &[
    bad_scenario(
        "regolith table on the elastic plane",
        "[surface.regolith]\nbekker_n = 1.1\n",
        &[
            "`surface.regolith`",
            "no [surface.regolith] table unless surface.kind = \"regolith\"",
        ],
    ),
    bad_scenario(
        "unknown surface kind",
        "[surface]\nkind = \"sand\"\n",
        &["`surface.kind`", "one of \"elastic\", \"regolith\""],
    ),
    bad_scenario(
        "misspelt regolith key",
        "[surface]\nkind = \"regolith\"\n[surface.regolith]\nbekker_kphi = 1.0e5\n",
        &[
            "`surface.regolith.bekker_kphi` is unknown",
            "did you mean `bekker_k_phi`?",
        ],
    ),
    bad_scenario(
        "regolith exponent of 0",
        "[surface]\nkind = \"regolith\"\n[surface.regolith]\nbekker_n = 0.0\n",
        &["`surface.regolith.bekker_n`", "greater than 0"],
    ),
    bad_scenario(
        "regolith friction angle of 90 deg",
        "[surface]\nkind = \"regolith\"\n[surface.regolith]\nfriction_angle_deg = { dist = \"uniform\", min = 30.0, max = 90.0 }\n",
        &[
            "`surface.regolith.friction_angle_deg`",
            "an angle below 90 deg",
        ],
    ),
    bad_scenario(
        "regolith that bears nothing",
        "[surface]\nkind = \"regolith\"\n[surface.regolith]\nbekker_k_c = 0.0\nbekker_k_phi = 0.0\n",
        &["`surface.regolith.bekker_k_phi`", "a soil that bears"],
    ),
    bad_scenario(
        "footpad area of 0",
        "[lander]\nfootpad_area_m2 = 0.0\n",
        &["`lander.footpad_area_m2`", "greater than 0"],
    ),
];

#[test]
fn bad_ground_is_refused_with_a_message_naming_the_key() {
    let failures: Vec<String> = BAD_GROUNDS
        .iter()
        .flat_map(|case| check_bad_input("sweep", case, &["samples"]))
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
