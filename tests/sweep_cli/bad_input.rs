//! Bad input: refused before any work; a full disk is reported and leaves no file.

use crate::common::{BadInput, SHORT, TempDir, bad_args, bad_scenario, check_bad_input};
use std::process::Command;

const BAD_SWEEP_INPUTS: &[BadInput] = &[
    bad_args(
        "zero samples",
        &["--samples", "0"],
        &["--samples", "at least 1"],
    ),
    bad_args(
        "negative samples",
        &["--samples", "-5"],
        &["--samples", "'-5'", "not a whole number"],
    ),
    bad_args(
        "negative samples, with =",
        &["--samples=-5"],
        &["--samples", "'-5'", "not a whole number"],
    ),
    bad_args(
        "fractional samples",
        &["--samples", "1.5"],
        &["--samples", "'1.5'", "not a whole number"],
    ),
    bad_args(
        "samples not a number",
        &["--samples", "many"],
        &["--samples", "'many'", "not a whole number"],
    ),
    bad_args(
        "zero threads",
        &["--threads", "0"],
        &["--threads", "'0'", "at least 1"],
    ),
    bad_args(
        "negative threads",
        &["--threads", "-1"],
        &["--threads", "'-1'"],
    ),
    bad_args(
        "too many threads",
        &["--threads", "5000"],
        &["--threads", "'5000'", "at most 1024"],
    ),
    bad_args(
        "unknown format",
        &["--format", "csv"],
        &["--format", "'csv'", "arrow", "parquet"],
    ),
    bad_args("negative seed", &["--seed", "-1"], &["--seed", "'-1'"]),
    bad_args(
        "output where no file can be made",
        &["--out", "/proc/sweep.arrow"],
        &["cannot write output file /proc/sweep.arrow.partial"],
    ),
    bad_args(
        "output in a folder that is a file",
        &["--out", "/proc/self/status/sweep.arrow"],
        &["/proc/self/status is a file, not a folder"],
    ),
    bad_args(
        "resume with nothing to resume",
        &["--resume", "gone.arrow"],
        &["nothing to resume", "gone.arrow.interrupted"],
    ),
    bad_args(
        "resume with settings of its own",
        &["--resume", "gone.arrow", "--samples", "5"],
        &["--resume", "cannot be used with", "--samples"],
    ),
    bad_args(
        "shard index past the count",
        &["--shard", "4/4"],
        &["--shard", "\"4/4\"", "K from 0 to N-1"],
    ),
    bad_args(
        "zero shards",
        &["--shard", "0/0"],
        &["--shard", "\"0/0\"", "K from 0 to N-1"],
    ),
    bad_args(
        "shard not K/N",
        &["--shard", "2"],
        &["--shard", "\"2\"", "K from 0 to N-1"],
    ),
    bad_args(
        "seed beyond what a scenario file can hold",
        &["--seed", "9223372036854775808"],
        &["--seed", "at most 9223372036854775807 (2^63 - 1)"],
    ),
    // The limit is written one way, whatever way the number is written.
    bad_args(
        "seed beyond it, written as a float",
        &["--seed", "1e19"],
        &["--seed", "at most 9223372036854775807 (2^63 - 1)"],
    ),
    // With a scenario that does not exist, so that a sweep that takes the count fails at
    // once rather than running for ever.
    bad_args(
        "samples 2^63",
        &[
            "--samples",
            "9223372036854775808",
            "--scenario",
            "missing.toml",
        ],
        &[
            "--samples",
            "too large: at most 9223372036854775807 (2^63 - 1)",
        ],
    ),
    bad_args(
        "samples 2^64 - 1",
        &[
            "--samples",
            "18446744073709551615",
            "--scenario",
            "missing.toml",
        ],
        &[
            "--samples",
            "too large: at most 9223372036854775807 (2^63 - 1)",
        ],
    ),
    bad_args(
        "samples 1.8e19",
        &["--samples", "1.8e19", "--scenario", "missing.toml"],
        &[
            "--samples",
            "too large: at most 9223372036854775807 (2^63 - 1)",
        ],
    ),
    bad_args(
        "a flag of trace",
        &["--every", "3"],
        &["unexpected argument '--every'"],
    ),
    bad_args(
        "output in a missing folder",
        &["--out", "missing/sweep.arrow"],
        &["missing/sweep.arrow", "folder missing does not exist"],
    ),
    bad_args(
        "output path that names no file",
        &["--out", "."],
        &["output path \".\"", "names no file"],
    ),
    bad_args(
        "missing scenario file",
        &["--scenario", "missing.toml"],
        &["cannot read scenario file missing.toml"],
    ),
    bad_scenario(
        "zero samples in the scenario",
        "samples = 0\n",
        &["`samples` = 0 ", "from 1 to"],
    ),
    bad_scenario(
        "bad scenario",
        "[lander]\nmass_kg = -5\n",
        &["`lander.mass_kg` = -5 ", "greater than 0"],
    ),
    bad_args(
        "resume naming the interrupted file",
        &["--resume", "b2.arrow.interrupted"],
        &[
            "--resume takes the output of the sweep",
            "touchdown sweep --resume b2.arrow",
        ],
    ),
    bad_args(
        "format contradicting the extension",
        &["--out", "x.parquet", "--format", "arrow"],
        &["--format arrow contradicts", "x.parquet", "a parquet file"],
    ),
    bad_args(
        "format contradicting the extension, the other way",
        &["--out", "x.feather", "--format", "parquet"],
        &["--format parquet contradicts", "x.feather", "an arrow file"],
    ),
    // Set-ups that defeat themselves: refused with the reason, before any work.
    bad_scenario(
        "a footpad above the CG",
        "[lander]\nleg_tips_m = [[0.4, 0.4, 0.1], [0.4, -0.4, -0.4], [-0.4, -0.4, -0.4], \
         [-0.4, 0.4, -0.4]]\n",
        &[
            "`lander.leg_tips_m`",
            "footpad 0 at [0.4, 0.4, 0.1]",
            "below the CG",
        ],
    ),
    bad_scenario(
        "footpads above the CG by a negative height",
        "[lander]\ncg_height_m = -0.2\n",
        &["`lander.cg_height_m`"],
    ),
    bad_scenario(
        "three footpads on a line",
        "[lander]\nleg_tips_m = [[0.4, 0.0, -0.4], [0.0, 0.0, -0.4], [-0.4, 0.0, -0.4]]\n",
        &["`lander.leg_tips_m`", "not on one line", "no area"],
    ),
    bad_scenario(
        "the CG beside the footpads",
        "[lander]\nleg_tips_m = [[0.4, 0.1, -0.4], [0.8, 0.1, -0.4], [0.6, 0.5, -0.4]]\n",
        &[
            "`lander.leg_tips_m`",
            "CG",
            "inside of their support polygon",
        ],
    ),
    bad_scenario(
        "struts pointing up with dampers on",
        "[damper]\nenabled = true\nstrut_axis = [0.0, 0.0, 1.0]\n",
        &["`damper.strut_axis` = [0, 0, 1]", "never stroke"],
    ),
    bad_scenario(
        "a hold time longer than the run",
        "[simulation]\nt_max_s = 1.5\n",
        &["`outcome.hold_time_s` = 2 s", "simulation.t_max_s = 1.5 s"],
    ),
    bad_scenario(
        "no gravity",
        "gravity_m_s2 = 0.0\n",
        &["`gravity_m_s2` = 0 ", "greater than 0"],
    ),
    bad_scenario(
        "a run too short to reach the surface",
        "[initial]\nclearance_m = 5.0\n\n[simulation]\nt_max_s = 3.0\n",
        &[
            "`simulation.t_max_s` = 3 s",
            "reach the surface",
            "clearance_m = 5 m",
        ],
    ),
    bad_scenario(
        "a descent start without a descent law",
        "[initial]\nstart = \"descent\"\n",
        &["`initial.start` = \"descent\"", "[control.descent]"],
    ),
    bad_scenario(
        "a descent law without a descent start",
        concat!(
            "[[thrusters]]\nposition_m = [0.4, 0.0, 0.3]\ndirection = [0.0, 0.0, 1.0]\n",
            "max_thrust_n = 2.0\nmin_on_time_s = 0.01\n",
            "[[thrusters]]\nposition_m = [-0.4, 0.0, 0.3]\ndirection = [0.0, 0.0, 1.0]\n",
            "max_thrust_n = 2.0\nmin_on_time_s = 0.01\n",
            "[control]\n[control.descent]\n",
        ),
        &["`control.descent`", "initial.start = \"descent\""],
    ),
    bad_scenario(
        "a descent braking harder than the thrusters can",
        concat!(
            "[initial]\nstart = \"descent\"\n",
            "[[thrusters]]\nposition_m = [0.4, 0.0, 0.3]\ndirection = [0.0, 0.0, 1.0]\n",
            "max_thrust_n = 2.0\nmin_on_time_s = 0.01\n",
            "[[thrusters]]\nposition_m = [-0.4, 0.0, 0.3]\ndirection = [0.0, 0.0, 1.0]\n",
            "max_thrust_n = 2.0\nmin_on_time_s = 0.01\n",
            "[control]\n[control.descent]\nbraking_m_s2 = 0.05\n",
        ),
        &[
            "`control.descent.braking_m_s2` = up to 0.05",
            "6.6800 N along +Z_B",
            "at most 4.0000 N",
        ],
    ),
    bad_scenario(
        "a descent nulling the lateral velocity without lateral thrusters",
        concat!(
            "[initial]\nstart = \"descent\"\n",
            "[[thrusters]]\nposition_m = [0.4, 0.0, 0.3]\ndirection = [0.0, 0.0, 1.0]\n",
            "max_thrust_n = 2.0\nmin_on_time_s = 0.01\n",
            "[[thrusters]]\nposition_m = [-0.4, 0.0, 0.3]\ndirection = [0.0, 0.0, 1.0]\n",
            "max_thrust_n = 2.0\nmin_on_time_s = 0.01\n",
            "[control]\n[control.descent]\nnull_lateral_velocity = true\n",
        ),
        &[
            "`control.descent.null_lateral_velocity` = true",
            "push pure both ways along X_B and Y_B",
        ],
    ),
    bad_scenario(
        "a thruster whose shortest firing is longer than a control period",
        concat!(
            "[[thrusters]]\nposition_m = [0.4, 0.0, 0.3]\ndirection = [0.0, 0.0, 1.0]\n",
            "max_thrust_n = 2.0\nmin_on_time_s = 0.01\n",
            "[[thrusters]]\nposition_m = [-0.4, 0.0, 0.3]\ndirection = [0.0, 0.0, 1.0]\n",
            "max_thrust_n = 2.0\nmin_on_time_s = 0.25\n",
            "[control]\nrate_hz = 5.0\n[control.attitude_hold]\n",
        ),
        &[
            "`thrusters[1].min_on_time_s` = 0.25 s",
            "1 / control.rate_hz = 0.2 s",
            "never fires",
        ],
    ),
    bad_scenario(
        "a hold-down that cannot end before t_max",
        concat!(
            "[simulation]\nt_max_s = 30.0\n",
            "[[thrusters]]\nposition_m = [0.4, 0.0, 0.3]\ndirection = [0.0, 0.0, -1.0]\n",
            "max_thrust_n = 2.0\nmin_on_time_s = 0.01\n",
            "[[thrusters]]\nposition_m = [-0.4, 0.0, 0.3]\ndirection = [0.0, 0.0, -1.0]\n",
            "max_thrust_n = 2.0\nmin_on_time_s = 0.01\n",
            "[control]\n[control.hold_down]\nthrust_n = 1.0\n",
            "duration_s = { dist = \"uniform\", min = 10.0, max = 40.0 }\n",
        ),
        &[
            "`control.hold_down.duration_s` = up to 40 s",
            "less than simulation.t_max_s = 30 s",
        ],
    ),
    bad_scenario(
        "an unknown law of the user's beside the built-in ones",
        concat!(
            "[[thrusters]]\nposition_m = [0.4, 0.0, 0.3]\ndirection = [0.0, 0.0, -1.0]\n",
            "max_thrust_n = 2.0\nmin_on_time_s = 0.01\n",
            "[control]\nlaw = \"unknown\"\n[control.hold_down]\n",
        ),
        &["`control.law` = \"unknown\"", "this program registers none"],
    ),
    BadInput {
        name: "bad scenario with an explicit output path and format",
        scenario: Some("[lander]\nmass_kg = 0\n"),
        args: &["--out", "explicit.parquet", "--format", "parquet"],
        expect: &["`lander.mass_kg` = 0 "],
    },
];

#[test]
fn bad_sweep_input_is_refused_before_any_work() {
    let failures: Vec<String> = BAD_SWEEP_INPUTS
        .iter()
        .flat_map(|case| check_bad_input("sweep", case, &["touchdown sweep:"]))
        .collect();
    assert!(
        failures.is_empty(),
        "{} of {} bad inputs were not refused properly:\n\n{}",
        failures.len(),
        BAD_SWEEP_INPUTS.len(),
        failures.join("\n\n")
    );
}

/// A full disk, simulated by a file size limit (and SIGXFSZ ignored, as a full disk sends
/// no signal): the write fails, the sweep says which file and why, exits 2 and leaves no
/// file behind.
#[test]
fn a_full_disk_is_reported_and_leaves_no_file() {
    let dir = TempDir::new("sweep-full-disk");
    dir.write("short.toml", SHORT);
    let out = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "trap '' XFSZ; ulimit -f 512; exec {} sweep --scenario short.toml --samples 20000 \\
             --quiet --out full.arrow",
            crate::common::BIN
        ))
        .current_dir(dir.path())
        .output()
        .expect("run sh");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "stderr: {stderr}");
    assert!(
        stderr.contains("cannot write output file full.arrow.partial")
            && stderr.contains("File too large"),
        "stderr: {stderr}"
    );
    assert!(!stderr.contains("panicked"), "stderr: {stderr}");
    assert_eq!(dir.entries(), ["short.toml"]);
}

/// A terrain tile of a table far past any surface's tiles (1e18, a whole number held as a
/// float) is refused with the allowed range, not called "not a whole number".
#[test]
fn a_huge_terrain_tile_is_out_of_range() {
    let dir = TempDir::new("huge-tile");
    for (name, cell) in [
        ("float.csv", "1e18"),
        ("integer.csv", "1000000000000000000"),
    ] {
        dir.write(name, &format!("slope_deg,terrain_tile\n10,{cell}\n"));
        let run = crate::common::touchdown(
            dir.path(),
            &["sweep", "--inputs", name, "--quiet", "--out", "o.arrow"],
        );
        assert_eq!(run.code, Some(2), "{run}");
        assert!(
            run.stderr.contains(
                "column terrain_tile: 1000000000000000000 is out of range: a terrain tile is a \
                 whole number from 0 to surface.roughness.tiles - 1"
            ),
            "{run}"
        );
    }
}
