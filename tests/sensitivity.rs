//! Saltelli's design in a sweep (`design = "sobol-indices"`) and `touchdown sensitivity` on
//! it: the rows of each block are A, B and A with one input from B; the indices rank the
//! inputs as the statics of the gear says they must; bad use is refused.

use crate::common::{SET_DOWN, TempDir, arrow_column, set_down_lines, touchdown};

/// Landers set down (no fall, no errors) at any yaw on slopes of 0-70 deg, past the default
/// gear's static limit (44.7 deg with a side downhill, 54.4 with a leg downhill, MODEL.md
/// section 8), with friction high enough that none slides: whether it stands is the slope's
/// doing above all, the yaw's (which side faces downhill) where the slope is between the two
/// limits, and a drop of at most 2 mm changes little. The three are drawn; the rest fixed.
fn design() -> String {
    let set_down = set_down_lines!("{ dist = \"uniform\", min = 0.0, max = 0.002 }", "0.0");
    format!(
        "design = \"sobol-indices\"\n[surface]\nfriction_coefficient = 1.5\n[inputs]\n\
         slope_deg = {{ dist = \"uniform\", min = 0.0, max = 70.0 }}\n\
         downhill_azimuth_deg = 0.0\n\
         yaw_deg = {{ dist = \"uniform\", min = 0.0, max = 360.0 }}\n\
         {set_down}\
         [initial]\nattitude_reference = \"surface\"\nclearance_m = 1.0e-6\n\
         [simulation]\nt_max_s = 40.0\n"
    )
}

/// Column `name` of a sweep file.
fn column(path: &std::path::Path, name: &str) -> Vec<f64> {
    arrow_column(path, name).expect("the column")
}

#[test]
fn the_design_varies_one_input_per_row_and_the_indices_rank_slope_first() {
    let dir = TempDir::new("sensitivity");
    dir.write("design.toml", &design());
    // 3 inputs drawn: blocks of 5 samples; 600 base points.
    touchdown(
        dir.path(),
        &[
            "sweep",
            "--quiet",
            "--scenario",
            "design.toml",
            "--samples",
            "3000",
            "--out",
            "d.arrow",
        ],
    );
    assert!(dir.join("d.arrow").is_file());
    // In the order of the sweep's input columns.
    let names = ["slope_deg", "release_height_m", "yaw_deg"];
    let cols: Vec<Vec<f64>> = names
        .iter()
        .map(|n| column(&dir.join("d.arrow"), n))
        .collect();
    for base in 0..600 {
        let row = |m: usize| -> Vec<f64> { cols.iter().map(|c| c[5 * base + m]).collect() };
        let (a, b) = (row(0), row(1));
        assert!(
            a.iter().zip(&b).all(|(x, y)| x != y),
            "A and B are independent draws"
        );
        for q in 0..3 {
            let ab = row(2 + q);
            for k in 0..3 {
                let want = if k == q { b[k] } else { a[k] };
                assert_eq!(ab[k], want, "base {base}, AB_{q}, {}", names[k]);
            }
        }
    }
    let run = touchdown(
        dir.path(),
        &[
            "sensitivity",
            "d.arrow",
            "--bootstrap",
            "300",
            "--png",
            "d.png",
        ],
    );
    run.assert_ok();
    // The bar chart: 4 panels of 3 inputs, each with a blue (first-order) and an orange
    // (total) bar; the slope's bars are long, so both colours cover many pixels.
    let png = image::open(dir.join("d.png")).expect("a PNG").to_rgb8();
    assert_eq!(png.dimensions(), (1400, 60 + 2 * (110 + 26 * 3)));
    let count = |c: [u8; 3]| png.pixels().filter(|p| p.0 == c).count();
    let (blue, orange) = (count([31, 119, 180]), count([255, 127, 14]));
    assert!(blue > 5000 && orange > 5000, "blue {blue}, orange {orange}");
    let report = &run.stdout;
    assert!(report.contains("600 base points"), "{report}");
    // The rows of the P(stable) table: input, S, interval, ST, interval.
    let table: Vec<(String, f64, f64)> = report
        .split("## P(stable)")
        .nth(1)
        .expect("a P(stable) section")
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| input"))
        .take(3)
        .map(|l| {
            let f: Vec<&str> = l.split('|').map(str::trim).collect();
            (
                f[1].to_string(),
                f[2].parse().unwrap(),
                f[4].parse().unwrap(),
            )
        })
        .collect();
    println!("{report}");
    let get = |n: &str| {
        table
            .iter()
            .find(|r| r.0 == n)
            .unwrap_or_else(|| panic!("{n}"))
    };
    let (slope, yaw, drop) = (get("slope_deg"), get("yaw_deg"), get("release_height_m"));
    // Standing or not is mostly the slope's: below 44.7 deg all stand, above 54.4 none, so
    // the slope alone explains most of the variance of a 0/1 outcome whose mean is near
    // 0.7. The yaw matters only between the limits (about 14 % of the slopes): its total
    // index is small but real. A 2 mm drop barely matters.
    assert!(slope.1 > 0.6 && slope.2 > 0.6, "slope: {slope:?}");
    assert!(yaw.2 < slope.2 && yaw.2 > 0.01, "yaw: {yaw:?}");
    assert!(drop.2 < 0.1, "drop: {drop:?}");
}

#[test]
fn the_design_flag_and_the_sobol_sequence() {
    let dir = TempDir::new("design-flag");
    dir.write(
        "plain.toml",
        "[surface]\nfriction_coefficient = { dist = \"uniform\", min = 0.3, max = 0.9 }\n\
         [simulation]\nt_max_s = 5.0\n",
    );
    // --design sobol-indices on a scenario without the key: the file stores the design
    // with the scenario, and `sensitivity` takes it.
    let sweep = |design: &str, out: &str, samples: &str| {
        touchdown(
            dir.path(),
            &[
                "sweep",
                "--quiet",
                "--scenario",
                "plain.toml",
                "--design",
                design,
                "--samples",
                samples,
                "--out",
                out,
            ],
        )
    };
    let run = sweep("sobol-indices", "i.arrow", "140");
    assert!(dir.join("i.arrow").is_file(), "{run}");
    // 11 inputs and the friction drawn: blocks of 14; row 2 + 11 is A with B's friction.
    let mu = column(&dir.join("i.arrow"), "friction_coefficient");
    let slope = column(&dir.join("i.arrow"), "slope_deg");
    assert_eq!((mu[13], slope[13]), (mu[1], slope[0]));
    let run = touchdown(dir.path(), &["sensitivity", "i.arrow", "--bootstrap", "50"]);
    run.assert_ok();
    assert!(run.stdout.contains("| friction_coefficient |"), "{run}");

    // The scrambled Sobol sequence: its first 2^m points put one value of each drawn input
    // in each of 2^m equal slices of its range (independent draws leave about 37 % of the
    // slices empty).
    let run = sweep("sobol-sequence", "q.arrow", "64");
    assert!(dir.join("q.arrow").is_file(), "{run}");
    for (name, lo, hi) in [("slope_deg", 0.0, 45.0), ("friction_coefficient", 0.3, 0.9)] {
        let x = column(&dir.join("q.arrow"), name);
        let mut slices: Vec<usize> = x
            .iter()
            .map(|v| ((v - lo) / (hi - lo) * 64.0) as usize)
            .collect();
        slices.sort_unstable();
        assert_eq!(slices, (0..64).collect::<Vec<_>>(), "{name}");
    }
    // The same sweep again: the same bits (a pure function of seed and index).
    sweep("sobol-sequence", "q2.arrow", "64");
    assert_eq!(
        column(&dir.join("q.arrow"), "slope_deg"),
        column(&dir.join("q2.arrow"), "slope_deg")
    );

    // A design the scenario cannot run is refused, naming the flag.
    dir.write(
        "grid.toml",
        "[inputs]\nslope_deg = { dist = \"grid\", min = 0.0, max = 10.0, count = 3 }\n",
    );
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--scenario",
            "grid.toml",
            "--design",
            "sobol-sequence",
            "--out",
            "g.arrow",
        ],
    );
    assert_eq!(run.code, Some(2), "{run}");
    assert!(
        run.stderr.contains("--design sobol-sequence") && run.stderr.contains("is a grid"),
        "{run}"
    );
    assert!(!dir.join("g.arrow").exists());
}

#[test]
fn sensitivity_refuses_a_sweep_without_the_design() {
    let dir = TempDir::new("sensitivity-refused");
    dir.write("plain.toml", "[simulation]\nt_max_s = 5.0\n");
    touchdown(
        dir.path(),
        &[
            "sweep",
            "--quiet",
            "--scenario",
            "plain.toml",
            "--samples",
            "16",
            "--out",
            "p.arrow",
        ],
    );
    assert!(dir.join("p.arrow").is_file());
    let run = touchdown(dir.path(), &["sensitivity", "p.arrow"]);
    assert_eq!(run.code, Some(2), "{run}");
    assert!(
        run.stderr
            .contains("was not run with design = \"sobol-indices\""),
        "{run}"
    );
    // A design over a grid, or over fixed inputs only, is refused before any work.
    for (text, message) in [
        (
            "design = \"sobol-indices\"\n[inputs]\nslope_deg = { dist = \"grid\", min = 0.0, max = 10.0, count = 3 }\n",
            "inputs.slope_deg is a grid",
        ),
        (
            &*format!(
                "design = \"sobol-indices\"\n[inputs]\nslope_deg = 5.0\ndownhill_azimuth_deg = 0.0\n{SET_DOWN}"
            ),
            "every input is fixed",
        ),
        ("design = \"saltelli\"\n", "design"),
    ] {
        dir.write("bad.toml", text);
        let run = touchdown(
            dir.path(),
            &["sweep", "--scenario", "bad.toml", "--out", "b.arrow"],
        );
        assert_eq!(run.code, Some(2), "{run}");
        assert!(run.stderr.contains(message), "{message}: {run}");
        assert!(!dir.join("b.arrow").exists());
    }
}

#[test]
fn sensitivity_says_a_file_is_an_interrupted_sweep() {
    let dir = TempDir::new("sensitivity-interrupted");
    dir.write("d.toml", &design());
    let (code, stderr) = crate::interrupt::interrupt(
        &dir,
        &[
            "sweep",
            "--scenario",
            "d.toml",
            "--samples",
            "300000",
            "--out",
            "s.arrow",
        ],
        "s.arrow",
        "INT",
    );
    assert_eq!(code, Some(130), "{stderr}");
    let run = touchdown(
        dir.path(),
        &["sensitivity", "s.arrow.interrupted", "--bootstrap", "20"],
    );
    assert_eq!(run.code, Some(0), "{run}");
    assert!(
        run.stdout.contains(
            " of 300,000 samples: an interrupted sweep; `touchdown sweep --resume s.arrow` \
             finishes it"
        ),
        "{run}"
    );
}
