//! Studies that compare like with like: two sweeps of scenarios that differ in one input
//! draw the same values of every other input, sample by sample (common random numbers), and
//! `touchdown compare` counts what changed; a sweep file's row can be traced from the file
//! alone; the output format follows the extension of `--out`.

use crate::common::{SHORT, TempDir, read_bytes, touchdown};
use crate::sweep_cli::read_sweep;
use std::collections::BTreeMap;
use std::path::PathBuf;
use touchdown::reference::Outcome;
use touchdown::scenario::INPUT_FIELDS;

/// A study file of `scenarios/`.
fn study(name: &str) -> String {
    let path: PathBuf = [env!("CARGO_MANIFEST_DIR"), "scenarios", name]
        .iter()
        .collect();
    path.to_string_lossy().into_owned()
}

/// Runs `touchdown sweep` with `args` and `--quiet`, and checks that it succeeds.
fn sweep(dir: &TempDir, args: &[&str]) {
    let run = touchdown(dir.path(), &[&["sweep", "--quiet"], args].concat());
    assert_eq!(run.code, Some(0), "{run}");
}

#[test]
fn a_sweep_whose_landers_never_touch_says_so() {
    // Let go 0.5 m above the surface, rising at 0.2-0.3 m/s in 0.0168 m/s^2: back after
    // 24-36 s, beyond the 20 s run. The reach check of the scenario (the nominal landing,
    // no velocity error, touches after 7.7 s) lets it run; the sweep warns afterwards.
    let dir = TempDir::new("studies-untouched");
    dir.write(
        "up.toml",
        "[inputs]\nrelease_height_m = 0.0\n\
         velocity_error_z_m_s = { dist = \"uniform\", min = 0.2, max = 0.3 }\n\n\
         [initial]\nclearance_m = 0.5\n\n[simulation]\nt_max_s = 20.0\n",
    );
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--scenario",
            "up.toml",
            "--samples",
            "40",
            "--out",
            "up.arrow",
        ],
    );
    assert_eq!(run.code, Some(0), "{run}");
    assert!(
        run.stderr.contains(
            "touchdown: warning: 40 of the 40 samples run never touched the surface before \
             simulation.t_max_s = 20 s"
        ),
        "{run}"
    );
    assert!(
        run.stderr
            .contains("40 still in flight at the end (bouncing)")
            && !run.stderr.contains("turned past 90 deg"),
        "{run}"
    );
    let f = read_sweep(&dir.join("up.arrow"));
    assert!(f.strings("outcome").iter().all(|o| o == "bouncing"));
    // Landers spun over in the fall: tipped in flight, for another reason than a release
    // too high, and told so.
    dir.write(
        "spin.toml",
        "[initial]\nclearance_m = 3.0\n[inputs]\nrate_x_deg_s = 200.0\n\
         [simulation]\nt_max_s = 20.0\n",
    );
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--scenario",
            "spin.toml",
            "--samples",
            "40",
            "--out",
            "spin.arrow",
        ],
    );
    assert_eq!(run.code, Some(0), "{run}");
    assert!(
        run.stderr
            .contains("40 of the 40 samples run never touched the surface")
            && run.stderr.contains(
                "40 turned past 90 deg in flight (tipped) before reaching it: body rates"
            )
            && !run.stderr.contains("release too high"),
        "{run}"
    );
    // On a steep slope a lander released upright already leans from the ground's normal by
    // the slope (the tilt is taken from it): there the slope is named, not just the rates.
    dir.write(
        "steep.toml",
        "[initial]\nclearance_m = 3.0\n[inputs]\nslope_deg = 80.0\nrate_x_deg_s = 20.0\n\
         [simulation]\nt_max_s = 20.0\n",
    );
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--scenario",
            "steep.toml",
            "--samples",
            "40",
            "--out",
            "steep.arrow",
        ],
    );
    assert_eq!(run.code, Some(0), "{run}");
    assert!(
        run.stderr.contains(
            "40 turned past 90 deg in flight (tipped) before reaching it, all on slopes of \
             80.0 deg or more"
        ),
        "{run}"
    );
    // A descent braked on its profile from 15 m needs over a minute (scenarios/descent.toml
    // releases after 17-43 s and falls for 24-35 s more); cut to 40 s, the landers are
    // still in the powered descent at the end, or released and still falling: those in
    // the descent are told apart and pointed at the descent's keys (the run's reach
    // check, unbraked, lets it run).
    let descent = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/descent.toml"),
    )
    .unwrap()
    .replace("t_max_s = 150.0", "t_max_s = 40.0");
    dir.write("descent.toml", &descent);
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--scenario",
            "descent.toml",
            "--samples",
            "16",
            "--out",
            "descent.arrow",
        ],
    );
    assert_eq!(run.code, Some(0), "{run}");
    assert!(
        run.stderr
            .contains("16 of the 16 samples run never touched the surface")
            && run
                .stderr
                .contains("still in the powered descent at the end (bouncing), never released")
            && run.stderr.contains("control.descent.braking_m_s2"),
        "{run}"
    );
    // Landers that all touch: no warning.
    dir.write("s.toml", SHORT);
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--scenario",
            "s.toml",
            "--samples",
            "40",
            "--out",
            "s.arrow",
        ],
    );
    assert_eq!(run.code, Some(0), "{run}");
    assert!(!run.stderr.contains("warning"), "{run}");
}

/// The rows of the transition table of a `touchdown compare` report: outcome in A, then
/// the counts of each outcome in B.
fn transitions(report: &str) -> BTreeMap<String, Vec<u64>> {
    let table = report
        .split("## Samples by outcome in A (rows) and in B (columns)")
        .nth(1)
        .unwrap_or_else(|| panic!("no transition table in\n{report}"));
    table
        .lines()
        .filter_map(|l| {
            let cells: Vec<&str> = l.split('|').map(str::trim).collect();
            let name = *cells.get(1)?;
            Outcome::from_name(name)?;
            let counts = cells[2..cells.len() - 1]
                .iter()
                .map(|c| c.parse().unwrap_or_else(|_| panic!("cell {c:?} in {l:?}")))
                .collect();
            Some((name.to_string(), counts))
        })
        .collect()
}

#[test]
fn paired_studies_draw_the_same_other_inputs_and_compare_counts_what_changed() {
    let dir = TempDir::new("studies-paired");
    let n = 400;
    let samples = n.to_string();
    let common = ["--samples", &samples, "--seed", "3"];
    let (flat, rate) = (study("flat.toml"), study("flat-rate-y.toml"));
    sweep(
        &dir,
        &[&common[..], &["--scenario", &flat, "--out", "a.arrow"]].concat(),
    );
    sweep(
        &dir,
        &[&common[..], &["--scenario", &rate, "--out", "b.arrow"]].concat(),
    );
    let (a, b) = (
        read_sweep(&dir.join("a.arrow")),
        read_sweep(&dir.join("b.arrow")),
    );

    // flat-rate-y.toml differs from flat.toml only in rate_y_deg_s (fixed at 5 deg/s):
    // every other input, the sample seeds and the terrain draws are the same bits.
    for (name, _) in INPUT_FIELDS {
        let (x, y) = (a.f64s(name), b.f64s(name));
        if name == "rate_y_deg_s" {
            assert!(y.iter().all(|v| *v == 5.0), "rate_y_deg_s of flat-rate-y");
            assert!(
                x.iter().filter(|v| **v == 5.0).count() == 0,
                "rate_y_deg_s of flat"
            );
            continue;
        }
        let differ = (0..n).filter(|&i| x[i].to_bits() != y[i].to_bits()).count();
        assert_eq!(differ, 0, "{name}: {differ} of {n} samples differ");
    }
    assert_eq!(a.u64s("sample_seed"), b.u64s("sample_seed"));
    assert_eq!(a.u32s("terrain_tile"), b.u32s("terrain_tile"));

    // Max and final tilt come from the same states: the maximum is never below the end.
    for (file, f) in [("a.arrow", &a), ("b.arrow", &b)] {
        let (max, fin) = (f.f64s("max_tilt_deg"), f.f64s("final_tilt_deg"));
        let below: Vec<usize> = (0..n).filter(|&i| max[i] < fin[i]).collect();
        assert!(
            below.is_empty(),
            "{file}: max tilt below the final tilt in samples {below:?}"
        );
    }

    // The comparison's transition table holds the outcome pairs of the two files.
    let run = touchdown(dir.path(), &["compare", "a.arrow", "b.arrow"]);
    assert_eq!(run.code, Some(0), "{run}");
    // Passive sweeps: `held` is not listed.
    let names: Vec<&str> = Outcome::listed(false).map(Outcome::name).collect();
    let mut expected: BTreeMap<String, Vec<u64>> = names
        .iter()
        .map(|o| (o.to_string(), vec![0; names.len()]))
        .collect();
    let (oa, ob) = (a.strings("outcome"), b.strings("outcome"));
    for (x, y) in oa.iter().zip(&ob) {
        let column = names.iter().position(|o| o == y).unwrap();
        expected.get_mut(x).unwrap()[column] += 1;
    }
    assert_eq!(transitions(&run.stdout), expected, "{}", run.stdout);
    let changed = oa.iter().zip(&ob).filter(|(x, y)| x != y).count();
    assert!(
        run.stdout
            .contains(&format!("\n{changed} of {n} samples (")),
        "no count of the {changed} changed samples in\n{}",
        run.stdout
    );
    assert!(
        changed > 0,
        "a 5 deg/s rate about Y_B changed no outcome of {n}"
    );

    // Sweeps that are not the same landers are refused.
    let other_seed = ["--samples", &samples, "--seed", "4"];
    sweep(
        &dir,
        &[&other_seed[..], &["--scenario", &rate, "--out", "c.arrow"]].concat(),
    );
    sweep(
        &dir,
        &[
            "--samples",
            "200",
            "--seed",
            "3",
            "--scenario",
            &rate,
            "--out",
            "d.arrow",
        ],
    );
    with_engine(
        &dir.join("b.arrow"),
        &dir.join("e.arrow"),
        "touchdown 0.2.0",
    );
    for (other, expect) in [
        (
            "e.arrow",
            "e.arrow by touchdown 0.2.0: engines of other versions",
        ),
        ("c.arrow", "a.arrow has seed 3 and c.arrow seed 4"),
        ("d.arrow", "do not hold the same sample indices"),
        ("missing.arrow", "cannot read missing.arrow"),
    ] {
        let run = touchdown(dir.path(), &["compare", "a.arrow", other]);
        assert_eq!(run.code, Some(2), "{run}");
        assert!(run.stderr.contains(expect), "{run}");
    }
}

/// Copies the Arrow file `from` to `to` with `touchdown.engine` set to `engine`, as if
/// another version had written it.
fn with_engine(from: &std::path::Path, to: &std::path::Path, engine: &str) {
    let reader =
        arrow_ipc::reader::FileReader::try_new(std::fs::File::open(from).unwrap(), None).unwrap();
    let mut meta = reader.schema().metadata().clone();
    meta.insert("touchdown.engine".to_string(), engine.to_string());
    let schema = std::sync::Arc::new(reader.schema().as_ref().clone().with_metadata(meta));
    let file = std::fs::File::create(to).unwrap();
    let mut writer = arrow_ipc::writer::FileWriter::try_new(file, &schema).unwrap();
    for batch in reader {
        let columns = batch.unwrap().columns().to_vec();
        let batch = arrow_array::RecordBatch::try_new(schema.clone(), columns).unwrap();
        writer.write(&batch).unwrap();
    }
    writer.finish().unwrap();
}

#[test]
fn max_tilt_is_never_below_the_final_tilt() {
    // The default scenario tips most of its landers: before 0.2 the maximum was taken
    // before each step and the final value after the last, and most tipped rows had
    // max < final.
    let dir = TempDir::new("studies-tilt");
    dir.write("s.toml", SHORT);
    sweep(
        &dir,
        &[
            "--scenario",
            "s.toml",
            "--samples",
            "2000",
            "--out",
            "s.arrow",
        ],
    );
    let f = read_sweep(&dir.join("s.arrow"));
    let (max, fin) = (f.f64s("max_tilt_deg"), f.f64s("final_tilt_deg"));
    let tipped = f
        .strings("outcome")
        .iter()
        .filter(|o| *o == "tipped")
        .count();
    assert!(
        tipped > 1000,
        "only {tipped} of 2000 tipped: not the test it was"
    );
    let below: Vec<usize> = (0..max.len()).filter(|&i| max[i] < fin[i]).collect();
    assert!(
        below.is_empty(),
        "max tilt below the final tilt in samples {below:?}"
    );
}

#[test]
fn trace_of_a_sweep_file_refuses_what_it_cannot_trace() {
    let dir = TempDir::new("studies-trace-sweep");
    dir.write("s.toml", SHORT);
    sweep(
        &dir,
        &[
            "--scenario",
            "s.toml",
            "--samples",
            "50",
            "--seed",
            "7",
            "--out",
            "s.arrow",
        ],
    );
    let traced = touchdown(
        dir.path(),
        &[
            "trace", "--sweep", "s.arrow", "--sample", "49", "--out", "t.arrow",
        ],
    );
    assert_eq!(traced.code, Some(0), "{traced}");
    assert!(
        traced.stdout.starts_with("sample 49 of seed 7 "),
        "{traced}"
    );
    for (args, expect) in [
        (
            &["--sweep", "s.arrow", "--sample", "50"][..],
            "--sample 50: s.arrow has samples 0 to 49",
        ),
        (
            &["--sweep", "t.arrow"][..],
            "t.arrow is not a sweep file of touchdown (it is a trace file)",
        ),
        (
            &["--sweep", "s.arrow", "--seed", "3"][..],
            "cannot be used with",
        ),
        (
            &["--sweep", "s.arrow", "--scenario", "s.toml"][..],
            "cannot be used with",
        ),
        (
            &["--sweep", "missing.arrow"][..],
            "cannot read missing.arrow",
        ),
    ] {
        let run = touchdown(dir.path(), &[&["trace", "--out", "u.arrow"], args].concat());
        assert_eq!(run.code, Some(2), "{run}");
        assert!(run.stderr.contains(expect), "expected {expect:?}:\n{run}");
    }
    assert!(!dir.join("u.arrow").exists(), "a refused trace left a file");
}

#[test]
fn output_format_follows_the_extension() {
    let dir = TempDir::new("studies-format");
    dir.write("s.toml", SHORT);
    let is_parquet = |name: &str| read_bytes(&dir.join(name)).starts_with(b"PAR1");
    let is_arrow = |name: &str| read_bytes(&dir.join(name)).starts_with(b"ARROW1");
    let base = ["--scenario", "s.toml", "--samples", "60"];
    for (out, format, parquet) in [
        ("x.parquet", None, true),
        ("x.PQ", None, true),
        ("x.arrow", None, false),
        ("x.feather", None, false),
        ("x.data", None, false),
        ("y.data", Some("parquet"), true),
        ("y.parquet", Some("parquet"), true),
    ] {
        let mut args = [&base[..], &["--out", out]].concat();
        if let Some(f) = format {
            args.extend(["--format", f]);
        }
        sweep(&dir, &args);
        let ok = if parquet {
            is_parquet(out)
        } else {
            is_arrow(out)
        };
        assert!(
            ok,
            "{out} (--format {format:?}) is not {}",
            if parquet { "Parquet" } else { "Arrow" }
        );
    }
    // Shards merged into a .parquet are Parquet, and read as the one-process sweep does.
    for k in ["0/2", "1/2"] {
        let out = format!("s{}.arrow", &k[..1]);
        sweep(&dir, &[&base[..], &["--shard", k, "--out", &out]].concat());
    }
    let merged = touchdown(
        dir.path(),
        &["merge", "s0.arrow", "s1.arrow", "--out", "m.parquet"],
    );
    assert_eq!(merged.code, Some(0), "{merged}");
    assert!(
        is_parquet("m.parquet"),
        "merge --out m.parquet is not Parquet"
    );
    let report = |f: &str| {
        touchdown(dir.path(), &["report", f])
            .stdout
            .replace(f, "FILE")
    };
    assert_eq!(report("m.parquet"), report("x.parquet"));
    let refused = touchdown(
        dir.path(),
        &[
            "merge", "s0.arrow", "s1.arrow", "--out", "m.arrow", "--format", "parquet",
        ],
    );
    assert_eq!(refused.code, Some(2), "{refused}");
    assert!(
        refused
            .stderr
            .contains("--format parquet contradicts the extension of --out m.arrow"),
        "{refused}"
    );
    assert!(!dir.join("m.arrow").exists());
}
